// Mesh helpers (mesh.h): flat and smooth normals, tangents, degenerate triangles, transforms.
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "common/scene/mesh.h"
#include "common/scene/primitives.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

glm::vec3 faceNormal(const Mesh& m, const glm::uvec3& t) {
    return glm::normalize(glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]));
}

// Two triangles sharing the edge (1, 2), folded along it so that their normals differ.
Mesh foldedQuad() {
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 1}};
    m.uvs = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
    m.triangles = {{0, 1, 2}, {1, 3, 2}};
    m.material = 3;
    return m;
}

TEST(MeshNormals, FlatNormalsGiveEachTriangleItsOwnVertices) {
    Mesh m = foldedQuad();
    const glm::vec3 n0 = faceNormal(m, m.triangles[0]), n1 = faceNormal(m, m.triangles[1]);
    ASSERT_LT(glm::dot(n0, n1), 0.99f) << "the fixture should be folded";
    const Mesh before = m;
    makeFlatNormals(m);
    ASSERT_EQ(m.triangleCount(), 2u);
    ASSERT_EQ(m.vertexCount(), 6u);
    ASSERT_EQ(m.normals.size(), 6u);
    ASSERT_EQ(m.uvs.size(), 6u);
    EXPECT_EQ(m.material, 3u);
    for (std::size_t t = 0; t < 2; ++t) {
        const glm::vec3 expected = t == 0 ? n0 : n1;
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t v = m.triangles[t][k];
            const std::uint32_t original = before.triangles[t][k];
            EXPECT_EQ(v, 3 * t + k) << "each triangle gets its own three vertices";
            EXPECT_VEC_NEAR(m.positions[v], before.positions[original], 0.0f);
            EXPECT_VEC_NEAR(m.uvs[v], before.uvs[original], 0.0f);
            EXPECT_VEC_NEAR(m.normals[v], expected, 1e-6f);
        }
    }
    EXPECT_VEC_NEAR(n0, glm::vec3(0, 0, 1), 1e-6f);
}

TEST(MeshNormals, SmoothNormalsAreAreaWeighted) {
    // The corner of a 1 x 2 x 3 box at the origin, one triangle per face, facing out of the box
    // (towards negative x, y and z). The face normals weighted by area are (-bc, 0, 0) = (-6, 0, 0),
    // (0, -ac, 0) = (0, -3, 0) and (0, 0, -ab) = (0, 0, -2), whose sum has length 7: the corner
    // normal is -(6, 3, 2) / 7. An unweighted average would be -(1, 1, 1) / sqrt(3).
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 2, 0}, {0, 0, 3}};
    m.triangles = {{0, 2, 1} /* z = 0 */, {0, 1, 3} /* y = 0 */, {0, 3, 2} /* x = 0 */};
    makeSmoothNormals(m);
    ASSERT_EQ(m.normals.size(), 4u);
    EXPECT_EQ(m.vertexCount(), 4u) << "smooth normals keep the shared vertices";
    EXPECT_VEC_NEAR(m.normals[0], glm::vec3(-6, -3, -2) / 7.0f, 1e-6f);
    // (1, 0, 0) touches the z = 0 face (area 1) and the y = 0 face (area 1.5).
    EXPECT_VEC_NEAR(m.normals[1], glm::normalize(glm::vec3(0, -3, -2)), 1e-6f);
    // (0, 2, 0): z = 0 (area 1) and x = 0 (area 3).
    EXPECT_VEC_NEAR(m.normals[2], glm::normalize(glm::vec3(-6, 0, -2)), 1e-6f);
    // (0, 0, 3): y = 0 (area 1.5) and x = 0 (area 3).
    EXPECT_VEC_NEAR(m.normals[3], glm::normalize(glm::vec3(-6, -3, 0)), 1e-6f);

    // A flat mesh keeps its face normal.
    Mesh plane = makePlane();
    plane.normals.clear();
    makeSmoothNormals(plane);
    for (const auto& n : plane.normals) EXPECT_VEC_NEAR(n, glm::vec3(0, 1, 0), 1e-6f);
}

TEST(MeshDegenerateTriangles, RepeatedIndicesAndZeroAreaAreDropped) {
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {1, 1, 0}, {1, 0, 0}};
    m.triangles = {
        {0, 1, 2},  // good
        {0, 0, 1},  // repeated index
        {1, 2, 1},  // repeated index
        {0, 1, 3},  // collinear: (0,0,0), (1,0,0), (2,0,0)
        {1, 5, 2},  // vertices 1 and 5 are distinct indices at the same position
        {1, 4, 2},  // good
    };
    EXPECT_EQ(dropDegenerateTriangles(m), 4u);
    ASSERT_EQ(m.triangleCount(), 2u);
    EXPECT_EQ(m.triangles[0], glm::uvec3(0, 1, 2));
    EXPECT_EQ(m.triangles[1], glm::uvec3(1, 4, 2));
    EXPECT_EQ(m.vertexCount(), 6u) << "vertices are kept";
    EXPECT_EQ(dropDegenerateTriangles(m), 0u);

    // Thin is not degenerate.
    Mesh thin;
    thin.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1e-3f, 0}};
    thin.triangles = {{0, 1, 2}};
    EXPECT_EQ(dropDegenerateTriangles(thin), 0u);
}

// Every triangle counter-clockwise about its vertex normals, and normals pointing away from the
// centre (for convex meshes).
void expectOutwardCounterClockwise(const Mesh& m, glm::vec3 centre) {
    for (const auto& t : m.triangles) {
        glm::vec3 g = glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]);
        glm::vec3 mid = (m.positions[t.x] + m.positions[t.y] + m.positions[t.z]) / 3.0f;
        EXPECT_GT(glm::dot(g, mid - centre), 0.0f);
        for (int k = 0; k < 3; ++k) {
            EXPECT_GT(glm::dot(g, m.normals[t[k]]), 0.0f);
            EXPECT_NEAR(glm::length(m.normals[t[k]]), 1.0f, 1e-5f);
        }
    }
}

TEST(MeshTransform, PositionsNormalsAndTangentsFollowTheMatrix) {
    Mesh m = makeCube();
    computeTangents(m);
    glm::mat4 M = glm::translate(glm::mat4(1.0f), glm::vec3(1, 2, 3)) * glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(0, 1, 0)) *
                  glm::scale(glm::mat4(1.0f), glm::vec3(2, 1, 1));
    Mesh t = m;
    transformMesh(t, M);
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
        EXPECT_VEC_NEAR(t.positions[i], glm::vec3(M * glm::vec4(m.positions[i], 1.0f)), 1e-5f);
        EXPECT_VEC_NEAR(t.tangents[i], glm::vec4(glm::normalize(glm::mat3(M) * glm::vec3(m.tangents[i])), m.tangents[i].w), 1e-5f);
    }
    // Rotating +X by 90 degrees about Y gives -Z.
    EXPECT_VEC_NEAR(t.normals[0], glm::vec3(0, 0, -1), 1e-6f);
    expectOutwardCounterClockwise(t, glm::vec3(1, 2, 3));

    // Non-uniform scale: on the ellipsoid x^2 + (y/4)^2 + (z/0.25)^2 = 0.25 made from the sphere,
    // the normal is the gradient (x, y/16, 16 z).
    Mesh e = makeSphere(16, 8);
    transformMesh(e, glm::scale(glm::mat4(1.0f), glm::vec3(1, 4, 0.25f)));
    expectOutwardCounterClockwise(e, glm::vec3(0.0f));
    for (std::size_t i = 0; i < e.positions.size(); ++i) {
        glm::vec3 p = e.positions[i];
        EXPECT_VEC_NEAR(e.normals[i], glm::normalize(glm::vec3(p.x, p.y / 16.0f, 16.0f * p.z)), 1e-4f);
    }
}

TEST(MeshTransform, MirroringKeepsTrianglesCounterClockwise) {
    const glm::mat4 mirrors[] = {
        glm::scale(glm::mat4(1.0f), glm::vec3(-1, 1, 1)),
        glm::scale(glm::mat4(1.0f), glm::vec3(2, -3, 0.5f)),
        glm::rotate(glm::mat4(1.0f), 0.7f, glm::normalize(glm::vec3(1, 2, 3))) * glm::scale(glm::mat4(1.0f), glm::vec3(-1, -1, -1)),
    };
    for (const auto& M : mirrors) {
        ASSERT_LT(glm::determinant(glm::mat3(M)), 0.0f);
        for (Mesh m : {makeCube(), makeSphere(12, 6), makeCylinder(9)}) {
            SCOPED_TRACE(m.name);
            transformMesh(m, M);
            expectOutwardCounterClockwise(m, glm::vec3(0.0f));
        }
        // The bitangent, cross(n, t) * w, is the mapped one: a mirror flips w.
        Mesh plane = makePlane();
        computeTangents(plane);
        Mesh mirrored = plane;
        transformMesh(mirrored, M);
        for (std::size_t i = 0; i < plane.positions.size(); ++i) {
            const glm::vec3 bitangent = glm::cross(plane.normals[i], glm::vec3(plane.tangents[i])) * plane.tangents[i].w;
            const glm::vec3 mapped = glm::normalize(glm::mat3(M) * bitangent);
            const glm::vec3 rebuilt = glm::cross(mirrored.normals[i], glm::vec3(mirrored.tangents[i])) * mirrored.tangents[i].w;
            EXPECT_GT(glm::dot(glm::normalize(rebuilt), mapped), 0.5f);
        }
    }
}

TEST(MeshTangents, TangentsFollowIncreasingU) {
    Mesh m = makePlane();
    computeTangents(m);
    ASSERT_EQ(m.tangents.size(), m.positions.size());
    for (std::size_t i = 0; i < m.tangents.size(); ++i) {
        const glm::vec3 t(m.tangents[i]);
        EXPECT_VEC_NEAR(t, glm::vec3(1, 0, 0), 1e-6f) << "u increases with x";
        EXPECT_NEAR(glm::length(t), 1.0f, 1e-6f);
        // glTF: bitangent = cross(normal, tangent) * w points along increasing v, which is +z.
        EXPECT_VEC_NEAR(glm::cross(m.normals[i], t) * m.tangents[i].w, glm::vec3(0, 0, 1), 1e-6f);
    }

    // On a sphere: unit length and perpendicular to the normal everywhere, poles included.
    Mesh sphere = makeSphere(24, 12);
    computeTangents(sphere);
    ASSERT_EQ(sphere.tangents.size(), sphere.positions.size());
    for (std::size_t i = 0; i < sphere.tangents.size(); ++i) {
        const glm::vec3 t(sphere.tangents[i]);
        EXPECT_NEAR(glm::length(t), 1.0f, 1e-5f);
        EXPECT_NEAR(glm::dot(t, sphere.normals[i]), 0.0f, 1e-5f);
        EXPECT_TRUE(sphere.tangents[i].w == 1.0f || sphere.tangents[i].w == -1.0f);
    }

    // Without uvs there is nothing to compute.
    Mesh bare = makePlane();
    bare.uvs.clear();
    computeTangents(bare);
    EXPECT_TRUE(bare.tangents.empty());
}

}  // namespace
}  // namespace hybridlab
