#pragma once
// Layers of a lens system's environment (Hakura & Snyder 2001 §4.2): LBG clustering (Linde, Buzo
// & Gray 1980) of the environment intersections' distances from the lens centre, over all viewpoint
// samples at once; whole objects go to one cluster; each shell sits at its cluster's mean distance,
// where the intersections of one continued ray count only by its frontmost member in the cluster.
// clusterLayers clusters each object's mean inverse distance (see there for why).
#include <cstdint>
#include <vector>

namespace hybridlab {

// One environment intersection as clustering sees it.
struct ClusterSample {
    float distance = 0.0f;      // from the lens centre
    std::uint32_t object = 0;   // scene object it lies on
    std::uint64_t ray = 0;      // the outgoing ray it was found along (unique over all viewpoints)
    std::uint16_t order = 0;    // 0 for the ray's first intersection, 1 for the next, ...
};

struct LbgClusters {
    std::vector<double> centers;   // ascending
    std::vector<int> assignment;   // per value: index into centers
    double distortion = 0.0;       // mean squared distance to the assigned centre
    int iterations = 0;
};

// LBG with k clusters on scalar values. The paper starts from random distances; this starts from
// the values' quantiles, which is deterministic and never leaves a cluster empty at the start.
// Iterates assignment and means until no value changes cluster.
LbgClusters lbgCluster(const std::vector<float>& values, int k);

// The smallest k in [1, maxClusters] whose RMS distortion is at most maxRelativeRms times the mean
// value, or maxClusters.
LbgClusters lbgClusterAuto(const std::vector<float>& values, int maxClusters, double maxRelativeRms);

struct LayerPartition {
    std::vector<int> objectLayer;     // per scene object: its layer, -1 when it has no sample
    std::vector<int> sampleLayer;     // per sample: its object's layer
    std::vector<bool> frontmost;      // per sample: the first of its ray in its layer
    std::vector<double> shellRadius;  // per layer: mean distance of its frontmost samples (ascending)
    std::vector<std::uint64_t> samplesPerLayer;  // frontmost samples per layer
};

// The whole-object rule and the shell distances. Layers left without an object are dropped and
// the rest renumbered in order of distance.
LayerPartition partitionByWholeObjects(const std::vector<ClusterSample>& samples, const LbgClusters& clusters,
                                       std::size_t objectCount);

// Objects the lens images never met (objectLayer -1) but `seen` samples do (the direct images from
// the EM origin): each joins the layer whose shell is nearest to it by mean inverse distance, the
// metric clusterLayers uses. The paper places layers by the lens images' records alone (§4.2) but
// infers them from direct images too (§4.3), which image such objects, so each needs a layer: the
// top of a wall that only a view above the viewpoint samples' plane sees in a cup. The shells
// stay where the lens records put them.
void assignObjectsOnlyDirectImagesSee(LayerPartition& partition, const std::vector<ClusterSample>& seen);

// Clusters the objects by their samples' mean inverse distance (k = layers, or automatic when
// layers == 0) and partitions.
LayerPartition clusterLayers(const std::vector<ClusterSample>& samples, std::size_t objectCount, int layers,
                             int maxLayers = 4, double maxRelativeRms = 0.1);

}  // namespace hybridlab
