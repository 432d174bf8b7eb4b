// EM layers (Hakura & Snyder 2001 §4.2): LBG on synthetic distances with known clusters, the
// whole-object rule, shell radii from frontmost intersections, the quad impostor's plane fit and
// the shell-kind choice, from intersection points and from the objects' surfaces.
#include <cmath>
#include <random>

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include "common/scene/primitives.h"
#include "common/scene/scene.h"
#include "common/scene/surface_samples.h"
#include "techniques/layered_em/layer_clustering.h"
#include "techniques/layered_em/layer_shells.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

TEST(LayerClustering, LbgFindsKnownClusters) {
    std::mt19937 rng(7);
    std::normal_distribution<float> noise(0.0f, 0.1f);
    const float truth[3] = {2.0f, 5.0f, 14.0f};
    std::vector<float> values;
    std::vector<int> label;
    for (int i = 0; i < 900; ++i) {
        values.push_back(truth[i % 3] + noise(rng));
        label.push_back(i % 3);
    }
    LbgClusters c = lbgCluster(values, 3);
    ASSERT_EQ(c.centers.size(), 3u);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(c.centers[k], truth[k], 0.02);
    for (std::size_t i = 0; i < values.size(); ++i) EXPECT_EQ(c.assignment[i], label[i]);
    EXPECT_NEAR(c.distortion, 0.01, 0.002);

    LbgClusters automatic = lbgClusterAuto(values, 5, 0.05);
    EXPECT_EQ(automatic.centers.size(), 3u) << "the smallest k under the distortion threshold";
    EXPECT_EQ(lbgClusterAuto(values, 2, 0.05).centers.size(), 2u) << "capped";
}

TEST(LayerClustering, WholeObjectsGoToTheirMajorityClusterAndShellsUseFrontmostHits) {
    // Object 0 (a cup) at 2; object 1 (a long wall) mostly at 10 but one end reaches 6, nearer to
    // the middle cluster that object 2 (columns) forms at 5. Object 1 must stay whole.
    std::vector<ClusterSample> s;
    std::uint64_t ray = 0;
    for (int i = 0; i < 100; ++i) s.push_back({2.0f, 0, ray++, 0});
    for (int i = 0; i < 100; ++i) s.push_back({5.0f, 2, ray++, 0});
    for (int i = 0; i < 80; ++i) s.push_back({10.0f, 1, ray++, 0});
    for (int i = 0; i < 20; ++i) s.push_back({6.0f, 1, ray++, 0});
    // Continued rays: one ray meets the wall twice (front then further back): only the first
    // counts for the shell distance.
    s.push_back({10.0f, 1, ray, 0});
    s.push_back({30.0f, 1, ray++, 1});
    LayerPartition p = clusterLayers(s, 4, 3);
    ASSERT_EQ(p.shellRadius.size(), 3u);
    EXPECT_EQ(p.objectLayer[0], 0);
    EXPECT_EQ(p.objectLayer[2], 1);
    EXPECT_EQ(p.objectLayer[1], 2);
    EXPECT_EQ(p.objectLayer[3], -1) << "no samples";
    for (std::size_t i = 0; i < s.size(); ++i) EXPECT_EQ(p.sampleLayer[i], p.objectLayer[s[i].object]);
    EXPECT_FALSE(p.frontmost.back());
    EXPECT_NEAR(p.shellRadius[0], 2.0, 1e-9);
    EXPECT_NEAR(p.shellRadius[1], 5.0, 1e-9);
    EXPECT_NEAR(p.shellRadius[2], (81 * 10.0 + 20 * 6.0) / 101.0, 1e-9);
    EXPECT_EQ(p.samplesPerLayer[2], 101u);
}

TEST(LayerClustering, ObjectsOnlyDirectImagesSeeJoinTheNearestShellByInverseDistance) {
    // Shells at 2 and 10 from the lens images' objects 0 and 1. Objects 2 and 3 only the direct
    // images see: 2 at 4, which is nearer the shell at 2 in distance but nearer the one at 10 in
    // inverse distance (|1/4 - 1/10| < |1/4 - 1/2|: less parallax there), and 3 at 20; object 4
    // nobody sees; object 0's direct samples change nothing.
    std::vector<ClusterSample> lens;
    std::uint64_t ray = 0;
    for (int i = 0; i < 50; ++i) lens.push_back({2.0f, 0, ray++, 0});
    for (int i = 0; i < 50; ++i) lens.push_back({10.0f, 1, ray++, 0});
    LayerPartition p = clusterLayers(lens, 5, 2);
    ASSERT_EQ(p.shellRadius.size(), 2u);
    ASSERT_EQ(p.objectLayer[2], -1);
    std::vector<ClusterSample> direct;
    for (int i = 0; i < 10; ++i) direct.push_back({4.0f, 2, ray++, 0});
    for (int i = 0; i < 10; ++i) direct.push_back({20.0f, 3, ray++, 0});
    for (int i = 0; i < 10; ++i) direct.push_back({30.0f, 0, ray++, 0});
    const std::vector<double> shells = p.shellRadius;
    assignObjectsOnlyDirectImagesSee(p, direct);
    EXPECT_EQ(p.objectLayer[0], 0) << "a layer the lens images gave stays";
    EXPECT_EQ(p.objectLayer[1], 1);
    EXPECT_EQ(p.objectLayer[2], 1) << "by inverse distance, not distance";
    EXPECT_EQ(p.objectLayer[3], 1);
    EXPECT_EQ(p.objectLayer[4], -1) << "seen by nothing";
    EXPECT_EQ(p.shellRadius, shells) << "the lens records place the shells";
}

TEST(LayerShells, PlaneFitAndQuadImpostor) {
    // Noisy points on the plane through (1, 2, -6) with normal (0.3, 0, 1) normalised.
    const glm::vec3 n = glm::normalize(glm::vec3(0.3f, 0.0f, 1.0f)), p0(1, 2, -6);
    const glm::vec3 u = glm::normalize(glm::cross(glm::vec3(0, 1, 0), n)), v = glm::cross(n, u);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> in(-2.0f, 2.0f);
    std::normal_distribution<float> off(0.0f, 0.01f);
    std::vector<glm::vec3> pts;
    for (int i = 0; i < 500; ++i) pts.push_back(p0 + in(rng) * u + in(rng) * v + off(rng) * n);
    Plane plane = fitPlane(pts, glm::vec3(0.0f));
    EXPECT_GT(glm::dot(plane.normal, n), 0.9999f) << "normal, turned towards the viewer at the origin";
    EXPECT_NEAR(glm::dot(plane.point - p0, n), 0.0f, 0.005f);

    std::vector<OutgoingRay> rays;
    for (const glm::vec3& q : pts) rays.push_back({glm::vec3(0.0f), glm::normalize(q)});
    Shell quad = fitQuadShell(glm::vec3(0.0f), pts, rays);
    EXPECT_EQ(quad.kind, ShellKind::Quad);
    EXPECT_GT(quad.extentMax.x - quad.extentMin.x, 3.9f);
    EXPECT_LT(quad.extentMax.x - quad.extentMin.x, 4.1f);
    // A ray through a point of the plane indexes that point; one travelling away is forced onto
    // the plane, far out along its tangential direction.
    glm::vec3 target = p0 + 0.5f * u;
    EXPECT_VEC_NEAR(shellPoint(quad, glm::vec3(0.0f), glm::normalize(target)), target, 0.03f);
    glm::vec3 away = shellPoint(quad, glm::vec3(0.0f), glm::normalize(n + 0.2f * u));
    EXPECT_NEAR(glm::dot(away - quad.planePoint, quad.planeNormal), 0.0f, 1e-5f * quad.farDistance);
    EXPECT_GT(glm::dot(away - quad.planePoint, u), 0.99f * quad.farDistance);
    EXPECT_EQ(chooseShellKind(glm::vec3(0.0f), pts, {}), ShellKind::Quad) << "a small patch of the sky";
    // The quad's texture holds its rectangle (the points span +-2 along u and v): what a ray from
    // the origin meets inside it, a little margin, and neither the forced index nor a far miss.
    EXPECT_TRUE(shellHolds(quad, glm::normalize(target - quad.center), 0.0f));
    EXPECT_TRUE(shellHolds(quad, glm::normalize(p0 + 2.05f * u - quad.center), 0.02f)) << "within the margin";
    EXPECT_FALSE(shellHolds(quad, glm::normalize(p0 + 2.5f * u - quad.center), 0.02f)) << "beyond it";
    EXPECT_FALSE(shellHolds(quad, away - quad.center, 0.02f)) << "a ray travelling away, forced far out";
    EXPECT_FALSE(shellHolds(quad, -n, 0.02f)) << "behind the origin";
    Shell sphere;
    EXPECT_TRUE(shellHolds(sphere, -n, 0.0f)) << "a sphere holds every direction";

    // Thin columns on all sides of the origin (a ring seen in a convex mirror) occupy as few
    // directions, but no plane holds them: rays leaving away from it would be forced onto it.
    std::vector<glm::vec3> columns;
    for (float azimuth : {0.3f, 1.6f, 2.9f, 4.2f}) {
        for (int j = 0; j < 9; ++j) columns.push_back({6.0f * std::cos(azimuth), 0.5f * static_cast<float>(j), 6.0f * std::sin(azimuth) + 2.0f});
    }
    EXPECT_NE(chooseShellKind(glm::vec3(0.0f), columns, {}), ShellKind::Quad);
}

TEST(LayerShells, SphereAndCylinderShells) {
    Shell sphere;
    sphere.center = {1, 0, 0};
    sphere.radius = 4.0f;
    EXPECT_VEC_NEAR(shellPoint(sphere, {1, 0, 0}, {0, 1, 0}), glm::vec3(1, 4, 0), 1e-5f);
    EXPECT_VEC_NEAR(shellTextureDirection(sphere, {1, 0, 2}, {0, 0, 1}), glm::vec3(0, 0, 4), 1e-5f);
    Shell cyl = sphere;
    cyl.kind = ShellKind::Cylinder;
    EXPECT_VEC_NEAR(shellPoint(cyl, {1, 0, 0}, glm::normalize(glm::vec3(1, 1, 0))), glm::vec3(5, 4, 0), 1e-4f);

    // A ring of points at horizontal distance 5 over heights 0..8 is a cylinder; points at all
    // directions at distance 5 a sphere.
    std::vector<glm::vec3> ring, ball;
    for (int i = 0; i < 64; ++i) {
        for (int j = 0; j < 9; ++j) {
            float a = static_cast<float>(i) * 0.0982f;
            ring.push_back({5 * std::cos(a), static_cast<float>(j) - 1.0f, 5 * std::sin(a)});
            float el = (static_cast<float>(j) - 4.0f) * 0.35f;
            ball.push_back(5.0f * glm::vec3(std::cos(el) * std::cos(a), std::sin(el), std::cos(el) * std::sin(a)));
        }
    }
    EXPECT_EQ(chooseShellKind(glm::vec3(0.0f), ring, {}), ShellKind::Cylinder);
    EXPECT_EQ(chooseShellKind(glm::vec3(0.0f), ball, {}), ShellKind::Sphere);
}

// Two tall columns on either side of the EM origin, at horizontal distances 2.75 and 4.25 (their
// faces), 10 high, the origin 1 above their base. The viewpoint samples see them only in a band
// of elevations around the origin's, where distance from the origin and from its vertical axis
// nearly agree (and the 3D one varies relatively less: a sphere); their surfaces, seen from above
// that band too, say cylinder (the cup's columns in teapot-lens, above the samples' plane).
TEST(LayerShells, ColumnsSeenInABandAreACylinderByTheirGeometry) {
    Scene scene;
    scene.meshes.push_back(makeCylinder(24));
    for (glm::vec3 base : {glm::vec3(3.0f, 0.0f, 0.0f), glm::vec3(-4.5f, 0.0f, 0.0f)}) {
        SceneObject column;
        column.name = "column";
        column.meshes = {0};
        column.transform.position = base + glm::vec3(0.0f, 5.0f, 0.0f);
        column.transform.scale = {0.5f, 10.0f, 0.5f};
        scene.objects.push_back(column);
    }
    const glm::vec3 origin(0.0f, 1.0f, 0.0f);
    std::vector<glm::vec3> band;
    for (int j = 0; j <= 12; ++j) {
        const float y = 0.7f + 0.05f * static_cast<float>(j);
        band.push_back({2.75f, y, 0.0f});
        band.push_back({-4.25f, y, 0.0f});
    }
    EXPECT_EQ(chooseShellKind(origin, band, {}), ShellKind::Sphere) << "from what the band saw";
    const std::vector<glm::vec3> surface = sampleObjectSurfaces(scene, {0, 1}, 4096, 2001);
    ASSERT_EQ(surface.size(), 4096u);
    EXPECT_EQ(chooseShellKind(origin, band, surface), ShellKind::Cylinder) << "from the columns themselves";
}

}  // namespace
}  // namespace hybridlab
