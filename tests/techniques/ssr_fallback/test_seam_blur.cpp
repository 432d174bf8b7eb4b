// The seam blur of the reflection composer (techniques/ssr_fallback/seam_blur.h): only a band of
// the given radius around the boundary between SSR and ray-traced texels changes; a constant
// reflection stays constant; texels without a reflection never bleed in; radius 0 is off; the
// bilateral variant smooths a small step at the seam and keeps a reflected edge inside the band.
#include <gtest/gtest.h>

#include "techniques/ssr_fallback/seam_blur.h"

namespace hybridlab {
namespace {

constexpr int kW = 20, kH = 10;

// Left half SSR with value `left`, right half ray traced with value `right`.
struct Halves {
    std::vector<glm::vec3> reflection;
    std::vector<ReflectionSource> source;
    Halves(float left, float right) : reflection(kW * kH), source(kW * kH) {
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                reflection[y * kW + x] = glm::vec3(x < kW / 2 ? left : right);
                source[y * kW + x] = x < kW / 2 ? ReflectionSource::Ssr : ReflectionSource::RayTraced;
            }
    }
};

TEST(SeamBlur, RadiusZeroChangesNothing) {
    Halves h(1.0f, 0.0f);
    const auto before = h.reflection;
    EXPECT_EQ(blurReflectionSeams(h.reflection, h.source, kW, kH, 0), 0u);
    EXPECT_EQ(h.reflection, before);
}

TEST(SeamBlur, OnlyTheBandAroundTheSeamIsBlurredSymmetrically) {
    Halves h(1.0f, 0.0f);
    const int radius = 2;
    // The seam is columns 9 and 10; the band reaches 2 columns further on each side.
    EXPECT_EQ(blurReflectionSeams(h.reflection, h.source, kW, kH, radius), static_cast<std::size_t>(6 * kH));
    for (int y = 0; y < kH; ++y) {
        for (int x = 0; x < kW; ++x) {
            const float v = h.reflection[y * kW + x].r;
            if (x < 7) {
                EXPECT_EQ(v, 1.0f) << x;
            } else if (x > 12) {
                EXPECT_EQ(v, 0.0f) << x;
            } else if (x == 9 || x == 10) {
                EXPECT_TRUE(v > 0.0f && v < 1.0f) << x;
            }
        }
        // The Gaussian is symmetric: mirrored texels across the seam sum to 1.
        for (int d = 0; d < 3; ++d) EXPECT_NEAR(h.reflection[y * kW + 9 - d].r + h.reflection[y * kW + 10 + d].r, 1.0f, 1e-5f);
        // And monotonic across the seam.
        for (int x = 7; x < 12; ++x) EXPECT_GE(h.reflection[y * kW + x].r, h.reflection[y * kW + x + 1].r);
    }
}

TEST(SeamBlur, AConstantReflectionStaysConstant) {
    Halves h(0.5f, 0.5f);
    blurReflectionSeams(h.reflection, h.source, kW, kH, 3);
    for (const glm::vec3& v : h.reflection) EXPECT_NEAR(v.r, 0.5f, 1e-6f);
}

TEST(SeamBlur, TexelsWithoutAReflectionDoNotBleedIn) {
    Halves h(1.0f, 0.0f);
    for (int x = 0; x < kW; ++x) {  // the top row reflects nothing and holds a large value
        h.source[x] = ReflectionSource::None;
        h.reflection[x] = glm::vec3(100.0f);
    }
    blurReflectionSeams(h.reflection, h.source, kW, kH, 2);
    for (int i = kW; i < kW * kH; ++i) EXPECT_LE(h.reflection[i].r, 1.0f) << i;
    for (int x = 0; x < kW; ++x) EXPECT_EQ(h.reflection[x].r, 100.0f);
}

TEST(SeamBlur, TheBilateralBlurSmoothsASmallSeamStepAndKeepsAReflectedEdge) {
    // A small step between the two paths' results (0.50 against 0.52): smoothed as by the Gaussian.
    Halves step(0.5f, 0.52f), stepGaussian(0.5f, 0.52f);
    blurReflectionSeams(step.reflection, step.source, kW, kH, 2, 0.1f);
    blurReflectionSeams(stepGaussian.reflection, stepGaussian.source, kW, kH, 2);
    for (int x = 7; x <= 12; ++x) EXPECT_NEAR(step.reflection[5 * kW + x].r, stepGaussian.reflection[5 * kW + x].r, 1e-3f) << x;
    EXPECT_GT(step.reflection[5 * kW + 9].r, 0.5f);
    // A thin reflected pole (one bright column) inside the band: the Gaussian smears it, the
    // bilateral blur keeps it and its dark surroundings.
    Halves pole(0.1f, 0.1f), poleGaussian(0.1f, 0.1f);
    for (Halves* h : {&pole, &poleGaussian})
        for (int y = 0; y < kH; ++y) h->reflection[y * kW + 8] = glm::vec3(2.0f);
    blurReflectionSeams(pole.reflection, pole.source, kW, kH, 2, 0.1f);
    blurReflectionSeams(poleGaussian.reflection, poleGaussian.source, kW, kH, 2);
    EXPECT_NEAR(pole.reflection[5 * kW + 8].r, 2.0f, 1e-3f);
    EXPECT_NEAR(pole.reflection[5 * kW + 9].r, 0.1f, 1e-3f);
    EXPECT_LT(poleGaussian.reflection[5 * kW + 8].r, 1.5f);
    EXPECT_GT(poleGaussian.reflection[5 * kW + 9].r, 0.3f);
}

}  // namespace
}  // namespace hybridlab
