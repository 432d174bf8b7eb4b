#include "techniques/layered_em/layer_clustering.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

namespace hybridlab {

LbgClusters lbgCluster(const std::vector<float>& values, int k) {
    LbgClusters out;
    if (values.empty() || k < 1) return out;
    std::vector<float> sorted = values;
    std::sort(sorted.begin(), sorted.end());
    for (int i = 0; i < k; ++i) {
        std::size_t q = static_cast<std::size_t>((i + 0.5) / k * static_cast<double>(sorted.size()));
        out.centers.push_back(sorted[std::min(q, sorted.size() - 1)]);
    }
    out.assignment.assign(values.size(), -1);
    for (;;) {
        ++out.iterations;
        bool changed = false;
        for (std::size_t i = 0; i < values.size(); ++i) {
            int best = 0;
            for (int c = 1; c < k; ++c) {
                if (std::abs(values[i] - out.centers[c]) < std::abs(values[i] - out.centers[best])) best = c;
            }
            if (best != out.assignment[i]) changed = true;
            out.assignment[i] = best;
        }
        if (!changed) break;
        std::vector<double> sum(k, 0.0);
        std::vector<std::size_t> count(k, 0);
        for (std::size_t i = 0; i < values.size(); ++i) {
            sum[out.assignment[i]] += values[i];
            ++count[out.assignment[i]];
        }
        for (int c = 0; c < k; ++c) {
            if (count[c]) out.centers[c] = sum[c] / static_cast<double>(count[c]);
        }
    }
    // Centres ascending, assignments renumbered to match.
    std::vector<int> order(k);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return out.centers[a] < out.centers[b]; });
    std::vector<int> rank(k);
    std::vector<double> centers(k);
    for (int r = 0; r < k; ++r) {
        rank[order[r]] = r;
        centers[r] = out.centers[order[r]];
    }
    out.centers = centers;
    for (int& a : out.assignment) a = rank[a];
    double d = 0.0;
    for (std::size_t i = 0; i < values.size(); ++i) d += std::pow(values[i] - out.centers[out.assignment[i]], 2.0);
    out.distortion = d / static_cast<double>(values.size());
    return out;
}

LbgClusters lbgClusterAuto(const std::vector<float>& values, int maxClusters, double maxRelativeRms) {
    if (values.empty()) return {};
    const double mean = std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
    LbgClusters c;
    for (int k = 1; k <= maxClusters; ++k) {
        c = lbgCluster(values, k);
        if (std::sqrt(c.distortion) <= maxRelativeRms * mean) break;
    }
    return c;
}

LayerPartition partitionByWholeObjects(const std::vector<ClusterSample>& samples, const LbgClusters& clusters,
                                       std::size_t objectCount) {
    const int k = static_cast<int>(clusters.centers.size());
    // Votes: the cluster holding most of an object's samples takes the whole object.
    std::vector<std::vector<std::uint64_t>> votes(objectCount, std::vector<std::uint64_t>(k, 0));
    for (std::size_t i = 0; i < samples.size(); ++i) ++votes[samples[i].object][clusters.assignment[i]];
    std::vector<int> cluster(objectCount, -1);
    for (std::size_t o = 0; o < objectCount; ++o) {
        auto it = std::max_element(votes[o].begin(), votes[o].end());
        if (it != votes[o].end() && *it > 0) cluster[o] = static_cast<int>(it - votes[o].begin());
    }
    // Frontmost sample of each ray in each cluster.
    std::map<std::pair<std::uint64_t, int>, std::size_t> first;
    for (std::size_t i = 0; i < samples.size(); ++i) {
        auto key = std::make_pair(samples[i].ray, cluster[samples[i].object]);
        auto [it, added] = first.emplace(key, i);
        if (!added && samples[i].order < samples[it->second].order) it->second = i;
    }
    std::vector<double> sum(k, 0.0);
    std::vector<std::uint64_t> count(k, 0);
    LayerPartition out;
    out.frontmost.assign(samples.size(), false);
    for (const auto& [key, i] : first) {
        out.frontmost[i] = true;
        sum[key.second] += samples[i].distance;
        ++count[key.second];
    }
    // Drop empty clusters; order by mean distance.
    std::vector<int> kept;
    for (int c = 0; c < k; ++c) {
        if (count[c]) kept.push_back(c);
    }
    std::sort(kept.begin(), kept.end(), [&](int a, int b) { return sum[a] / count[a] < sum[b] / count[b]; });
    std::vector<int> layerOf(k, -1);
    for (std::size_t l = 0; l < kept.size(); ++l) {
        layerOf[kept[l]] = static_cast<int>(l);
        out.shellRadius.push_back(sum[kept[l]] / static_cast<double>(count[kept[l]]));
        out.samplesPerLayer.push_back(count[kept[l]]);
    }
    out.objectLayer.resize(objectCount);
    for (std::size_t o = 0; o < objectCount; ++o) out.objectLayer[o] = cluster[o] < 0 ? -1 : layerOf[cluster[o]];
    out.sampleLayer.resize(samples.size());
    for (std::size_t i = 0; i < samples.size(); ++i) out.sampleLayer[i] = out.objectLayer[samples[i].object];
    return out;
}

namespace {

// Per object, the mean inverse distance of its samples (0 for an object without one) and the count.
std::pair<std::vector<double>, std::vector<std::uint64_t>> meanInverseDistances(const std::vector<ClusterSample>& samples, std::size_t objectCount) {
    std::vector<double> sum(objectCount, 0.0);
    std::vector<std::uint64_t> count(objectCount, 0);
    for (const ClusterSample& s : samples) {
        sum[s.object] += 1.0 / std::max(static_cast<double>(s.distance), 1e-6);
        ++count[s.object];
    }
    for (std::size_t o = 0; o < objectCount; ++o) {
        if (count[o]) sum[o] /= static_cast<double>(count[o]);
    }
    return {sum, count};
}

}  // namespace

void assignObjectsOnlyDirectImagesSee(LayerPartition& partition, const std::vector<ClusterSample>& seen) {
    if (partition.shellRadius.empty()) return;
    const auto [inverse, count] = meanInverseDistances(seen, partition.objectLayer.size());
    for (std::size_t o = 0; o < partition.objectLayer.size(); ++o) {
        if (partition.objectLayer[o] >= 0 || !count[o]) continue;
        int best = 0;
        for (std::size_t l = 1; l < partition.shellRadius.size(); ++l) {
            if (std::abs(inverse[o] - 1.0 / partition.shellRadius[l]) < std::abs(inverse[o] - 1.0 / partition.shellRadius[static_cast<std::size_t>(best)]))
                best = static_cast<int>(l);
        }
        partition.objectLayer[o] = best;
    }
}

LayerPartition clusterLayers(const std::vector<ClusterSample>& samples, std::size_t objectCount, int layers, int maxLayers,
                             double maxRelativeRms) {
    // LBG runs on each object's mean inverse distance, and the objects' clusters go to their samples.
    // Inverse distance: a point at distance d drawn on a shell at r moves on screen by about
    // b |1/d - 1/r| for a viewpoint offset b (parallax), so squared error in 1/d is the error the
    // shells make. Per object rather than per sample: the whole-object rule (§4.2) makes layers
    // unions of objects anyway, and over samples the many hits on large far objects (the walls)
    // claim the clusters, so that a small near layer (the cup before the teapot) merges with the next.
    const auto [inverse, count] = meanInverseDistances(samples, objectCount);
    std::vector<float> objectValues;
    std::vector<int> valueOf(objectCount, -1);
    for (std::size_t o = 0; o < objectCount; ++o) {
        if (!count[o]) continue;
        valueOf[o] = static_cast<int>(objectValues.size());
        objectValues.push_back(static_cast<float>(inverse[o]));
    }
    const int k = std::min<int>(layers, static_cast<int>(objectValues.size()));
    const LbgClusters objects = layers > 0 ? lbgCluster(objectValues, k) : lbgClusterAuto(objectValues, maxLayers, maxRelativeRms);
    LbgClusters c = objects;
    c.assignment.resize(samples.size());
    for (std::size_t i = 0; i < samples.size(); ++i) c.assignment[i] = objects.assignment[valueOf[samples[i].object]];
    return partitionByWholeObjects(samples, c, objectCount);
}

}  // namespace hybridlab
