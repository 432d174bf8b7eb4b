// The experiment runner end to end on built-in scenes at a small size: the run list, the
// reference cache, resume after an interruption, shards and merge, and bad configs.
#include <sched.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <map>
#include <set>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/core/input_error.h"
#include "common/core/realtime_priority.h"
#include "experiments/runner/experiment_runner.h"
#include "experiments/runner/results_store.h"
#include "experiments/runner/shard_partition.h"
#include "techniques/technique.h"
#include "tests/support/cli_runner.h"
#include "tests/support/realtime_privilege.h"
#include "tests/support/report_checks.h"
#include "tests/support/runner_checks.h"
#include "tests/support/shell_command.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::TempDir;

// 2 scenes x (1 camera + 2 path frames, and 1 camera) x (3 + 2 parameter sets) = (3 + 1) * 5 = 20.
const char* kConfig = R"(
[experiment]
name = "e2e"
warmup_frames = 0
repeats = 1

[reference]
params = { max_depth = 4 }

[[scenes]]
scene = "whitted-classic"
resolutions = [[48, 27]]
[[scenes.views]]
[[scenes.views]]
path = "orbit"
frames = [0, 30]
stride = 30

[[scenes]]
scene = "cornell-mirror-glass"
resolutions = [[48, 27]]

[[techniques]]
name = "whitted"
label = "depth"
params = { max_depth = [0, 1, 2] }

[[techniques]]
name = "whitted"
label = "cutoff"
param_sets = [ { importance_cutoff = 0.1 }, { importance_cutoff = 0.3, max_depth = 3 } ]
)";

fs::path writeConfig(const TempDir& dir, const std::string& text, const std::string& name = "e2e.toml") {
    fs::path p = dir.path() / name;
    test::writeTextFile(p, text);
    return p;
}


void expectSameResults(const fs::path& a, const fs::path& b) {
    auto ra = test::readResults(a), rb = test::readResults(b);
    ASSERT_EQ(ra.size(), rb.size());
    for (std::size_t i = 0; i < ra.size(); ++i) EXPECT_EQ(test::comparableRecord(ra[i]), test::comparableRecord(rb[i])) << ra[i].at("id");
}

// Every run's images, reference and error maps exist; the path's second frame has temporal errors.
void expectEveryRunsFiles(const fs::path& out, const std::vector<json>& rows) {
    for (const auto& r : rows) {
        for (const char* key : {"exr", "png"}) EXPECT_TRUE(fs::exists(out / r.at("images").at(key).get<std::string>()));
        EXPECT_TRUE(fs::exists(out / r.at("reference").at("exr").get<std::string>()));
        EXPECT_TRUE(fs::exists(out / r.at("images").at("maps").get<std::string>() / "flip.png"));
        // Frame 30 of the path has a temporal error against frame 0; the camera views have none.
        EXPECT_EQ(r.contains("temporal_error"), r.at("frame").get<int>() == 30) << r.at("id");
        // The scene has reflective pixels: the reference's mask is saved, and the temporal error
        // is also taken on them alone.
        ASSERT_TRUE(r.at("reference").contains("mask")) << r.at("id");
        EXPECT_TRUE(fs::exists(out / r.at("reference").at("mask").get<std::string>()));
        EXPECT_EQ(r.contains("temporal_error_masked"), r.contains("temporal_error")) << r.at("id");
        if (r.contains("temporal_error_masked")) {
            // A mean over other pixels than the whole image's.
            EXPECT_GT(r.at("temporal_error_masked").get<double>(), 0.0);
            EXPECT_NE(r.at("temporal_error_masked").get<double>(), r.at("temporal_error").get<double>());
        }
    }
}

// `config` run as three shards and merged: the same result set as the unsharded run in dir/a, and
// each shard's estimated cost beside the time its runs took.
void expectThreeShardsMergeToTheUnshardedSet(const ExperimentConfig& config, const TempDir& dir, const fs::path& cache) {
    std::vector<fs::path> shards;
    for (int i = 0; i < 3; ++i) {
        RunnerOptions s = test::quietRunnerOptions(dir.path() / ("shard" + std::to_string(i)), cache);
        s.shardIndex = i;
        s.shardCount = 3;
        EXPECT_TRUE(runExperiment(config, s).complete);
        shards.push_back(s.outDir);
    }
    const std::vector<MergedShard> merged = mergeShards(shards, dir.path() / "merged");
    expectSameResults(dir.path() / "a", dir.path() / "merged");
    // Each shard's estimated cost as its experiment.json recorded it, and the time its runs took.
    const ShardPartition partition = partitionRuns(config, planRuns(config), 3);
    ASSERT_EQ(merged.size(), 3u);
    std::size_t mergedRuns = 0;
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(merged[i].index, i);
        EXPECT_EQ(merged[i].dir, shards[i]);
        EXPECT_EQ(merged[i].runs, partition.runsOf(planRuns(config), i).size());
        EXPECT_DOUBLE_EQ(merged[i].estimatedCost, partition.estimatedCost[i]);
        EXPECT_GT(merged[i].seconds, 0.0);
        mergedRuns += merged[i].runs;
    }
    EXPECT_EQ(mergedRuns, 20u);
    EXPECT_THROW(mergeShards({shards[0], shards[1]}, dir.path() / "merged2"), InputError);  // shard 2 missing
    EXPECT_FALSE(fs::exists(dir.path() / "merged2"));
}

// The report of `results` in `report`: every link and image of index.html resolves, every figure
// has content, and the summary, the Pareto table and each run's row give its scores.
void expectReportShowsEveryRun(const fs::path& results, const fs::path& report, const std::vector<json>& rows) {
    test::CliResult r = test::runHybridlab({"report", results.string(), "--out", report.string()});
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    EXPECT_CONTAINS(r.out, "report: " + (report / "index.html").string() + "\n");
    EXPECT_CONTAINS(r.out, "viewer: " + (report / "viewer.html").string() + " (hybridlab view ");
    const std::string page = test::readReportPage(report);
    EXPECT_GT(test::expectReportLinksResolve(report), 20u * 4);  // per run at least: thumbnail, image, exr, reference (+ maps)
    // SVG + PDF of: 2 scenes x (speed-accuracy, stages) + 1 path (+ its "where methods fail" figure)
    EXPECT_GE(test::expectFiguresHaveContent(report), 2u * (2 * 2 + 1));
    EXPECT_TRUE(fs::exists(report / "report.md"));
    // The summary and the verdict's Pareto table give each setting's SSIM, FLIP (LDR) and HDR-FLIP
    // on the reflective and refractive pixels beside the whole image's (one frame a setting on
    // cornell-mirror-glass: the means and medians are the run's own).
    const std::string markdown = test::readTextFile(report / "report.md");
    const std::string scoreHeader =
        "| SSIM | FLIP (LDR) | HDR-FLIP | SSIM refl./refr. | FLIP (LDR) refl./refr. | HDR-FLIP refl./refr. |";
    EXPECT_NE(markdown.find("| x rt_only " + scoreHeader), std::string::npos) << markdown;
    EXPECT_NE(markdown.find("| frame ms (median, mean over frames) " + scoreHeader), std::string::npos) << markdown;
    EXPECT_CONTAINS(page, "<th>FLIP (LDR)</th><th>HDR-FLIP</th>");
    const auto lineFrom = [&](std::size_t at) { return markdown.substr(at, markdown.find('\n', at) - at); };
    std::size_t summarised = 0, paretoRows = 0;
    for (const auto& row : rows) {
        if (row.at("scene") != "cornell-mirror-glass") continue;
        std::string cells;
        for (const char* region : {"whole", "masked"}) {
            const json& m = row.at("metrics").at(region);
            cells += " | " + test::formatNumber("%.4f", m.at("ssim").get<double>()) + " | " +
                     test::formatNumber("%.4f", m.at("flip").at("mean").get<double>()) + " | " +
                     test::formatNumber("%.4f", m.at("flip_hdr").at("mean").get<double>());
        }
        const std::string start = "| " + test::reportVariant(row) + " | 1 | ";
        const std::size_t at = markdown.find(start);
        ASSERT_NE(at, std::string::npos) << start << "\n" << markdown;
        const std::string line = lineFrom(at);
        EXPECT_EQ(line.substr(line.size() - cells.size() - 2), cells + " |") << line;
        ++summarised;
        // A Pareto row starts with the setting's link (the threshold table's rows with the quality).
        const std::size_t pareto = markdown.find("\n| [" + test::reportVariant(row) + "](viewer.html#run=" + row.at("id").get<std::string>() + ") | ");
        if (pareto != std::string::npos) {
            const std::string paretoLine = lineFrom(pareto + 1);
            EXPECT_EQ(paretoLine.substr(paretoLine.size() - cells.size() - 2), cells + " |") << paretoLine;
            ++paretoRows;
        }
        // Every run's row of index.html (its last table): FLIP (LDR) then HDR-FLIP, and the HDR-FLIP
        // map's link.
        const std::size_t tr = page.rfind("viewer.html#run=" + row.at("id").get<std::string>() + "\"");
        ASSERT_NE(tr, std::string::npos) << row.at("id");
        const std::string html = page.substr(tr, page.find("</tr>", tr) - tr);
        const json& whole = row.at("metrics").at("whole");
        EXPECT_CONTAINS(html, "<td>" + test::formatNumber("%.4f", whole.at("flip").at("mean").get<double>()) + "</td><td>" +
                                  test::formatNumber("%.4f", whole.at("flip_hdr").at("mean").get<double>()) + "</td>");
        EXPECT_CONTAINS(html, "/flip_hdr.png\">flip_hdr</a>");
    }
    EXPECT_EQ(summarised, 5u);
    EXPECT_GE(paretoRows, 1u);
    // Every run opens in the viewer from the table (the viewer itself: tests/report/viewer).
    for (const auto& row : rows) EXPECT_NE(page.find("viewer.html#run=" + row.at("id").get<std::string>()), std::string::npos);
    EXPECT_TRUE(fs::exists(report / "viewer" / "main.js"));
    EXPECT_TRUE(fs::exists(report / "viewer" / "settings.json"));
}

TEST(ExperimentRunner, RunsEveryCombinationCachesReferencesAndResumes) {
    TempDir dir;
    const ExperimentConfig config = loadExperimentConfig(writeConfig(dir, kConfig));
    const fs::path cache = dir.path() / "cache";

    // Rows: scenes x frames x techniques x parameter sets.
    RunnerSummary first = runExperiment(config, test::quietRunnerOptions(dir.path() / "a", cache));
    EXPECT_TRUE(first.complete);
    EXPECT_EQ(first.runsRendered, 20u);
    // One per distinct camera and size: orbit's frame 0 is the scene camera of whitted-classic,
    // and the cache keys on the camera, not on the view's name.
    EXPECT_EQ(first.referencesRendered, 3u);
    auto rows = test::readResults(dir.path() / "a");
    ASSERT_EQ(rows.size(), 20u);
    std::string csv;
    {
        std::ifstream in(dir.path() / "a" / "results.csv");
        csv.assign(std::istreambuf_iterator<char>(in), {});
    }
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 21);  // header + 20 rows
    expectEveryRunsFiles(dir.path() / "a", rows);
    // depth 0 is the local colour only: far from the reference on the reflective pixels.
    EXPECT_LT(rows[0].at("metrics").at("masked").at("ssim").get<double>(), rows[2].at("metrics").at("masked").at("ssim").get<double>());

    // The same experiment again: every reference from the cache, each counted once however many
    // runs and groups it scores, and identical metrics.
    RunnerSummary second = runExperiment(config, test::quietRunnerOptions(dir.path() / "b", cache));
    EXPECT_EQ(second.referencesRendered, 0u);
    EXPECT_EQ(second.referenceCacheHits, 3u);
    expectSameResults(dir.path() / "a", dir.path() / "b");

    // Interrupted after 7 runs, then resumed: the same result set as the uninterrupted run.
    RunnerOptions stop = test::quietRunnerOptions(dir.path() / "c", cache);
    stop.maxRuns = 7;
    RunnerSummary part = runExperiment(config, stop);
    EXPECT_FALSE(part.complete);
    EXPECT_EQ(test::readResults(dir.path() / "c").size(), 7u);
    RunnerOptions resume = test::quietRunnerOptions(dir.path() / "c", cache);
    resume.resume = true;
    RunnerSummary rest = runExperiment(config, resume);
    EXPECT_TRUE(rest.complete);
    EXPECT_EQ(rest.runsSkipped, 7u);
    EXPECT_EQ(rest.runsRendered, 13u);
    expectSameResults(dir.path() / "a", dir.path() / "c");

    // Rounds pair only within one timing: each group's runs share one timing id, every group its
    // own, and the group split by the stop (2 of its 5 runs before it, 3 after) has two.
    const auto timingIds = [](const std::vector<json>& records) {
        std::map<std::string, std::set<std::string>> ids;
        for (const json& r : records) ids[r.at("timing").at("group").get<std::string>()].insert(r.at("timing").at("timing_id").get<std::string>());
        return ids;
    };
    std::set<std::string> distinct;
    for (const auto& [group, ids] : timingIds(rows)) {
        EXPECT_EQ(ids.size(), 1u) << group;
        for (const std::string& id : ids) EXPECT_EQ(id.size(), 16u) << id;
        distinct.insert(ids.begin(), ids.end());
    }
    EXPECT_EQ(distinct.size(), 4u);
    std::map<std::size_t, std::size_t> groupsBySplit;
    for (const auto& [group, ids] : timingIds(test::readResults(dir.path() / "c"))) ++groupsBySplit[ids.size()];
    EXPECT_EQ(groupsBySplit, (std::map<std::size_t, std::size_t>{{1, 3}, {2, 1}}));

    // Three shards merged: the same result set as the unsharded run.
    expectThreeShardsMergeToTheUnshardedSet(config, dir, cache);

    // An output folder is never overwritten without --resume.
    EXPECT_THROW(runExperiment(config, test::quietRunnerOptions(dir.path() / "a", cache)), InputError);

    // The report: every link and image of index.html resolves to a file, every figure has content.
    expectReportShowsEveryRun(dir.path() / "a", dir.path() / "report", rows);
}

std::size_t recordCount(const fs::path& out) {
    std::size_t n = 0;
    if (fs::exists(out / "runs"))
        for (const auto& e : fs::directory_iterator(out / "runs")) n += e.path().filename().string().front() != '.';
    return n;
}

TEST(ExperimentRunner, KilledMidRunLeavesWholeFilesAndResumesToTheSameResults) {
    TempDir dir;
    std::string text = kConfig;
    text.replace(text.find("repeats = 1"), 11, "repeats = 2");  // slower runs: room to kill mid-way
    const fs::path configFile = writeConfig(dir, text);
    const fs::path cache = dir.path() / "cache", killed = dir.path() / "killed";

    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        execl(HYBRIDLAB_BIN, HYBRIDLAB_BIN, "run", configFile.c_str(), "--out", killed.c_str(), "--cache", cache.c_str(), "--quiet",
              static_cast<char*>(nullptr));
        _exit(127);
    }
    // Kill it (no chance to clean up) once a few runs are recorded.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (recordCount(killed) < 4 && std::chrono::steady_clock::now() < deadline) std::this_thread::sleep_for(std::chrono::milliseconds(2));
    kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
    const std::size_t before = recordCount(killed);
    ASSERT_GE(before, 4u);
    if (WIFEXITED(status)) GTEST_SKIP() << "the run finished before it could be killed";
    // Every file it left is whole: the records and results parse, and hold the same runs.
    for (const auto& e : fs::directory_iterator(killed / "runs")) {
        if (e.path().filename().string().front() == '.') continue;  // an interrupted temporary, ignored by design
        std::ifstream in(e.path());
        EXPECT_NO_THROW(json::parse(in)) << e.path();
    }
    // results.json is written when the runner stops (results_store.h), so a killed one left none:
    // never a stale one. The readers take the records: the table scripts from runs/ directly,
    // `report` by writing results.json and results.csv first, as the runner would have.
    EXPECT_FALSE(fs::exists(killed / "results.json"));
    EXPECT_FALSE(fs::exists(killed / "results.csv"));
    const std::string load = "/usr/bin/python3 -c 'import sys; sys.path.insert(0, \"" + (test::sourceDir() / "report").string() +
                             "\"); import results; print(\" \".join(str(r[\"index\"]) for r in results.load(sys.argv[1])))' '" +
                             killed.string() + "' 2>/dev/null";
    std::string indices;
    for (std::size_t i = 0; i < before; ++i) indices += (i ? " " : "") + std::to_string(i);
    EXPECT_EQ(test::commandOutput(load).out, indices + "\n");  // the runs are recorded in index order
    const test::CliResult report = test::runHybridlab({"report", killed.string(), "--out", (dir.path() / "killed-report").string()});
    ASSERT_EQ(report.exitStatus, 0) << report.err;
    EXPECT_CONTAINS(report.out, killed.string() + ": its runner stopped before writing results.json and results.csv; wrote them from its " +
                                    std::to_string(before) + " records\n");
    EXPECT_EQ(test::readResults(killed).size(), before);
    const std::string csv = test::readTextFile(killed / "results.csv");
    EXPECT_EQ(static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n')), before + 1);  // header + a row a record

    // Resumed, and an uninterrupted run to compare with, through the same program (the program's
    // hash is part of the reference cache key).
    auto outcomes = test::runHybridlabAll(
        {{{"run", configFile.string(), "--out", killed.string(), "--cache", cache.string(), "--resume", "--quiet"}, {}},
         {{"run", configFile.string(), "--out", (dir.path() / "whole").string(), "--cache", cache.string(), "--quiet"}, {}}});
    ASSERT_EQ(outcomes[0].exitStatus, 0) << outcomes[0].err;
    ASSERT_EQ(outcomes[1].exitStatus, 0) << outcomes[1].err;
    EXPECT_NE(outcomes[0].out.find(std::to_string(before) + " already done"), std::string::npos) << outcomes[0].out;
    expectSameResults(dir.path() / "whole", killed);
}

TEST(ExperimentRunner, ChangedSceneContentInvalidatesTheCachedReference) {
    TempDir dir;
    fs::copy_file(test::builtinSceneFile("whitted-classic"), dir.path() / "scene.toml");
    std::string config = "[experiment]\nrepeats = 1\nwarmup_frames = 0\n[[scenes]]\nscene = \"" + (dir.path() / "scene.toml").string() +
                         "\"\nresolutions = [[24, 16]]\n[[techniques]]\nname = \"whitted\"\n";
    const ExperimentConfig c = loadExperimentConfig(writeConfig(dir, config));
    const fs::path cache = dir.path() / "cache";
    EXPECT_EQ(runExperiment(c, test::quietRunnerOptions(dir.path() / "a", cache)).referencesRendered, 1u);
    EXPECT_EQ(runExperiment(c, test::quietRunnerOptions(dir.path() / "b", cache)).referencesRendered, 0u);
    std::ofstream(dir.path() / "scene.toml", std::ios::app) << "\n# an edit\n";
    EXPECT_EQ(runExperiment(c, test::quietRunnerOptions(dir.path() / "c", cache)).referencesRendered, 1u);
    // A damaged entry is rendered again, not scored against.
    for (const auto& f : fs::directory_iterator(cache))
        if (f.path().extension() == ".exr") fs::resize_file(f.path(), fs::file_size(f.path()) / 2);
    EXPECT_EQ(runExperiment(c, test::quietRunnerOptions(dir.path() / "d", cache)).referencesRendered, 1u);
    EXPECT_EQ(runExperiment(c, test::quietRunnerOptions(dir.path() / "e", cache)).referencesRendered, 0u);
}

// A run's counters are a function of the run alone: the same whitted run in an experiment of its
// own (its reference rendered first), and after `raster` with the reference from the cache, in
// fresh processes of the program, where the order once mattered (10588 shadow rays instead of
// 10395 here: TBB's workers had started in another floating-point mode, see
// test_technique_determinism.cpp).
TEST(ExperimentRunner, ARunsCountersDoNotDependOnTheRunsBeforeIt) {
    TempDir dir;
    const std::string head = "[experiment]\nname = \"order\"\nwarmup_frames = 0\nrepeats = 1\n[[scenes]]\nscene = \"whitted-classic\"\n"
                             "resolutions = [[96, 54]]\n[[scenes.views]]\n";
    const fs::path alone = writeConfig(dir, head + "[[techniques]]\nname = \"whitted\"\n", "alone.toml");
    const fs::path afterRaster = writeConfig(dir, head + "[[techniques]]\nname = \"raster\"\n[[techniques]]\nname = \"whitted\"\n", "after-raster.toml");
    const fs::path cache = dir.path() / "cache";
    auto whittedRecord = [&](const fs::path& config, const std::string& out) {
        const test::CliResult r = test::runHybridlab({"run", config.string(), "--out", (dir.path() / out).string(), "--cache", cache.string(), "--quiet"});
        EXPECT_EQ(r.exitStatus, 0) << r.err;
        for (const json& record : test::readResults(dir.path() / out))
            if (record.at("technique") == "whitted") return record;
        ADD_FAILURE() << out << ": no whitted run";
        return json();
    };
    const json first = whittedRecord(alone, "alone");
    const json second = whittedRecord(afterRaster, "after-raster");
    ASSERT_FALSE(first.is_null() || second.is_null());
    EXPECT_FALSE(first["reference"]["cache_hit"].get<bool>());
    EXPECT_TRUE(second["reference"]["cache_hit"].get<bool>());
    std::size_t compared = 0;
    for (const auto& [name, value] : first.at("counters").items()) {
        if (name.ends_with("_ms") || name.ends_with("_per_second")) continue;  // measurements, not counts
        EXPECT_EQ(value, second.at("counters").value(name, json())) << "counter " << name;
        ++compared;
    }
    EXPECT_GT(first.at("counters").at("rays_shadow").get<double>(), 0.0);
    std::printf("[ counters ] whitted alone and after raster: %zu counters compared\n", compared);
}

// A scene given by a path relative to the config file resolves against the config's folder (not the
// working folder), and the records call it by its own name; --resume on a result set whose config
// has changed says what changed and how to go on.
TEST(ExperimentRunner, ScenePathsResolveAgainstTheConfigAndResumeExplainsAChangedConfig) {
    TempDir dir;
    fs::create_directories(dir.path() / "my-scenes");
    fs::copy_file(test::builtinSceneFile("whitted-classic"), dir.path() / "my-scenes" / "copy.toml");  // [scene] name = "whitted-classic"
    const std::string head = "[experiment]\nname = \"relative\"\nrepeats = 1\nwarmup_frames = 0\n[[scenes]]\nscene = \"my-scenes/copy.toml\"\n"
                             "resolutions = [[24, 16]]\n[[techniques]]\nname = \"raster\"\n";
    const ExperimentConfig config = loadExperimentConfig(writeConfig(dir, head, "relative.toml"));
    EXPECT_EQ(config.scenes[0].file, dir.path() / "my-scenes" / "copy.toml");
    const fs::path out = dir.path() / "out", cache = dir.path() / "cache";
    ASSERT_TRUE(runExperiment(config, test::quietRunnerOptions(out, cache)).complete);
    const RunRecord record = ResultsStore(out).loadRecords().at(0);
    EXPECT_EQ(record.scene, "whitted-classic");
    EXPECT_NE(record.id.find("-whitted-classic-"), std::string::npos) << record.id;

    // The same experiment with a second technique: one run the folder does not hold.
    const ExperimentConfig changed =
        loadExperimentConfig(writeConfig(dir, head + "[[techniques]]\nname = \"whitted\"\n", "relative.toml"));
    RunnerOptions resume = test::quietRunnerOptions(out, cache);
    resume.resume = true;
    try {
        runExperiment(changed, resume);
        ADD_FAILURE() << "--resume continued a result set of another config";
    } catch (const InputError& e) {
        const std::string m = e.what();
        EXPECT_CONTAINS(m, out.string() + ": holds experiment 'relative' made with another config (hash " + config.hash.substr(0, 12) +
                               " there, " + changed.hash.substr(0, 12) + " in " + changed.file.string() + "; its runs: 1 then, 2 now)");
        EXPECT_CONTAINS(m, "1 run(s) of the config are not recorded (00001-whitted-classic-camera-24x16-whitted-");
        EXPECT_CONTAINS(m, "give this config another --out; to redo them with this config, remove the folder first");
    }
}

// One run of about a millisecond a frame (whitted at 24x14), after the [experiment] table's keys.
const char* kOneTinyRun = R"(
repeats = 2
keep = []
metrics = ["rmse"]
[[scenes]]
scene = "whitted-classic"
resolutions = [[24, 14]]
[[techniques]]
name = "whitted"
params = { max_depth = 1 }
)";

TEST(ExperimentRunner, WarmupGoesOnForWarmupMilliseconds) {
    TempDir dir;
    // 250 ms of warm-up is many frames.
    const std::string body = kOneTinyRun;
    auto run = [&](const std::string& name, const std::string& warmup) {
        const fs::path out = dir.path() / name;
        RunnerOptions o = test::quietRunnerOptions(out, dir.path() / "cache");
        EXPECT_TRUE(runExperiment(loadExperimentConfig(writeConfig(dir, "[experiment]\n" + warmup + body, name + ".toml")), o).complete);
        const auto records = test::readResults(out);
        EXPECT_EQ(records.size(), 1u);
        return records.empty() ? json() : records[0];
    };
    // 3 frames, then on until the last two agree within 10%, 5 at most (interleaved_timing.h).
    const json frames = run("frames", "warmup_frames = 3\n");
    EXPECT_GE(frames.at("warmup_frames"), 3);
    EXPECT_LE(frames.at("warmup_frames"), 5);
    if (frames.at("warmup_frames") < 5) {
        EXPECT_TRUE(frames.at("timing").at("steady").get<bool>());  // it stopped on agreeing frames
    }
    const json timed = run("timed", "warmup_frames = 1\nwarmup_ms = 250\n");
    const double frameMs = timed.at("frame_ms").at("median").get<double>();
    // At least as many frames as fit in 250 ms at the slowest timed frame's pace, and the run took that long.
    EXPECT_GE(timed.at("warmup_frames").get<double>(), std::min(250.0 / timed.at("frame_ms").at("max").get<double>(), 20.0)) << frameMs;
    EXPECT_GE(timed.at("run_seconds").get<double>(), 0.25);
}

TEST(ExperimentRunner, ConfigChoosesTheMetricsAndTheImagesKept) {
    TempDir dir;
    // heuristic_rt writes debug images; three frames of a path give two temporal errors.
    const std::string body = R"(
warmup_frames = 0
repeats = 1
[[scenes]]
scene = "whitted-classic"
resolutions = [[48, 27]]
[[scenes.views]]
path = "orbit"
frames = [0, 20]
stride = 10
[[techniques]]
name = "heuristic_rt"
)";
    auto run = [&](const std::string& name, const std::string& choice) {
        const fs::path out = dir.path() / name;
        RunnerOptions o = test::quietRunnerOptions(out, dir.path() / "cache");
        EXPECT_TRUE(runExperiment(loadExperimentConfig(writeConfig(dir, "[experiment]\n" + choice + body, name + ".toml")), o).complete);
        return test::readResults(out);
    };
    const auto everything = run("all", "");
    const auto ssimTemporal = run("ssim-temporal", "metrics = [\"ssim\", \"temporal\"]\nkeep = []\n");
    const auto flipMaps = run("flip-maps", "metrics = [\"flip\"]\nkeep = [\"error_maps\"]\n");
    ASSERT_EQ(everything.size(), 3u);
    ASSERT_EQ(ssimTemporal.size(), 3u);
    ASSERT_EQ(flipMaps.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) {
        SCOPED_TRACE(i);
        // By default: every metric, error maps and debug images.
        const json& all = everything[i];
        for (const char* m : {"ssim", "flip", "flip_hdr", "rmse", "psnr_db"}) EXPECT_TRUE(all.at("metrics").at("whole").contains(m)) << m;
        EXPECT_TRUE(fs::exists(dir.path() / "all" / all.at("images").at("maps").get<std::string>() / "flip.png"));
        ASSERT_TRUE(all.at("images").contains("debug"));
        for (const auto& [name, file] : all.at("images").at("debug").items()) EXPECT_TRUE(fs::exists(dir.path() / "all" / file.get<std::string>())) << name;
        EXPECT_EQ(all.contains("temporal_error"), i > 0);

        // SSIM and the temporal error alone, no optional images: the same values as with everything.
        const json& st = ssimTemporal[i];
        EXPECT_EQ(st.at("metrics").at("whole").at("ssim"), all.at("metrics").at("whole").at("ssim"));
        EXPECT_EQ(st.at("metrics").at("masked").at("ssim"), all.at("metrics").at("masked").at("ssim"));
        for (const char* m : {"flip", "rmse", "psnr_db"}) EXPECT_FALSE(st.at("metrics").at("whole").contains(m)) << m;
        EXPECT_TRUE(st.at("images").at("maps").is_null());
        EXPECT_FALSE(st.at("images").contains("debug"));
        if (i > 0) {
            EXPECT_EQ(st.at("temporal_error"), all.at("temporal_error"));
        }

        // FLIP with its map only; no temporal error.
        const json& fm = flipMaps[i];
        EXPECT_EQ(fm.at("metrics").at("whole").at("flip"), all.at("metrics").at("whole").at("flip"));
        EXPECT_FALSE(fm.at("metrics").at("whole").contains("ssim"));
        const fs::path maps = dir.path() / "flip-maps" / fm.at("images").at("maps").get<std::string>();
        EXPECT_TRUE(fs::exists(maps / "flip.png"));
        EXPECT_FALSE(fs::exists(maps / "ssim.png"));
        EXPECT_FALSE(fs::exists(maps / "diff.png"));
        EXPECT_FALSE(fm.contains("temporal_error"));
    }
    // A report of a result set without FLIP still draws its figures.
    const fs::path report = dir.path() / "report";
    const test::CliResult r = test::runHybridlab({"report", (dir.path() / "ssim-temporal").string(), "--out", report.string()});
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    EXPECT_GT(test::expectReportLinksResolve(report), 3u * 3);
    EXPECT_GE(test::expectFiguresHaveContent(report), 2u * 4);  // speed-accuracy, stages, path, where methods fail
    // Its summary row: SSIM, then a dash for each metric the config left out (FLIP (LDR), HDR-FLIP),
    // on the whole image and on the reflective pixels.
    const std::string markdown = test::readTextFile(report / "report.md");
    const std::size_t at = markdown.find("| heuristic_rt | 3 | ");
    ASSERT_NE(at, std::string::npos) << markdown;
    const std::string line = markdown.substr(at, markdown.find('\n', at) - at);
    EXPECT_EQ(line.substr(line.size() - 10), " | - | - |") << line;
    EXPECT_CONTAINS(line.substr(0, line.size() - 10), " | - | - | ");
}

TEST(ExperimentConfigs, EveryShippedConfigIsValid) {
    // quick.toml needs no assets; stability.toml and paper.toml need the paper scenes' models.
    const fs::path configs = test::sourceDir() / "experiments" / "configs";
    const ExperimentConfig quick = loadExperimentConfig(configs / "quick.toml");
    EXPECT_GT(planRuns(quick).size(), 10u);
    // stability.toml: every registered technique at its defaults and at least two other
    // settings, along a camera path of every scene (the failure scenes and sponza-spheres, the
    // baseline), all at one size so that the baseline compares (320x180: the 45-minute budget, see
    // the file's header), each path from its first frame to its last.
    const ExperimentConfig stability = loadExperimentConfig(configs / "stability.toml");
    for (const auto& info : registeredTechniques()) {
        int entries = 0, defaults = 0;
        for (const auto& t : stability.techniques) {
            if (t.name != info.name) continue;
            entries += static_cast<int>(t.parameterSets.size());
            for (const auto& set : t.parameterSets) defaults += set.empty();
        }
        EXPECT_GE(entries, 3) << info.name;
        EXPECT_EQ(defaults, 1) << info.name;
    }
    EXPECT_GE(stability.scenes.size(), 12u);
    EXPECT_TRUE(std::any_of(stability.scenes.begin(), stability.scenes.end(), [](const SceneSpec& s) { return s.name == "sponza-spheres"; }));
    for (const auto& s : stability.scenes) {
        for (const auto& v : s.views) {
            EXPECT_FALSE(v.cameraPath.empty()) << s.name;
            EXPECT_EQ(v.firstFrame, 0) << s.name;
            EXPECT_EQ((v.lastFrame - v.firstFrame) % v.stride, 0) << s.name << ": the path's last frame is left out";
        }
    }
    for (const auto& r : planRuns(stability)) {
        EXPECT_EQ(std::make_pair(r.width, r.height), std::make_pair(320, 180));
        ASSERT_GE(r.frame, 0) << r.id;
    }
    const ExperimentConfig paper = loadExperimentConfig(configs / "paper.toml");
    for (const auto& r : planRuns(paper)) EXPECT_EQ(std::make_pair(r.width, r.height), std::make_pair(1280, 720));
    // And every other config shipped beside them (the paper reproductions) loads and plans runs.
    for (const auto& entry : fs::directory_iterator(configs)) {
        if (entry.path().extension() != ".toml") continue;
        SCOPED_TRACE(entry.path().filename().string());
        EXPECT_FALSE(planRuns(loadExperimentConfig(entry.path())).empty());
    }
}

// `run --realtime`: the rounds timed at real-time priority and the records saying so; refused
// before anything is written where the process may not take it.
TEST(ExperimentRunner, RealTimeTimingIsRecordedOrRefusedBeforeAnythingIsWritten) {
    TempDir dir;
    const ExperimentConfig config = loadExperimentConfig(writeConfig(dir, std::string("[experiment]\n") + kOneTinyRun));
    RunnerOptions normal = test::quietRunnerOptions(dir.path() / "normal", dir.path() / "cache");
    ASSERT_TRUE(runExperiment(config, normal).complete);
    for (const json& r : test::readResults(normal.outDir)) EXPECT_EQ(r.at("timing").at("priority"), "normal");

    RunnerOptions ahead = test::quietRunnerOptions(dir.path() / "realtime", dir.path() / "cache");
    ahead.realTime = true;
    if (realTimePriorityUnavailable()) {
        EXPECT_THROW(runExperiment(config, ahead), InputError);
    } else {
        ASSERT_TRUE(runExperiment(config, ahead).complete);
        const auto records = test::readResults(ahead.outDir);
        ASSERT_EQ(records.size(), 1u);
        for (const json& r : records) EXPECT_EQ(r.at("timing").at("priority"), "realtime");
        EXPECT_EQ(sched_getscheduler(0), SCHED_OTHER);  // back to normal once the rounds are done
    }
    // Without the privilege: "--realtime: ..." naming what would allow it, and no folder written.
    const fs::path refusedOut = dir.path() / "refused";
    const int status = test::inChildWithoutRealTimePrivilege(0, [&] {
        RunnerOptions o = test::quietRunnerOptions(refusedOut, dir.path() / "cache");
        o.realTime = true;
        try {
            runExperiment(config, o);
            return 1;
        } catch (const InputError& e) {
            const std::string m = e.what();
            return m.rfind("--realtime: this process may not run at real-time priority", 0) == 0 && m.find("CAP_SYS_NICE") != std::string::npos
                       ? 0
                       : 2;
        }
    });
    if (status != test::kChildCannotDrop) {
        EXPECT_EQ(status, 0);
    }
    EXPECT_FALSE(fs::exists(refusedOut));
}

TEST(ExperimentRunner, BadConfigsAreRejectedBeforeAnythingIsWrittenWithOrWithoutDryRun) {
    TempDir dir;
    const std::string scene = "[[scenes]]\nscene = \"whitted-classic\"\nresolutions = [[32, 18]]\n";
    const std::string technique = "[[techniques]]\nname = \"whitted\"\n";
    struct Case {
        std::string name, text, message;
    };
    const std::vector<Case> cases = {
        {"syntax", "[experiment\n", "TOML syntax error"},
        {"unknown-key", "[experiment]\nrepeat = 3\n" + scene + technique, "experiment.repeat: unknown key"},
        {"unknown-technique", scene + "[[techniques]]\nname = \"raytrace-everything\"\n", "unknown technique 'raytrace-everything'"},
        {"unknown-parameter", scene + "[[techniques]]\nname = \"whitted\"\nparams = { depth = 3 }\n", "unknown parameter 'depth'"},
        {"parameter-range", scene + "[[techniques]]\nname = \"whitted\"\nparams = { max_depth = [1, 99] }\n", "an integer in [0, 64], got 99"},
        {"sweep-and-sets", scene + "[[techniques]]\nname = \"whitted\"\nparams = { max_depth = 1 }\nparam_sets = [ { max_depth = 2 } ]\n",
         "not both"},
        {"duplicate-label", scene + technique + technique, "two techniques are labelled 'whitted'"},
        {"unknown-scene", "[[scenes]]\nscene = \"atlantis\"\nresolutions = [[32, 18]]\n" + technique, "unknown scene 'atlantis'"},
        {"unknown-path", scene + "[[scenes.views]]\npath = \"spiral\"\n" + technique, "has no camera path 'spiral' (paths: orbit)"},
        {"frames-out-of-range", scene + "[[scenes.views]]\npath = \"orbit\"\nframes = [0, 500]\n" + technique, "path 'orbit' has 61 frames"},
        {"tiny-resolution", "[[scenes]]\nscene = \"whitted-classic\"\nresolutions = [[8, 8]]\n" + technique, "resolutions: expected an integer in [11, 16384], got 8"},
        {"no-techniques", scene, "an experiment needs at least one technique"},
        {"no-scenes", technique, "an experiment needs at least one scene"},
        {"unknown-metric", "[experiment]\nmetrics = [\"ssim\", \"lpips\"]\n" + scene + technique,
         "experiment.metrics: 'lpips' is not one of: ssim, flip, flip_hdr, rmse, psnr, temporal"},
        {"no-metrics", "[experiment]\nmetrics = []\n" + scene + technique, "experiment.metrics: an empty list measures nothing"},
        {"warmup-ms-range", "[experiment]\nwarmup_ms = -5\n" + scene + technique, "experiment.warmup_ms: expected a number in [0, 600000], got -5"},
        {"metrics-not-names", "[experiment]\nmetrics = \"ssim\"\n" + scene + technique, "experiment.metrics: expected an array of strings"},
        {"unknown-keep", "[experiment]\nkeep = [\"thumbnails\"]\n" + scene + technique,
         "experiment.keep: 'thumbnails' is not one of: error_maps, debug_images"},
        {"maps-without-metric", "[experiment]\nmetrics = [\"temporal\"]\nkeep = [\"error_maps\"]\n" + scene + technique,
         "experiment.keep: error_maps needs ssim, flip, flip_hdr, rmse or psnr in metrics"},
        // The tie band [1 - t, 1 / (1 - t)] has no meaning from t = 1 on.
        {"precision-range", "[experiment]\nprecision = 1\n" + scene + technique, "experiment.precision: expected a number in [0, 0.5], got 1"},
        {"warmup-past-its-most", "[experiment]\nwarmup_frames = 5\nmax_warmup_frames = 0\n" + scene + technique,
         "experiment.max_warmup_frames: expected at least warmup_frames (5)"},
        {"no-parameter-sets", scene + "[[techniques]]\nname = \"whitted\"\nparam_sets = []\n", "techniques[0].param_sets: an empty list of sets renders nothing"},
    };
    std::vector<test::CliRun> runs;
    for (const auto& c : cases) {
        fs::path config = writeConfig(dir, c.text, c.name + ".toml");
        runs.push_back({{"run", config.string(), "--out", (dir.path() / ("out-" + c.name)).string(), "--quiet"}, {}});
        runs.push_back({{"run", config.string(), "--out", (dir.path() / ("out-" + c.name)).string(), "--dry-run"}, {}});
    }
    auto both = test::runHybridlabAll(runs);
    std::vector<test::CliResult> outcomes;
    for (std::size_t i = 0; i < cases.size(); ++i) {
        SCOPED_TRACE(cases[i].name);
        // --dry-run checks the config as `run` does: the same message and exit status.
        const test::CliResult& dry = both[2 * i + 1];
        EXPECT_EQ(dry.exitStatus, 2) << dry.err;
        EXPECT_EQ(dry.err, both[2 * i].err);
        EXPECT_EQ(dry.out, "");
        outcomes.push_back(both[2 * i]);
    }
    for (std::size_t i = 0; i < cases.size(); ++i) {
        SCOPED_TRACE(cases[i].name);
        EXPECT_EQ(outcomes[i].exitStatus, 2) << outcomes[i].err;
        EXPECT_NE(outcomes[i].err.find(cases[i].message), std::string::npos) << outcomes[i].err;
        EXPECT_NE(outcomes[i].err.find(cases[i].name + ".toml:"), std::string::npos) << outcomes[i].err;  // file and line
        EXPECT_FALSE(fs::exists(dir.path() / ("out-" + cases[i].name)));
    }
}

}  // namespace
}  // namespace hybridlab
