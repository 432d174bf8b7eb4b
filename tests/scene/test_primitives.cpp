// Built-in primitives (primitives.h): triangle and vertex counts, outward counter-clockwise
// winding, unit normals, the unit box, uvs in [0, 1].
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "common/scene/mesh.h"
#include "common/scene/primitives.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

constexpr float kBoxTolerance = 1e-6f;

// What every primitive promises, whatever its shape.
void expectWellFormed(const Mesh& m, const std::string& what) {
    SCOPED_TRACE(what);
    ASSERT_GT(m.triangleCount(), 0u);
    ASSERT_EQ(m.normals.size(), m.positions.size());
    ASSERT_EQ(m.uvs.size(), m.positions.size());
    int badNormals = 0, outside = 0, badUvs = 0, badWinding = 0, badIndex = 0;
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
        if (std::abs(glm::length(m.normals[i]) - 1.0f) > 1e-5f) ++badNormals;
        for (int c = 0; c < 3; ++c) {
            if (std::abs(m.positions[i][c]) > 0.5f + kBoxTolerance) ++outside;
        }
        for (int c = 0; c < 2; ++c) {
            if (m.uvs[i][c] < 0.0f || m.uvs[i][c] > 1.0f) ++badUvs;
        }
    }
    for (const auto& t : m.triangles) {
        if (t.x >= m.positions.size() || t.y >= m.positions.size() || t.z >= m.positions.size()) {
            ++badIndex;
            continue;
        }
        // Counter-clockwise seen from outside: the geometric normal agrees with every vertex normal.
        glm::vec3 g = glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]);
        for (int k = 0; k < 3; ++k) {
            if (!(glm::dot(g, m.normals[t[k]]) > 0.0f)) {
                ++badWinding;
                break;
            }
        }
    }
    EXPECT_EQ(badIndex, 0) << "triangles with an index past the last vertex";
    EXPECT_EQ(badNormals, 0) << "normals that are not unit length";
    EXPECT_EQ(outside, 0) << "vertex coordinates outside [-0.5, 0.5]";
    EXPECT_EQ(badUvs, 0) << "uv coordinates outside [0, 1]";
    EXPECT_EQ(badWinding, 0) << "triangles whose winding disagrees with their vertex normals";
    Mesh copy = m;
    EXPECT_EQ(dropDegenerateTriangles(copy), 0u) << "degenerate triangles";
}

void expectBounds(const Mesh& m, glm::vec3 lo, glm::vec3 hi) {
    Aabb b = m.bounds();
    EXPECT_VEC_NEAR(b.lo, lo, kBoxTolerance);
    EXPECT_VEC_NEAR(b.hi, hi, kBoxTolerance);
}

TEST(Primitives, PlaneIsTwoTrianglesFacingUp) {
    Mesh m = makePlane();
    EXPECT_EQ(m.triangleCount(), 2u);
    EXPECT_EQ(m.vertexCount(), 4u);
    expectWellFormed(m, "plane");
    expectBounds(m, {-0.5f, 0.0f, -0.5f}, {0.5f, 0.0f, 0.5f});
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
        EXPECT_VEC_NEAR(m.normals[i], glm::vec3(0, 1, 0), 0.0f);
        // u grows with x and v with z, so that a texture on the floor is not mirrored.
        EXPECT_VEC_NEAR(m.uvs[i], glm::vec2(m.positions[i].x + 0.5f, m.positions[i].z + 0.5f), 1e-6f);
    }
}

TEST(Primitives, CubeIsTwelveTrianglesOnTwentyFourVertices) {
    Mesh m = makeCube();
    EXPECT_EQ(m.triangleCount(), 12u);
    EXPECT_EQ(m.vertexCount(), 24u);
    expectWellFormed(m, "cube");
    expectBounds(m, glm::vec3(-0.5f), glm::vec3(0.5f));
    // One flat quad per axis direction.
    const std::vector<glm::vec3> axes = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const auto& axis : axes) {
        int vertices = 0;
        for (std::size_t i = 0; i < m.positions.size(); ++i) {
            if (glm::dot(m.normals[i], axis) > 0.999f) {
                ++vertices;
                // Every vertex of the +X face lies at x = 0.5, and so on.
                EXPECT_NEAR(glm::dot(m.positions[i], axis), 0.5f, 1e-6f);
            }
        }
        EXPECT_EQ(vertices, 4) << "face (" << axis.x << ", " << axis.y << ", " << axis.z << ")";
    }
}

TEST(Primitives, SphereTriangleCountsAndShape) {
    const std::pair<int, int> sizes[] = {{3, 2}, {4, 3}, {5, 7}, {16, 8}, {32, 16}, {48, 24}, {64, 32}};
    for (const auto& [slices, stacks] : sizes) {
        const std::string name = "sphere " + std::to_string(slices) + "x" + std::to_string(stacks);
        SCOPED_TRACE(name);
        Mesh m = makeSphere(slices, stacks);
        EXPECT_EQ(m.triangleCount(), static_cast<std::size_t>(2 * slices * (stacks - 1)));
        // The seam and the poles are duplicated: (slices + 1) x (stacks + 1) vertices.
        EXPECT_EQ(m.vertexCount(), static_cast<std::size_t>((slices + 1) * (stacks + 1)));
        expectWellFormed(m, name);
        for (std::size_t i = 0; i < m.positions.size(); ++i) {
            ASSERT_NEAR(glm::length(m.positions[i]), 0.5f, 1e-5f) << "vertex " << i;
            ASSERT_VEC_NEAR(m.normals[i], glm::normalize(m.positions[i]), 1e-5f) << "vertex " << i;
        }
        // The poles are always there; slice 0 lies in the +X half-plane.
        Aabb b = m.bounds();
        EXPECT_NEAR(b.lo.y, -0.5f, kBoxTolerance);
        EXPECT_NEAR(b.hi.y, 0.5f, kBoxTolerance);
        const float widestRing = std::sin(std::numbers::pi_v<float> * static_cast<float>(stacks / 2) / static_cast<float>(stacks));
        EXPECT_NEAR(b.hi.x, 0.5f * widestRing, 1e-6f);
    }
    Mesh m = makeSphere(64, 32);
    EXPECT_EQ(m.triangleCount(), 3968u);
    expectBounds(m, glm::vec3(-0.5f), glm::vec3(0.5f));
}

TEST(Primitives, CylinderTriangleCountsAndShape) {
    for (int slices : {3, 5, 8, 32, 48, 64}) {
        const std::string name = "cylinder " + std::to_string(slices);
        SCOPED_TRACE(name);
        Mesh m = makeCylinder(slices);
        EXPECT_EQ(m.triangleCount(), static_cast<std::size_t>(4 * slices));
        expectWellFormed(m, name);
        Aabb b = m.bounds();
        EXPECT_NEAR(b.lo.y, -0.5f, kBoxTolerance);
        EXPECT_NEAR(b.hi.y, 0.5f, kBoxTolerance);
        EXPECT_NEAR(b.hi.x, 0.5f, kBoxTolerance);
        if (slices % 4 == 0) expectBounds(m, glm::vec3(-0.5f), glm::vec3(0.5f));
        // Side vertices sit on the radius-0.5 circle with radial normals; caps have flat normals.
        for (std::size_t i = 0; i < m.positions.size(); ++i) {
            const glm::vec3 p = m.positions[i], n = m.normals[i];
            if (std::abs(n.y) > 0.5f) {
                EXPECT_NEAR(n.y * p.y, 0.5f, 1e-6f) << "a cap vertex lies on its cap";
            } else {
                EXPECT_NEAR(glm::length(glm::vec2(p.x, p.z)), 0.5f, 1e-5f);
                EXPECT_VEC_NEAR(n, glm::normalize(glm::vec3(p.x, 0.0f, p.z)), 1e-5f);
            }
        }
    }
}

}  // namespace
}  // namespace hybridlab
