#include "experiments/runner/experiment_runner.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <iterator>
#include <memory>
#include <set>

#include <nlohmann/json.hpp>

#include "common/core/atomic_file.h"
#include "common/core/directory_lock.h"
#include "common/core/input_error.h"
#include "common/image/image_io.h"
#include "common/scene/scene_file.h"
#include "common/scene/view.h"
#include "common/core/content_hash.h"
#include "experiments/runner/parameter_json.h"
#include "experiments/runner/device_record.h"
#include "experiments/runner/progress.h"
#include "experiments/runner/reference_cache.h"
#include "experiments/runner/results_store.h"
#include "metrics/metrics.h"
#include "metrics/report_files.h"
#include "techniques/technique.h"

namespace hybridlab {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

struct Spread {
    double median = 0.0, min = 0.0, max = 0.0;
};

Spread spread(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return {n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]), v.front(), v.back()};
}

json toJson(const Spread& s) { return {{"median", s.median}, {"min", s.min}, {"max", s.max}}; }

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

json experimentJson(const ExperimentConfig& config, std::size_t runsTotal, int shardIndex, int shardCount) {
    return {{"name", config.name},
            {"config_hash", config.hash},
            {"runs_total", runsTotal},
            {"shard", {{"index", shardIndex}, {"count", shardCount}}},
            {"metrics", metricNames(config)},
            {"program", programVersionHash()},
            {"device", deviceRecord()}};
}

json readJson(const fs::path& p) {
    std::ifstream in(p);
    return json::parse(in);
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

// Refuses to touch a folder that is not this experiment's (or empty/new), or one another runner
// is writing; returns the lock that keeps others out while this runner writes.
std::unique_ptr<DirectoryLock> prepareOutputFolder(const ExperimentConfig& config, const RunnerOptions& o, std::size_t runsTotal,
                                                   RunnerSummary& summary) {
    const fs::path meta = o.outDir / "experiment.json";
    if (fs::exists(o.outDir)) {
        if (fs::exists(meta)) {
            json m = readJson(meta);
            if (m.at("config_hash") != config.hash) throw InputError(configChangedMessage(config, o.outDir, m, runsTotal));
            if (m.at("shard").at("index") != o.shardIndex || m.at("shard").at("count") != o.shardCount) {
                throw InputError(o.outDir.string() + ": holds shard " + m.at("shard").at("index").dump() + "/" + m.at("shard").at("count").dump() +
                                 " of this experiment, not " + std::to_string(o.shardIndex) + "/" + std::to_string(o.shardCount) +
                                 "; choose another --out");
            }
            if (!o.resume) {
                throw InputError(o.outDir.string() + ": already holds results of this experiment; pass --resume to continue it, or choose another --out");
            }
        } else if (!fs::is_directory(o.outDir) || !fs::is_empty(o.outDir)) {
            throw InputError(o.outDir.string() + ": exists and is not an experiment folder; choose another --out");
        }
    }
    ResultsStore(o.outDir).createLayout();
    auto lock = std::make_unique<DirectoryLock>(o.outDir);
    // What runs killed mid-write left (their ".tmp-PID-*" files); only a resumed folder has any.
    if (o.resume) summary.staleTemporariesRemoved = removeStaleTemporaries(o.outDir);
    writeFileAtomically(meta, experimentJson(config, runsTotal, o.shardIndex, o.shardCount).dump(1) + "\n");
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
    json stats;  // the scene's size, for tables that list it (Sabino 2012 Table 3)

    void load(const ExperimentConfig& config, std::size_t i) {
        if (i == index) return;
        techniques.clear();
        context.reset();
        scene = std::make_unique<Scene>(loadSceneFile(config.scenes[i].file));
        context = std::make_unique<SceneContext>(*scene);
        const SceneStats s = scene->stats();
        stats = {{"objects", s.objects}, {"vertices", s.vertices}, {"triangles", s.triangles},
                 {"lights", s.lights}, {"reflective", s.reflectiveObjects}, {"refractive", s.refractiveObjects}};
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
        ++summary.referenceCacheHits;
        return std::move(*cached);
    }
    Technique& whitted = active.technique("\x01reference", "whitted", config.referenceParameters);
    FrameResult r = whitted.render(*active.context, request);
    CachedReference ref{key, std::move(r.image), reflectiveRefractiveMask(active.context->rayScene(view.time), view.camera, run.width, run.height),
                        r.totalMilliseconds(), false};
    cache.store(ref);
    ++summary.referencesRendered;
    return ref;
}

// A technique's frame after the warm-up frames, with every timed repeat's stage and frame times.
struct TimedFrame {
    FrameResult result;  // the last repeat
    std::map<std::string, std::vector<double>> stageTimes;
    std::vector<double> frameTimes;
};

TimedFrame timeTechnique(const ExperimentConfig& config, Technique& technique, SceneContext& context, const FrameRequest& request) {
    for (int i = 0; i < config.warmupFrames; ++i) technique.render(context, request);
    TimedFrame timed;
    for (int i = 0; i < config.repeats; ++i) {
        timed.result = technique.render(context, request);
        for (const auto& s : timed.result.stages) timed.stageTimes[s.name].push_back(s.milliseconds);
        timed.frameTimes.push_back(timed.result.totalMilliseconds());
    }
    return timed;
}

// The results record of one run (experiments/README.md): what ran, its times, counters and scores,
// and the paths of its images beside the reference's.
json runRecord(const RunSpec& run, const SceneSpec& sceneSpec, const json& sceneStats, const View& view, const TechniqueSpec& techSpec,
               const TimedFrame& timed, const MetricReport& report, const ReportSources& sources, const CachedReference& ref, bool masked,
               const std::string& image, const json& maps) {
    const std::string& key = ref.key;
    json record;
    record["index"] = run.index;
    record["id"] = run.id;
    record["scene"] = sceneSpec.label;
    record["scene_stats"] = sceneStats;
    record["view"] = run.cameraPath.empty() ? "camera" : run.cameraPath;
    record["frame"] = run.frame;
    record["time"] = view.time;
    record["width"] = run.width;
    record["height"] = run.height;
    record["technique"] = techSpec.name;
    record["label"] = techSpec.label;
    record["parameters"] = json::object();
    for (const auto& [k, v] : run.parameters) record["parameters"][k] = parameterJson(v);
    record["parameters_text"] = run.parametersText;
    record["sequence"] = run.sequenceKey;
    record["frame_ms"] = toJson(spread(timed.frameTimes));
    record["stages"] = json::object();
    for (const auto& [name, times] : timed.stageTimes) record["stages"][name] = toJson(spread(times));
    record["counters"] = timed.result.counters;
    record["metrics"] = reportJson(report, sources);
    record["reference"] = {{"key", key}, {"exr", "references/" + key + ".exr"}, {"png", "references/" + key + ".png"},
                           {"frame_ms", ref.frameMilliseconds}, {"cache_hit", ref.cacheHit}};
    if (masked) record["reference"]["mask"] = "references/" + key + ".mask.png";
    record["images"] = {{"exr", image + ".exr"}, {"png", image + ".png"}, {"maps", maps}};
    return record;
}

}  // namespace

RunnerSummary runExperiment(const ExperimentConfig& config, const RunnerOptions& o) {
    if (o.shardCount < 1 || o.shardIndex < 0 || o.shardIndex >= o.shardCount) {
        throw InputError("--shard " + std::to_string(o.shardIndex) + "/" + std::to_string(o.shardCount) + ": expected i/n with 0 <= i < n");
    }
    const std::vector<RunSpec> all = planRuns(config);
    std::vector<const RunSpec*> mine;
    for (const auto& r : all)
        if (static_cast<int>(r.index % o.shardCount) == o.shardIndex) mine.push_back(&r);
    RunnerSummary summary;
    const auto lock = prepareOutputFolder(config, o, all.size(), summary);

    const ResultsStore store(o.outDir);
    const ReferenceCache cache(o.cacheDir);
    summary.runsPlanned = mine.size();
    Progress progress(mine.size(), o.quiet);
    ActiveScene active;
    std::size_t done = 0;
    for (const RunSpec* run : mine) {
        if (o.resume && store.hasRecord(run->id)) {
            ++summary.runsSkipped;
            ++done;
            continue;
        }
        if (o.maxRuns >= 0 && static_cast<long>(summary.runsRendered) >= o.maxRuns) break;
        const SceneSpec& sceneSpec = config.scenes[run->scene];
        const TechniqueSpec& techSpec = config.techniques[run->technique];
        progress.start(done, run->id);
        active.load(config, run->scene);
        const Scene& scene = *active.scene;
        const View view = resolveView(scene, run->cameraPath, run->frame >= 0 ? std::optional<int>(run->frame) : std::nullopt, std::nullopt);
        const FrameRequest request{view.camera, view.time, run->width, run->height};

        const CachedReference ref = referenceFor(config, cache, active, *run, view, request, summary);
        const std::string& key = ref.key;

        // The technique: warm-up frames, then timed repeats (medians, min and max per stage).
        Technique& technique = active.technique(std::to_string(run->technique) + "|" + run->parametersText, techSpec.name, run->parameters);
        const TimedFrame timed = timeTechnique(config, technique, *active.context, request);
        const FrameResult& result = timed.result;

        const PixelMask mask = PixelMask::fromImage(ref.mask);
        writeReferenceCopy(store, ref, mask.count() > 0);
        MetricOptions scoring;
        scoring.selection = config.metrics;
        const MetricReport report = computeMetrics(result.image, ref.image, scoring, mask.count() > 0 ? &mask : nullptr);
        const std::string image = "images/" + run->id;
        writeImageAtomically(o.outDir / (image + ".exr"), result.image);
        writeImageAtomically(o.outDir / (image + ".png"), result.image);
        const ReportSources sources{image + ".exr", "references/" + key + ".exr",
                                    mask.count() > 0 ? std::optional<std::string>("reflective and refractive pixels") : std::nullopt};
        json maps = nullptr;
        if (config.keepErrorMaps) {
            writeReportFiles(store.mapsDir() / run->id, report, sources);
            maps = "maps/" + run->id;
        }

        json record = runRecord(*run, sceneSpec, active.stats, view, techSpec, timed, report, sources, ref, mask.count() > 0, image, maps);
        if (config.keepDebugImages) {
            for (const auto& [name, dbg] : result.debugImages) {
                const std::string p = image + "." + name + ".png";
                writeImageAtomically(o.outDir / p, dbg);
                record["images"]["debug"][name] = p;
            }
        }
        store.writeRecord(record);
        store.writeResults(store.loadRecords());
        ++summary.runsRendered;
        ++done;
    }
    progress.finish();

    std::vector<json> records = store.loadRecords();
    summary.complete = true;
    for (const RunSpec* run : mine) summary.complete &= store.hasRecord(run->id);
    // Temporal errors need neighbouring frames, which another shard may hold: `merge` adds them.
    if (summary.complete && o.shardCount == 1 && config.temporalError) {
        addTemporalErrors(records, o.outDir);
        store.writeResults(records);
    }
    return summary;
}

ExperimentPlan planExperiment(const ExperimentConfig& config, const RunnerOptions& o) {
    if (o.shardCount < 1 || o.shardIndex < 0 || o.shardIndex >= o.shardCount) {
        throw InputError("--shard " + std::to_string(o.shardIndex) + "/" + std::to_string(o.shardCount) + ": expected i/n with 0 <= i < n");
    }
    ExperimentPlan plan;
    plan.runs = planRuns(config);
    const ReferenceCache cache(o.cacheDir);
    std::set<std::string> keys;
    std::unique_ptr<Scene> scene;
    std::size_t loaded = static_cast<std::size_t>(-1);
    for (const auto& run : plan.runs) {
        if (static_cast<int>(run.index % o.shardCount) != o.shardIndex) continue;
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

void mergeShards(const std::vector<fs::path>& shardDirs, const fs::path& outDir, bool allowMixedDevices) {
    if (shardDirs.empty()) throw InputError("merge: no shard folders given");
    json first;
    std::vector<bool> seen;
    std::vector<json> deviceByShard;
    for (const auto& d : shardDirs) {
        const fs::path meta = d / "experiment.json";
        if (!fs::exists(meta)) throw InputError(d.string() + ": not an experiment folder (no experiment.json)");
        json m = readJson(meta);
        if (first.is_null()) {
            first = m;
            seen.assign(m.at("shard").at("count").get<std::size_t>(), false);
        }
        if (m.at("config_hash") != first.at("config_hash") || m.at("shard").at("count") != first.at("shard").at("count")) {
            throw InputError(d.string() + ": a shard of another experiment than " + shardDirs.front().string());
        }
        const auto i = m.at("shard").at("index").get<std::size_t>();
        if (seen.at(i)) throw InputError(d.string() + ": shard " + std::to_string(i) + " given twice");
        seen[i] = true;
        deviceByShard.resize(seen.size());
        deviceByShard[i] = m.value("device", json());
        if (!allowMixedDevices && !sameDevice(deviceByShard[i], first.value("device", json()))) {
            throw InputError("merge: " + d.string() + " was measured on another device than " + shardDirs.front().string() + ":\n  " +
                             shardDirs.front().string() + ": " + deviceSummary(first.value("device", json())) + "\n  " + d.string() + ": " +
                             deviceSummary(deviceByShard[i]) + "\ntimes from two devices do not compare; pass --allow-mixed-devices to merge them "
                             "anyway (each run then keeps its device)");
        }
    }
    for (std::size_t i = 0; i < seen.size(); ++i)
        if (!seen[i]) throw InputError("merge: shard " + std::to_string(i) + "/" + std::to_string(seen.size()) + " is missing");
    if (fs::exists(outDir) && (!fs::is_directory(outDir) || !fs::is_empty(outDir))) {
        throw InputError(outDir.string() + ": exists and is not empty; choose another --out");
    }

    const ResultsStore out(outDir);
    out.createLayout();
    for (const auto& d : shardDirs) {
        for (const char* sub : {"runs", "images", "maps", "references"}) {
            if (fs::exists(d / sub))
                fs::copy(d / sub, outDir / sub, fs::copy_options::recursive | fs::copy_options::skip_existing);
        }
    }
    fs::copy_file(shardDirs.front() / "config.toml", outDir / "config.toml", fs::copy_options::overwrite_existing);
    json meta = first;
    meta["shard"] = {{"index", 0}, {"count", 1}};
    std::vector<json> records = out.loadRecords();
    if (records.size() != first.at("runs_total").get<std::size_t>()) {
        throw InputError("merge: the shards hold " + std::to_string(records.size()) + " of " + std::to_string(first.at("runs_total").get<std::size_t>()) +
                         " runs (finish them with `hybridlab run --resume --shard i/n` first)");
    }
    // Mixed devices: each run keeps its shard's device, and experiment.json lists them all.
    bool mixed = false;
    for (const json& d : deviceByShard) mixed |= !sameDevice(d, deviceByShard.front());
    if (mixed) {
        json devices = json::array();
        for (const json& d : deviceByShard)
            if (std::none_of(devices.begin(), devices.end(), [&](const json& k) { return sameDevice(k, d); })) devices.push_back(d);
        meta["devices"] = devices;
        for (json& r : records) {
            r["device"] = deviceByShard.at(r.at("index").get<std::size_t>() % deviceByShard.size());
            out.writeRecord(r);
        }
    }
    // Without "temporal" in the config's metrics (older result sets list none: they all had it).
    const json metrics = first.value("metrics", json::array({"temporal"}));
    if (std::find(metrics.begin(), metrics.end(), "temporal") != metrics.end()) addTemporalErrors(records, outDir);
    out.writeResults(records);
    writeFileAtomically(outDir / "experiment.json", meta.dump(1) + "\n");
}

}  // namespace hybridlab
