#include "experiments/runner/run_record.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

#include "common/core/number_check.h"
#include "experiments/runner/parameter_json.h"
#include "experiments/runner/timing_statistics.h"

namespace hybridlab {
using nlohmann::json;

Spread spreadOf(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return {n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]), v.front(), v.back(), std::nullopt, std::nullopt};
}

Spread intervalSpreadOf(std::vector<double> values) {
    Spread s = spreadOf(values);
    if (const MedianInterval m = medianInterval(std::move(values)); m.hasInterval) {
        s.ciLow = m.low;
        s.ciHigh = m.high;
    }
    return s;
}

namespace {

json spreadJson(const Spread& s) {
    json j = {{"median", s.median}, {"min", s.min}, {"max", s.max}};
    if (s.ciLow) j["ci_low"] = *s.ciLow;
    if (s.ciHigh) j["ci_high"] = *s.ciHigh;
    return j;
}

json timingJson(const RunTiming& t) {
    json j = {{"group", t.group}, {"rounds", t.rounds}, {"frame_ms_rounds", t.frameRounds}, {"reference_ms_rounds", t.referenceRounds},
              {"cpu_ms", spreadJson(t.cpu)}, {"cpu_ms_rounds", t.cpuRounds}, {"precision", t.precision},
              {"precision_reached", t.precisionReached}, {"warmup_ms", t.warmupMs}, {"steady", t.steady}};
    if (t.device) {
        j["device_ms"] = spreadJson(*t.device);
        j["device_ms_rounds"] = t.deviceRounds;
    }
    if (t.timingId) j["timing_id"] = *t.timingId;
    if (t.budgetClock) j["budget_clock"] = *t.budgetClock;
    if (t.otherLoad) j["other_load"] = *t.otherLoad;
    if (t.priority) j["priority"] = *t.priority;
    if (t.gpuClocks) j["gpu_clocks"] = *t.gpuClocks;
    return j;
}

json sceneStatsJson(const SceneStats& s) {
    return {{"objects", s.objects}, {"vertices", s.vertices}, {"triangles", s.triangles},
            {"lights", s.lights}, {"reflective", s.reflectiveObjects}, {"refractive", s.refractiveObjects}};
}

json referenceJson(const ReferenceEntry& r) {
    json j = {{"key", r.key}, {"exr", r.exr}, {"png", r.png}, {"frame_ms", r.frameMilliseconds}, {"cache_hit", r.cacheHit}};
    if (r.mask) j["mask"] = *r.mask;
    return j;
}

json imagesJson(const RunImages& i) {
    json j = {{"exr", i.exr}, {"png", i.png}, {"maps", i.maps ? json(*i.maps) : json(nullptr)}};
    if (!i.debug.empty()) j["debug"] = i.debug;
    return j;
}

}  // namespace

json toJson(const RunRecord& r) {
    json j;
    j["schema_version"] = r.schemaVersion;
    j["index"] = r.index;
    j["id"] = r.id;
    j["scene"] = r.scene;
    j["scene_stats"] = sceneStatsJson(r.sceneStats);
    j["view"] = r.view;
    j["frame"] = r.frame;
    j["time"] = r.time;
    j["width"] = r.width;
    j["height"] = r.height;
    j["technique"] = r.technique;
    j["label"] = r.label;
    j["parameters"] = json::object();
    for (const auto& [k, v] : r.parameters) j["parameters"][k] = parameterJson(v);
    j["parameters_text"] = r.parametersText;
    j["sequence"] = r.sequence;
    j["frame_ms"] = spreadJson(r.frameMilliseconds);
    if (r.warmupFrames) j["warmup_frames"] = *r.warmupFrames;
    if (r.timing) j["timing"] = timingJson(*r.timing);
    if (!r.speedup.empty()) {
        j["speedup"] = json::object();
        for (const auto& [over, s] : r.speedup) {
            j["speedup"][over] = {{"ratio", s.ratio}};
            if (s.low) j["speedup"][over]["low"] = *s.low;
            if (s.high) j["speedup"][over]["high"] = *s.high;
        }
    }
    j["stages"] = json::object();
    for (const auto& [name, s] : r.stages) j["stages"][name] = spreadJson(s);
    j["counters"] = json::object();
    for (const auto& [name, value] : r.counters) j["counters"][name] = value;
    j["metrics"] = r.metrics;
    j["reference"] = referenceJson(r.reference);
    j["images"] = imagesJson(r.images);
    if (r.runSeconds) j["run_seconds"] = *r.runSeconds;
    if (r.device) j["device"] = *r.device;
    if (r.temporalError) j["temporal_error"] = *r.temporalError;
    if (r.temporalErrorMasked) j["temporal_error_masked"] = *r.temporalErrorMasked;
    if (r.temporalPreviousFrame) j["temporal_previous_frame"] = *r.temporalPreviousFrame;
    return j;
}

namespace {

// Reads the fields of one JSON object, each by name and type; `finish` refuses a field nobody read.
class FieldReader {
public:
    FieldReader(const json& object, std::string where) : object_(object), where_(std::move(where)) {
        if (!object_.is_object()) fail(where_, "expected an object");
    }

    const json& required(const std::string& key) {
        read_.insert(key);
        if (!object_.contains(key)) fail(where_, "missing '" + key + "'");
        return object_.at(key);
    }
    const json* optional(const std::string& key) {
        read_.insert(key);
        return object_.contains(key) ? &object_.at(key) : nullptr;
    }
    std::string path(const std::string& key) const { return where_ + "." + key; }

    // A field of type T; a number also within `range`.
    template <typename T>
    T get(const std::string& key, NumberRange range = {}) { return as<T>(required(key), path(key), range); }
    template <typename T>
    std::optional<T> getOptional(const std::string& key, NumberRange range = {}) {
        const json* v = optional(key);
        return v ? std::optional<T>(as<T>(*v, path(key), range)) : std::nullopt;
    }

    void finish() const {
        for (const auto& [key, value] : object_.items())
            if (!read_.count(key)) fail(where_, "unexpected '" + key + "'");
    }

    [[noreturn]] static void fail(const std::string& where, const std::string& what) {
        throw std::runtime_error("results record " + where + ": " + what);
    }

    // `v` as a T; a number also finite and within `range` (number_check.h's words).
    template <typename T>
    static T as(const json& v, const std::string& where, NumberRange range = {}) {
        if constexpr (std::is_same_v<T, bool>) {
            if (!v.is_boolean()) fail(where, "expected a boolean");
        } else if constexpr (std::is_same_v<T, std::string>) {
            if (!v.is_string()) fail(where, "expected a string");
        } else if constexpr (std::is_integral_v<T>) {
            if (std::is_unsigned_v<T> ? !v.is_number_unsigned() : !v.is_number_integer())
                fail(where, std::is_unsigned_v<T> ? "expected an integer >= 0" : "expected an integer");
            // Within T, and within the integers the report and the viewer read exactly (2^53): a
            // 2^63 in an int field is out of range, not the 0 it would wrap to.
            exactInteger(v, where, std::max({range.min, static_cast<double>(std::numeric_limits<T>::min()), -kExactInteger}),
                         std::min({range.max, static_cast<double>(std::numeric_limits<T>::max()), kExactInteger}));
        } else {
            if (!v.is_number()) fail(where, "expected a number");
            // As written, where JSON can write it (it writes infinities as null).
            const double d = v.get<double>();
            if (const std::string problem = numberProblem(d, range.min, range.max, std::isfinite(d) ? v.dump() : ""); !problem.empty())
                fail(where, problem);
        }
        return v.get<T>();
    }

    // JSON integer `v` within [min, max] (and the integers read exactly, 2^53): never wrapped.
    static long long exactInteger(const json& v, const std::string& where, double min = -kExactInteger, double max = kExactInteger) {
        const long long n = v.is_number_unsigned() ? static_cast<long long>(std::min(v.get<unsigned long long>(), kPastExact))
                                                   : v.get<long long>();
        if (const std::string problem = integerProblem(n, static_cast<long long>(min), static_cast<long long>(max), v.dump()); !problem.empty())
            fail(where, problem);
        return n;
    }

private:
    static constexpr double kExactInteger = 9007199254740992.0;  // 2^53
    static constexpr unsigned long long kPastExact = (1ULL << 53) + 1;
    const json& object_;
    std::string where_;
    std::set<std::string> read_;
};

// Times, their ratios, errors and counts: finite and not negative.
constexpr NumberRange kNotNegative{0.0, std::numeric_limits<double>::infinity()};

Spread spreadFrom(const json& j, const std::string& where) {
    FieldReader f(j, where);
    Spread s{f.get<double>("median", kNotNegative), f.get<double>("min", kNotNegative), f.get<double>("max", kNotNegative),
             f.getOptional<double>("ci_low", kNotNegative), f.getOptional<double>("ci_high", kNotNegative)};
    f.finish();
    return s;
}

std::vector<double> timesFrom(const json& j, const std::string& where) {
    if (!j.is_array()) FieldReader::fail(where, "expected an array of numbers");
    std::vector<double> v;
    for (std::size_t k = 0; k < j.size(); ++k) v.push_back(FieldReader::as<double>(j[k], where + "[" + std::to_string(k) + "]", kNotNegative));
    return v;
}

RunTiming timingFrom(const json& j, const std::string& where) {
    FieldReader f(j, where);
    RunTiming t;
    t.group = f.get<std::string>("group");
    t.timingId = f.getOptional<std::string>("timing_id");
    t.rounds = f.get<int>("rounds", kNotNegative);
    t.frameRounds = timesFrom(f.required("frame_ms_rounds"), f.path("frame_ms_rounds"));
    t.referenceRounds = timesFrom(f.required("reference_ms_rounds"), f.path("reference_ms_rounds"));
    t.cpu = spreadFrom(f.required("cpu_ms"), f.path("cpu_ms"));
    t.cpuRounds = timesFrom(f.required("cpu_ms_rounds"), f.path("cpu_ms_rounds"));
    if (const json* d = f.optional("device_ms")) {
        t.device = spreadFrom(*d, f.path("device_ms"));
        t.deviceRounds = timesFrom(f.required("device_ms_rounds"), f.path("device_ms_rounds"));
    }
    t.precision = f.get<double>("precision");
    t.precisionReached = f.get<bool>("precision_reached");
    t.budgetClock = f.getOptional<std::string>("budget_clock");
    t.otherLoad = f.getOptional<double>("other_load");
    t.priority = f.getOptional<std::string>("priority");
    t.warmupMs = f.get<double>("warmup_ms", kNotNegative);
    t.steady = f.get<bool>("steady");
    if (const json* g = f.optional("gpu_clocks")) t.gpuClocks = *g;
    f.finish();
    return t;
}

std::map<std::string, RatioInterval> speedupFrom(const json& j, const std::string& where) {
    FieldReader f(j, where);
    std::map<std::string, RatioInterval> out;
    for (const auto& [over, value] : j.items()) {
        FieldReader r(f.required(over), f.path(over));
        out[over] = {r.get<double>("ratio", kNotNegative), r.getOptional<double>("low", kNotNegative),
                     r.getOptional<double>("high", kNotNegative)};
        r.finish();
    }
    f.finish();
    return out;
}

SceneStats sceneStatsFrom(const json& j, const std::string& where) {
    FieldReader f(j, where);
    SceneStats s;
    s.objects = f.get<std::size_t>("objects");
    s.vertices = f.get<std::size_t>("vertices");
    s.triangles = f.get<std::size_t>("triangles");
    s.lights = f.get<std::size_t>("lights");
    s.reflectiveObjects = f.get<std::size_t>("reflective");
    s.refractiveObjects = f.get<std::size_t>("refractive");
    f.finish();
    return s;
}

ParameterList parametersFrom(const json& j, const std::string& where) {
    if (!j.is_object()) FieldReader::fail(where, "expected an object");
    ParameterList list;
    for (const auto& [k, v] : j.items()) {
        if (v.is_boolean()) list.emplace_back(k, v.get<bool>());
        else if (v.is_number_integer()) list.emplace_back(k, FieldReader::exactInteger(v, where + "." + k));
        else if (v.is_number_float()) list.emplace_back(k, v.get<double>());
        else if (v.is_string()) list.emplace_back(k, v.get<std::string>());
        else FieldReader::fail(where + "." + k, "expected a boolean, number or string");
    }
    return list;
}

ReferenceEntry referenceFrom(const json& j, const std::string& where) {
    FieldReader f(j, where);
    ReferenceEntry r;
    r.key = f.get<std::string>("key");
    r.exr = f.get<std::string>("exr");
    r.png = f.get<std::string>("png");
    r.mask = f.getOptional<std::string>("mask");
    r.frameMilliseconds = f.get<double>("frame_ms", kNotNegative);
    r.cacheHit = f.get<bool>("cache_hit");
    f.finish();
    return r;
}

RunImages imagesFrom(const json& j, const std::string& where) {
    FieldReader f(j, where);
    RunImages i;
    i.exr = f.get<std::string>("exr");
    i.png = f.get<std::string>("png");
    if (const json& maps = f.required("maps"); !maps.is_null()) i.maps = FieldReader::as<std::string>(maps, f.path("maps"));
    if (const json* debug = f.optional("debug")) {
        FieldReader d(*debug, f.path("debug"));
        for (const auto& [name, file] : debug->items()) i.debug[name] = d.get<std::string>(name);
        d.finish();
    }
    f.finish();
    return i;
}

}  // namespace

RunRecord fromJson(const json& j) {
    FieldReader f(j, "$");
    RunRecord r;
    r.schemaVersion = f.getOptional<int>("schema_version").value_or(1);
    r.index = f.get<std::size_t>("index");
    r.id = f.get<std::string>("id");
    r.scene = f.get<std::string>("scene");
    r.sceneStats = sceneStatsFrom(f.required("scene_stats"), f.path("scene_stats"));
    r.view = f.get<std::string>("view");
    // Within what the runner renders and writes: a path's frames or -1 (the scene camera), the
    // scene time and image sides `run` accepts (number_check.h).
    r.frame = f.get<int>("frame", {-1.0, limits::kFrame});
    r.time = f.get<double>("time", {-limits::kSceneTime, limits::kSceneTime});
    r.width = f.get<int>("width", {1.0, limits::kImageSide});
    r.height = f.get<int>("height", {1.0, limits::kImageSide});
    r.technique = f.get<std::string>("technique");
    r.label = f.get<std::string>("label");
    r.parameters = parametersFrom(f.required("parameters"), f.path("parameters"));
    r.parametersText = f.get<std::string>("parameters_text");
    r.sequence = f.get<std::string>("sequence");
    r.frameMilliseconds = spreadFrom(f.required("frame_ms"), f.path("frame_ms"));
    const json& stages = f.required("stages");
    FieldReader s(stages, f.path("stages"));
    for (const auto& [name, spread] : stages.items()) r.stages[name] = spreadFrom(s.required(name), s.path(name));
    const json& counters = f.required("counters");
    FieldReader c(counters, f.path("counters"));
    for (const auto& [name, value] : counters.items()) r.counters[name] = c.get<double>(name);
    r.metrics = f.required("metrics");
    if (!r.metrics.is_object()) FieldReader::fail(f.path("metrics"), "expected an object");
    r.reference = referenceFrom(f.required("reference"), f.path("reference"));
    r.images = imagesFrom(f.required("images"), f.path("images"));
    r.runSeconds = f.getOptional<double>("run_seconds", kNotNegative);
    r.warmupFrames = f.getOptional<int>("warmup_frames", kNotNegative);
    if (const json* t = f.optional("timing")) r.timing = timingFrom(*t, f.path("timing"));
    if (const json* s = f.optional("speedup")) r.speedup = speedupFrom(*s, f.path("speedup"));
    if (const json* device = f.optional("device")) r.device = *device;
    r.temporalError = f.getOptional<double>("temporal_error", kNotNegative);
    r.temporalErrorMasked = f.getOptional<double>("temporal_error_masked", kNotNegative);
    r.temporalPreviousFrame = f.getOptional<int>("temporal_previous_frame", {0.0, limits::kFrame});
    f.finish();
    return r;
}

}  // namespace hybridlab
