#include "experiments/runner/experiment_runner.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <map>
#include <iterator>
#include <memory>
#include <optional>
#include <set>
#include <tuple>

#include <random>
#include <nlohmann/json.hpp>

#include "common/core/atomic_file.h"
#include "common/core/directory_lock.h"
#include "common/core/input_error.h"
#include "common/core/input_file.h"
#include "common/core/io_error.h"
#include "common/image/image_io.h"
#include "common/image/non_finite_pixels.h"
#include "common/scene/scene_file.h"
#include "common/scene/view.h"
#include "common/core/content_hash.h"
#include "common/core/other_load.h"
#include "common/core/realtime_priority.h"
#include "common/core/process_cpu_clock.h"
#include "common/core/progress.h"
#include "common/core/wall_clock.h"
#include "experiments/runner/device_record.h"
#include "experiments/runner/gpu_clocks.h"
#include "experiments/runner/interleaved_timing.h"
#include "experiments/runner/timing_statistics.h"
#include "experiments/runner/reference_cache.h"
#include "experiments/runner/resolution_scale.h"
#include "experiments/runner/results_store.h"
#include "experiments/runner/run_record.h"
#include "experiments/runner/shard_partition.h"
#include "metrics/metrics.h"
#include "metrics/parallel_tasks.h"
#include "metrics/report_files.h"
#include "techniques/technique.h"

namespace hybridlab {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// 1 where the camera ray's first hit is a reflective or refractive material: the region of the
// masked metrics ("on the reflective/refractive pixels").
Image reflectiveRefractiveMask(const RayScene& rays, const Camera& camera, int width, int height) {
    Image mask(width, height, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            SurfaceHit hit;
            if (rays.intersect(camera.rayThroughNdc(pixelCenterNdc(x, y, width, height), aspect), 0.0f,
                               std::numeric_limits<float>::infinity(), hit) &&
                (hit.material->isReflective() || hit.material->isRefractive())) {
                mask.at(x, y) = glm::vec4(1.0f);
            }
        }
    }
    return mask;
}

// How `--shard i/n` splits the runs (shard_partition.h); shard folders of another partition do
// not resume or merge with these. Folders that predate the field split by index modulo n (one
// shard holds every run however they split).
constexpr const char* kPartition = "estimated-cost";
std::string partitionOf(const json& meta) {
    const json& shard = meta.at("shard");
    return shard.value("count", 1) <= 1 ? kPartition : shard.value("partition", "index-modulo");
}

json experimentJson(const ExperimentConfig& config, std::size_t runsTotal, const RunnerOptions& o, std::size_t runsInShard, double estimatedCost) {
    return {{"name", config.name},
            {"config_hash", config.hash},
            {"runs_total", runsTotal},
            {"shard", {{"index", o.shardIndex}, {"count", o.shardCount}, {"partition", kPartition}, {"runs", runsInShard}, {"estimated_cost", estimatedCost}}},
            {"metrics", metricNames(config)},
            {"metric_table", metricTableJson()},
            {"program", programVersionHash()},
            {"resolution_scale", config.resolutionScale},
            {"device", deviceRecord()}};
}

// "a, b, c and 4 more" of at most three names.
std::string someOf(const std::vector<std::string>& names) {
    std::string out;
    for (std::size_t i = 0; i < names.size() && i < 3; ++i) out += (i ? ", " : "") + names[i];
    if (names.size() > 3) out += " and " + std::to_string(names.size() - 3) + " more";
    return out;
}

// Why --resume cannot continue a result set made with another config: the hashes, which runs the
// folder holds that the config no longer makes and which the config makes anew (by run id, which
// names the scene, view, size, technique label and parameters), and what to do.
std::string configChangedMessage(const ExperimentConfig& config, const fs::path& outDir, const json& meta, std::size_t runsTotal) {
    std::set<std::string> planned, recorded;
    for (const auto& r : planRuns(config)) planned.insert(r.id);
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(ResultsStore(outDir).runsDir(), ec))
        if (e.path().extension() == ".json") recorded.insert(e.path().stem().string());
    std::vector<std::string> gone, added;
    std::set_difference(recorded.begin(), recorded.end(), planned.begin(), planned.end(), std::back_inserter(gone));
    std::set_difference(planned.begin(), planned.end(), recorded.begin(), recorded.end(), std::back_inserter(added));
    std::string s = outDir.string() + ": holds experiment '" + meta.at("name").get<std::string>() + "' made with another config (hash " +
                    meta.at("config_hash").get<std::string>().substr(0, 12) + " there, " + config.hash.substr(0, 12) + " in " +
                    config.file.string() + "; its runs: " + meta.value("runs_total", json(0)).dump() + " then, " +
                    std::to_string(runsTotal) + " now). ";
    if (gone.empty() && added.empty()) {
        s += "The recorded runs are the same, so only settings that are not in the run ids changed (repeats, metrics, reference, ...). ";
    } else {
        if (!gone.empty()) s += std::to_string(gone.size()) + " recorded run(s) are not in the config (" + someOf(gone) + "). ";
        if (!added.empty()) s += std::to_string(added.size()) + " run(s) of the config are not recorded (" + someOf(added) + "). ";
    }
    return s + "Its config is " + (outDir / "config.toml").string() +
           ". To keep those results, give this config another --out; to redo them with this config, remove the folder first";
}

// The devices a result set was measured on: experiment.json's "devices" where a merge or a
// resume mixed them, else its "device" (null in sets older than device records).
std::vector<json> recordedDevices(const json& meta) {
    if (meta.contains("devices")) return meta.at("devices").get<std::vector<json>>();
    return {meta.value("device", json())};
}

bool knownDevice(const std::vector<json>& devices, const json& d) {
    return std::any_of(devices.begin(), devices.end(), [&](const json& k) { return sameDevice(k, d); });
}

// A result set measured on several devices, once this runner adds runs measured here: each run
// keeps its device. experiment.json lists them all as "devices" and keeps its first "device".
struct MixedDevices {
    json first;                 // the result set's "device" before it was mixed
    std::vector<json> devices;  // every device
    json here;                  // this machine's, for the runs rendered now
};

// Refuses to touch a folder that is not this experiment's (or empty/new), one measured on another
// device (unless allowed: then `mixed` is set), or one another runner is writing; returns the lock
// that keeps others out while this runner writes.
std::unique_ptr<DirectoryLock> prepareOutputFolder(const ExperimentConfig& config, const RunnerOptions& o, std::size_t runsTotal,
                                                   std::size_t runsInShard, double estimatedCost, RunnerSummary& summary,
                                                   std::optional<MixedDevices>& mixed) {
    const fs::path meta = o.outDir / "experiment.json";
    // The folder is looked at under its lock: a runner that started a moment earlier may be
    // setting it up, and the one who loses the race is told who holds it. A folder that is plainly
    // not an experiment's (a file, or files and no lock) is refused without writing into it.
    const auto notExperimentFolder = [&] { return InputError(o.outDir.string() + ": exists and is not an experiment folder; choose another --out"); };
    // Files other than a lock and the temporaries of the runners that try to take it.
    const auto holdsOtherFiles = [&] {
        return std::any_of(fs::directory_iterator(o.outDir), fs::directory_iterator(), [](const fs::directory_entry& e) {
            const std::string name = e.path().filename().string();
            return name != DirectoryLock::kFileName && name.rfind(".tmp-", 0) != 0;
        });
    };
    // In this order: a runner setting the folder up takes the lock, then makes files, then writes
    // experiment.json, then releases the lock; so other files seen first mean the lock or
    // experiment.json is there when looked for after them.
    if (fs::exists(o.outDir) &&
        (!fs::is_directory(o.outDir) || (holdsOtherFiles() && !fs::exists(o.outDir / DirectoryLock::kFileName) && !fs::exists(meta))))
        throw notExperimentFolder();
    createDirectories(o.outDir);
    auto lock = std::make_unique<DirectoryLock>(o.outDir);
    try {
        if (fs::exists(meta)) {
            json m = readSetJson(meta);
            if (m.at("config_hash") != config.hash) throw InputError(configChangedMessage(config, o.outDir, m, runsTotal));
            if (const double recorded = m.value("resolution_scale", 1.0); recorded != config.resolutionScale) {
                throw InputError(o.outDir.string() + ": was rendered at " + formatScale(recorded) + " of the configured size (--scale " +
                                 formatScale(recorded) + "), not at " + formatScale(config.resolutionScale) + " (--scale " +
                                 formatScale(config.resolutionScale) + "); resume it with --scale " + formatScale(recorded) +
                                 ", or choose another --out");
            }
            if (m.at("shard").at("index") != o.shardIndex || m.at("shard").at("count") != o.shardCount || partitionOf(m) != kPartition) {
                throw InputError(o.outDir.string() + ": holds shard " + m.at("shard").at("index").dump() + "/" + m.at("shard").at("count").dump() +
                                 " of this experiment (runs split by " + partitionOf(m) + "), not " + std::to_string(o.shardIndex) + "/" +
                                 std::to_string(o.shardCount) + " (split by " + kPartition + "); choose another --out");
            }
            if (!o.resume) {
                throw InputError(o.outDir.string() + ": already holds results of this experiment; pass --resume to continue it, or choose another --out");
            }
            const json here = deviceRecord();
            std::vector<json> devices = recordedDevices(m);
            if (!knownDevice(devices, here)) {
                if (!o.allowMixedDevices) {
                    std::string recorded;
                    for (const json& d : devices) recorded += "\n  " + (o.outDir / "experiment.json").string() + ": " + deviceSummary(d);
                    throw InputError(o.outDir.string() + ": was measured on another device than this one:" + recorded + "\n  here: " +
                                     deviceSummary(here) + "\ntimes from two devices do not compare; pass --allow-mixed-devices to resume it "
                                     "anyway (each run then keeps its device), or choose another --out");
                }
                devices.push_back(here);
            }
            if (devices.size() > 1) mixed = MixedDevices{m.value("device", json()), devices, here};
        } else if (holdsOtherFiles()) {
            throw notExperimentFolder();
        }
    } catch (const json::exception& e) {
        throw notExperimentJson(meta, e);
    }
    const ResultsStore store(o.outDir);
    // A resumed set's records are read (and checked) before anything changes: one that is bad
    // input stops the runner here, with results.json/csv still there, not after the remaining runs.
    if (o.resume && fs::exists(meta)) (void)store.loadRecords();
    store.createLayout();
    // Records are about to be added: results.json/csv are written again when the runner stops.
    store.removeResults();
    // What runs killed mid-write left (their ".tmp-PID-*" files); only a resumed folder has any.
    if (o.resume) summary.staleTemporariesRemoved = removeStaleTemporaries(o.outDir);
    json m = experimentJson(config, runsTotal, o, runsInShard, estimatedCost);
    if (mixed) {
        // The runs recorded before the set was mixed were measured on its one device.
        for (RunRecord& r : store.loadRecords()) {
            if (r.device) continue;
            r.device = mixed->first;
            store.writeRecord(r);
        }
        m["device"] = mixed->first;
        m["devices"] = mixed->devices;
    }
    writeFileAtomically(meta, m.dump(1) + "\n");
    std::ifstream in(config.file, std::ios::binary);
    writeFileAtomically(o.outDir / "config.toml", std::string(std::istreambuf_iterator<char>(in), {}));
    return lock;
}

void writeReferenceCopy(const ResultsStore& store, const CachedReference& ref, bool withMask) {
    // Each file on its own: a runner killed between the EXR and the PNG leaves the EXR alone.
    for (const char* ext : {".exr", ".png"}) {
        const fs::path copy = store.referencesDir() / (ref.key + ext);
        if (!fs::exists(copy)) writeImageAtomically(copy, ref.image);
    }
    const fs::path mask = store.referencesDir() / (ref.key + ".mask.png");
    if (withMask && !fs::exists(mask)) writeImageAtomically(mask, ref.mask);
}

// The scene being rendered, its shared state, and the techniques prepared for it.
struct ActiveScene {
    std::size_t index = static_cast<std::size_t>(-1);
    std::unique_ptr<Scene> scene;
    std::unique_ptr<SceneContext> context;
    std::map<std::string, std::unique_ptr<Technique>> techniques;
    SceneStats stats;  // the scene's size, for tables that list it (Sabino 2012 Table 3)

    void load(const ExperimentConfig& config, std::size_t i) {
        if (i == index) return;
        techniques.clear();
        context.reset();
        scene = std::make_unique<Scene>(loadSceneFile(config.scenes[i].file));
        context = std::make_unique<SceneContext>(*scene);
        stats = scene->stats();
        index = i;
    }

    Technique& technique(const std::string& key, const std::string& name, const ParameterList& params) {
        auto& t = techniques[key];
        if (!t) {
            t = createTechnique(name, params);
            t->prepare(*context);
        }
        return *t;
    }
};

// The reference of one run: from the cache, or rendered now (by `active`'s whitted) and cached.
CachedReference referenceFor(const ExperimentConfig& config, const ReferenceCache& cache, ActiveScene& active, const RunSpec& run,
                             const View& view, const FrameRequest& request, RunnerSummary& summary) {
    const std::string key = ReferenceCache::key(*active.scene, view, run.width, run.height, config.referenceParameters);
    if (std::optional<CachedReference> cached = cache.find(key)) {
        if (summary.referenceKeys.insert(key).second) ++summary.referenceCacheHits;
        return std::move(*cached);
    }
    Technique& whitted = active.technique("\x01reference", "whitted", config.referenceParameters);
    FrameResult r = whitted.render(*active.context, request);
    CachedReference ref{key, std::move(r.image), reflectiveRefractiveMask(active.context->rayScene(view.time), view.camera, run.width, run.height),
                        r.totalMilliseconds(), false};
    cache.store(ref);
    summary.referenceKeys.insert(key);
    ++summary.referencesRendered;
    return ref;
}

// A run's image scored against its reference. Its pixels holding a NaN or an infinity are counted
// (`nonFinite`, for the record) and scored as black in both images, so that the metrics stay
// numbers (non_finite_pixels.h).
MetricReport scoreImage(const Image& image, const Image& reference, const MetricOptions& options, const PixelMask* mask,
                        std::size_t& nonFinite) {
    nonFinite = findNonFinite(image).count;
    if (nonFinite == 0) return computeMetrics(image, reference, options, mask);
    Image finiteImage = image, finiteReference = reference;
    blackOutNonFinite(finiteImage, finiteReference);
    return computeMetrics(finiteImage, finiteReference, options, mask);
}

// One setting of a group as the protocol times it (interleaved_timing.h): each frame's clocks, its
// stage times by round, and its last frame, which is scored (renders are deterministic, so every
// timed frame's image is the same).
struct TimedSetting {
    Technique* technique = nullptr;
    FrameResult last;
    std::map<std::string, std::vector<double>> stageTimes;

    FrameClocks render(SceneContext& context, const FrameRequest& request) {
        const double cpuStart = processCpuMilliseconds();
        last = technique->render(context, request);
        FrameClocks c;
        c.cpuMs = processCpuMilliseconds() - cpuStart;
        c.wallMs = last.totalMilliseconds();
        // The device's timestamps, where the frame's device work recorded them (gpu_<pass>_ms).
        for (const auto& [name, value] : last.counters) {
            if (name.rfind("gpu_", 0) == 0 && name.size() > 7 && name.compare(name.size() - 3, 3, "_ms") == 0)
                c.deviceMs = c.deviceMs.value_or(0.0) + value;
        }
        return c;
    }
};

// The runs of one group: same scene, view, frame and size, timed together (experiments/README.md
// "Timing"); consecutive in the plan's order.
bool sameGroup(const RunSpec& a, const RunSpec& b) {
    return a.scene == b.scene && a.cameraPath == b.cameraPath && a.frame == b.frame && a.width == b.width && a.height == b.height;
}

std::string groupName(const ExperimentConfig& config, const RunSpec& run) {
    return config.scenes[run.scene].label + "|" + (run.cameraPath.empty() ? "camera" : run.cameraPath) + "|" + std::to_string(run.frame) +
           "|" + std::to_string(run.width) + "x" + std::to_string(run.height);
}

// The run whose speed-ups are read as "over rt_only": the group's default rt_only (no parameters).
const RunSpec* rtOnlyOf(const ExperimentConfig& config, const std::vector<const RunSpec*>& group) {
    for (const RunSpec* r : group)
        if (config.techniques[r->technique].name == "rt_only" && r->parameters.empty()) return r;
    return nullptr;
}

// The results record of one run (run_record.h): what ran, its times, counters and scores, and the
// paths of its images beside the reference's.
RunRecord runRecord(const RunSpec& run, const SceneSpec& sceneSpec, const SceneStats& sceneStats, const View& view,
                    const TechniqueSpec& techSpec, const TimedSetting& timed, const MetricReport& report, const ReportSources& sources,
                    const CachedReference& ref, bool masked, const std::string& image, std::optional<std::string> maps) {
    RunRecord r;
    r.index = run.index;
    r.id = run.id;
    r.scene = sceneSpec.label;
    r.sceneStats = sceneStats;
    r.view = run.cameraPath.empty() ? "camera" : run.cameraPath;
    r.frame = run.frame;
    r.time = view.time;
    r.width = run.width;
    r.height = run.height;
    r.technique = techSpec.name;
    r.label = techSpec.label;
    r.parameters = run.parameters;
    r.parametersText = run.parametersText;
    r.sequence = run.sequenceKey;
    for (const auto& [name, times] : timed.stageTimes) r.stages[name] = spreadOf(times);
    r.counters = timed.last.counters;
    r.metrics = reportJson(report, sources);
    const std::string reference = "references/" + ref.key;
    r.reference = {ref.key, reference + ".exr", reference + ".png",
                   masked ? std::optional<std::string>(reference + ".mask.png") : std::nullopt, ref.frameMilliseconds, ref.cacheHit};
    r.images = {image + ".exr", image + ".png", std::move(maps), {}};
    return r;
}

// A run's timing fields (run_record.h's RunTiming), its frame time's interval and its speed-ups
// over the reference and rt_only, paired over the group's rounds.
void addTiming(RunRecord& record, const ExperimentConfig& config, const std::string& group, const std::string& timingId, const GroupTiming& timing, const SettingTiming& st,
               const std::vector<double>& referenceRounds, const std::optional<std::vector<double>>& rtOnlyRounds,
               const std::optional<nlohmann::json>& gpuClocks, std::optional<double> otherLoad) {
    const std::vector<double> wall = wallTimes(st);
    record.frameMilliseconds = intervalSpreadOf(wall);
    record.warmupFrames = st.warmupFrames;
    RunTiming t;
    t.group = group;
    t.timingId = timingId;
    t.rounds = timing.rounds;
    t.frameRounds = wall;
    t.referenceRounds = referenceRounds;
    t.cpuRounds = cpuTimes(st);
    t.cpu = intervalSpreadOf(t.cpuRounds);
    if (const auto device = deviceTimes(st)) {
        t.deviceRounds = *device;
        t.device = intervalSpreadOf(*device);
    }
    t.precision = config.timing.precision;
    t.precisionReached = timing.precisionReached;
    t.budgetClock = timing.budgetClock == BudgetClock::CpuPerCore ? "cpu_per_core" : "wall";
    t.warmupMs = st.warmupMs;
    t.steady = st.steady;
    t.gpuClocks = gpuClocks;
    t.otherLoad = otherLoad;
    record.timing = std::move(t);
    const auto speedupOver = [&](const std::vector<double>& other) {
        const MedianInterval m = pairedRatio(other, wall);
        return m.hasInterval ? RatioInterval{m.median, m.low, m.high} : RatioInterval{m.median, std::nullopt, std::nullopt};
    };
    if (config.timeReference) {
        record.reference.frameMilliseconds = spreadOf(referenceRounds).median;
        record.speedup["reference"] = speedupOver(referenceRounds);
    }
    if (rtOnlyRounds) record.speedup["rt_only"] = speedupOver(*rtOnlyRounds);
}

// A name for one call's rounds, unique across processes and machines (shards, resumed runs): 64
// random bits.
std::string newTimingId() {
    std::random_device device;
    const std::uint64_t bits = (static_cast<std::uint64_t>(device()) << 32) ^ device();
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(bits));
    return text;
}

// A group's rounds (interleaved_timing.h) and what was measured around them.
struct TimedGroup {
    std::string timingId;                      // the rounds' name: they pair only with each other
    GroupTiming timing;
    std::optional<double> otherLoad;           // other processes' share of the cores meanwhile
    std::optional<nlohmann::json> gpuClocks;   // at the start and end, on an NVIDIA GPU
};

TimedGroup timeGroup(const std::vector<TimedRender>& renders, const TimingProtocol& protocol, bool realTime) {
    const std::optional<GpuClockSample> clocksBefore = sampleGpuClocks();
    const OtherLoadMeter otherLoad;
    TimedGroup g;
    g.timingId = newTimingId();
    {
        std::optional<RealTimePriority> aheadOfOtherProcesses;
        if (realTime) aheadOfOtherProcesses.emplace();
        g.timing = timeInterleaved(renders, protocol);
    }  // scoring and files at the normal priority
    g.otherLoad = otherLoad.fraction();
    const std::optional<GpuClockSample> clocksAfter = sampleGpuClocks();
    if (clocksBefore && clocksAfter) g.gpuClocks = gpuClocksJson(*clocksBefore, *clocksAfter);
    return g;
}

// Times a group's pending runs and the reference in interleaved rounds (with the group's default
// rt_only, recorded or not, for the speed-ups over it), then scores and records each run. Returns
// the runs recorded.
std::size_t renderGroup(const ExperimentConfig& config, const RunnerOptions& o, const ResultsStore& store, const ReferenceCache& cache,
                        ActiveScene& active, const std::vector<const RunSpec*>& group, const std::vector<const RunSpec*>& pending,
                        const TimingProtocol& protocol, const std::optional<MixedDevices>& mixed, Progress& progress, std::size_t done,
                        RunnerSummary& summary) {
    const auto groupStart = WallClock::now();
    const RunSpec& head = *pending.front();
    const std::string name = groupName(config, head);
    progress.start(done, name + ": timing " + std::to_string(pending.size()) + " run(s) and the reference in rounds", pending.size());
    active.load(config, head.scene);
    const View view = resolveView(*active.scene, head.cameraPath, head.frame >= 0 ? std::optional<int>(head.frame) : std::nullopt, std::nullopt);
    const FrameRequest request{view.camera, view.time, head.width, head.height};
    const CachedReference ref = referenceFor(config, cache, active, head, view, request, summary);

    // The settings timed together: the pending runs, the reference, and rt_only where it is not pending.
    std::vector<const RunSpec*> timedRuns = pending;
    const RunSpec* rtOnly = rtOnlyOf(config, group);
    if (rtOnly && std::find(pending.begin(), pending.end(), rtOnly) == pending.end()) timedRuns.push_back(rtOnly);
    std::vector<TimedSetting> settings(timedRuns.size() + (config.timeReference ? 1 : 0));
    for (std::size_t i = 0; i < timedRuns.size(); ++i) {
        const RunSpec& run = *timedRuns[i];
        settings[i].technique = &active.technique(std::to_string(run.technique) + "|" + run.parametersText, config.techniques[run.technique].name,
                                                  run.parameters);
    }
    const std::size_t referenceIndex = timedRuns.size();
    if (config.timeReference) settings[referenceIndex].technique = &active.technique("\x01reference", "whitted", config.referenceParameters);
    std::vector<TimedRender> renders;
    for (TimedSetting& s : settings) {
        renders.push_back([&s, &active, &request] {
            FrameClocks c = s.render(*active.context, request);
            for (const auto& st : s.last.stages) s.stageTimes[st.name].push_back(st.milliseconds);
            return c;
        });
    }
    const TimedGroup timed = timeGroup(renders, protocol, o.realTime);
    const GroupTiming& timing = timed.timing;
    // Only the rounds' stage times: the warm-up's are not the setting's steady state.
    for (TimedSetting& s : settings) {
        for (auto& [stage, times] : s.stageTimes)
            times.erase(times.begin(), times.end() - std::min<std::ptrdiff_t>(timing.rounds, static_cast<std::ptrdiff_t>(times.size())));
    }
    const std::vector<double> referenceRounds = config.timeReference ? wallTimes(timing.settings[referenceIndex]) : std::vector<double>{};
    const double timingSeconds = millisecondsSince(groupStart) / 1000.0;

    const PixelMask mask = PixelMask::fromImage(ref.mask);
    writeReferenceCopy(store, ref, mask.count() > 0);
    for (std::size_t i = 0; i < pending.size(); ++i) {
        const auto runStart = WallClock::now();
        const RunSpec* run = pending[i];
        const SettingTiming& st = timing.settings[i];
        const FrameResult& result = settings[i].last;
        MetricOptions scoring;
        scoring.selection = config.metrics;
        std::size_t nonFinite = 0;
        const MetricReport report = scoreImage(result.image, ref.image, scoring, mask.count() > 0 ? &mask : nullptr, nonFinite);
        const std::string image = "images/" + run->id;
        const ReportSources sources{image + ".exr", "references/" + ref.key + ".exr",
                                    mask.count() > 0 ? std::optional<std::string>("reflective and refractive pixels") : std::nullopt};
        // The run's files side by side: each image's encoding is serial, and on a GPU machine
        // they take longer than the frames.
        std::vector<std::function<void()>> writes = {[&] { writeImageAtomically(o.outDir / (image + ".exr"), result.image); },
                                                     [&] { writeImageAtomically(o.outDir / (image + ".png"), result.image); }};
        std::optional<std::string> maps;
        if (config.keepErrorMaps) {
            writes.push_back([&] { writeReportFiles(store.mapsDir() / run->id, report, sources); });
            maps = "maps/" + run->id;
        }
        std::map<std::string, std::string> debugImages;
        if (config.keepDebugImages) {
            for (const auto& [debugName, dbg] : result.debugImages) {
                const std::string p = image + "." + debugName + ".png";
                debugImages[debugName] = p;
                writes.push_back([&o, p, &dbg = dbg] { writeImageAtomically(o.outDir / p, dbg); });
            }
        }
        runInParallel(writes);

        RunRecord record = runRecord(*run, config.scenes[run->scene], active.stats, view, config.techniques[run->technique], settings[i], report,
                                     sources, ref, mask.count() > 0, image, maps);
        record.counters["nonfinite_pixels"] = static_cast<double>(nonFinite);
        const std::optional<std::vector<double>> rtOnlyRounds =
            rtOnly ? std::optional(wallTimes(timing.settings[static_cast<std::size_t>(std::find(timedRuns.begin(), timedRuns.end(), rtOnly) -
                                                                                      timedRuns.begin())]))
                   : std::nullopt;
        addTiming(record, config, name, timed.timingId, timing, st, referenceRounds, rtOnlyRounds, timed.gpuClocks, timed.otherLoad);
        record.timing->priority = o.realTime ? "realtime" : "normal";
        // The run's time: its share of the group's (scene, reference, warm-up, rounds), then its
        // scoring and files: what `merge` sums per shard beside the shard's estimated cost.
        record.runSeconds = timingSeconds / static_cast<double>(pending.size()) + millisecondsSince(runStart) / 1000.0;
        if (mixed) record.device = mixed->here;
        record.images.debug = std::move(debugImages);
        store.recordRun(record);
        ++summary.runsRendered;
    }
    return pending.size();
}

void checkShard(const RunnerOptions& o) {
    if (o.shardCount < 1 || o.shardIndex < 0 || o.shardIndex >= o.shardCount) {
        throw InputError("--shard " + std::to_string(o.shardIndex) + "/" + std::to_string(o.shardCount) + ": expected i/n with 0 <= i < n");
    }
}

// The options this process can carry out, checked before anything is written.
void checkOptions(const RunnerOptions& o) {
    checkShard(o);
    if (o.realTime) {
        if (const auto reason = realTimePriorityUnavailable()) throw InputError("--realtime: " + *reason);
    }
}

}  // namespace

namespace {

// Renders, times, scores and records `mine` into the prepared folder o.outDir.
void renderRuns(const ExperimentConfig& config, const RunnerOptions& o, const std::vector<const RunSpec*>& mine,
                const std::optional<MixedDevices>& mixed, RunnerSummary& summary) {
    const ResultsStore store(o.outDir);
    const ReferenceCache cache(o.cacheDir);
    summary.runsPlanned = mine.size();
    Progress progress(mine.size(), o.quiet);
    ActiveScene active;
    std::size_t done = 0;
    // Each scene and size's budget, shared by its groups (interleaved_timing.h).
    std::map<std::tuple<std::size_t, int, int>, int> groupsOfScene;
    // The budget's clock (interleaved_timing.h): CPU time per core where the frames run on the CPU.
    const bool onCpu = rendersOnCpu();
    for (std::size_t k = 0; k < mine.size(); ++k)
        if (k == 0 || !sameGroup(*mine[k - 1], *mine[k])) ++groupsOfScene[{mine[k]->scene, mine[k]->width, mine[k]->height}];
    for (std::size_t first = 0; first < mine.size();) {
        std::size_t last = first + 1;
        while (last < mine.size() && sameGroup(*mine[first], *mine[last])) ++last;
        const std::vector<const RunSpec*> group(mine.begin() + static_cast<std::ptrdiff_t>(first), mine.begin() + static_cast<std::ptrdiff_t>(last));
        first = last;
        std::vector<const RunSpec*> pending;
        for (const RunSpec* run : group) {
            if (o.resume && store.hasRecord(run->id)) {
                ++summary.runsSkipped;
                ++done;
            } else if (o.maxRuns < 0 || static_cast<long>(summary.runsRendered + pending.size()) < o.maxRuns) {
                pending.push_back(run);
            }
        }
        if (pending.empty()) continue;
        TimingProtocol protocol = config.timing;
        protocol.groupBudgetMs = protocol.sceneBudgetMs / groupsOfScene.at({group.front()->scene, group.front()->width, group.front()->height});
        protocol.budgetClock = onCpu ? BudgetClock::CpuPerCore : BudgetClock::Wall;
        protocol.cores = usableCores();
        protocol.settingsCompared = static_cast<int>(group.size());
        done += renderGroup(config, o, store, cache, active, group, pending, protocol, mixed, progress, done, summary);
        if (o.maxRuns >= 0 && static_cast<long>(summary.runsRendered) >= o.maxRuns) break;
    }
    progress.finish();

    summary.complete = true;
    for (const RunSpec* run : mine) summary.complete &= store.hasRecord(run->id);
    // Once, now that the records are final (results_store.h).
    store.writeResults(store.finalRecords(readSetJson(o.outDir / "experiment.json")));
}

}  // namespace

RunnerSummary runExperiment(const ExperimentConfig& config, const RunnerOptions& o) {
    checkOptions(o);
    const std::vector<RunSpec> all = planRuns(config);
    const ShardPartition partition = partitionRuns(config, all, o.shardCount);
    const std::vector<const RunSpec*> mine = partition.runsOf(all, o.shardIndex);
    RunnerSummary summary;
    std::optional<MixedDevices> mixed;
    // Bad input found once rendering has begun (a texture that does not decode: the config's check
    // reads scenes without decoding them) leaves no folder behind where this runner made it and
    // recorded nothing in it.
    std::error_code error;
    const bool existed = fs::exists(o.outDir, error);
    const bool madeHere = !existed || (fs::is_directory(o.outDir, error) && fs::is_empty(o.outDir, error));
    auto lock = prepareOutputFolder(config, o, all.size(), mine.size(), partition.estimatedCost.at(o.shardIndex), summary, mixed);
    try {
        renderRuns(config, o, mine, mixed, summary);
    } catch (const InputError&) {
        // A folder made here holds records only where this runner recorded some.
        if (madeHere && summary.runsRendered == 0) {
            lock.reset();
            if (existed) {
                for (const fs::directory_entry& e : fs::directory_iterator(o.outDir, error)) fs::remove_all(e.path(), error);
            } else {
                fs::remove_all(o.outDir, error);
            }
        }
        throw;
    }
    return summary;
}

ExperimentPlan planExperiment(const ExperimentConfig& config, const RunnerOptions& o) {
    checkOptions(o);
    ExperimentPlan plan;
    plan.runs = planRuns(config);
    const ShardPartition partition = partitionRuns(config, plan.runs, o.shardCount);
    plan.estimatedCost = partition.estimatedCost.at(o.shardIndex);
    const ReferenceCache cache(o.cacheDir);
    std::set<std::string> keys;
    std::unique_ptr<Scene> scene;
    std::size_t loaded = static_cast<std::size_t>(-1);
    for (const RunSpec* mine : partition.runsOf(plan.runs, o.shardIndex)) {
        const RunSpec& run = *mine;
        if (run.scene != loaded) {
            // With textures: the reference key hashes every file the scene was built from.
            scene = std::make_unique<Scene>(loadSceneFile(config.scenes[run.scene].file));
            loaded = run.scene;
        }
        const View view = resolveView(*scene, run.cameraPath, run.frame >= 0 ? std::optional<int>(run.frame) : std::nullopt, std::nullopt);
        const std::string key = ReferenceCache::key(*scene, view, run.width, run.height, config.referenceParameters);
        const bool cached = cache.contains(key);
        plan.mine.push_back({&run, cached});
        if (keys.insert(key).second) {
            ++plan.references;
            plan.referencesCached += cached;
        }
    }
    return plan;
}

namespace {

// A shard folder's experiment.json, or InputError naming it: every field merge reads is there
// and of its type (older shards lack the optional ones).
json readShardMeta(const fs::path& dir) {
    const fs::path file = dir / "experiment.json";
    if (inputPathKind(file) == InputPathKind::Missing) throw InputError(dir.string() + ": not an experiment folder (no experiment.json)");
    const json m = readSetJson(file);
    struct Field {
        const char* name;
        bool (json::*is)() const noexcept;
        const char* type;
        bool required;
    };
    static const Field kFields[] = {
        {"config_hash", &json::is_string, "a string", true},      {"runs_total", &json::is_number_unsigned, "an integer >= 0", true},
        {"shard", &json::is_object, "an object", true},           {"shard.index", &json::is_number_integer, "an integer", true},
        {"shard.count", &json::is_number_integer, "an integer", true}, {"shard.partition", &json::is_string, "a string", false},
        {"shard.runs", &json::is_number_integer, "an integer", false}, {"shard.estimated_cost", &json::is_number, "a number", false},
        {"name", &json::is_string, "a string", false},            {"resolution_scale", &json::is_number, "a number", false},
        {"metrics", &json::is_array, "an array", false},
    };
    if (!m.is_object()) throw InputError(file.string() + ": not an experiment record (expected a JSON object, got " + m.dump() + ")");
    for (const Field& f : kFields) {
        std::string pointer = std::string("/") + f.name;
        std::replace(pointer.begin(), pointer.end(), '.', '/');
        const json::json_pointer at(pointer);
        if (!m.contains(at)) {
            if (f.required) throw InputError(file.string() + ": not an experiment record (no " + f.name + ")");
        } else if (!(m.at(at).*f.is)()) {
            throw InputError(file.string() + ": " + f.name + ": expected " + f.type + ", got " + m.at(at).dump());
        }
    }
    return m;
}

std::string shardName(const json& meta) {
    return std::to_string(meta.at("shard").at("index").get<long long>()) + "/" + std::to_string(meta.at("shard").at("count").get<long long>());
}

// The folders of a shard that merge copies whole.
constexpr const char* kCopiedFolders[] = {"images", "maps", "references"};

// A shard's files other than its records, checked before anything is written: its config, and
// the folders merge copies, each absent or a folder.
void checkShardFolder(const fs::path& dir) {
    requireInputFile(dir / "config.toml", "the config the shard was run with");
    for (const char* sub : kCopiedFolders) (void)inputFolderPresent(dir / sub, std::string("the shard's ") + sub);
}

// fs::copy of a folder's tree, skipping files already there; IoError naming both where it fails.
void copyTree(const fs::path& from, const fs::path& to) {
    std::error_code ec;
    fs::copy(from, to, fs::copy_options::recursive | fs::copy_options::skip_existing, ec);
    if (ec) throw IoError(from.string() + ": cannot be copied into " + to.string() + " (" + ec.message() + ")");
}

// Writes into `outDir` the merged result set of shards mergeShards has checked: their records (each
// with its shard's device where they were measured on several), images and references,
// experiment.json as one unsharded run's, results.json and results.csv.
void writeMergedSet(const std::vector<fs::path>& shardDirs, const std::vector<json>& metas, const std::vector<std::vector<RunRecord>>& records,
                    const fs::path& outDir) {
    const ResultsStore out(outDir);
    out.createLayout();
    for (const auto& d : shardDirs)
        for (const char* sub : kCopiedFolders)
            if (inputPathKind(d / sub) == InputPathKind::Directory) copyTree(d / sub, outDir / sub);
    writeFileAtomically(outDir / "config.toml", readInputFile(shardDirs.front() / "config.toml", "the config the shard was run with"));
    json meta = metas.front();
    meta["shard"] = {{"index", 0}, {"count", 1}, {"partition", kPartition}};
    // Mixed devices: each run keeps its shard's device, and experiment.json lists them all.
    bool mixed = false;
    for (const json& m : metas) mixed |= !sameDevice(m.value("device", json()), metas.front().value("device", json()));
    if (mixed) {
        json devices = json::array();
        for (const json& m : metas)
            if (std::none_of(devices.begin(), devices.end(), [&](const json& k) { return sameDevice(k, m.value("device", json())); }))
                devices.push_back(m.value("device", json()));
        meta["devices"] = devices;
    }
    for (std::size_t k = 0; k < records.size(); ++k) {
        for (RunRecord r : records[k]) {
            if (mixed) r.device = metas[k].value("device", json());
            out.writeRecord(r);
        }
    }
    out.writeResults(out.finalRecords(meta));
    writeFileAtomically(outDir / "experiment.json", meta.dump(1) + "\n");
}

}  // namespace

std::vector<MergedShard> mergeShards(const std::vector<fs::path>& shardDirs, const fs::path& outDir, bool allowMixedDevices) {
    if (shardDirs.empty()) throw InputError("merge: no shard folders given");
    // Everything checked before anything is written: the same experiment, split the same way, every
    // shard once, on one device (unless allowed), every run recorded once, every record and the
    // files it names whole.
    std::vector<json> metas;
    for (const auto& d : shardDirs) metas.push_back(readShardMeta(d));
    const json& first = metas.front();
    const fs::path& firstDir = shardDirs.front();
    const long long count = first.at("shard").at("count").get<long long>();
    if (count < 1 || count > 1000000) throw InputError((firstDir / "experiment.json").string() + ": shard count " + std::to_string(count) + " out of range");
    std::vector<int> given(static_cast<std::size_t>(count), -1);  // shard index -> position in shardDirs
    for (std::size_t k = 0; k < metas.size(); ++k) {
        const json& m = metas[k];
        const fs::path& d = shardDirs[k];
        if (m.at("config_hash") != first.at("config_hash") || m.at("shard").at("count") != first.at("shard").at("count") ||
            partitionOf(m) != partitionOf(first)) {
            throw InputError("merge: " + d.string() + " is shard " + shardName(m) + " of experiment '" + m.value("name", "?") + "' (config hash " +
                             m.at("config_hash").get<std::string>().substr(0, 12) + ", runs split by " + partitionOf(m) + "), not of " +
                             firstDir.string() + "'s experiment '" + first.value("name", "?") + "' (shard " + shardName(first) + ", config hash " +
                             first.at("config_hash").get<std::string>().substr(0, 12) + ", runs split by " + partitionOf(first) + ")");
        }
        const long long i = m.at("shard").at("index").get<long long>();
        if (i < 0 || i >= count) throw InputError("merge: " + d.string() + ": shard index " + std::to_string(i) + " outside 0.." + std::to_string(count - 1));
        if (given[i] >= 0) throw InputError("merge: " + d.string() + " and " + shardDirs[given[i]].string() + " are both shard " + shardName(m));
        given[i] = static_cast<int>(k);
        if (const double a = first.value("resolution_scale", 1.0), b = m.value("resolution_scale", 1.0); a != b) {
            throw InputError("merge: " + d.string() + " was rendered at " + formatScale(b) + " of the configured size (--scale " + formatScale(b) +
                             "), " + firstDir.string() + " at " + formatScale(a) + " (--scale " + formatScale(a) + ")");
        }
        if (!allowMixedDevices && !sameDevice(m.value("device", json()), first.value("device", json()))) {
            throw InputError("merge: " + d.string() + " was measured on another device than " + firstDir.string() + ":\n  " +
                             firstDir.string() + ": " + deviceSummary(first.value("device", json())) + "\n  " + d.string() + ": " +
                             deviceSummary(m.value("device", json())) + "\ntimes from two devices do not compare; pass --allow-mixed-devices to merge them "
                             "anyway (each run then keeps its device)");
        }
    }
    for (long long i = 0; i < count; ++i) {
        if (given[i] < 0) {
            throw InputError("merge: shard " + std::to_string(i) + "/" + std::to_string(count) + " of experiment '" + first.value("name", "?") +
                             "' is missing (run it with `hybridlab run CONFIG --shard " + std::to_string(i) + "/" + std::to_string(count) +
                             "`, then give its folder too)");
        }
    }
    std::vector<MergedShard> shards(metas.size());
    std::vector<std::vector<RunRecord>> records(metas.size());
    std::map<std::string, std::size_t> shardOfId;
    for (std::size_t k = 0; k < metas.size(); ++k) {
        MergedShard& s = shards[k];
        s.dir = shardDirs[k];
        s.index = metas[k].at("shard").at("index").get<int>();
        s.count = static_cast<int>(count);
        s.estimatedCost = metas[k].at("shard").value("estimated_cost", -1.0);
        records[k] = ResultsStore(s.dir).loadRecords();
        s.runs = records[k].size();
        for (const RunRecord& r : records[k]) {
            s.seconds += r.runSeconds.value_or(0.0);
            if (const auto [at, added] = shardOfId.emplace(r.id, k); !added) {
                throw InputError("merge: run '" + r.id + "' is recorded by two shards: " + (ResultsStore(shardDirs[at->second]).runsDir() / (r.id + ".json")).string() +
                                 " and " + (ResultsStore(s.dir).runsDir() / (r.id + ".json")).string());
            }
        }
        // A shard that says how many runs it has names itself when it is unfinished.
        const long long planned = metas[k].at("shard").value("runs", -1LL);
        if (planned >= 0 && static_cast<long long>(s.runs) < planned) {
            throw InputError("merge: " + s.dir.string() + " (shard " + shardName(metas[k]) + ") holds " + std::to_string(s.runs) + " of its " +
                             std::to_string(planned) + " runs (finish it with `hybridlab run CONFIG --resume --shard " + shardName(metas[k]) +
                             " --out " + s.dir.string() + "` first)");
        }
    }
    const std::size_t runsTotal = first.at("runs_total").get<std::size_t>();
    if (shardOfId.size() != runsTotal) {
        throw InputError("merge: the shards hold " + std::to_string(shardOfId.size()) + " of " + std::to_string(runsTotal) +
                         " runs (finish them with `hybridlab run --resume --shard i/n` first)");
    }
    if (const InputPathKind kind = inputPathKind(outDir); kind != InputPathKind::Missing) {
        std::error_code ec;
        if (kind != InputPathKind::Directory || !fs::is_empty(outDir, ec) || ec)
            throw InputError(outDir.string() + ": exists and is not empty; choose another --out");
    }
    for (std::size_t k = 0; k < metas.size(); ++k) {
        checkShardFolder(shardDirs[k]);
        for (const RunRecord& r : records[k]) checkRecordFiles(shardDirs[k], r);
    }

    // Built beside outDir and renamed into place: a failure to write leaves no partial set.
    writeFolderAtomically(outDir, [&](const fs::path& staging) { writeMergedSet(shardDirs, metas, records, staging); });
    std::sort(shards.begin(), shards.end(), [](const MergedShard& a, const MergedShard& b) { return a.index < b.index; });
    return shards;
}

}  // namespace hybridlab
