// gbuffer = "rays" with rays = "vulkan": primary rays on the ray-tracing device written into the
// rasterizer's G-buffer targets where they lie (common/device_rays/device_gbuffer_caster.h). The
// cast G-buffer, read back from those targets, equals the rasterized one within the bounds of
// gbuffer_agreement.h (and Embree's ray-cast one), holds the same material records, and the
// hybrids that read it render as with Embree's ray-cast G-buffer, one primary ray a pixel.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "common/core/input_error.h"
#include "common/device_rays/device_gbuffer_caster.h"
#include "common/raster/frame_pass.h"
#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "metrics/metrics.h"
#include "techniques/scene_context.h"
#include "tests/support/gbuffer_agreement.h"
#include "tests/support/raster_test_support.h"
#include "tests/support/technique_test_support.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

constexpr GBufferTargets kCompared = kGBufferPosition | kGBufferNormal | kGBufferMaterial | kGBufferObjectId;

// One view's G-buffer from the rasterizer's pass and from the device's primary rays, both read
// back from the rasterizer's targets on the ray-tracing device.
struct BothGBuffers {
    GBuffer raster, cast;
    DeviceGBufferCast work;
    RasterFrame castFrame;  // the frame that read the cast targets
};

// At `time`, after a frame at t = 0 when `time` > 0 (so that the frame at `time` moves, and refits, what moved).
BothGBuffers renderBoth(const Scene& scene, double time, int width, int height) {
    SceneContext context(scene);
    Rasterizer& rasterizer = context.rasterizer({.rayTracing = true});
    RasterRequest request;
    request.camera = scene.camera;
    request.width = width;
    request.height = height;
    request.readback = kCompared;
    request.lighting = false;
    if (time > 0.0) {
        rasterizer.render(request);
        context.deviceRayScene(0.0);
    }
    request.time = time;
    BothGBuffers b;
    b.raster = rasterizer.render(request).gbuffer;
    DeviceGBufferCaster caster(context.deviceRayScene(time));
    b.work = caster.cast(rasterizer.gbufferStorage(width, height), scene.camera);
    request.deviceGBuffer = true;
    b.castFrame = rasterizer.render(request);
    b.cast = b.castFrame.gbuffer;
    return b;
}

// Where the ids agree, the material records the cast wrote against the G-buffer pass's: the
// untextured ones (emission, specular, optical) equal, the textured ones (ambient, diffuse) within
// what filtering over the ray cone instead of screen-space gradients changes (mean |difference|).
void expectSameMaterials(const BothGBuffers& b) {
    std::size_t compared = 0, differing = 0;
    double texturedDifference = 0.0;
    for (std::size_t i = 0; i < b.cast.pixelCount(); ++i) {
        if (b.cast.objectId[i] == kSkyObjectId || b.cast.objectId[i] != b.raster.objectId[i]) continue;
        ++compared;
        differing += glm::vec3(b.cast.emission[i]) != glm::vec3(b.raster.emission[i]) || b.cast.specular[i] != b.raster.specular[i] ||
                     b.cast.optical[i] != b.raster.optical[i];
        texturedDifference += glm::length(glm::vec3(b.cast.diffuse[i]) - glm::vec3(b.raster.diffuse[i]));
    }
    ASSERT_GT(compared, 0u);
    texturedDifference /= static_cast<double>(compared);
    std::printf("[ device   ] materials: %zu of %zu texels differ in emission, specular or optical; diffuse mean |difference| %.4f\n",
                differing, compared, texturedDifference);
    EXPECT_EQ(differing, 0u);
    EXPECT_LT(texturedDifference, 0.02);
}

// Every check of one view: the cast against the rasterized G-buffer (returned), against Embree's
// cast, its materials, one primary ray a pixel and no G-buffer pass.
test::GBufferAgreement expectCastAgrees(const Scene& scene, const BothGBuffers& b, const RayScene& rays) {
    const double diagonal = glm::length(scene.bounds(rays.time()).extent());
    const test::GBufferAgreement raster = test::compareGBuffers(b.cast, b.raster, diagonal);
    std::printf("[ device   ] %s: %zu covered pixels, ids agree with the raster on %.4f%%; where they do: %zu outliers, elsewhere max "
                "position error %.3g of the diagonal and max normal error %.4f deg; facing agrees on %zu of %zu; geometric normals "
                "differ on %zu\n",
                scene.name.c_str(), raster.covered, 100.0 * raster.idAgreement(), raster.outliers, raster.maxPositionError,
                raster.maxNormalDegrees, raster.facingMatches, raster.idMatches, raster.geometricOutliers);
    EXPECT_GT(raster.covered, b.cast.pixelCount() / 10);
    test::expectGBuffersAgree(raster);
    EXPECT_GE(raster.facingMatches, raster.idMatches - raster.idMatches / 1000);
    EXPECT_LE(raster.geometricOutliers, raster.idMatches / 1000);

    // The same rays on Embree: the two backends' casts agree at least as well.
    const test::GBufferAgreement embree = test::compareWithPrimaryRays(rays, b.cast);
    std::printf("[ device   ] %s: ids agree with Embree's cast on %.4f%%, %zu outliers, max position error %.3g, max normal error %.4f deg\n",
                scene.name.c_str(), 100.0 * embree.idAgreement(), embree.outliers, embree.maxPositionError, embree.maxNormalDegrees);
    test::expectGBuffersAgree(embree);

    expectSameMaterials(b);
    EXPECT_EQ(b.work.primaryRays, b.cast.pixelCount());
    EXPECT_GT(b.work.gpuMilliseconds, 0.0);
    EXPECT_EQ(b.castFrame.gpuMilliseconds("gbuffer"), 0.0);  // the G-buffer pass did not run
    EXPECT_EQ(b.castFrame.draws, 0u);
    return raster;
}

class DeviceGBufferRays : public ::testing::TestWithParam<const char*> {};

TEST_P(DeviceGBufferRays, EqualsTheRasterizedGBuffer) {
    REQUIRE_RAY_TRACING_DEVICE();
    const Scene scene = loadSceneFile(findSceneFile(GetParam()));
    const BothGBuffers b = renderBoth(scene, 0.0, 320, 180);
    expectCastAgrees(scene, b, RayScene(scene));
}

INSTANTIATE_TEST_SUITE_P(Device, DeviceGBufferRays, ::testing::Values("whitted-classic", "cornell-mirror-glass", "sponza-spheres"),
                         test::SceneTestName());

// The deforming object of the raster's test at t = 0.7 s: the device's refitted bottom level and
// moved instance hold the surface the rasterizer's re-uploaded vertices hold.
TEST(DeviceGBufferRaysOnADeformingObject, EqualsTheRasterizedGBuffer) {
    REQUIRE_RAY_TRACING_DEVICE();
    test::TempDir dir;
    test::writeTextFile(dir / "wave.toml", test::kDeformingObjectScene);
    const Scene scene = loadSceneFile(dir / "wave.toml");
    const BothGBuffers b = renderBoth(scene, 0.7, 160, 90);
    RayScene rays(scene);
    rays.setTime(0.7);
    EXPECT_GT(expectCastAgrees(scene, b, rays).covered, 160u * 90u / 2u);
}

// The rasterizer reads a cast G-buffer only at the size it was cast, and has no depth target of it.
TEST(DeviceGBufferRaysMisuse, AFrameOfAnotherSizeOrAskingForDepthIsRefused) {
    REQUIRE_RAY_TRACING_DEVICE();
    const Scene scene = loadSceneFile(findSceneFile("whitted-classic"));
    SceneContext context(scene);
    Rasterizer& rasterizer = context.rasterizer({.rayTracing = true});
    DeviceGBufferCaster caster(context.deviceRayScene(0.0));
    caster.cast(rasterizer.gbufferStorage(64, 36), scene.camera);
    RasterRequest request;
    request.camera = scene.camera;
    request.width = 32;
    request.height = 18;
    request.deviceGBuffer = true;
    EXPECT_THROW(rasterizer.render(request), VulkanError);
    request.width = 64;
    request.height = 36;
    request.readback = kGBufferDepth;
    EXPECT_THROW(rasterizer.render(request), VulkanError);
    request.readback = kGBufferObjectId;
    request.occlusionQueries = true;
    EXPECT_THROW(rasterizer.render(request), VulkanError);
    request.occlusionQueries = false;
    EXPECT_EQ(rasterizer.render(request).gbuffer.objectId.size(), 64u * 36u);
}

bool hasStage(const FrameResult& r, const std::string& name) {
    return std::any_of(r.stages.begin(), r.stages.end(), [&](const StageTime& s) { return s.name == name; });
}

// A hybrid with gbuffer = "rays" on both backends at 160x90: SSIM >= 0.995, one primary ray a
// pixel on each, the secondary rays within 1%; the device's frame casts its G-buffer (stage
// gbuffer.rays) and neither rasterizes it nor uploads it.
void expectCastOnBothBackendsAgrees(const std::string& technique, const std::string& sceneName) {
    SCOPED_TRACE(technique + " on " + sceneName);
    const Scene scene = loadSceneFile(findSceneFile(sceneName));
    constexpr int kWidth = 160, kHeight = 90;
    auto on = [&](const std::string& rays) {
        return test::renderFrame(scene, technique, {{"gbuffer", std::string("rays")}, {"rays", rays}}, kWidth, kHeight);
    };
    const FrameResult embree = on("embree"), device = on("vulkan");
    const double ssim = computeMetrics(device.image, embree.image).whole.ssim;
    std::printf("[ device   ] %s %s gbuffer = rays: SSIM vulkan against embree %.5f", sceneName.c_str(), technique.c_str(), ssim);
    EXPECT_GE(ssim, 0.995);
    EXPECT_EQ(device.counters.at("rays_primary"), static_cast<double>(kWidth * kHeight));
    EXPECT_EQ(device.counters.at("rays_primary"), embree.counters.at("rays_primary"));
    for (const char* kind : {"rays_shadow", "rays_reflection", "rays_refraction"}) {
        const double e = embree.counters.at(kind), d = device.counters.at(kind);
        EXPECT_LE(std::abs(d - e), 0.01 * e + 10.0) << kind << ": vulkan " << d << ", embree " << e;
        std::printf(", %s %.0f / %.0f", kind + 5, d, e);
    }
    std::printf("\n");
    EXPECT_TRUE(hasStage(device, "gbuffer.rays"));
    EXPECT_FALSE(hasStage(device, "gbuffer"));
    EXPECT_FALSE(hasStage(device, "gbuffer.upload"));
    EXPECT_TRUE(hasStage(embree, "gbuffer.upload"));
}

TEST(DeviceGBufferRaysInHybrids, HeuristicRtAgreesWithEmbreesCastOnTheFourScenes) {
    REQUIRE_RAY_TRACING_DEVICE();
    for (const char* scene : {"whitted-classic", "cornell-mirror-glass", "sponza-spheres", "teapot-lens"})
        expectCastOnBothBackendsAgrees("heuristic_rt", scene);
}

TEST(DeviceGBufferRaysInHybrids, SsrFallbackAgreesWithEmbreesCastOnTheFourScenes) {
    REQUIRE_RAY_TRACING_DEVICE();
    for (const char* scene : {"whitted-classic", "cornell-mirror-glass", "sponza-spheres", "teapot-lens"})
        expectCastOnBothBackendsAgrees("ssr_fallback", scene);
}

// What stays refused with rays = "vulkan" is what the Embree cast refuses too: occlusion queries
// need the G-buffer pass. Said when the technique is created, before any device is asked for.
TEST(DeviceGBufferRaysInHybrids, OcclusionQueriesStillNeedTheRasterizedGBuffer) {
    try {
        createTechnique("heuristic_rt",
                        {{"rays", std::string("vulkan")}, {"gbuffer", std::string("rays")}, {"visible_pixels", std::string("queries")}});
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        EXPECT_CONTAINS(e.what(), "heuristic_rt: visible_pixels = \"queries\" needs the rasterizer's G-buffer (gbuffer = \"raster\")");
    }
    for (const char* technique : {"heuristic_rt", "ssr_fallback"})
        EXPECT_NO_THROW(createTechnique(technique, {{"rays", std::string("vulkan")}, {"gbuffer", std::string("rays")}})) << technique;
}

}  // namespace
}  // namespace hybridlab
