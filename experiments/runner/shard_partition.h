#pragma once
// Which shard renders which run under `hybridlab run --shard i/n`: the runs split so that every
// shard has about the same estimated cost, however sizes and techniques are mixed (index modulo n
// can give one shard every 1280x720 run). Every shard computes the same partition from the config
// alone (not from what its reference cache holds, which differs between shards and over time).
#include <vector>

#include "experiments/runner/experiment_config.h"

namespace hybridlab {

// Estimated costs in one unit: one pixel of one frame of the Whitted reference (at its default
// depth); each technique's TechniqueInfo::relativeCost scales its pixels.
//   run:       pixels x ((warmup + repeats) x the technique's relative cost + the metrics' cost)
//   reference: pixels x the reference's relative cost (it is rendered once and cached)
double estimatedRunCost(const ExperimentConfig& config, const RunSpec& run);
double estimatedReferenceCost(const ExperimentConfig& config, const RunSpec& run);

struct ShardPartition {
    std::vector<int> shardOfRun;          // by run index
    std::vector<double> estimatedCost;    // by shard: its runs and the references they need
    std::vector<const RunSpec*> runsOf(const std::vector<RunSpec>& runs, int shard) const;  // in index order
};

// Longest processing time first: runs by estimated cost (largest first, then by index), each to
// the shard whose total it raises least, a reference costing only the first time a shard needs it
// (its cache then holds it), so runs that share a reference go together where the balance allows.
// A reference needed by two shards is counted on both: run at the same time, both render it.
// Deterministic: ties go to the lower shard. Needs 1 <= shardCount.
ShardPartition partitionRuns(const ExperimentConfig& config, const std::vector<RunSpec>& runs, int shardCount);

}  // namespace hybridlab
