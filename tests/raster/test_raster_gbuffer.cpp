// The G-buffer against the reference's primary rays, within the bounds gbuffer_agreement.h states
// (DESIGN.md "Invariants that tests hold"), and the two ways of counting visible pixels per object
// (Walewski 2019 §3.2's A) agree.
#include <cstdio>
#include <limits>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "common/raster/rasterizer.h"
#include "common/raytrace/ray_scene.h"
#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "techniques/shared/ray_cast_gbuffer.h"
#include "tests/support/gbuffer_agreement.h"
#include "tests/support/raster_test_support.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

using test::compareWithPrimaryRays;
using test::GBufferAgreement;

constexpr int kWidth = 640, kHeight = 360;

class GBufferAgreesWithPrimaryRays : public ::testing::TestWithParam<const char*> {};

TEST_P(GBufferAgreesWithPrimaryRays, OnTheScene) {
    const std::string name = GetParam();
    const Scene scene = loadSceneFile(findSceneFile(name));
    RASTERIZER_OR_SKIP(raster, scene);
    RasterRequest request;
    request.camera = scene.camera;
    request.width = kWidth;
    request.height = kHeight;
    request.readback = kGBufferPosition | kGBufferNormal | kGBufferGeometricNormal | kGBufferObjectId;
    request.lighting = false;
    const RasterFrame frame = raster->render(request);
    const GBufferAgreement a = compareWithPrimaryRays(RayScene(scene), frame.gbuffer);
    std::printf("[ raster   ] %s: %zu covered pixels, ids agree on %.4f%%; where they do: %zu outliers (creases, inner "
                "silhouettes, coincident faces), elsewhere max position error %.3g of the diagonal and max normal error %.4f deg; "
                "facing agrees on %zu of %zu; geometric normals differ on %zu\n",
                name.c_str(), a.covered, 100.0 * a.idAgreement(), a.outliers, a.maxPositionError, a.maxNormalDegrees, a.facingMatches,
                a.idMatches, a.geometricOutliers);
    RecordProperty("id_agreement", std::to_string(a.idAgreement()));
    RecordProperty("outliers", std::to_string(a.outliers));
    EXPECT_GT(a.covered, static_cast<std::size_t>(kWidth * kHeight / 10));
    test::expectGBuffersAgree(a);
    EXPECT_GE(a.facingMatches, a.idMatches - a.idMatches / 1000);
    EXPECT_LE(a.geometricOutliers, a.idMatches / 1000);
}

class VisiblePixelCounts : public ::testing::TestWithParam<const char*> {};

// A deforming object (a `deform` block, deformation.h) beside a rigidly moving one, at t > 0 after
// a frame at t = 0: the rasterizer's re-uploaded vertices and the refitted Embree BVH hold the same
// surface, within the same bounds as the static scenes; and it did deform (the G-buffer is far from
// the rest pose's hits on many pixels).
TEST(GBufferAgreesWithPrimaryRays, OnADeformingObject) {
    test::TempDir dir;
    test::writeTextFile(dir / "wave.toml", test::kDeformingObjectScene);
    const Scene scene = loadSceneFile(dir / "wave.toml");
    RASTERIZER_OR_SKIP(raster, scene);
    RasterRequest request;
    request.camera = scene.camera;
    request.width = 160;
    request.height = 90;
    request.readback = kGBufferPosition | kGBufferNormal | kGBufferGeometricNormal | kGBufferObjectId;
    request.lighting = false;
    raster->render(request);  // t = 0 first: the frame at t updates what moved
    request.time = 0.7;
    const RasterFrame frame = raster->render(request);
    RayScene rays(scene);
    const RayScene rest(scene);
    rays.setTime(request.time);
    EXPECT_EQ(rays.deformingTriangles(), scene.objectTriangleCount(1));
    EXPECT_EQ(rays.rigidMovingTriangles(), scene.objectTriangleCount(2));
    const GBufferAgreement a = compareWithPrimaryRays(rays, frame.gbuffer);
    std::printf("[ raster   ] deforming: %zu covered pixels, ids agree on %.4f%%, %zu outliers, max position error %.3g, "
                "max normal error %.4f deg\n",
                a.covered, 100.0 * a.idAgreement(), a.outliers, a.maxPositionError, a.maxNormalDegrees);
    EXPECT_GT(a.covered, 160u * 90u / 2u);
    test::expectGBuffersAgree(a);

    const GBuffer& g = frame.gbuffer;
    std::size_t deformedPixels = 0;
    for (int y = 0; y < g.height; ++y) {
        for (int x = 0; x < g.width; ++x) {
            const std::size_t i = g.index(x, y);
            if (g.objectId[i] != 2u) continue;  // the ball
            const Ray ray = scene.camera.rayThroughNdc(pixelCenterNdc(x, y, g.width, g.height), 160.0f / 90.0f);
            SurfaceHit hit;
            if (!rest.intersect(ray, 0.0f, std::numeric_limits<float>::infinity(), hit) || hit.object != 1) continue;
            deformedPixels += glm::length(glm::vec3(g.position[i]) - hit.position) > 0.01f;
        }
    }
    EXPECT_GT(deformedPixels, 500u) << "the ball deforms";
}

// Walewski 2019 counts an object's visible pixels A with occlusion queries in a depth-equal pass
// (Listing 6); counting object ids in the read-back target gives the same numbers.
TEST_P(VisiblePixelCounts, FromTheIdTargetEqualTheOcclusionQueries) {
    const std::string name = GetParam();
    const Scene scene = loadSceneFile(findSceneFile(name));
    RASTERIZER_OR_SKIP(raster, scene);
    RasterRequest request;
    request.camera = scene.camera;
    request.width = kWidth;
    request.height = kHeight;
    request.readback = kGBufferObjectId;
    request.lighting = false;
    request.occlusionQueries = true;
    const RasterFrame frame = raster->render(request);
    const std::vector<std::uint64_t> fromIds = visiblePixelsFromIds(frame.gbuffer, scene.objects.size());
    ASSERT_EQ(frame.visiblePixelsByQuery.size(), scene.objects.size());
    std::size_t visibleObjects = 0;
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        EXPECT_EQ(fromIds[o], frame.visiblePixelsByQuery[o]) << scene.objects[o].name;
        visibleObjects += fromIds[o] > 0;
    }
    EXPECT_GE(visibleObjects, 2u);  // the comparison is not vacuous
}

// The lighting pass of a G-buffer uploaded from the host (as gbuffer = "rays" hands the ray-cast
// one over) is the lighting pass of the rasterized one when the upload holds what the G-buffer pass
// wrote: the read-back targets, uploaded again, light to the same image bit for bit (the 16-bit
// targets round-trip exactly). And a ray-cast G-buffer lights to nearly the same image.
TEST(GBufferUpload, LightsAsTheRasterizedGBuffer) {
    const Scene scene = loadSceneFile(findSceneFile("cornell-mirror-glass"));
    RASTERIZER_OR_SKIP(raster, scene);
    RasterRequest request;
    request.camera = scene.camera;
    request.width = 160;
    request.height = 90;
    request.readback = kGBufferPosition | kGBufferNormal | kGBufferMaterial | kGBufferObjectId;
    request.lighting = true;
    request.lightingOptions.shadows = true;
    const RasterFrame rasterized = raster->render(request);
    ASSERT_GT(rasterized.gpuMilliseconds("gbuffer"), 0.0);

    RasterRequest upload = request;
    upload.hostGBuffer = &rasterized.gbuffer;
    const RasterFrame uploaded = raster->render(upload);
    EXPECT_EQ(uploaded.gpuMilliseconds("gbuffer"), 0.0);  // the G-buffer pass did not run
    EXPECT_GT(uploaded.gpuMilliseconds("gbuffer.upload"), 0.0);
    EXPECT_EQ(uploaded.draws, 0u);
    ASSERT_EQ(uploaded.lighting.width(), 160);
    std::size_t differing = 0;
    for (std::size_t i = 0; i < rasterized.gbuffer.pixelCount(); ++i) differing += uploaded.lighting.data()[i] != rasterized.lighting.data()[i];
    EXPECT_EQ(differing, 0u);

    GBuffer cast;
    RayStats stats;
    rayCastGBuffer(RayScene(scene), scene.camera, 160, 90, request.readback, cast, stats);
    upload.hostGBuffer = &cast;
    const RasterFrame fromRays = raster->render(upload);
    double meanAbs = 0.0;
    for (std::size_t i = 0; i < cast.pixelCount(); ++i)
        meanAbs += glm::length(glm::vec3(fromRays.lighting.data()[i] - rasterized.lighting.data()[i])) / cast.pixelCount();
    std::printf("[ raster   ] lighting a ray-cast G-buffer: mean |difference| %.4g to the rasterized one's\n", meanAbs);
    EXPECT_LT(meanAbs, 0.01);

    // A host G-buffer of another size, or without every colour target, is refused.
    GBuffer partial = cast;
    partial.targets = kGBufferPosition;
    upload.hostGBuffer = &partial;
    EXPECT_THROW(raster->render(upload), VulkanError);
}

INSTANTIATE_TEST_SUITE_P(Raster, VisiblePixelCounts, ::testing::Values("whitted-classic", "cornell-mirror-glass", "sponza-spheres"),
                         test::SceneTestName());

INSTANTIATE_TEST_SUITE_P(Raster, GBufferAgreesWithPrimaryRays, ::testing::Values("whitted-classic", "cornell-mirror-glass", "sponza-spheres"),
                         test::SceneTestName());

}  // namespace
}  // namespace hybridlab
