#pragma once
// Running a small experiment in a test, as the runner tests, the report tests and the paper-table
// tests all do: quiet runner options into a temporary folder, and the result set read back.
#include <filesystem>
#include <fstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiments/runner/experiment_runner.h"

namespace hybridlab::test {

// Results into `out`, references cached in `cache`, no progress output.
inline RunnerOptions quietRunnerOptions(const std::filesystem::path& out, const std::filesystem::path& cache) {
    RunnerOptions o;
    o.outDir = out;
    o.cacheDir = cache;
    o.quiet = true;
    return o;
}

// The records of the result set in `out` (results.json).
inline std::vector<nlohmann::json> readResults(const std::filesystem::path& out) {
    std::ifstream in(out / "results.json");
    return nlohmann::json::parse(in).get<std::vector<nlohmann::json>>();
}

// A record without what legitimately differs between two runs of the same experiment: timings
// (the warm-up's length too: it ends when frame times agree) and whether the reference came from
// the cache.
inline nlohmann::json comparableRecord(nlohmann::json r) {
    r.erase("frame_ms");
    r.erase("timing");
    r.erase("speedup");
    r.erase("warmup_frames");
    r.erase("stages");
    r.erase("run_seconds");
    r["reference"].erase("cache_hit");
    r["reference"].erase("frame_ms");
    return r;
}

}  // namespace hybridlab::test
