// Work counts that carry over between machines: the G-buffer pass's fragment-shader invocations
// (a Vulkan pipeline-statistics query) on a scene without overdraw are the pixels it covers; SSR's
// march steps are the same on two runs and grow with max_steps.
#include <cstdio>

#include <gtest/gtest.h>

#include "common/raster/rasterizer.h"
#include "common/scene/scene_file.h"
#include "tests/support/raster_test_support.h"
#include "tests/support/ssr_scenes.h"
#include "tests/support/technique_test_support.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

TEST(WorkCounts, GBufferFragmentInvocationsAreTheCoveredPixels) {
    test::TempDir dir;
    // One quad, seen at an angle, covering part of the view: every covered pixel is shaded once.
    test::writeTextFile(dir / "quad.toml", R"(
[materials.grey]
diffuse = [0.6, 0.6, 0.6]

[[objects]]
name = "quad"
primitive = "plane"
material = "grey"
scale = [2.0, 1.0, 2.0]

[camera]
position = [0.5, 2.0, 3.0]
look_at = [0.0, 0.0, 0.0]
)");
    const Scene scene = loadSceneFile(dir / "quad.toml");
    RASTERIZER_OR_SKIP(raster, scene);
    RasterRequest request;
    request.camera = scene.camera;
    request.width = 320;
    request.height = 180;
    request.readback = kGBufferObjectId;
    request.lighting = true;
    const RasterFrame frame = raster->render(request);
    const auto stage = [&](const std::string& name) -> const RasterStageTime& {
        for (const RasterStageTime& s : frame.gpuStages)
            if (s.name == name) return s;
        throw std::runtime_error("no stage " + name);
    };
    if (!stage("gbuffer").counted) GTEST_SKIP() << "the Vulkan device has no pipeline-statistics queries";
    std::size_t covered = 0;
    for (std::uint32_t id : frame.gbuffer.objectId) covered += id != kSkyObjectId;
    const RasterStageTime& g = stage("gbuffer");
    std::printf("[ work     ] quad: %zu covered pixels; G-buffer pass: %llu fragment invocations, %llu input and %llu clipped primitives\n",
                covered, static_cast<unsigned long long>(g.fragmentInvocations), static_cast<unsigned long long>(g.inputPrimitives),
                static_cast<unsigned long long>(g.clippingPrimitives));
    EXPECT_GT(covered, 320u * 180u / 10u);
    EXPECT_LT(covered, 320u * 180u * 9u / 10u);
    EXPECT_NEAR(static_cast<double>(g.fragmentInvocations), static_cast<double>(covered), 0.02 * static_cast<double>(covered));
    EXPECT_GT(g.inputPrimitives, 0u);
    // The lighting pass is one full-screen draw: a fragment per pixel, no compute.
    EXPECT_NEAR(static_cast<double>(stage("lighting").fragmentInvocations), 320.0 * 180.0, 0.02 * 320.0 * 180.0);
    EXPECT_EQ(stage("gbuffer").computeInvocations, 0u);
}

TEST(WorkCounts, SsrStepsRepeatAndGrowWithMaxSteps) {
    const Scene scene = test::mirrorFloorScene(0.8f);
    RASTERIZER_OR_SKIP(probe, scene);
    constexpr int kWidth = 160, kHeight = 90;
    auto steps = [&](long long maxSteps) {
        const FrameResult r = test::renderFrame(scene, "ssr_fallback", {{"traversal", std::string("linear")}, {"max_steps", maxSteps}},
                                                kWidth, kHeight);
        EXPECT_LE(r.counters.at("ssr_steps_per_reflective_pixel"), static_cast<double>(maxSteps));
        EXPECT_GT(r.counters.at("ssr_steps_per_reflective_pixel"), 0.0);
        return r.counters.at("ssr_march_steps");
    };
    const double s8 = steps(8), s32 = steps(32), s32again = steps(32), s128 = steps(128);
    std::printf("[ work     ] SSR march steps at max_steps 8, 32, 32, 128: %.0f %.0f %.0f %.0f\n", s8, s32, s32again, s128);
    EXPECT_EQ(s32, s32again);
    EXPECT_LT(s8, s32);
    EXPECT_LT(s32, s128);
}

}  // namespace
}  // namespace hybridlab
