// Vertex ray tracing and adaptive tessellation (Hakura & Snyder 2001 §5): refinement happens
// exactly where the paths at a triangle's vertices differ (and the triangle is still large on
// screen), and the result has no t-junction: on a closed lens every edge is shared by exactly two
// triangles.
#include <map>

#include <gtest/gtest.h>

#include "techniques/layered_em/lens_tessellation.h"
#include "tests/support/lens_test_scenes.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

std::map<std::pair<std::uint32_t, std::uint32_t>, int> edgeUses(const std::vector<glm::uvec3>& triangles) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
    for (const glm::uvec3& t : triangles) {
        for (int k = 0; k < 3; ++k) uses[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}]++;
    }
    return uses;
}

TEST(LensTessellation, GlassSphereRefinesWherePathsDifferWithoutTJunctions) {
    Scene scene = test::glassSphereScene({0, 0, 0}, 1.0f, glm::vec3(0.0f), 24, 12);
    LensSystem system(scene, findLensSystems(scene).at(0));
    LensMesh mesh = buildLensMesh(system);
    ASSERT_EQ(mesh.positions.size(), 24u * 11u + 2u) << "seam and pole vertices welded";
    const int width = 160, height = 160;
    const Camera camera = test::lookingAt({0, 0, 6}, {0, 0, 0}, 40.0f);
    TessellationSettings settings;
    settings.tauPixels = 4.0f;
    TessellatedLens t = tessellateLens(system, mesh, camera, width, height, settings);

    EXPECT_GT(t.stats.splits, 50u);
    EXPECT_GT(t.stats.skippedVertices, 50u) << "the back half is not traced";
    EXPECT_GT(t.stats.tJunctionTriangles, 0u);
    // Every subdivided triangle had differing paths; every leaf that faces the viewer and is not
    // hidden either has agreeing paths or edges already shorter than tau.
    for (const glm::uvec3& s : t.splits) {
        const auto& v = t.vertices;
        EXPECT_TRUE(pathsDiffer(v[s[0]].paths, v[s[1]].paths, 3.0f) || pathsDiffer(v[s[1]].paths, v[s[2]].paths, 3.0f) ||
                    pathsDiffer(v[s[2]].paths, v[s[0]].paths, 3.0f));
    }
    int agreeing = 0, short_ = 0;
    for (const glm::uvec3& l : t.leaves) {
        const auto& v = t.vertices;
        if (!v[l[0]].traced || !v[l[1]].traced || !v[l[2]].traced) continue;
        glm::vec3 n = glm::cross(v[l[1]].position - v[l[0]].position, v[l[2]].position - v[l[0]].position);
        if (glm::dot(n, camera.position - v[l[0]].position) <= 0.0f) continue;
        bool differ = false;
        for (int k = 0; k < 3; ++k) differ = differ || pathsDiffer(v[l[k]].paths, v[l[(k + 1) % 3]].paths, 3.0f);
        if (!differ) {
            ++agreeing;
            continue;
        }
        ++short_;
        for (int k = 0; k < 3; ++k) {
            float len = glm::length(projectToPixels(camera, width, height, v[l[k]].position) -
                                    projectToPixels(camera, width, height, v[l[(k + 1) % 3]].position));
            EXPECT_LT(len, settings.tauPixels);
        }
    }
    EXPECT_GT(short_, 0) << "refraction through a sphere differs everywhere: refined down to tau";
    RecordProperty("leaves_with_agreeing_paths", agreeing);
    // No t-junctions: the closed sphere stays closed.
    for (const auto& [edge, uses] : edgeUses(t.triangles)) EXPECT_EQ(uses, 2) << edge.first << "-" << edge.second;
    // The edge hash kept every vertex from being traced twice.
    EXPECT_EQ(t.stats.tracedVertices + t.stats.skippedVertices, t.vertices.size());
}

TEST(LensTessellation, DistantFlatMirrorIsNotRefined) {
    // An opaque mirror cube seen face-on from far away: every front vertex reflects once and the
    // outgoing directions are within a degree of each other, so nothing is subdivided.
    test::SceneBuilder b;
    Material mirror;
    mirror.reflectivity = 1.0f;
    b.object("mirror", makeCube(), b.material(mirror));
    b.scene().objects[0].lens = true;
    LensSystem system(b.scene(), findLensSystems(b.scene()).at(0));
    LensMesh mesh = buildLensMesh(system);
    TessellatedLens t = tessellateLens(system, mesh, test::lookingAt({0, 0, 50}, {0, 0, 0}, 3.0f), 160, 160, {});
    EXPECT_EQ(t.stats.splits, 0u);
    EXPECT_EQ(t.stats.tracedVertices, 4u) << "only the front face faces the viewer";
    EXPECT_EQ(t.triangles.size(), 12u);
    for (const LensVertex& v : t.vertices) {
        if (!v.traced) continue;
        EXPECT_TRUE(v.visible);
        EXPECT_TRUE(v.paths.reflection().exists);
        EXPECT_FALSE(v.paths.refraction().exists) << "an opaque mirror has one term";
        EXPECT_NEAR(v.paths.reflection().fresnel, 1.0f, 1e-6f);
    }
}

}  // namespace
}  // namespace hybridlab
