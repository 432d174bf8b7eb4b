// `hybridlab run` and `hybridlab merge`: experiments (DESIGN.md "Experiments and results").
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "common/core/cli_number_validators.h"
#include "common/core/input_error.h"
#include "experiments/cli/commands.h"
#include "experiments/cli/python_script.h"
#include "experiments/runner/experiment_runner.h"
#include "experiments/runner/reference_cache.h"
#include "experiments/runner/resolution_scale.h"

namespace hybridlab::cli {

namespace {

struct RunOptions {
    std::string config;
    std::string out;
    std::string shard = "0/1";
    std::string cache;
    std::string scale = "1";
    bool resume = false;
    bool allowMixedDevices = false;
    long maxRuns = -1;
    bool quiet = false;
    bool dryRun = false;
    bool realTime = false;
};

// "i/n": two decimal numbers and one slash, nothing else (sscanf would take "1/2/3" and " 1/2").
std::pair<int, int> parseShard(const std::string& text) {
    constexpr long kMaxShards = 100000;
    const auto number = [&](std::size_t from, std::size_t to) {
        if (to <= from || to - from > 6) return -1L;
        long v = 0;
        for (std::size_t k = from; k < to; ++k) {
            if (text[k] < '0' || text[k] > '9') return -1L;
            v = v * 10 + (text[k] - '0');
        }
        return v;
    };
    const std::size_t slash = text.find('/');
    const long i = slash == std::string::npos ? -1 : number(0, slash);
    const long n = slash == std::string::npos ? -1 : number(slash + 1, text.size());
    if (i < 0 || n < 1 || n > kMaxShards || i >= n) {
        throw InputError("--shard " + text + ": expected i/n, whole numbers with 0 <= i < n <= " + std::to_string(kMaxShards) +
                         " (shards count from 0: 0/3, 1/3 and 2/3 make three)");
    }
    return {static_cast<int>(i), static_cast<int>(n)};
}

// --dry-run: the config checked and its runs listed, with how many references are cached; nothing
// written.
void listRuns(const ExperimentConfig& config, const RunnerOptions& r) {
    const ExperimentPlan plan = planExperiment(config, r);
    std::printf("experiment %s (%s, config hash %s): %zu runs", config.name.c_str(), config.file.string().c_str(),
                config.hash.substr(0, 12).c_str(), plan.runs.size());
    if (r.shardCount > 1) std::printf(", %zu in shard %d/%d (estimated cost %.3g)", plan.mine.size(), r.shardIndex, r.shardCount, plan.estimatedCost);
    std::printf("; references: %zu, %zu of them cached in %s\n", plan.references, plan.referencesCached, r.cacheDir.string().c_str());
    if (config.resolutionScale != 1.0) std::printf("sizes at --scale %g of the configured ones\n", config.resolutionScale);
    std::size_t sceneWidth = 5, viewWidth = 4, techniqueWidth = 9;
    for (const auto& p : plan.mine) {
        sceneWidth = std::max(sceneWidth, config.scenes[p.run->scene].label.size());
        viewWidth = std::max(viewWidth, p.run->cameraPath.empty() ? 6 : p.run->cameraPath.size());
        techniqueWidth = std::max(techniqueWidth, config.techniques[p.run->technique].label.size());
    }
    std::printf("%5s  %-*s  %-*s  %5s  %-9s  %-*s  %-9s  %s\n", "index", static_cast<int>(sceneWidth), "scene", static_cast<int>(viewWidth), "view",
                "frame", "size", static_cast<int>(techniqueWidth), "technique", "reference", "parameters");
    for (const auto& p : plan.mine) {
        const RunSpec& run = *p.run;
        const std::string frame = run.frame >= 0 ? std::to_string(run.frame) : "-";
        const std::string size = std::to_string(run.width) + "x" + std::to_string(run.height);
        std::printf("%5zu  %-*s  %-*s  %5s  %-9s  %-*s  %-9s  %s\n", run.index, static_cast<int>(sceneWidth), config.scenes[run.scene].label.c_str(),
                    static_cast<int>(viewWidth), run.cameraPath.empty() ? "camera" : run.cameraPath.c_str(), frame.c_str(), size.c_str(),
                    static_cast<int>(techniqueWidth), config.techniques[run.technique].label.c_str(), p.referenceCached ? "cached" : "to render",
                    run.parametersText.empty() ? "(defaults)" : run.parametersText.c_str());
    }
}

// What a run found, in a few lines: the runs and references rendered and reused, where the results
// are, the verdict's first sentences (report/verdict.py) and the command that writes the report.
void printClosingSummary(const ExperimentConfig& config, const RunnerOptions& r, const RunnerSummary& s, const RunOptions& o, double scale) {
    std::printf("experiment %s (shard %d/%d): %zu runs, %zu rendered, %zu already done; references: %zu rendered, %zu "
                "reused from the cache (%s)\n",
                config.name.c_str(), r.shardIndex, r.shardCount, s.runsPlanned, s.runsRendered, s.runsSkipped, s.referencesRendered,
                s.referenceCacheHits, r.cacheDir.string().c_str());
    if (!s.complete) {
        std::printf("stopped with runs left; `hybridlab run %s --out %s%s --resume` continues\n", o.config.c_str(), r.outDir.string().c_str(),
                    scale == 1.0 ? "" : (" --scale " + o.scale).c_str());
        return;
    }
    std::printf("results in %s (results.csv, results.json)\n", r.outDir.string().c_str());
    if (r.quiet) return;
    if (r.shardCount > 1) {
        std::printf("a shard: `hybridlab merge` joins the shards, then `hybridlab report` writes the report\n");
        return;
    }
    // The verdict in words, a sentence per scene and size; the report has the rest.
    constexpr std::size_t kSentences = 3;
    std::string verdict;
    if (runReportScript("verdict.py", {r.outDir.string()}, Interrupt::StopsBoth, &verdict) == 0) {
        std::vector<std::string> sentences;
        for (std::size_t at = 0, end; at < verdict.size(); at = end + 1) {
            end = verdict.find('\n', at);
            if (end == std::string::npos) end = verdict.size();
            if (end > at) sentences.push_back(verdict.substr(at, end - at));
        }
        std::printf("verdict:\n");
        for (std::size_t i = 0; i < std::min(sentences.size(), kSentences); ++i) std::printf("  %s\n", sentences[i].c_str());
        if (sentences.size() > kSentences) std::printf("  (%zu more scenes and sizes in the report)\n", sentences.size() - kSentences);
    }
    std::printf("report: `hybridlab report %s` writes %s\n", r.outDir.string().c_str(), (r.outDir / "report" / "index.html").string().c_str());
}

void run(const RunOptions& o) {
    const double scale = parseResolutionScale(o.scale);  // before the config: a bad argument is named first
    ExperimentConfig config = loadExperimentConfig(o.config);
    scaleResolutions(config, scale);
    RunnerOptions r;
    std::tie(r.shardIndex, r.shardCount) = parseShard(o.shard);
    r.outDir = o.out.empty() ? std::filesystem::path("results") / config.name : std::filesystem::path(o.out);
    if (o.out.empty() && r.shardCount > 1) r.outDir += "-shard" + std::to_string(r.shardIndex) + "of" + std::to_string(r.shardCount);
    r.cacheDir = o.cache.empty() ? defaultReferenceCacheDir() : std::filesystem::path(o.cache);
    r.resume = o.resume;
    r.allowMixedDevices = o.allowMixedDevices;
    r.maxRuns = o.maxRuns;
    r.quiet = o.quiet;
    r.realTime = o.realTime;
    if (o.dryRun) return listRuns(config, r);
    const RunnerSummary s = runExperiment(config, r);
    if (s.staleTemporariesRemoved > 0)
        std::printf("removed %zu partial file(s) (.tmp-*) left by interrupted runs\n", s.staleTemporariesRemoved);
    printClosingSummary(config, r, s, o, scale);
}

// Each shard's estimated cost beside the time its runs took, both also as shares of the whole: how
// well the partition balanced them.
void printMergedShards(const std::vector<MergedShard>& shards) {
    double cost = 0.0, seconds = 0.0;
    bool estimated = true;
    for (const auto& s : shards) {
        cost += s.estimatedCost;
        seconds += s.seconds;
        estimated &= s.estimatedCost >= 0.0;
    }
    std::printf("shard  runs  estimated cost (share)  time s (share)  folder\n");
    for (const auto& s : shards) {
        char est[64] = "-";
        if (estimated) std::snprintf(est, sizeof est, "%.4g (%.0f%%)", s.estimatedCost, cost > 0 ? 100.0 * s.estimatedCost / cost : 0.0);
        char time[64];
        std::snprintf(time, sizeof time, "%.2f (%.0f%%)", s.seconds, seconds > 0 ? 100.0 * s.seconds / seconds : 0.0);
        const std::string name = std::to_string(s.index) + "/" + std::to_string(s.count);
        std::printf("%-5s  %4zu  %-22s  %-14s  %s\n", name.c_str(), s.runs, est, time, s.dir.string().c_str());
    }
}

}  // namespace

void addRunCommand(CLI::App& app) {
    auto o = std::make_shared<RunOptions>();
    auto* cmd = app.add_subcommand("run", "Run an experiment: render every configured run, score it against the cached reference, record it");
    cmd->add_option("config", o->config, "Experiment config (TOML, see experiments/README.md)")->required();
    cmd->add_option("--out", o->out, "Output folder (default: results/<experiment name>)");
    cmd->add_flag("--resume", o->resume, "Continue an interrupted run in --out, skipping recorded runs");
    cmd->add_flag("--allow-mixed-devices", o->allowMixedDevices,
                  "With --resume: continue a result set measured on another device; each run keeps its device");
    cmd->add_option("--shard", o->shard, "Run only the i-th of n parts of the run list (0 <= i < n), balanced by estimated cost")->capture_default_str();
    cmd->add_option("--scale", o->scale,
                    "Render every configured resolution times this fraction (0 < S <= 1; even pixels, at least 16), "
                    "budgets unscaled; recorded in experiment.json, and --resume keeps it")
        ->capture_default_str();
    cmd->add_option("--cache", o->cache, "Reference cache folder (default: $HYBRIDLAB_CACHE or ~/.cache/hybridlab)");
    cmd->add_option("--max-runs", o->maxRuns, "Stop after rendering this many runs (--resume continues)")->check(CLI::Range(0L, 100000000L));
    cmd->add_flag("--quiet", o->quiet, "No progress output, and no verdict at the end");
    cmd->add_flag("--realtime", o->realTime,
                  "Time each group's frames at real-time priority (SCHED_FIFO), ahead of other processes' load, so that a busy "
                  "machine ranks settings as an idle one does (needs root, CAP_SYS_NICE or an RLIMIT_RTPRIO; the kernel leaves "
                  "other processes 5% of each second); recorded as timing.priority");
    cmd->add_flag("--dry-run", o->dryRun,
                  "Check the config and list the runs (index, scene, view, frame, size, technique, reference cached or not, "
                  "parameters); render and write nothing");
    cmd->callback([o] { run(*o); });

    auto out = std::make_shared<std::string>();
    auto shards = std::make_shared<std::vector<std::string>>();
    auto mixed = std::make_shared<bool>(false);
    auto* merge = app.add_subcommand("merge", "Join the shard folders of one experiment into one result set");
    merge->add_option("--out", *out, "Folder for the merged result set (new or empty)")
        ->required()
        ->check(nonEmpty("a folder"));
    merge->add_option("shards", *shards, "Shard folders written by `hybridlab run --shard i/n`")->required();
    merge->add_flag("--allow-mixed-devices", *mixed, "Merge shards measured on different devices; each run keeps its device");
    merge->callback([out, shards, mixed] {
        std::vector<std::filesystem::path> dirs(shards->begin(), shards->end());
        printMergedShards(mergeShards(dirs, *out, *mixed));
        std::printf("merged %zu shards into %s\n", dirs.size(), out->c_str());
    });
}

}  // namespace hybridlab::cli
