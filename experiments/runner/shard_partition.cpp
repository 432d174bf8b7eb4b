#include "experiments/runner/shard_partition.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <set>
#include <tuple>

#include "techniques/technique.h"

namespace hybridlab {

namespace {

double pixels(const RunSpec& run) { return static_cast<double>(run.width) * static_cast<double>(run.height); }

// What the reference cache keys a run's reference on, as far as the config tells (the cache also
// hashes the scene's files and the camera, which are the same for these within one config).
using ReferenceId = std::tuple<std::size_t, std::string, int, int, int>;
ReferenceId referenceOf(const RunSpec& run) { return {run.scene, run.cameraPath, run.frame, run.width, run.height}; }

// Scoring a pixel, in reference pixels: `hybridlab compare` with every metric and its maps takes
// about 8 reference frames of the same size (320x180, 1.8 s against 0.22 s), shared by the metrics
// as their table's costs weigh them.
double scoringCost(const MetricSelection& chosen) {
    double cost = 0.1;
    for (const MetricDefinition& m : kMetricTable) cost += chosen.chosen(m.key) ? m.cost : 0.0;
    return cost;
}

}  // namespace

double estimatedRunCost(const ExperimentConfig& config, const RunSpec& run) {
    const double frames = config.timing.warmupFrames + config.timing.minRounds;
    const double relative = findTechnique(config.techniques.at(run.technique).name).relativeCost;
    return pixels(run) * (frames * relative + scoringCost(config.metrics));
}

double estimatedReferenceCost(const ExperimentConfig& config, const RunSpec& run) {
    (void)config;  // the reference's parameters do not change its class
    return pixels(run) * findTechnique("whitted").relativeCost;
}

std::vector<const RunSpec*> ShardPartition::runsOf(const std::vector<RunSpec>& runs, int shard) const {
    std::vector<const RunSpec*> mine;
    for (const RunSpec& r : runs)
        if (shardOfRun.at(r.index) == shard) mine.push_back(&r);
    return mine;
}

ShardPartition partitionRuns(const ExperimentConfig& config, const std::vector<RunSpec>& runs, int shardCount) {
    ShardPartition p;
    p.shardOfRun.assign(runs.size(), 0);
    p.estimatedCost.assign(static_cast<std::size_t>(shardCount), 0.0);
    std::vector<double> cost(runs.size());
    for (const RunSpec& r : runs) cost[r.index] = estimatedRunCost(config, r);
    std::vector<std::size_t> order(runs.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return cost[a] > cost[b]; });

    std::vector<std::set<ReferenceId>> referencesOf(static_cast<std::size_t>(shardCount));
    for (const std::size_t i : order) {
        const RunSpec& run = runs[i];
        const ReferenceId ref = referenceOf(run);
        const double referenceCost = estimatedReferenceCost(config, run);
        std::size_t best = 0;
        double bestTotal = 0.0;
        for (std::size_t s = 0; s < p.estimatedCost.size(); ++s) {
            const double total = p.estimatedCost[s] + cost[i] + (referencesOf[s].count(ref) ? 0.0 : referenceCost);
            if (s == 0 || total < bestTotal) {
                best = s;
                bestTotal = total;
            }
        }
        p.shardOfRun[i] = static_cast<int>(best);
        p.estimatedCost[best] = bestTotal;
        referencesOf[best].insert(ref);
    }
    return p;
}

}  // namespace hybridlab
