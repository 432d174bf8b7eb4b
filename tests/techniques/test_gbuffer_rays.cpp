// gbuffer = "rays" in the hybrid techniques: the G-buffer from primary rays instead of the
// rasterizer's pass, everything after it unchanged. The frame is then the rasterized G-buffer's
// frame up to where the two G-buffers legitimately differ (silhouette pixels, texture filtering:
// test_raster_gbuffer.cpp holds the G-buffers themselves to each other), it casts one primary ray
// a pixel, and the G-buffer pass does not run.
#include <algorithm>
#include <cstdio>

#include <glm/common.hpp>

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

double maxDifference(const Image& a, const Image& b) {
    double d = 0.0;
    for (std::size_t i = 0; i < a.pixelCount(); ++i) {
        const glm::vec4 e = glm::abs(a.data()[i] - b.data()[i]);
        d = std::max(d, static_cast<double>(std::max({e.r, e.g, e.b})));
    }
    return d;
}

// heuristic_rt's lighting = "cpu": the P-buffer lit on the host by the shading model that the
// rasterizer's lighting pass computes (RasterLighting holds the two equal), on the same ray-cast
// G-buffer, so the frame is the rasterizer-lit one (shadows off in both: the maps are the
// rasterizer's) while no rasterizer stage runs.
TEST(GBufferRays, HeuristicCpuLightingEqualsTheRasterizersLightingPass) {
    const test::TechniqueParams cpu = {{"gbuffer", std::string("rays")}, {"raster_shadows", std::string("off")},
                                       {"lighting", std::string("cpu")}, {"budget", 2e4}};
    const test::TechniqueParams raster = {{"gbuffer", std::string("rays")}, {"raster_shadows", std::string("off")}, {"budget", 2e4}};
    for (const char* name : {"whitted-classic", "cornell-mirror-glass", "sponza-spheres"}) {
        SCOPED_TRACE(name);
        const Scene scene = loadSceneFile(findSceneFile(name));
        const FrameResult onCpu = test::renderFrame(scene, "heuristic_rt", cpu, kWidth, kHeight, 2);
        EXPECT_TRUE(hasStage(onCpu, "lighting.cpu"));
        for (const char* rasterStage : {"gbuffer.upload", "lighting", "readback", "overhead", "shadow_maps"})
            EXPECT_FALSE(hasStage(onCpu, rasterStage)) << rasterStage;
        EXPECT_EQ(onCpu.counters.at("rays_primary"), static_cast<double>(kWidth * kHeight));
        RASTERIZER_OR_SKIP(probe, scene);
        const FrameResult lit = test::renderFrame(scene, "heuristic_rt", raster, kWidth, kHeight, 2);
        const double ssim = computeMetrics(onCpu.image, lit.image).whole.ssim;
        const double difference = maxDifference(onCpu.image, lit.image);
        std::printf("[ lighting ] heuristic_rt on %s: lighting cpu against raster SSIM %.6f, max |difference| %.3g; %g of %d pixels traced\n",
                    name, ssim, difference, onCpu.counters.at("pixels_ray_traced"), kWidth * kHeight);
        EXPECT_GE(ssim, 0.999);
        // The same selection, so the same traced pixels and rays.
        EXPECT_EQ(onCpu.counters.at("pixels_ray_traced"), lit.counters.at("pixels_ray_traced"));
        EXPECT_EQ(onCpu.counters.at("rays_total"), lit.counters.at("rays_total"));
        EXPECT_GT(onCpu.counters.at("pixels_ray_traced"), 0.0);
    }
}

// With shadow rays in place of the maps, on a scene that neither reflects nor refracts and a budget
// that selects nothing, the CPU-lit frame is the reference's: the same primary hits, local colour
// and shadow rays.
TEST(GBufferRays, HeuristicCpuLightingWithShadowRaysIsTheReferenceOnMatteScenes) {
    Scene scene = loadSceneFile(findSceneFile("cornell-mirror-glass"));
    for (Material& m : scene.materials) {
        m.reflectivity = 0.0f;
        m.opacity = 1.0f;
        m.fresnel = false;
    }
    const test::TechniqueParams cpu = {{"gbuffer", std::string("rays")}, {"raster_shadows", std::string("rays")},
                                       {"lighting", std::string("cpu")}, {"budget", 1.0}};
    const FrameResult onCpu = test::renderFrame(scene, "heuristic_rt", cpu, kWidth, kHeight);
    const FrameResult reference = test::renderFrame(scene, "whitted", {}, kWidth, kHeight);
    const double ssim = computeMetrics(onCpu.image, reference.image).whole.ssim;
    std::printf("[ lighting ] heuristic_rt lighting cpu with shadow rays against whitted on matte cornell-mirror-glass: SSIM %.6f, "
                "max |difference| %.3g; shadow rays %g against %g\n",
                ssim, maxDifference(onCpu.image, reference.image), onCpu.counters.at("rays_shadow"), reference.counters.at("rays_shadow"));
    EXPECT_EQ(onCpu.counters.at("pixels_ray_traced"), 0.0);
    EXPECT_GE(ssim, 0.999);
    EXPECT_NEAR(onCpu.counters.at("rays_shadow"), reference.counters.at("rays_shadow"), 0.001 * reference.counters.at("rays_shadow"));
    EXPECT_GT(onCpu.counters.at("rays_shadow"), 0.0);
}

TEST(GBufferRays, CpuLightingNeedsTheRayCastGBufferAndShadowsWithoutMaps) {
    const auto make = [](const std::string& gbuffer, const std::string& lighting, const std::string& shadows) {
        return createTechnique("heuristic_rt", {{"gbuffer", gbuffer}, {"lighting", lighting}, {"raster_shadows", shadows}});
    };
    EXPECT_THROW(make("raster", "cpu", "off"), InputError);
    EXPECT_THROW(make("rays", "cpu", "map"), InputError);
    EXPECT_THROW(make("rays", "raster", "rays"), InputError);
    EXPECT_NO_THROW(make("rays", "cpu", "rays"));
    // The host lights Embree's G-buffer: with the device's rays there is none.
    EXPECT_THROW(createTechnique("heuristic_rt", {{"gbuffer", std::string("rays")}, {"lighting", std::string("cpu")},
                                                  {"raster_shadows", std::string("rays")}, {"rays", std::string("vulkan")}}),
                 InputError);
    EXPECT_NO_THROW(make("rays", "cpu", "off"));
}

TEST(GBufferRays, OcclusionQueriesNeedTheRasterizedGBuffer) {
    EXPECT_THROW(createTechnique("heuristic_rt", {{"gbuffer", std::string("rays")}, {"visible_pixels", std::string("queries")}}), InputError);
}

}  // namespace
}  // namespace hybridlab
