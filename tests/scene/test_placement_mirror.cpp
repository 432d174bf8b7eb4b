// Mirrored placements (placement_mirror.h): a scene file's negative scale factors move into the
// object's meshes on load, leaving every world-space vertex where the file puts it (at rest, at
// each keyframe, deformed) and every triangle wound counter-clockwise about its outward normal in
// world space, which is what each rendering path takes the outside from.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "common/scene/deformation.h"
#include "common/scene/primitives.h"
#include "common/scene/scene_file.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

const char* kScene = R"(
[materials.grey]
diffuse = [0.5, 0.5, 0.5]

[[objects]]
name = "ball"
primitive = "sphere"
slices = 12
stacks = 6
material = "grey"
position = [1.0, 2.0, 3.0]
rotation = [0.0, 30.0, 0.0]
scale = [-1.5, 2.0, 0.5]

[[objects]]
name = "box"
primitive = "cube"
material = "grey"
animation = { keys = [{ time = 0.0, scale = [-1.0, 1.0, 1.0] }, { time = 1.0, position = [2.0, 0.0, 0.0], scale = [-2.0, 1.0, 1.0] }] }

[[objects]]
name = "wave"
primitive = "plane"
material = "grey"
scale = [-3.0, 1.0, 3.0]
deform = { amplitude = 0.1, wavelength = 0.5, direction = [1.0, 0.0, 0.2], axis = [0.0, 1.0, 0.0] }

[camera]
position = [0.0, 1.0, 8.0]
look_at = [0.0, 0.0, 0.0]
)";

// Every triangle's world-space winding normal points away from `centre` (a convex object).
void expectWoundOutward(const Mesh& mesh, const glm::mat4& toWorld, glm::vec3 centre) {
    for (const auto& t : mesh.triangles) {
        const glm::vec3 p0(toWorld * glm::vec4(mesh.positions[t.x], 1.0f)), p1(toWorld * glm::vec4(mesh.positions[t.y], 1.0f)),
            p2(toWorld * glm::vec4(mesh.positions[t.z], 1.0f));
        EXPECT_GT(glm::dot(glm::cross(p1 - p0, p2 - p0), (p0 + p1 + p2) / 3.0f - centre), 0.0f);
    }
}

glm::mat4 placement(glm::vec3 position, glm::vec3 degrees, glm::vec3 scale) {
    return Transform{position, eulerDegreesToQuat(degrees), scale}.matrix();
}

TEST(PlacementMirror, VerticesStayWhereTheFilePutsThemAndTrianglesFaceOutward) {
    test::TempDir dir;
    test::writeTextFile(dir / "mirrored.toml", kScene);
    const Scene scene = loadSceneFile(dir / "mirrored.toml");

    // The ball: its placement now scales by positive factors, and the world is the file's.
    const SceneObject& ball = scene.objects[0];
    EXPECT_VEC_NEAR(ball.transform.scale, glm::vec3(1.5f, 2.0f, 0.5f), 1e-6f);
    const Mesh rest = makeSphere(12, 6), &baked = scene.meshes[ball.meshes[0]];
    const glm::mat4 file = placement({1, 2, 3}, {0, 30, 0}, {-1.5f, 2.0f, 0.5f});
    ASSERT_EQ(baked.positions.size(), rest.positions.size());
    for (std::size_t i = 0; i < rest.positions.size(); ++i)
        EXPECT_VEC_NEAR(glm::vec3(ball.worldMatrix(0.0) * glm::vec4(baked.positions[i], 1.0f)), glm::vec3(file * glm::vec4(rest.positions[i], 1.0f)),
                        1e-5f);
    expectWoundOutward(baked, ball.worldMatrix(0.0), {1, 2, 3});

    // The box, at each keyframe and between them.
    const SceneObject& box = scene.objects[1];
    const Mesh cube = makeCube(), &bakedCube = scene.meshes[box.meshes[0]];
    for (double t : {0.0, 0.5, 1.0}) {
        SCOPED_TRACE(t);
        const float s = 1.0f + static_cast<float>(t);
        const glm::mat4 expected = placement({2.0f * static_cast<float>(t), 0, 0}, {0, 0, 0}, {-s, 1.0f, 1.0f});
        for (std::size_t i = 0; i < cube.positions.size(); ++i)
            EXPECT_VEC_NEAR(glm::vec3(box.worldMatrix(t) * glm::vec4(bakedCube.positions[i], 1.0f)), glm::vec3(expected * glm::vec4(cube.positions[i], 1.0f)),
                            1e-5f);
        expectWoundOutward(bakedCube, box.worldMatrix(t), glm::vec3(2.0f * static_cast<float>(t), 0, 0));
    }

    // The wave: deformed vertices in the world as the file's deformation of the file's plane.
    const SceneObject& wave = scene.objects[2];
    Deformation fileWave;
    fileWave.amplitude = 0.1f;
    fileWave.wavelength = 0.5f;
    fileWave.direction = glm::normalize(glm::vec3(1.0f, 0.0f, 0.2f));
    fileWave.axis = glm::vec3(0, 1, 0);
    DeformedVertices expected, actual;
    deformMesh(fileWave, makePlane(), 0.3, expected);
    deformMesh(wave.deformation, scene.meshes[wave.meshes[0]], 0.3, actual);
    const glm::mat4 fileToWorld = placement({0, 0, 0}, {0, 0, 0}, {-3.0f, 1.0f, 3.0f});
    for (std::size_t i = 0; i < expected.positions.size(); ++i) {
        EXPECT_VEC_NEAR(glm::vec3(wave.worldMatrix(0.3) * glm::vec4(actual.positions[i], 1.0f)), glm::vec3(fileToWorld * glm::vec4(expected.positions[i], 1.0f)),
                        1e-5f);
        EXPECT_VEC_NEAR(glm::normalize(normalMatrix(wave.worldMatrix(0.3)) * actual.normals[i]),
                        glm::normalize(normalMatrix(fileToWorld) * expected.normals[i]), 1e-5f);
    }
}

}  // namespace
}  // namespace hybridlab
