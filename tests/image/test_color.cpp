// sRGB transfer functions (color.h): known values, the linear segment, round trips, display clamp.
#include <cmath>

#include <gtest/gtest.h>

#include "common/image/color.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

TEST(Srgb, KnownValuesAndTheLinearSegment) {
    EXPECT_FLOAT_EQ(linearToSrgb(0.0f), 0.0f);
    EXPECT_FLOAT_EQ(linearToSrgb(1.0f), 1.0f);
    EXPECT_NEAR(linearToSrgb(0.5f), 0.735357f, 1e-5f);  // 1.055 * 0.5^(1/2.4) - 0.055
    EXPECT_NEAR(linearToSrgb(0.18f), 0.461356f, 1e-5f);  // photographic mid grey
    EXPECT_NEAR(srgbToLinear(0.5f), 0.214041f, 1e-5f);
    EXPECT_NEAR(srgbToLinear(128.0f / 255.0f), 0.215861f, 1e-5f);
    EXPECT_FLOAT_EQ(srgbToLinear(0.0f), 0.0f);
    EXPECT_FLOAT_EQ(srgbToLinear(1.0f), 1.0f);

    // The linear segment near black.
    EXPECT_FLOAT_EQ(linearToSrgb(0.001f), 0.01292f);
    EXPECT_FLOAT_EQ(srgbToLinear(0.01292f), 0.001f);
    // The two pieces meet at 0.0031308 (linear) / 0.04045 (encoded).
    EXPECT_NEAR(linearToSrgb(0.0031308f), 0.04045f, 1e-5f);
    EXPECT_NEAR(srgbToLinear(0.04045f), 0.0031308f, 1e-6f);
    EXPECT_NEAR(linearToSrgb(0.0031309f), 0.04045f, 1e-5f) << "continuous across the break";
}

TEST(Srgb, RoundTripsMonotonicityAndDisplayClamp) {
    float previous = -1.0f;
    for (int i = 0; i <= 1000; ++i) {
        const float x = static_cast<float>(i) / 1000.0f;
        EXPECT_NEAR(srgbToLinear(linearToSrgb(x)), x, 2e-6f) << x;
        EXPECT_NEAR(linearToSrgb(srgbToLinear(x)), x, 2e-6f) << x;
        const float e = linearToSrgb(x);
        EXPECT_GT(e, previous) << x;
        previous = e;
    }
    const glm::vec3 v(0.1f, 0.5f, 0.9f);
    EXPECT_VEC_NEAR(srgbToLinear(linearToSrgb(v)), v, 2e-6f);
    EXPECT_VEC_NEAR(linearToSrgb(v), glm::vec3(linearToSrgb(0.1f), linearToSrgb(0.5f), linearToSrgb(0.9f)), 0.0f);

    // The display encoding clamps colour and alpha, and does not encode alpha.
    EXPECT_VEC_NEAR(linearToDisplay({-0.5f, 2.0f, 0.5f, 1.5f}), glm::vec4(0.0f, 1.0f, linearToSrgb(0.5f), 1.0f), 1e-7f);
    EXPECT_VEC_NEAR(linearToDisplay({0.25f, 0.25f, 0.25f, 0.3f}), glm::vec4(glm::vec3(linearToSrgb(0.25f)), 0.3f), 1e-7f)
        << "alpha is not encoded";
}

}  // namespace
}  // namespace hybridlab
