// gbuffer = "rays" in the hybrid techniques: the G-buffer from primary rays instead of the
// rasterizer's pass, everything after it unchanged. The frame is then the rasterized G-buffer's
// frame up to where the two G-buffers legitimately differ (silhouette pixels, texture filtering:
// test_raster_gbuffer.cpp holds the G-buffers themselves to each other), it casts one primary ray
// a pixel, and the G-buffer pass does not run.
#include <algorithm>
#include <cstdio>

#include <gtest/gtest.h>

#include "common/core/input_error.h"
#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "metrics/metrics.h"
#include "tests/support/raster_test_support.h"
#include "tests/support/ssr_scenes.h"
#include "tests/support/technique_test_support.h"

namespace hybridlab {
namespace {

constexpr int kWidth = 160, kHeight = 90;

bool hasStage(const FrameResult& r, const std::string& name) {
    return std::any_of(r.stages.begin(), r.stages.end(), [&](const StageTime& s) { return s.name == name; });
}

struct Case {
    const char* technique;
    const char* scene;
    test::TechniqueParams params;
};

TEST(GBufferRays, FramesMatchTheRasterizedGBuffersAndCastOnePrimaryRayAPixel) {
    const std::vector<Case> cases = {
        {"heuristic_rt", "cornell-mirror-glass", {}},
        {"heuristic_rt", "whitted-classic", {{"budget", 2e4}}},
        {"ssr_fallback", "whitted-classic", {}},
        {"ssr_fallback", "mirror-floor", {{"shadows", std::string("rt")}}},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(std::string(c.technique) + " on " + c.scene);
        const Scene scene = std::string(c.scene) == "mirror-floor" ? test::mirrorFloorScene(0.8f) : loadSceneFile(findSceneFile(c.scene));
        RASTERIZER_OR_SKIP(probe, scene);
        test::TechniqueParams rays = c.params;
        rays.push_back({"gbuffer", std::string("rays")});
        // Two frames: the second is the steady state (heuristic_rt's selection keeps last frame's objects).
        const FrameResult raster = test::renderFrame(scene, c.technique, c.params, kWidth, kHeight, 2);
        const FrameResult cast = test::renderFrame(scene, c.technique, rays, kWidth, kHeight, 2);
        const double ssim = computeMetrics(cast.image, raster.image).whole.ssim;
        std::printf("[ gbuffer  ] %s on %s: SSIM gbuffer rays against raster %.5f; rays %g against %g\n", c.technique, c.scene, ssim,
                    cast.counters.at("rays_total"), raster.counters.at("rays_total"));
        EXPECT_GE(ssim, 0.98);
        EXPECT_EQ(cast.counters.at("rays_primary"), static_cast<double>(kWidth * kHeight));
        EXPECT_EQ(raster.counters.at("rays_primary"), 0.0);
        // The secondary rays start from nearly the same texels.
        const double secondary = cast.counters.at("rays_total") - cast.counters.at("rays_primary");
        EXPECT_NEAR(secondary, raster.counters.at("rays_total"), 0.02 * raster.counters.at("rays_total") + 10.0);
        EXPECT_TRUE(hasStage(cast, "gbuffer.rays"));
        EXPECT_FALSE(hasStage(raster, "gbuffer.rays"));
        EXPECT_TRUE(hasStage(cast, "gbuffer.upload"));
        EXPECT_FALSE(hasStage(cast, "gbuffer"));  // the G-buffer pass
        if (std::string(c.technique) == "ssr_fallback") {
            EXPECT_NEAR(cast.counters.at("ssr_hits"), raster.counters.at("ssr_hits"), 0.02 * raster.counters.at("ssr_hits") + 5.0);
            EXPECT_GT(raster.counters.at("ssr_hits"), 0.0);
        }
    }
}

TEST(GBufferRays, OcclusionQueriesNeedTheRasterizedGBuffer) {
    EXPECT_THROW(createTechnique("heuristic_rt", {{"gbuffer", std::string("rays")}, {"visible_pixels", std::string("queries")}}), InputError);
}

}  // namespace
}  // namespace hybridlab
