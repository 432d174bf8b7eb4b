// ssr_fallback's stage settings as the device reads them (ssr_texel.h, packSsrOptions and
// unpackSsrPolicy, one text for C++ and GLSL): every combination comes back as it went in, and
// the bits are those the device's shaders test directly (shadows, SSR off).
#include "techniques/ssr_fallback/shaders/ssr_texel.h"

#include <gtest/gtest.h>

namespace hybridlab {
namespace {

namespace sl = shading_language;

TEST(SsrTexelOptions, EveryPolicyComesBackAsItWentIn) {
    for (int bits = 0; bits < 16; ++bits) {
        for (int fallback : {sl::kSsrFallbackRayTraced, sl::kSsrFallbackSky, sl::kSsrFallbackNone}) {
            for (bool ssrOn : {false, true}) {
                const sl::SsrTexelPolicy in{(bits & 1) != 0, (bits & 2) != 0, fallback, (bits & 4) != 0};
                const std::uint32_t word = sl::packSsrOptions(in, ssrOn);
                const sl::SsrTexelPolicy out = sl::unpackSsrPolicy(word);
                SCOPED_TRACE(word);
                EXPECT_EQ(out.rayTracedShadows, in.rayTracedShadows);
                EXPECT_EQ(out.ssrRefracts, in.ssrRefracts);
                EXPECT_EQ(out.fallback, in.fallback);
                EXPECT_EQ(out.recursionTraced, in.recursionTraced);
                EXPECT_EQ((word & sl::kSsrOptionSsrOff) != 0, !ssrOn);
                EXPECT_EQ((word & sl::kSsrOptionRayTracedShadows) != 0, in.rayTracedShadows);
                EXPECT_LT(word, 64u);
            }
        }
    }
}

}  // namespace
}  // namespace hybridlab
