#include "experiments/runner/experiment_config.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "common/core/input_error.h"
#include "common/core/number_check.h"
#include "common/core/toml_reader.h"
#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "common/core/content_hash.h"
#include "techniques/technique.h"

namespace hybridlab {
namespace fs = std::filesystem;

namespace {

// A TOML value as a technique parameter value; arrays are handled by the caller (sweeps).
ParamValue toParamValue(const TomlTable& t, const std::string& key, const toml::node& n) {
    if (auto b = n.as_boolean()) return b->get();
    if (auto i = n.as_integer()) return static_cast<long long>(i->get());
    if (auto f = n.as_floating_point()) return f->get();
    if (auto s = n.as_string()) return s->get();
    t.fail(key, "expected a boolean, number or string");
}

// A technique's parameter values as a config gives them: typed (a string "3" is not an integer),
// each checked at its own position and quoted as written.
class ParameterChecker {
public:
    explicit ParameterChecker(const std::string& technique) : technique_(technique), info_(findTechnique(technique)) {}

    // One value of `key` (a sweep's list element, or the value itself) at `t`.
    ParamValue value(const TomlTable& t, const std::string& key, const toml::node& n) const {
        ParamValue v = toParamValue(t, key, n);
        try {
            resolveParameters(info_.parameters, {{key, v}}, owner(), ParameterSource::Typed, {t.written(n)});
        } catch (const InputError& e) {
            t.fail(key, e.what());
        }
        return v;
    }

    // A whole set, its defaults filled in: what a run renders with.
    std::map<std::string, ParamValue> resolved(const TomlTable& at, const ParameterList& set) const {
        try {
            return resolveParameters(info_.parameters, set, owner(), ParameterSource::Typed).values();
        } catch (const InputError& e) {
            at.failHere(e.what());
        }
    }

private:
    std::string owner() const { return "technique " + technique_; }
    std::string technique_;
    const TechniqueInfo& info_;
};

// The table's keys with their values (each checked by `checker`); a list of values makes a sweep:
// the Cartesian product, in key order.
std::vector<ParameterList> expandSweep(const TomlTable& t, const ParameterChecker& checker) {
    std::vector<ParameterList> sets(1);
    for (const auto& key : t.keys()) {
        const toml::node& n = t.node(key);
        std::vector<ParamValue> values;
        if (auto a = n.as_array()) {
            if (a->empty()) t.fail(key, "an empty list sweeps over nothing");
            for (const auto& e : *a) values.push_back(checker.value(t, key, e));
        } else {
            values.push_back(checker.value(t, key, n));
        }
        std::vector<ParameterList> next;
        for (const auto& s : sets) {
            for (const auto& v : values) {
                ParameterList p = s;
                p.emplace_back(key, v);
                next.push_back(std::move(p));
            }
        }
        sets = std::move(next);
    }
    return sets;
}

std::string parametersText(const ParameterList& set) {
    std::string text;
    for (const auto& [k, v] : set) text += (text.empty() ? "" : " ") + k + "=" + formatParamValue(v);
    return text.empty() ? "the defaults" : text;
}

// The `metrics` names, in the order results list them: the metric table's (metrics/metric_table.h)
// and the temporal error between path frames.
constexpr const char* kTemporal = "temporal";

std::vector<std::string> allMetricNames() {
    std::vector<std::string> names;
    for (const MetricDefinition& m : kMetricTable) names.push_back(m.key);
    names.push_back(kTemporal);
    return names;
}

const std::vector<std::string> kKeepNames = {"error_maps", "debug_images"};

bool contains(const std::vector<std::string>& list, const std::string& name) { return std::find(list.begin(), list.end(), name) != list.end(); }

// `metrics = [...]` and `keep = [...]` of [experiment].
void readMetricsAndKeep(const TomlTable& e, ExperimentConfig& c) {
    const std::vector<std::string> all = allMetricNames();
    const std::vector<std::string> metrics = e.choiceArray("metrics", all, all);
    if (metrics.empty()) e.fail("metrics", "an empty list measures nothing (metrics: " + commaSeparated(all) + ")");
    for (const MetricDefinition& m : kMetricTable) c.metrics.chosen(m.key) = contains(metrics, m.key);
    c.temporalError = contains(metrics, kTemporal);
    const std::vector<std::string> keep = e.choiceArray("keep", kKeepNames, kKeepNames);
    c.keepDebugImages = contains(keep, "debug_images");
    c.keepErrorMaps = contains(keep, "error_maps") && c.metrics.any();
    // Asked for explicitly, error maps without a metric that has one are a mistake; by default
    // they are simply not written.
    if (e.has("keep") && contains(keep, "error_maps") && !c.metrics.any())
        e.fail("keep", "error_maps needs ssim, flip, flip_hdr, rmse or psnr in metrics (each map is one of theirs)");
}

std::string safeName(const std::string& s) {
    std::string out;
    for (char c : s) out += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '.') ? c : '_';
    return out;
}

// The names a run's file names are made of (scene, camera path, technique label; RunSpec::id) are
// at most this long, so that the longest file a run writes stays within a file system's 255 bytes.
constexpr std::size_t kLongestNameInFiles = 64;

// `name`, read from `key`, as a part of run file names: refused, at `key`, when too long for one.
void checkNameInFiles(const TomlTable& t, const std::string& key, const std::string& what, const std::string& name) {
    if (name.empty() || name.size() > kLongestNameInFiles)
        t.fail(key, what + " '" + (name.size() > kLongestNameInFiles ? name.substr(0, 24) + "..." : name) + "' is " +
                        std::to_string(name.size()) + " characters long; run file names take 1 to " +
                        std::to_string(kLongestNameInFiles));
}

// A scene path (not a scenes/ name) relative to the config file's folder, as paths in a scene file
// are relative to the scene file's: the config means the same from any working folder.
std::string sceneFileAsWritten(const std::string& written, const fs::path& configFile) {
    const fs::path p(written);
    const bool isPath = written.find('/') != std::string::npos || p.extension() == ".toml";
    return isPath && p.is_relative() ? (configFile.parent_path() / p).string() : written;
}

// One [[scenes.views]] entry of the scene `sceneName`: a camera path and its frames, or the scene's camera.
ViewSpec readView(const TomlTable& v, const Scene& scene, const std::string& sceneName) {
    ViewSpec view;
    view.cameraPath = v.string("path", "");
    if (v.has("path")) checkNameInFiles(v, "path", "camera path", view.cameraPath);
    if (view.cameraPath.empty()) {
        if (v.has("frames") || v.has("stride")) v.failHere("frames and stride need a camera path ('path')");
    } else {
        const CameraPath* p = scene.findCameraPath(view.cameraPath);
        if (!p) {
            std::string known;
            for (const auto& cp : scene.cameraPaths) known += (known.empty() ? "" : ", ") + cp.name;
            v.fail("path", "scene " + sceneName + " has no camera path '" + view.cameraPath + "'" + (known.empty() ? "" : " (paths: " + known + ")"));
        }
        const int last = p->frameCount() - 1;
        view.stride = v.integer("stride", 1, 1, 1000000);
        if (v.has("frames")) {
            auto fr = v.node("frames").as_array();
            if (!fr || fr->size() != 2 || !fr->get(0)->is_integer() || !fr->get(1)->is_integer())
                v.fail("frames", "expected [first, last] frame numbers");
            const long long first = fr->get(0)->as_integer()->get(), lastAsked = fr->get(1)->as_integer()->get();
            if (!integerProblem(first, 0, last).empty() || !integerProblem(lastAsked, 0, last).empty() || first > lastAsked)
                v.fail("frames", "expected 0 <= first <= last <= " + std::to_string(last) + " (path '" + view.cameraPath + "' has " +
                                     std::to_string(last + 1) + " frames), got [" + std::to_string(first) + ", " +
                                     std::to_string(lastAsked) + "]");
            view.firstFrame = static_cast<int>(first);
            view.lastFrame = static_cast<int>(lastAsked);
            v.node("frames");  // (marked as read above)
        } else {
            view.firstFrame = 0;
            view.lastFrame = last;
        }
    }
    v.rejectUnknownKeys();
    return view;
}

// One [[scenes]] entry: the scene (resolved against the config file's folder), its resolutions and views.
SceneSpec readSceneSpec(const TomlTable& t, const fs::path& configFile) {
    SceneSpec s;
    s.name = t.requiredString("scene");
    try {
        s.file = findSceneFile(sceneFileAsWritten(s.name, configFile));
    } catch (const InputError& e) {
        t.fail("scene", e.what());
    }
    Scene scene;
    try {
        scene = loadSceneFile(s.file, {.loadTextures = false});
    } catch (const InputError& e) {
        t.fail("scene", e.what());
    }
    s.label = scene.name;
    checkNameInFiles(t, "scene", "the scene's name", s.label);
    const toml::node* res = t.has("resolutions") ? &t.node("resolutions") : nullptr;
    if (!res) t.fail("resolutions", "missing (expected a list of [width, height] pairs)");
    auto arr = res->as_array();
    if (!arr || arr->empty()) t.fail("resolutions", "expected a non-empty list of [width, height] pairs");
    for (const auto& r : *arr) {
        auto pair = r.as_array();
        if (!pair || pair->size() != 2 || !pair->get(0)->is_integer() || !pair->get(1)->is_integer())
            t.fail("resolutions", "expected [width, height] pairs of integers");
        // SSIM's 11 x 11 window needs at least that many pixels.
        const int w = t.integerValue("resolutions", *pair->get(0), 11, limits::kImageSide);
        const int h = t.integerValue("resolutions", *pair->get(1), 11, limits::kImageSide);
        s.resolutions.emplace_back(w, h);
    }
    for (const auto& v : t.tableArray("views")) s.views.push_back(readView(v, scene, s.name));
    if (s.views.empty()) s.views.push_back(ViewSpec{});
    t.rejectUnknownKeys();
    return s;
}

// The sets of one [[techniques]] entry so far, resolved (defaults filled in), each with where it
// was written: two that resolve alike would render every run twice.
class DistinctParameterSets {
public:
    void add(const TomlTable& at, const std::string& where, const ParameterChecker& checker, const ParameterList& set) {
        const auto [seen, added] = sets_.emplace(checker.resolved(at, set), where + " (" + parametersText(set) + ")");
        if (!added)
            at.failHere("the settings " + parametersText(set) + " are, with the defaults filled in, those of " + seen->second +
                        ": every run of them would be rendered twice");
    }

private:
    // Ordered, so that a sweep of a hundred thousand sets is checked in n log n, not n squared.
    std::map<std::map<std::string, ParamValue>, std::string> sets_;
};

// Every (scene file, size, camera path, frame) of the [[scenes]] entries so far, with the entry
// that lists it: one listed twice (the same scene in two entries, or a size or view repeated)
// would render every run of it twice.
class DistinctViews {
public:
    void add(const TomlTable& t, const SceneSpec& s) {
        std::error_code ec;
        const fs::path file = fs::weakly_canonical(s.file, ec);
        for (const auto& [w, h] : s.resolutions) {
            for (const auto& view : s.views) {
                const bool onPath = !view.cameraPath.empty();
                for (int f = onPath ? view.firstFrame : -1; f <= (onPath ? view.lastFrame : -1); f += onPath ? view.stride : 1) {
                    const std::string size = std::to_string(w) + "x" + std::to_string(h);
                    const std::string viewName = onPath ? "frame " + std::to_string(f) + " of path '" + view.cameraPath + "'" : "the scene's camera";
                    const auto [at, added] = seen_.emplace((ec ? s.file : file).string() + "|" + size + "|" + viewName, t.path());
                    if (!added)
                        t.failHere("scene " + s.name + " at " + size + ", " + viewName + ", is listed again (first in " + at->second +
                                   "): every run of it would be rendered twice");
                }
            }
        }
    }

private:
    std::map<std::string, std::string> seen_;
};

// One [[techniques]] entry: a registered technique, its label (unique among `labels`, which gains
// it) and its parameter sets (a sweep, a list, or the defaults), no two alike. Two entries may
// share a set: their labels make them two series (two sweeps through the default point).
TechniqueSpec readTechniqueSpec(const TomlTable& t, std::set<std::string>& labels) {
    TechniqueSpec s;
    s.name = t.requiredString("name");
    try {
        findTechnique(s.name);
    } catch (const InputError& e) {
        t.fail("name", e.what());
    }
    const ParameterChecker checker(s.name);
    s.label = t.string("label", s.name);
    checkNameInFiles(t, "label", "label", s.label);
    if (!labels.insert(s.label).second) t.fail("label", "two techniques are labelled '" + s.label + "' (give each entry its own label)");
    auto params = t.table("params");
    auto sets = t.tableArray("param_sets");
    if (params && !sets.empty()) t.failHere("give 'params' (a sweep) or 'param_sets' (a list of sets), not both");
    if (sets.empty() && t.has("param_sets"))
        t.fail("param_sets", "an empty list of sets renders nothing (leave it out for the technique's defaults)");
    DistinctParameterSets distinct;
    if (params) {
        s.parameterSets = expandSweep(*params, checker);
        for (const auto& set : s.parameterSets) distinct.add(*params, params->path(), checker, set);
        params->rejectUnknownKeys();
    } else if (!sets.empty()) {
        // Each set may sweep too (a list value), e.g. one set on both ray backends.
        for (const auto& st : sets) {
            for (auto& set : expandSweep(st, checker)) {
                distinct.add(st, st.path(), checker, set);
                s.parameterSets.push_back(std::move(set));
            }
            st.rejectUnknownKeys();
        }
    } else {
        s.parameterSets.emplace_back();
    }
    t.rejectUnknownKeys();
    return s;
}

// The [experiment] keys of the timing protocol (interleaved_timing.h).
void readTimingProtocol(const TomlTable& e, TimingProtocol& t) {
    t.warmupFrames = static_cast<int>(e.integer("warmup_frames", t.warmupFrames, 0, 1000));
    t.warmupMs = e.number("warmup_ms", t.warmupMs, {0.0, 600000.0});
    t.steadyFrames = static_cast<int>(e.integer("steady_frames", t.steadyFrames, 0, 100));
    t.steadyTolerance = e.number("steady_tolerance", t.steadyTolerance, {0.0, 10.0});
    t.maxWarmupFrames = static_cast<int>(e.integer("max_warmup_frames", t.maxWarmupFrames, 0, 10000));
    t.minRounds = static_cast<int>(e.integer("repeats", t.minRounds, 1, 1000));
    t.maxRounds = static_cast<int>(e.integer("max_rounds", t.maxRounds, 1, 100000));
    // The tie band is [1 - precision, 1 / (1 - precision)] (experiments/README.md "Timing"): past a
    // half it ties settings twice as fast.
    t.precision = e.number("precision", t.precision, {0.0, 0.5});
    t.sceneBudgetMs = 1000.0 * e.number("budget_s", t.sceneBudgetMs / 1000.0, {0.0, 86400.0});
    if (t.maxRounds < t.minRounds) e.fail("max_rounds", "expected at least repeats (" + std::to_string(t.minRounds) + ")");
    // Both given: the most frames in all cannot be fewer than the least (alone, warmup_frames wins).
    if (e.has("max_warmup_frames") && e.has("warmup_frames") && t.maxWarmupFrames < t.warmupFrames)
        e.fail("max_warmup_frames", "expected at least warmup_frames (" + std::to_string(t.warmupFrames) + ")");
}

}  // namespace

ExperimentConfig loadExperimentConfig(const fs::path& file) {
    TomlDocument doc(file);
    TomlTable root = doc.root();
    ExperimentConfig c;
    c.file = file;
    c.hash = ContentHash().addFile(file).hex();
    c.name = file.stem().string();

    if (auto e = root.table("experiment")) {
        c.name = e->string("name", c.name);
        // The result set's folder, results/<name>: one folder name, inside results/.
        const bool folderName = !c.name.empty() && c.name.size() <= 100 && c.name != "." && c.name != ".." &&
                                std::none_of(c.name.begin(), c.name.end(), [](char ch) { return ch == '/' || ch == '\\' || std::iscntrl(static_cast<unsigned char>(ch)); });
        if (!folderName)
            e->fail("name", "expected a folder name for results/<name> (1 to 100 characters, no '/', '\\' or control characters, "
                            "not '.' or '..'), got '" + c.name.substr(0, 100) + "'");
        c.description = e->string("description", "");
        readTimingProtocol(*e, c.timing);
        readMetricsAndKeep(*e, c);
        e->rejectUnknownKeys();
    }
    if (auto r = root.table("reference")) {
        if (auto p = r->table("params")) {
            const ParameterChecker checker("whitted");
            for (const auto& key : p->keys()) c.referenceParameters.emplace_back(key, checker.value(*p, key, p->node(key)));
            p->rejectUnknownKeys();
        }
        c.timeReference = r->boolean("timed", c.timeReference);
        r->rejectUnknownKeys();
    }

    auto scenes = root.tableArray("scenes");
    if (scenes.empty()) root.failHere("no [[scenes]]: an experiment needs at least one scene");
    DistinctViews views;
    for (const auto& t : scenes) {
        c.scenes.push_back(readSceneSpec(t, file));
        views.add(t, c.scenes.back());
    }

    auto techniques = root.tableArray("techniques");
    if (techniques.empty()) root.failHere("no [[techniques]]: an experiment needs at least one technique");
    std::set<std::string> labels;
    for (const auto& t : techniques) c.techniques.push_back(readTechniqueSpec(t, labels));
    root.rejectUnknownKeys();
    return c;
}

std::vector<std::string> metricNames(const ExperimentConfig& config) {
    std::vector<std::string> names;
    for (const MetricDefinition& m : kMetricTable)
        if (config.metrics.chosen(m.key)) names.push_back(m.key);
    if (config.temporalError) names.push_back(kTemporal);
    return names;
}

std::vector<RunSpec> planRuns(const ExperimentConfig& config) {
    std::vector<RunSpec> runs;
    for (std::size_t si = 0; si < config.scenes.size(); ++si) {
        const SceneSpec& scene = config.scenes[si];
        for (const auto& [w, h] : scene.resolutions) {
            for (const auto& view : scene.views) {
                const bool onPath = !view.cameraPath.empty();
                for (int f = onPath ? view.firstFrame : -1; f <= (onPath ? view.lastFrame : -1); f += onPath ? view.stride : 1) {
                    for (std::size_t ti = 0; ti < config.techniques.size(); ++ti) {
                        const TechniqueSpec& tech = config.techniques[ti];
                        for (const auto& set : tech.parameterSets) {
                            RunSpec r;
                            r.index = runs.size();
                            r.scene = si;
                            r.cameraPath = view.cameraPath;
                            r.frame = f;
                            r.width = w;
                            r.height = h;
                            r.technique = ti;
                            r.parameters = set;
                            std::ostringstream text;
                            for (const auto& [k, v] : set) text << (text.tellp() > 0 ? " " : "") << k << "=" << formatParamValue(v);
                            r.parametersText = text.str();
                            const std::string viewLabel = onPath ? view.cameraPath + "@" + std::to_string(f) : "camera";
                            const std::string res = std::to_string(w) + "x" + std::to_string(h);
                            r.sequenceKey = scene.label + "|" + view.cameraPath + "|" + res + "|" + tech.label + "|" + r.parametersText;
                            char index[16];
                            std::snprintf(index, sizeof index, "%05zu", r.index);
                            r.id = std::string(index) + "-" + safeName(scene.label) + "-" + safeName(viewLabel) + "-" + res +
                                   "-" + safeName(tech.label) + "-" + ContentHash().add(r.parametersText).hex().substr(0, 8);
                            runs.push_back(std::move(r));
                        }
                    }
                }
            }
        }
    }
    return runs;
}

}  // namespace hybridlab
