#pragma once
// The results record of one run (experiments/README.md "Results"): runs/<id>.json, and each element
// of results.json. experiments/results.schema.json is its schema; toJson is its only writer, and
// fromJson reads back what toJson wrote (merge, resume and the temporal errors change records).
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/scene/scene.h"
#include "experiments/runner/experiment_config.h"

namespace hybridlab {

// The version of the record's format that toJson writes. A reader of an older record reads it as
// this one through the steps of experiments/results.migrations.json, whose last step ends here.
inline constexpr int kResultsSchemaVersion = 2;

// The median, minimum and maximum of a time over the timed rounds; for the frame's clocks also the
// median's distribution-free 95% interval (timing_statistics.h).
struct Spread {
    double median = 0.0, min = 0.0, max = 0.0;
    std::optional<double> ciLow, ciHigh;
};
Spread spreadOf(std::vector<double> values);          // values must not be empty
Spread intervalSpreadOf(std::vector<double> values);  // with the interval, where 6 or more values give one

// A speed-up over another setting timed in the same rounds: the median over the rounds of the
// other's time / this run's, with its 95% interval (none with fewer than 6 rounds).
struct RatioInterval {
    double ratio = 0.0;
    std::optional<double> low, high;
};

// How a run was timed (experiments/README.md "Timing"): interleaved rounds with every other run of
// its group (same scene, view, frame and size) and the reference.
struct RunTiming {
    std::string group;
    // The runner's call that timed the group's rounds: rounds pair only within one (a group split
    // by --max-runs, --resume or shards is timed in several). Absent in sets written before it.
    std::optional<std::string> timingId;
    int rounds = 0;
    std::vector<double> frameRounds;      // this run's frame time (wall) in round k at [k]
    std::vector<double> referenceRounds;  // the reference's, in the same rounds
    Spread cpu;                           // process CPU time per frame, all threads
    std::vector<double> cpuRounds;
    std::optional<Spread> device;         // the device's timestamps, where it has them
    std::vector<double> deviceRounds;
    double precision = 0.0;
    bool precisionReached = false;
    std::optional<std::string> budgetClock;  // "cpu_per_core" or "wall" (interleaved_timing.h); absent before it was recorded
    std::optional<double> otherLoad;         // other processes' share of the cores while timed (other_load.h)
    // "realtime" where the rounds ran ahead of other processes (`run --realtime`,
    // realtime_priority.h), "normal" otherwise; absent before it was recorded.
    std::optional<std::string> priority;
    double warmupMs = 0.0;
    bool steady = false;                  // the warm-up ended on agreeing frames, not on its cap
    std::optional<nlohmann::json> gpuClocks;  // gpu_clocks.h, on an NVIDIA GPU
};

// The reference image a run was scored against (paths relative to the result set's folder).
struct ReferenceEntry {
    std::string key;  // ReferenceCache::key
    std::string exr, png;
    std::optional<std::string> mask;  // the reflective and refractive pixels, when there are any
    double frameMilliseconds = 0.0;   // the reference's own render time
    bool cacheHit = false;
};

// The run's images (paths relative to the result set's folder).
struct RunImages {
    std::string exr, png;
    std::optional<std::string> maps;          // the error maps' folder; none when the config keeps none
    std::map<std::string, std::string> debug; // the technique's debug images by name, when kept
};

struct RunRecord {
    // The format the record was written in: kResultsSchemaVersion, or an older record's own
    // version (1 where it has none), which a round trip keeps.
    int schemaVersion = kResultsSchemaVersion;
    // What ran.
    std::size_t index = 0;  // the run's place in the plan
    std::string id;
    std::string scene;      // the scene's own name
    SceneStats sceneStats;
    std::string view;       // a camera path's name, or "camera"
    int frame = -1;         // on the path; -1 for the scene camera
    double time = 0.0;      // the scene time rendered
    int width = 0, height = 0;
    std::string technique, label;
    ParameterList parameters;  // as the config gave them
    std::string parametersText;
    std::string sequence;      // the frames of one path in one setting (the temporal error's pairs)
    // What it cost and produced.
    Spread frameMilliseconds;
    std::optional<int> warmupFrames;  // rendered before the timed rounds
    std::optional<RunTiming> timing;  // none in result sets written before interleaved timing
    std::map<std::string, RatioInterval> speedup;  // over "reference" and "rt_only"
    std::map<std::string, Spread> stages;
    std::map<std::string, double> counters;
    // The metric report as metrics/report_files.h's reportJson writes it: the same object is the
    // error maps' metrics.json and `hybridlab compare`'s output, so that module owns its format.
    nlohmann::json metrics;
    ReferenceEntry reference;
    RunImages images;
    std::optional<double> runSeconds;     // the run's whole time; merge sums it per shard
    std::optional<nlohmann::json> device; // in a set measured on several devices: this run's (device_record.h)
    // Added to results.json when the path's previous frame is recorded too (results_store.h).
    std::optional<double> temporalError, temporalErrorMasked;
    std::optional<int> temporalPreviousFrame;
};

// The record as JSON: the one writer of runs/<id>.json and results.json.
nlohmann::json toJson(const RunRecord& record);

// The record toJson wrote. Throws std::runtime_error naming the field for anything else (a missing
// or mistyped field, or one the record does not have), so that no field is dropped by a round trip,
// and for a number the runner cannot have written: not finite, a size outside 1..16384, a frame
// outside -1..10,000,000 or past its int, a negative time (number_check.h's limits).
RunRecord fromJson(const nlohmann::json& record);

}  // namespace hybridlab
