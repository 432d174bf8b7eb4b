// HDR-FLIP (metrics/hdr_flip.h) against NVIDIA's reference implementation on the committed pairs
// in tests/fixtures/hdr_flip (48 x 32, linear float EXR). The expected numbers were computed once,
// outside this repository, by a line-for-line port of NVlabs/flip python/flip_api.py
// (compute_exposure_params, tone_map, compute_ldrflip, compute_hdrflip) and flip.py's exposure
// count, with ACES, 67 pixels per degree, cv.filter2D's replicated border as
// scipy.ndimage.correlate(mode="nearest"): the mean of the HDR-FLIP map and the exposure range.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "common/image/image_io.h"
#include "metrics/hdr_flip.h"
#include "metrics/metric_input.h"

namespace hybridlab {
namespace {

struct NvidiaValues {
    const char* pair;
    double mean;   // of the HDR-FLIP map
    double start;  // exposure range
    double stop;
    int count;
};

// "hdr-highlights" holds values up to 30 (above 1).
constexpr NvidiaValues kNvidia[] = {
    {"ldr-noise", 0.102727413, 1.280307, 2.143707, 2},
    {"hdr-highlights", 0.154086381, -3.823594, 2.885964, 7},
    {"edges-shifted", 0.220081732, 1.787832, 2.513059, 2},
    {"dark", 0.085741818, 5.960863, 7.026881, 2},
};

cv::Mat3f linearRgb(const std::string& file) {
    return metricRgb(readImage(std::string(HYBRIDLAB_TEST_FIXTURES) + "/hdr_flip/" + file), ValueSpace::Linear);
}

TEST(HdrFlip, MatchesNvidiasReferenceImplementation) {
    for (const NvidiaValues& v : kNvidia) {
        SCOPED_TRACE(v.pair);
        const cv::Mat3f reference = linearRgb(std::string(v.pair) + ".reference.exr");
        const cv::Mat3f test = linearRgb(std::string(v.pair) + ".test.exr");
        const HdrFlipExposures e = hdrFlipExposures(reference);
        EXPECT_NEAR(e.start, v.start, 1e-5);
        EXPECT_NEAR(e.stop, v.stop, 1e-5);
        EXPECT_EQ(e.count, v.count);
        const double mean = cv::mean(hdrFlipMap(test, reference))[0];
        std::printf("[ hdr-flip ] %s: mean %.9f, NVIDIA's %.9f\n", v.pair, mean, v.mean);
        EXPECT_NEAR(mean, v.mean, 1e-4);
    }
}

TEST(HdrFlip, IsZeroForIdenticalImagesAndSeesErrorsAboveOne) {
    const cv::Mat3f reference = linearRgb("hdr-highlights.reference.exr");
    EXPECT_EQ(cv::countNonZero(hdrFlipMap(reference, reference) > 0.0f), 0);
    // Clamped to display values the highlights above 10 read 1 however bright: LDR-FLIP on the
    // display images cannot tell a highlight at 30 from one at 18; HDR-FLIP's short exposures can.
    cv::Mat3f dimmer = reference.clone();
    for (auto it = dimmer.begin(); it != dimmer.end(); ++it)
        for (int c = 0; c < 3; ++c)
            if ((*it)[c] > 10.0f) (*it)[c] *= 0.6f;
    auto display = [](const cv::Mat3f& linear) {
        cv::Mat3f m = linear.clone();
        for (auto it = m.begin(); it != m.end(); ++it)
            for (int c = 0; c < 3; ++c) {
                const float v = std::clamp((*it)[c], 0.0f, 1.0f);
                (*it)[c] = v > 0.0031308f ? 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f : 12.92f * v;
            }
        return m;
    };
    EXPECT_EQ(cv::countNonZero(flipMap(display(dimmer), display(reference)) > 0.0f), 0);
    EXPECT_GT(cv::mean(hdrFlipMap(dimmer, reference))[0], 1e-3);
}

}  // namespace
}  // namespace hybridlab
