// The per-vertex deformation (deformation.h): positions follow the travelling wave's formula, the
// analytic normals match the normals of the deformed surface itself (area-weighted face normals of
// a fine grid), tangents stay perpendicular to the normals, and the envelope holds every vertex;
// the scene file's `deform` block reads into it with precise errors; the cache the rasterizer and
// the ray scene share deforms once a frame.
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>

#include "common/core/input_error.h"
#include "common/scene/deformation.h"
#include "common/scene/deformed_mesh_cache.h"
#include "common/scene/scene_file.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

constexpr double kPi = 3.14159265358979323846;

// An n x n grid of vertices on [-1, 1]^2 in the XZ plane, normal +Y, tangent +X.
Mesh grid(int n) {
    Mesh m;
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            m.positions.push_back({-1.0f + 2.0f * i / (n - 1), 0.0f, -1.0f + 2.0f * j / (n - 1)});
            m.normals.push_back({0, 1, 0});
            m.uvs.push_back({static_cast<float>(i) / (n - 1), static_cast<float>(j) / (n - 1)});
            m.tangents.push_back({1, 0, 0, 1});
        }
    }
    for (int j = 0; j + 1 < n; ++j) {
        for (int i = 0; i + 1 < n; ++i) {
            const auto a = static_cast<std::uint32_t>(j * n + i), b = a + 1, c = a + static_cast<std::uint32_t>(n), d = c + 1;
            m.triangles.push_back({a, c, b});  // counter-clockwise seen from +Y
            m.triangles.push_back({b, c, d});
        }
    }
    return m;
}

Deformation wave() {
    Deformation d;
    d.amplitude = 0.1f;
    d.wavelength = 0.8f;
    d.speed = 0.5f;
    d.phaseRadians = 0.3f;
    d.direction = glm::normalize(glm::vec3(1, 0, 1));
    d.axis = {0, 1, 0};
    return d;
}

TEST(Deformation, PositionsNormalsTangentsAndEnvelope) {
    const int n = 201;
    const Mesh rest = grid(n);
    const Deformation d = wave();
    const double t = 0.7;
    DeformedVertices out;
    deformMesh(d, rest, t, out);
    ASSERT_EQ(out.positions.size(), rest.positions.size());
    ASSERT_EQ(out.tangents.size(), rest.tangents.size());

    // The formula, evaluated independently.
    const double k = 2.0 * kPi / d.wavelength;
    for (std::size_t v : {std::size_t{0}, std::size_t{12345}, rest.positions.size() - 1}) {
        const glm::vec3 p = rest.positions[v];
        const double s = k * (p.x + p.z) / std::sqrt(2.0) - k * d.speed * t + d.phaseRadians;
        EXPECT_NEAR(out.positions[v].y, d.amplitude * std::sin(s), 1e-5);
        EXPECT_FLOAT_EQ(out.positions[v].x, p.x);
        // The surface y = A sin(s(x, z)) has the normal (-dy/dx, 1, -dy/dz), normalised.
        const double slope = d.amplitude * k * std::cos(s) / std::sqrt(2.0);
        const glm::vec3 expected = glm::normalize(glm::vec3(static_cast<float>(-slope), 1.0f, static_cast<float>(-slope)));
        EXPECT_VEC_NEAR(out.normals[v], expected, 1e-5f);
    }

    // Against the deformed mesh's own geometry: the smooth normals of its faces at interior vertices.
    Mesh deformed = rest;
    deformed.positions = out.positions;
    makeSmoothNormals(deformed);
    double maxDegrees = 0.0, maxTangentDot = 0.0;
    const Aabb envelope = d.envelope(rest.bounds());
    for (int j = 1; j + 1 < n; ++j) {
        for (int i = 1; i + 1 < n; ++i) {
            const auto v = static_cast<std::size_t>(j * n + i);
            const float c = std::clamp(glm::dot(deformed.normals[v], out.normals[v]), -1.0f, 1.0f);
            maxDegrees = std::max(maxDegrees, static_cast<double>(glm::degrees(std::acos(c))));
            maxTangentDot = std::max(maxTangentDot, static_cast<double>(std::abs(glm::dot(glm::vec3(out.tangents[v]), out.normals[v]))));
        }
    }
    for (const glm::vec3& p : out.positions) {
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(p, envelope.lo)) && glm::all(glm::lessThanEqual(p, envelope.hi)));
    }
    EXPECT_LT(maxDegrees, 0.2) << "analytic normals against the deformed faces";
    EXPECT_LT(maxTangentDot, 1e-5) << "tangents stay in the deformed surface";
    EXPECT_NEAR(envelope.hi.y - envelope.lo.y, 2.0 * d.amplitude, 1e-6);

    // The wave travels: at t + wavelength / speed the surface is the same again.
    DeformedVertices later;
    deformMesh(d, rest, t + d.wavelength / d.speed, later);
    EXPECT_NEAR(later.positions[12345].y, out.positions[12345].y, 1e-4);
}

// The vertices both consumers take (deformed_mesh_cache.h): deformMesh's at the asked time, computed
// once for the pair of them, and again when a consumer asks a second time (its next frame).
TEST(Deformation, MeshCacheDeformsOncePerFrame) {
    Scene scene;
    scene.meshes = {grid(11), grid(5)};
    scene.objects.resize(2);
    scene.objects[1].meshes = {0, 1};
    scene.objects[1].deformation = wave();
    DeformedMeshCache cache(scene);
    auto expectDeformedAt = [&](const std::vector<DeformedVertices>& got, double time) {
        ASSERT_EQ(got.size(), 2u);
        for (std::size_t k = 0; k < 2; ++k) {
            DeformedVertices want;
            deformMesh(scene.objects[1].deformation, scene.meshes[k], time, want);
            EXPECT_EQ(got[k].positions, want.positions);
            EXPECT_EQ(got[k].normals, want.normals);
            EXPECT_EQ(got[k].tangents, want.tangents);
        }
    };
    expectDeformedAt(cache.vertices(1, 0.5, DeformedMeshCache::kRasterizer), 0.5);
    EXPECT_EQ(cache.deformations(), 1u);
    expectDeformedAt(cache.vertices(1, 0.5, DeformedMeshCache::kRayScene), 0.5);
    EXPECT_EQ(cache.deformations(), 1u) << "the second consumer takes the first one's";
    expectDeformedAt(cache.vertices(1, 0.5, DeformedMeshCache::kRayScene), 0.5);
    EXPECT_EQ(cache.deformations(), 2u) << "a repeated frame pays its deformation";
    expectDeformedAt(cache.vertices(1, 0.5, DeformedMeshCache::kRasterizer), 0.5);
    EXPECT_EQ(cache.deformations(), 2u);
    expectDeformedAt(cache.vertices(1, 1.25, DeformedMeshCache::kRasterizer), 1.25);
    expectDeformedAt(cache.vertices(1, 0.5, DeformedMeshCache::kRayScene), 0.5);
    EXPECT_EQ(cache.deformations(), 4u) << "another time is another deformation";
}

std::string sceneWithDeform(const std::string& deform) {
    return "[materials.grey]\ndiffuse = [0.5, 0.5, 0.5]\n\n"
           "[[objects]]\nname = \"ball\"\nprimitive = \"sphere\"\nmaterial = \"grey\"\n\n"
           "[objects.deform]\n" + deform +
           "\n[camera]\nposition = [0.0, 0.0, 5.0]\nlook_at = [0.0, 0.0, 0.0]\n";
}

std::string loadError(const std::filesystem::path& file) {
    try {
        loadSceneFile(file);
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(Deformation, SceneFileBlock) {
    test::TempDir dir;
    test::writeTextFile(dir / "wave.toml", sceneWithDeform("amplitude = 0.05\nwavelength = 0.5\nspeed = 2.0\nphase = 90.0\n"
                                                          "direction = [0.0, 0.0, 3.0]\naxis = [2.0, 0.0, 0.0]\n"));
    const Scene s = loadSceneFile(dir / "wave.toml");
    const SceneObject& o = s.objects.at(0);
    EXPECT_TRUE(o.isDeforming());
    EXPECT_FALSE(o.isAnimated());
    EXPECT_TRUE(o.isDynamic());
    EXPECT_TRUE(s.isAnimated());
    EXPECT_FLOAT_EQ(o.deformation.amplitude, 0.05f);
    EXPECT_FLOAT_EQ(o.deformation.wavelength, 0.5f);
    EXPECT_FLOAT_EQ(o.deformation.speed, 2.0f);
    EXPECT_NEAR(o.deformation.phaseRadians, kPi / 2.0, 1e-6);
    EXPECT_VEC_NEAR(o.deformation.direction, glm::vec3(0, 0, 1), 0.0f);
    EXPECT_VEC_NEAR(o.deformation.axis, glm::vec3(1, 0, 0), 0.0f);
    // The object's bounds cover the deformation at every time.
    EXPECT_NEAR(s.objectLocalBounds(0).hi.x, 0.55, 1e-6);
    EXPECT_NEAR(s.objectLocalBounds(0).hi.y, 0.5, 1e-6);

    test::writeTextFile(dir / "oblique.toml", sceneWithDeform("amplitude = 0.05\nwavelength = 0.5\naxis = [1.0, 1.0, 0.0]\n"));
    EXPECT_CONTAINS(loadError(dir / "oblique.toml"), "oblique.toml:12:8: objects[0].deform.axis: expected the displacement axis perpendicular");
    test::writeTextFile(dir / "missing.toml", sceneWithDeform("wavelength = 0.5\n"));
    EXPECT_CONTAINS(loadError(dir / "missing.toml"), "missing.toml:");
    EXPECT_CONTAINS(loadError(dir / "missing.toml"), "amplitude");
    test::writeTextFile(dir / "unknown.toml", sceneWithDeform("amplitude = 0.05\nwavelength = 0.5\nfrequency = 3.0\n"));
    EXPECT_CONTAINS(loadError(dir / "unknown.toml"), "unknown.toml:12:1: ");
    EXPECT_CONTAINS(loadError(dir / "unknown.toml"), "frequency");
    test::writeTextFile(dir / "zero.toml", sceneWithDeform("amplitude = 0.05\nwavelength = 0.0\n"));
    EXPECT_CONTAINS(loadError(dir / "zero.toml"), "zero.toml:11:14: objects[0].deform.wavelength: expected a number in");
}

}  // namespace
}  // namespace hybridlab
