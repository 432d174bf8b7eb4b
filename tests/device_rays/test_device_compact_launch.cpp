// The hybrids' ray stage on the device launched compacted (launch = "compact",
// DeviceGBufferTracer::setCompactLaunch): a classification pass lists the texels the
// ray-generation shader must see, writes the others' outputs itself, and the trace is launched
// over the list alone (vkCmdTraceRaysIndirectKHR). Its images and debug images equal the full
// launch's byte for byte, it traces the same rays, and it launches exactly the listed texels.
#include <cstdio>
#include <cstring>
#include <string>

#include <gtest/gtest.h>

#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "tests/support/raster_test_support.h"
#include "tests/support/technique_test_support.h"

namespace hybridlab {
namespace {

constexpr int kWidth = 48, kHeight = 27;

bool sameBytes(const Image& a, const Image& b) {
    return a.width() == b.width() && a.height() == b.height() &&
           std::memcmp(a.data(), b.data(), a.pixelCount() * sizeof(*a.data())) == 0;
}

void expectCompactLaunchEqualsFull(const std::string& technique, const test::TechniqueParams& params) {
    for (const char* sceneName : {"whitted-classic", "cornell-mirror-glass", "sponza-spheres"}) {
        SCOPED_TRACE(technique + " on " + sceneName);
        const Scene scene = loadSceneFile(findSceneFile(sceneName));
        auto render = [&](const char* launch) {
            test::TechniqueParams p = params;
            p.push_back({"rays", std::string("vulkan")});
            p.push_back({"launch", std::string(launch)});
            return test::renderFrame(scene, technique, p, kWidth, kHeight);
        };
        const FrameResult full = render("full"), compact = render("compact");
        EXPECT_TRUE(sameBytes(compact.image, full.image));
        ASSERT_EQ(compact.debugImages.size(), full.debugImages.size());
        for (const auto& [name, image] : full.debugImages) EXPECT_TRUE(sameBytes(compact.debugImages.at(name), image)) << name;
        for (const char* kind : {"rays_primary", "rays_shadow", "rays_reflection", "rays_refraction", "pixels_ray_traced"})
            EXPECT_EQ(compact.counters.at(kind), full.counters.at(kind)) << kind;

        const auto& c = compact.counters;
        EXPECT_EQ(full.counters.at("trace_invocations_launched"), kWidth * kHeight);
        EXPECT_EQ(full.counters.count("trace_texels_listed"), 0u);
        EXPECT_EQ(c.at("trace_invocations_launched"), c.at("trace_texels_listed"));
        EXPECT_EQ(c.at("trace_invocations_traced"), full.counters.at("trace_invocations_traced"));
        EXPECT_LE(c.at("trace_invocations_traced"), c.at("trace_invocations_launched"));
        std::printf("[ device   ] %s %s: full launch %.0f invocations, compacted %.0f listed, %.0f of them traced\n", sceneName,
                    technique.c_str(), full.counters.at("trace_invocations_launched"), c.at("trace_texels_listed"),
                    c.at("trace_invocations_traced"));
    }
}

// A budget that leaves objects out, so that the list is a part of the frame.
TEST(DeviceCompactLaunch, HeuristicRtEqualsTheFullLaunchOnThreeScenes) {
    REQUIRE_RAY_TRACING_DEVICE();
    expectCompactLaunchEqualsFull("heuristic_rt", {{"budget", 2000.0}});
    expectCompactLaunchEqualsFull("heuristic_rt", {{"gbuffer", std::string("rays")}});
}

TEST(DeviceCompactLaunch, SsrFallbackEqualsTheFullLaunchOnThreeScenes) {
    REQUIRE_RAY_TRACING_DEVICE();
    expectCompactLaunchEqualsFull("ssr_fallback", {});
    expectCompactLaunchEqualsFull("ssr_fallback", {{"shadows", std::string("rt")}});
}

}  // namespace
}  // namespace hybridlab
