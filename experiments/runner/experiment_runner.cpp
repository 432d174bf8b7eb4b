#include "experiments/runner/experiment_runner.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <memory>

#include <nlohmann/json.hpp>

#include "common/core/atomic_file.h"
#include "common/core/input_error.h"
#include "common/image/image_io.h"
#include "common/scene/scene_file.h"
#include "common/scene/view.h"
#include "common/core/content_hash.h"
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

json toJson(const ParamValue& v) {
    if (auto b = std::get_if<bool>(&v)) return *b;
    if (auto i = std::get_if<long long>(&v)) return *i;
    if (auto d = std::get_if<double>(&v)) return *d;
    return std::get<std::string>(v);
}

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

// Refuses to touch a folder that is not this experiment's (or empty/new).
void prepareOutputFolder(const ExperimentConfig& config, const RunnerOptions& o, std::size_t runsTotal) {
    const fs::path meta = o.outDir / "experiment.json";
    if (fs::exists(o.outDir)) {
        if (fs::exists(meta)) {
            json m = readJson(meta);
            if (m.at("config_hash") != config.hash || m.at("shard").at("index") != o.shardIndex || m.at("shard").at("count") != o.shardCount) {
                throw InputError(o.outDir.string() + ": holds another experiment or shard (" + m.at("name").get<std::string>() +
                                 "); choose another --out");
            }
            if (!o.resume) {
                throw InputError(o.outDir.string() + ": already holds results of this experiment; pass --resume to continue it, or choose another --out");
            }
        } else if (!fs::is_directory(o.outDir) || !fs::is_empty(o.outDir)) {
            throw InputError(o.outDir.string() + ": exists and is not an experiment folder; choose another --out");
        }
    }
    ResultsStore(o.outDir).createLayout();
    writeFileAtomically(meta, experimentJson(config, runsTotal, o.shardIndex, o.shardCount).dump(1) + "\n");
    std::ifstream in(config.file, std::ios::binary);
    writeFileAtomically(o.outDir / "config.toml", std::string(std::istreambuf_iterator<char>(in), {}));
}

void writeReferenceCopy(const ResultsStore& store, const CachedReference& ref, bool withMask) {
    const fs::path exr = store.referencesDir() / (ref.key + ".exr");
    if (!fs::exists(exr)) {
        writeImageAtomically(exr, ref.image);
        writeImageAtomically(store.referencesDir() / (ref.key + ".png"), ref.image);
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

}  // namespace

RunnerSummary runExperiment(const ExperimentConfig& config, const RunnerOptions& o) {
    if (o.shardCount < 1 || o.shardIndex < 0 || o.shardIndex >= o.shardCount) {
        throw InputError("--shard " + std::to_string(o.shardIndex) + "/" + std::to_string(o.shardCount) + ": expected i/n with 0 <= i < n");
    }
    const std::vector<RunSpec> all = planRuns(config);
    std::vector<const RunSpec*> mine;
    for (const auto& r : all)
        if (static_cast<int>(r.index % o.shardCount) == o.shardIndex) mine.push_back(&r);
    prepareOutputFolder(config, o, all.size());

    const ResultsStore store(o.outDir);
    const ReferenceCache cache(o.cacheDir);
    RunnerSummary summary;
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

        // The reference: from the cache, or rendered now and cached.
        const std::string key = ReferenceCache::key(scene, view, run->width, run->height, config.referenceParameters);
        std::optional<CachedReference> ref = cache.find(key);
        if (ref) {
            ++summary.referenceCacheHits;
        } else {
            Technique& whitted = active.technique("\x01reference", "whitted", config.referenceParameters);
            FrameResult r = whitted.render(*active.context, request);
            ref = CachedReference{key, std::move(r.image),
                                  reflectiveRefractiveMask(active.context->rayScene(view.time), view.camera, run->width, run->height),
                                  r.totalMilliseconds(), false};
            cache.store(*ref);
            ++summary.referencesRendered;
        }

        // The technique: warm-up frames, then timed repeats (medians, min and max per stage).
        Technique& technique = active.technique(std::to_string(run->technique) + "|" + run->parametersText, techSpec.name, run->parameters);
        for (int i = 0; i < config.warmupFrames; ++i) technique.render(*active.context, request);
        std::map<std::string, std::vector<double>> stageTimes;
        std::vector<double> frameTimes;
        FrameResult result;
        for (int i = 0; i < config.repeats; ++i) {
            result = technique.render(*active.context, request);
            for (const auto& s : result.stages) stageTimes[s.name].push_back(s.milliseconds);
            frameTimes.push_back(result.totalMilliseconds());
        }

        const PixelMask mask = PixelMask::fromImage(ref->mask);
        writeReferenceCopy(store, *ref, mask.count() > 0);
        MetricOptions scoring;
        scoring.selection = config.metrics;
        const MetricReport report = computeMetrics(result.image, ref->image, scoring, mask.count() > 0 ? &mask : nullptr);
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

        json record;
        record["index"] = run->index;
        record["id"] = run->id;
        record["scene"] = sceneSpec.name;
        record["scene_stats"] = active.stats;
        record["view"] = run->cameraPath.empty() ? "camera" : run->cameraPath;
        record["frame"] = run->frame;
        record["time"] = view.time;
        record["width"] = run->width;
        record["height"] = run->height;
        record["technique"] = techSpec.name;
        record["label"] = techSpec.label;
        record["parameters"] = json::object();
        for (const auto& [k, v] : run->parameters) record["parameters"][k] = toJson(v);
        record["parameters_text"] = run->parametersText;
        record["sequence"] = run->sequenceKey;
        record["frame_ms"] = toJson(spread(frameTimes));
        record["stages"] = json::object();
        for (const auto& [name, times] : stageTimes) record["stages"][name] = toJson(spread(times));
        record["counters"] = result.counters;
        record["metrics"] = reportJson(report, sources);
        record["reference"] = {{"key", key}, {"exr", "references/" + key + ".exr"}, {"png", "references/" + key + ".png"},
                               {"frame_ms", ref->frameMilliseconds}, {"cache_hit", ref->cacheHit}};
        if (mask.count() > 0) record["reference"]["mask"] = "references/" + key + ".mask.png";
        record["images"] = {{"exr", image + ".exr"}, {"png", image + ".png"}, {"maps", maps}};
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
