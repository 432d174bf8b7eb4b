#pragma once
// LDR-FLIP: Andersson, Nilsson, Akenine-Möller, Oskarsson, Åström and Fairchild, "FLIP: A
// Difference Evaluator for Alternating Images", Proc. ACM Comput. Graph. Interact. Tech. 3(2)
// (HPG 2020). The per-pixel perceived difference, in [0, 1], between a test and a reference
// image of display sRGB values in [0, 1], seen at a given number of pixels per degree of visual
// angle. flip.cpp follows the paper's definitions step by step; its constants were checked
// against NVIDIA's reference implementation (github.com/NVlabs/flip, python/flip_api.py and
// cpp/FLIP.h).
#include <vector>

#include <opencv2/core.hpp>

namespace hybridlab {

// The testbed's default viewing condition (the paper's, a 0.7 m wide 4K monitor seen from 0.7 m,
// is 67.02 pixels per degree).
constexpr double kDefaultPixelsPerDegree = 67.0;
// The viewing conditions flipMap takes. Its filters' radii grow with the pixels per degree (3 sigma
// of the widest, in pixels), so 10^5 already spends seconds on a 32 x 18 image and 10^10 more memory
// than a filter can have; 1000 is a 0.7 m wide 16K display seen from 1.5 m, beyond any real one.
constexpr double kSmallestPixelsPerDegree = 0.001;
constexpr double kLargestPixelsPerDegree = 1000.0;

// The FLIP map of `test` against `reference`, both display sRGB in [0, 1] (R, G, B order).
cv::Mat1f flipMap(const cv::Mat3f& test, const cv::Mat3f& reference, double pixelsPerDegree = kDefaultPixelsPerDegree);

// Pooling, as the paper and NVIDIA's tool report it: the mean, and percentiles of the
// value-weighted distribution (each pixel counts with a weight equal to its FLIP value, so that
// the large errors a viewer notices dominate: the paper's weighted histogram).
struct FlipStats {
    double mean = 0.0;
    double weightedMedian = 0.0;
    double weightedFirstQuartile = 0.0;
    double weightedThirdQuartile = 0.0;
};

// Over `region` (every pixel when null). The weighted p-percentile is that of the distribution in
// which each pixel weighs its own FLIP value, computed exactly: with the region's values sorted,
// v_1 <= ... <= v_n, it is the smallest v_k with v_1 + ... + v_k >= p (v_1 + ... + v_n); 0 when
// every value is 0.
// NVIDIA's tool estimates these from a 100-bucket histogram in which every pixel weighs its
// bucket's centre instead, so each error-free pixel still weighs 0.005: on images that are mostly
// right its quartiles come out lower (the whitted-classic depth-1 pair at 320 x 180: 0.661, 0.897,
// 0.967 there; 0.761, 0.936, 0.968 here), and identical images get 0.0025, 0.005, 0.0075 rather
// than 0. (The authors now recommend the mean as the single number.)
FlipStats flipStats(const cv::Mat1f& map, const cv::Mat1b* region);

// The value-weighted p-percentiles defined above, for each p of `ps`, of non-negative `values`
// (in any order).
std::vector<double> valueWeightedPercentiles(const std::vector<float>& values, const std::vector<double>& ps);

}  // namespace hybridlab
