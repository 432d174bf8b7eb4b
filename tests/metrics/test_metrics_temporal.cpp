// Temporal stability along a camera path: the temporal error is zero when a technique changes as
// the reference does and positive when its error alternates; flicker is the per-pixel standard
// deviation over repeated frames.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "common/core/input_error.h"
#include "metrics/temporal.h"
#include "tests/support/metric_test_images.h"

namespace hybridlab {
namespace {

// Frame k of a path: a gradient that slides to the right, in display values within [0.2, 0.8].
glm::vec3 referenceDisplay(int x, int y, int k) {
    const float v = 0.5f + 0.3f * std::sin(0.2f * static_cast<float>(x + 3 * k));
    return {v, 0.4f + 0.01f * static_cast<float>(y), 0.5f};
}

std::vector<Image> framesOf(int count, float offsetEven, float offsetOdd) {
    std::vector<Image> frames;
    for (int k = 0; k < count; ++k) {
        const float offset = k % 2 ? offsetOdd : offsetEven;
        frames.push_back(test::fromDisplay(32, 24, [&](int x, int y) { return referenceDisplay(x, y, k) + glm::vec3(offset); }));
    }
    return frames;
}

TEST(TemporalError, IsZeroWhenTheTechniqueChangesAsTheReferenceAndPositiveWhenItsErrorAlternates) {
    const std::vector<Image> reference = framesOf(6, 0.0f, 0.0f);
    const TemporalError exact = temporalError(reference, reference);
    ASSERT_EQ(exact.perFrame.size(), 5u);
    for (double v : exact.perFrame) EXPECT_EQ(v, 0.0);
    EXPECT_EQ(exact.mean, 0.0);
    // Off by the same amount in every frame: wrong, but stable.
    const TemporalError biased = temporalError(framesOf(6, 0.1f, 0.1f), reference);
    for (double v : biased.perFrame) EXPECT_NEAR(v, 0.0, 1e-6);

    // +e on even frames, -e on odd ones: every change is off by 2e in every channel.
    const float e = 0.05f;
    const TemporalError alternating = temporalError(framesOf(6, e, -e), framesOf(6, 0.0f, 0.0f));
    for (double v : alternating.perFrame) EXPECT_NEAR(v, 2.0 * e, 1e-6);
    EXPECT_NEAR(alternating.mean, 2.0 * e, 1e-6);
}

TEST(TemporalError, MaskAndBadInput) {
    const std::vector<Image> reference = framesOf(3, 0.0f, 0.0f);
    std::vector<Image> test = reference;
    for (Image& frame : test) frame.at(0, 0) = glm::vec4(1.0f);  // one pixel flickers with the path
    test[1].at(0, 0) = glm::vec4(0.0f);
    Image maskImage(32, 24, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    maskImage.at(5, 5) = glm::vec4(1.0f);
    const PixelMask away = PixelMask::fromImage(maskImage);
    EXPECT_GT(temporalError(test, reference).mean, 0.0);
    EXPECT_EQ(temporalError(test, reference, &away).mean, 0.0);

    EXPECT_THROW(temporalError(framesOf(3, 0, 0), framesOf(4, 0, 0)), InputError);
    EXPECT_THROW(temporalError(framesOf(1, 0, 0), framesOf(1, 0, 0)), InputError);
    std::vector<Image> mixed = framesOf(3, 0, 0);
    mixed[2] = Image(16, 16);
    EXPECT_THROW(temporalError(mixed, framesOf(3, 0, 0)), InputError);
}

TEST(Flicker, IsThePerPixelTemporalStandardDeviation) {
    // A static camera: the same frame four times, then alternating by +-e around it.
    std::vector<Image> still(4, framesOf(1, 0.0f, 0.0f)[0]);
    const Flicker none = flicker(still);
    EXPECT_EQ(none.mean, 0.0);
    double highest = 0.0;
    cv::minMaxLoc(none.map, nullptr, &highest);
    EXPECT_EQ(highest, 0.0);

    const float e = 0.04f;
    std::vector<Image> alternating;
    for (int k = 0; k < 4; ++k) {
        alternating.push_back(test::fromDisplay(32, 24, [&](int x, int y) { return referenceDisplay(x, y, 0) + glm::vec3(k % 2 ? -e : e); }));
    }
    const Flicker f = flicker(alternating);
    EXPECT_NEAR(f.mean, e, 1e-6);  // population standard deviation of {+e, -e, +e, -e}
    EXPECT_EQ(f.map.rows, 24);
    EXPECT_EQ(f.map.cols, 32);
    EXPECT_THROW(flicker({still[0]}), InputError);
}

}  // namespace
}  // namespace hybridlab
