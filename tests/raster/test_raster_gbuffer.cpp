// The G-buffer against the reference's primary rays (DESIGN.md "Invariants that tests hold"): at
// every pixel centre the rasterised object id, world position, shading normal and geometric
// normal agree with the Whitted reference's camera-ray hit, except for a thin band of silhouette
// pixels: the ids on at least 99% of the covered pixels; where they match, the position within
// 1e-3 of the scene's bounding-box diagonal and the normals within 0.5 degree. Where the ids match,
// the only pixels allowed outside those bounds are those where the two can legitimately pick
// different triangles of one object: pixel centres on a crease between flat faces or on an edge
// between two triangles (the normal jumps), on a silhouette inside one object (Sponza is one
// object), or on coincident faces; at most 0.1% of them.
// And the two ways of counting visible pixels per object (Walewski 2019 §3.2's A) agree.
#include <cmath>
#include <cstdio>
#include <limits>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "common/raster/rasterizer.h"
#include "common/raytrace/ray_scene.h"
#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "techniques/shared/ray_cast_gbuffer.h"
#include "tests/support/raster_test_support.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

constexpr int kWidth = 640, kHeight = 360;

constexpr double kMaxPositionError = 1e-3;  // of the bounding-box diagonal
constexpr double kMaxNormalDegrees = 0.5;

struct Agreement {
    std::size_t covered = 0, idMatches = 0, facingMatches = 0;
    std::size_t outliers = 0;       // pixels whose ids match but whose position or normal is out of bounds
    double maxPositionError = 0.0;  // over the other pixels whose ids match, relative to the bounding-box diagonal
    double maxNormalDegrees = 0.0;
    std::size_t geometricOutliers = 0;  // pixels whose ids match but whose triangles' normals differ by over 0.5 degree
                                        // (a pixel centre on an edge between two triangles)
    double idAgreement() const { return covered ? static_cast<double>(idMatches) / covered : 1.0; }
};

// The rasterized G-buffer `g` against the one primary rays cast from `rays` (at the time `g` was
// rendered): the ray-cast G-buffer (techniques/shared/ray_cast_gbuffer.h) is the primary rays' hits
// in the G-buffer's form, so this is both the raster G-buffer against the reference's camera rays
// and the two G-buffer sources against each other.
Agreement compareWithPrimaryRays(const RayScene& rays, const GBuffer& g) {
    const Scene& scene = rays.scene();
    const double diagonal = glm::length(scene.bounds(rays.time()).extent());
    GBuffer cast;
    RayStats stats;
    rayCastGBuffer(rays, scene.camera, g.width, g.height, kGBufferPosition | kGBufferNormal | kGBufferGeometricNormal | kGBufferObjectId,
                   cast, stats);
    EXPECT_EQ(stats.primary, g.pixelCount());
    Agreement a;
    for (std::size_t i = 0; i < g.pixelCount(); ++i) {
        const std::uint32_t reference = cast.objectId[i];
        if (reference == kSkyObjectId && g.objectId[i] == kSkyObjectId) continue;
        ++a.covered;
        if (reference != g.objectId[i]) continue;
        ++a.idMatches;
        const double positionError = glm::length(glm::vec3(g.position[i]) - glm::vec3(cast.position[i])) / diagonal;
        const float c = std::clamp(glm::dot(glm::normalize(glm::vec3(g.normal[i])), glm::vec3(cast.normal[i])), -1.0f, 1.0f);
        const double normalDegrees = glm::degrees(std::acos(c));
        if (positionError >= kMaxPositionError || normalDegrees >= kMaxNormalDegrees) {
            ++a.outliers;
        } else {
            a.maxPositionError = std::max(a.maxPositionError, positionError);
            a.maxNormalDegrees = std::max(a.maxNormalDegrees, normalDegrees);
        }
        const float cg = std::clamp(glm::dot(g.geometricNormal(i), cast.geometricNormal(i)), -1.0f, 1.0f);
        a.geometricOutliers += glm::degrees(std::acos(cg)) > kMaxNormalDegrees;
        a.facingMatches += cast.frontFace(i) == g.frontFace(i);
    }
    return a;
}

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
    const Agreement a = compareWithPrimaryRays(RayScene(scene), frame.gbuffer);
    std::printf("[ raster   ] %s: %zu covered pixels, ids agree on %.4f%%; where they do: %zu outliers (creases, inner "
                "silhouettes, coincident faces), elsewhere max position error %.3g of the diagonal and max normal error %.4f deg; "
                "facing agrees on %zu of %zu; geometric normals differ on %zu\n",
                name.c_str(), a.covered, 100.0 * a.idAgreement(), a.outliers, a.maxPositionError, a.maxNormalDegrees, a.facingMatches,
                a.idMatches, a.geometricOutliers);
    RecordProperty("id_agreement", std::to_string(a.idAgreement()));
    RecordProperty("outliers", std::to_string(a.outliers));
    EXPECT_GT(a.covered, static_cast<std::size_t>(kWidth * kHeight / 10));
    EXPECT_GE(a.idAgreement(), 0.99);
    EXPECT_LE(a.outliers, a.idMatches / 1000);
    EXPECT_LT(a.maxPositionError, kMaxPositionError);
    EXPECT_LT(a.maxNormalDegrees, kMaxNormalDegrees);
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
    test::writeTextFile(dir / "wave.toml", R"(
[materials.grey]
diffuse = [0.6, 0.6, 0.6]

[[objects]]
name = "floor"
primitive = "plane"
material = "grey"
scale = [8.0, 1.0, 8.0]

[[objects]]
name = "ball"
primitive = "sphere"
slices = 96
stacks = 48
material = "grey"
position = [0.0, 1.0, 0.0]
scale = 2.0
[objects.deform]
amplitude = 0.06
wavelength = 0.35
speed = 0.4
direction = [1.0, 0.0, 1.0]
axis = [0.0, 1.0, 0.0]

[[objects]]
name = "box"
primitive = "cube"
material = "grey"
[objects.animation]
keys = [ { time = 0.0, position = [-2.0, 0.5, 0.0] }, { time = 1.0, position = [2.0, 0.5, 1.0], rotation = [0.0, 90.0, 0.0] } ]

[camera]
position = [0.0, 2.5, 4.5]
look_at = [0.0, 0.8, 0.0]
)");
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
    const Agreement a = compareWithPrimaryRays(rays, frame.gbuffer);
    std::printf("[ raster   ] deforming: %zu covered pixels, ids agree on %.4f%%, %zu outliers, max position error %.3g, "
                "max normal error %.4f deg\n",
                a.covered, 100.0 * a.idAgreement(), a.outliers, a.maxPositionError, a.maxNormalDegrees);
    EXPECT_GT(a.covered, 160u * 90u / 2u);
    EXPECT_GE(a.idAgreement(), 0.99);
    EXPECT_LE(a.outliers, a.idMatches / 1000);
    EXPECT_LT(a.maxPositionError, kMaxPositionError);
    EXPECT_LT(a.maxNormalDegrees, kMaxNormalDegrees);

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
    EXPECT_GT(uploaded.gpuMilliseconds("gbuffer_upload"), 0.0);
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
