#pragma once
// `hybridlab run`: renders every run of an experiment (or one shard of them), scores each image
// against its (cached) reference, and records the results (DESIGN.md "Experiments and results").
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "experiments/runner/experiment_config.h"

namespace hybridlab {

struct RunnerOptions {
    std::filesystem::path outDir;
    std::filesystem::path cacheDir;  // the reference cache
    bool resume = false;
    // --resume on a result set measured on another device (device_record.h) goes on, each run
    // keeping its device as "device", instead of being refused.
    bool allowMixedDevices = false;
    int shardIndex = 0;  // this shard's runs, of shardCount balanced by estimated cost (shard_partition.h)
    int shardCount = 1;
    long maxRuns = -1;   // stop after this many renders (as if killed; for tests), -1: all
    bool quiet = false;
    // Each group's warm-up and rounds run at real-time priority (realtime_priority.h), ahead of
    // other processes' load; refused before anything is written where the process may not.
    bool realTime = false;
};

struct RunnerSummary {
    std::size_t runsPlanned = 0;   // in this shard
    std::size_t runsRendered = 0;
    std::size_t runsSkipped = 0;   // already recorded (--resume)
    std::size_t referencesRendered = 0;
    std::size_t referenceCacheHits = 0;
    // Each reference counts once: two groups may share one (a path's frame seen from the scene
    // camera), and the second finds in the cache what the first rendered.
    std::set<std::string> referenceKeys;
    std::size_t staleTemporariesRemoved = 0;  // partial files of killed runs, removed on --resume
    bool complete = false;         // every run of the shard is recorded
};

// Throws InputError for an output folder that holds another experiment (or anything else), one
// that exists without --resume, one measured on another device (unless allowMixedDevices), or one
// another runner is writing (its lock file, DirectoryLock); nothing is written then.
RunnerSummary runExperiment(const ExperimentConfig& config, const RunnerOptions& options);

// `hybridlab run --dry-run`: the runs of the shard, each with whether its reference is cached, and
// how many distinct references they need. Checks what `run` checks of the config; writes nothing.
struct PlannedRun {
    const RunSpec* run = nullptr;  // into ExperimentPlan::runs
    bool referenceCached = false;
};
struct ExperimentPlan {
    std::vector<RunSpec> runs;      // every run of the experiment
    std::vector<PlannedRun> mine;   // the shard's
    std::size_t references = 0;     // distinct references the shard's runs need
    std::size_t referencesCached = 0;
    double estimatedCost = 0.0;     // the shard's (shard_partition.h)
};
ExperimentPlan planExperiment(const ExperimentConfig& config, const RunnerOptions& options);

// `hybridlab merge`: joins shard folders of one experiment into `outDir`, as one unsharded run
// would have written it. Throws InputError, writing nothing, when they are not shards of the same
// experiment (config, shard count, partition), a shard is missing or given twice, runs are
// missing or recorded twice, a record or a file it names is not whole (results_store.h), or
// (unless `allowMixedDevices`) they were measured on different devices (device_record.h); with
// it, each record keeps its shard's device as "device". The set is built beside `outDir` and
// renamed into place, so a failure to write (IoError) leaves nothing either.
struct MergedShard {
    std::filesystem::path dir;
    int index = 0, count = 1;
    std::size_t runs = 0;
    double estimatedCost = -1.0;  // as the shard recorded it (-1: a folder from before estimates)
    double seconds = 0.0;         // its records' run_seconds summed: the time its runs took
};
std::vector<MergedShard> mergeShards(const std::vector<std::filesystem::path>& shardDirs, const std::filesystem::path& outDir,
                                     bool allowMixedDevices = false);

}  // namespace hybridlab
