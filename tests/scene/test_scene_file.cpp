// Scene files (scene_file.h): the built-in scenes load with exactly the objects, triangles,
// materials, lights and camera paths their files describe; and the file format's features
// (animation, orientation keys, models with glTF cameras, textures) work end to end.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "common/core/input_error.h"
#include "common/image/color.h"
#include "common/image/image_io.h"
#include "common/scene/deformation.h"
#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "common/scene/transform.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

using test::TempDir;
using test::writeTextFile;

std::size_t objectIndex(const Scene& s, const std::string& name) {
    for (std::size_t i = 0; i < s.objects.size(); ++i)
        if (s.objects[i].name == name) return i;
    ADD_FAILURE() << "no object named " << name;
    return 0;
}

const Material& objectMaterial(const Scene& s, const std::string& name) {
    return s.materials[s.meshes[s.objects[objectIndex(s, name)].meshes.at(0)].material];
}

std::string loadError(const std::filesystem::path& file) {
    try {
        loadSceneFile(file, {.loadTextures = false});
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

constexpr std::size_t kSphere64x32Triangles = 2 * 64 * (32 - 1);    // 3968
constexpr std::size_t kSphere64x32Vertices = (64 + 1) * (32 + 1);   // 2145

TEST(SceneCatalog, ListsAndFindsTheBuiltInScenes) {
    auto files = listSceneFiles();
    std::vector<std::string> names;
    for (const auto& f : files) names.push_back(f.stem().string());
    EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
    for (const char* scene : {"cornell-mirror-glass", "sponza-armadillo", "sponza-spheres", "teapot-lens", "whitted-classic"}) {
        EXPECT_NE(std::find(names.begin(), names.end(), scene), names.end()) << scene;
    }
    EXPECT_EQ(findSceneFile("whitted-classic"), scenesDirectory() / "whitted-classic.toml");
    EXPECT_THROW(findSceneFile("no-such-scene"), InputError);
    EXPECT_THROW(findSceneFile("missing/file.toml"), InputError);
}

TEST(WhittedClassic, ObjectsTrianglesAndStats) {
    Scene s = loadSceneFile(test::builtinSceneFile("whitted-classic"), {.loadTextures = false});
    EXPECT_EQ(s.name, "whitted-classic");
    ASSERT_EQ(s.objects.size(), 3u);
    EXPECT_EQ(s.objects[0].name, "floor");
    EXPECT_EQ(s.objects[1].name, "mirror-sphere");
    EXPECT_EQ(s.objects[2].name, "glass-sphere");
    EXPECT_EQ(s.objects[0].source, "plane");
    EXPECT_EQ(s.objects[1].source, "sphere");
    EXPECT_EQ(s.objectTriangleCount(0), 2u);
    EXPECT_EQ(s.objectTriangleCount(1), kSphere64x32Triangles);
    EXPECT_EQ(s.objectTriangleCount(2), kSphere64x32Triangles);
    SceneStats st = s.stats();
    EXPECT_EQ(st.objects, 3u);
    EXPECT_EQ(st.triangles, 7938u);  // 2 + 2 * 3968
    EXPECT_EQ(st.vertices, 4u + 2 * kSphere64x32Vertices);
    EXPECT_EQ(st.lights, 2u);
    // Glass reflects (Fresnel) and refracts but counts as refractive only: the counts are disjoint.
    const std::size_t glass = objectIndex(s, "glass-sphere");
    EXPECT_TRUE(s.objectIsReflective(glass));
    EXPECT_TRUE(s.objectIsRefractive(glass));
    EXPECT_EQ(st.reflectiveObjects, 1u);  // the mirror sphere
    EXPECT_EQ(st.refractiveObjects, 1u);  // the glass sphere
    EXPECT_EQ(s.droppedDegenerateTriangles, 0u);
    EXPECT_FALSE(s.isAnimated());
    EXPECT_FLOAT_EQ(s.objects[0].relevance, 0.5f);
    EXPECT_FLOAT_EQ(s.objects[1].relevance, 1.0f);

    // Placement: the mirror sphere has radius 0.5 scaled by 2 at (-1.1, 1, 0).
    Aabb b = s.objectBounds(1, 0.0);
    EXPECT_VEC_NEAR(b.lo, glm::vec3(-2.1f, 0.0f, -1.0f), 1e-5f);
    EXPECT_VEC_NEAR(b.hi, glm::vec3(-0.1f, 2.0f, 1.0f), 1e-5f);
    Aabb all = s.bounds();
    EXPECT_VEC_NEAR(all.lo, glm::vec3(-12.0f, 0.0f, -12.0f), 1e-5f);
    EXPECT_VEC_NEAR(all.hi, glm::vec3(12.0f, 2.1f, 12.0f), 1e-5f);  // glass sphere: 1.3 + 0.8
}

TEST(WhittedClassic, MaterialsAndTexture) {
    Scene s = loadSceneFile(test::builtinSceneFile("whitted-classic"));
    ASSERT_EQ(s.materials.size(), 3u);
    const Material& checker = objectMaterial(s, "floor");
    const Material& mirror = objectMaterial(s, "mirror-sphere");
    const Material& glass = objectMaterial(s, "glass-sphere");
    EXPECT_EQ(checker.name, "checker");
    EXPECT_EQ(mirror.name, "mirror");
    EXPECT_EQ(glass.name, "glass");

    EXPECT_FLOAT_EQ(mirror.reflectivity, 0.9f);
    EXPECT_FALSE(mirror.fresnel);
    EXPECT_FLOAT_EQ(mirror.opacity, 1.0f);
    EXPECT_FLOAT_EQ(mirror.specularExponent, 128.0f);
    EXPECT_TRUE(mirror.isReflective());
    EXPECT_FALSE(mirror.isRefractive());

    EXPECT_TRUE(glass.fresnel);
    EXPECT_FLOAT_EQ(glass.ior, 1.5f);
    EXPECT_FLOAT_EQ(glass.opacity, 0.0f);
    EXPECT_FLOAT_EQ(glass.reflectivity, 0.0f);
    EXPECT_TRUE(glass.isReflective()) << "Fresnel glass reflects";
    EXPECT_TRUE(glass.isRefractive());

    EXPECT_FALSE(checker.isReflective());
    EXPECT_FALSE(checker.isRefractive());
    EXPECT_VEC_NEAR(checker.textureTiling, glm::vec2(3.0f, 3.0f), 0.0f);
    ASSERT_EQ(s.textures.size(), 1u);
    ASSERT_EQ(checker.diffuseTexture, 0);
    const Texture& t = s.textures[0];
    EXPECT_EQ(t.source, "builtin:checker");
    EXPECT_TRUE(t.srgb);
    ASSERT_EQ(t.image.width(), 512);
    ASSERT_EQ(t.image.height(), 512);
    // 8 x 8 squares of 64 pixels, light grey (sRGB 0.9) at the top left, decoded to linear.
    EXPECT_VEC_NEAR(t.image.at(0, 0), glm::vec4(glm::vec3(srgbToLinear(0.9f)), 1.0f), 1e-6f);
    EXPECT_VEC_NEAR(t.image.at(63, 63), t.image.at(0, 0), 0.0f);
    EXPECT_VEC_NEAR(t.image.at(64, 0), glm::vec4(glm::vec3(srgbToLinear(0.15f)), 1.0f), 1e-6f);
    EXPECT_VEC_NEAR(t.image.at(0, 64), t.image.at(64, 0), 0.0f);
    EXPECT_VEC_NEAR(t.image.at(511, 511), t.image.at(0, 0), 0.0f);
}

TEST(WhittedClassic, LightsCameraAndPath) {
    Scene s = loadSceneFile(test::builtinSceneFile("whitted-classic"), {.loadTextures = false});
    ASSERT_EQ(s.lights.size(), 2u);
    EXPECT_EQ(s.lights[0].name, "key");
    EXPECT_EQ(s.lights[0].type, Light::Type::Point);
    EXPECT_VEC_NEAR(s.lights[0].position, glm::vec3(4, 8, 6), 0.0f);
    EXPECT_VEC_NEAR(s.lights[0].color, glm::vec3(1.0f, 0.95f, 0.9f), 1e-6f);
    EXPECT_FLOAT_EQ(s.lights[0].intensity, 80.0f);
    EXPECT_TRUE(s.lights[0].castsShadows);
    EXPECT_EQ(s.lights[1].name, "fill");
    EXPECT_EQ(s.lights[1].type, Light::Type::Point);
    EXPECT_FLOAT_EQ(s.lights[1].intensity, 40.0f);

    EXPECT_VEC_NEAR(s.sky.color, glm::vec3(0.35f, 0.55f, 0.9f), 1e-6f);
    EXPECT_FALSE(s.sky.hasCubeMap());
    EXPECT_VEC_NEAR(s.ambient, glm::vec3(0.08f, 0.08f, 0.1f), 1e-6f);
    EXPECT_FLOAT_EQ(s.ambientIor, 1.0f);

    EXPECT_EQ(s.camera.projection, Camera::Projection::Perspective);
    EXPECT_VEC_NEAR(s.camera.position, glm::vec3(0.0f, 2.2f, 9.0f), 1e-6f);
    EXPECT_VEC_NEAR(s.camera.forward(), glm::normalize(glm::vec3(0.0f, 1.0f, 0.0f) - glm::vec3(0.0f, 2.2f, 9.0f)), 1e-6f);
    EXPECT_FLOAT_EQ(s.camera.fovYDegrees, 40.0f);

    ASSERT_EQ(s.cameraPaths.size(), 1u);
    const CameraPath* p = s.findCameraPath("orbit");
    ASSERT_NE(p, nullptr);
    EXPECT_EQ(s.findCameraPath("nope"), nullptr);
    EXPECT_EQ(p->interpolation, Interpolation::CatmullRom);
    EXPECT_TRUE(p->keysLookAt);
    EXPECT_EQ(p->times.size(), 3u);
    EXPECT_DOUBLE_EQ(p->framesPerSecond, 30.0);
    EXPECT_DOUBLE_EQ(p->duration(), 2.0);
    EXPECT_EQ(p->frameCount(), 61);
    Camera last = p->evaluate(p->frameTime(p->frameCount() - 1), s.camera);
    EXPECT_VEC_NEAR(last.position, glm::vec3(8.0f, 3.0f, 2.0f), 1e-5f);
    EXPECT_FLOAT_EQ(last.fovYDegrees, 40.0f);
}

TEST(CornellMirrorGlass, ObjectsTrianglesMaterialsAndStats) {
    Scene s = loadSceneFile(test::builtinSceneFile("cornell-mirror-glass"));
    EXPECT_EQ(s.name, "cornell-mirror-glass");
    ASSERT_EQ(s.objects.size(), 7u);
    const char* planes[] = {"floor", "ceiling", "back-wall", "left-wall", "right-wall"};
    for (const char* name : planes) EXPECT_EQ(s.objectTriangleCount(objectIndex(s, name)), 2u) << name;
    EXPECT_EQ(s.objectTriangleCount(objectIndex(s, "mirror-cube")), 12u);
    EXPECT_EQ(s.objectTriangleCount(objectIndex(s, "glass-sphere")), kSphere64x32Triangles);
    SceneStats st = s.stats();
    EXPECT_EQ(st.triangles, 5 * 2 + 12 + kSphere64x32Triangles);  // 3990
    EXPECT_EQ(st.triangles, 3990u);
    EXPECT_EQ(st.vertices, 5 * 4 + 24 + kSphere64x32Vertices);
    EXPECT_EQ(st.lights, 1u);
    EXPECT_EQ(st.reflectiveObjects, 1u);
    EXPECT_EQ(st.refractiveObjects, 1u);
    EXPECT_TRUE(s.objectIsReflective(objectIndex(s, "mirror-cube")));
    EXPECT_FALSE(s.objectIsRefractive(objectIndex(s, "mirror-cube")));
    EXPECT_TRUE(s.objectIsRefractive(objectIndex(s, "glass-sphere")));
    EXPECT_TRUE(s.textures.empty());

    // Materials.
    ASSERT_EQ(s.materials.size(), 5u);
    EXPECT_EQ(objectMaterial(s, "left-wall").name, "red");
    EXPECT_EQ(objectMaterial(s, "right-wall").name, "green");
    EXPECT_VEC_NEAR(objectMaterial(s, "left-wall").diffuse, glm::vec3(0.63f, 0.065f, 0.05f), 1e-6f);
    const Material& mirror = objectMaterial(s, "mirror-cube");
    EXPECT_FLOAT_EQ(mirror.reflectivity, 0.95f);
    EXPECT_FALSE(mirror.fresnel);
    const Material& glass = objectMaterial(s, "glass-sphere");
    EXPECT_TRUE(glass.fresnel);
    EXPECT_FLOAT_EQ(glass.ior, 1.5f);
    EXPECT_FLOAT_EQ(glass.opacity, 0.0f);
    EXPECT_FLOAT_EQ(glass.specularExponent, 200.0f);
    // Unset keys keep the defaults.
    EXPECT_FLOAT_EQ(objectMaterial(s, "left-wall").specularExponent, 32.0f);
    EXPECT_VEC_NEAR(glass.ambient, glm::vec3(0.0f), 0.0f);
}

TEST(CornellMirrorGlass, WallsFaceIntoTheBox) {
    // The walls are planes (normal +Y) turned by Euler angles: a wrong angle order or sign would
    // turn one of them away from the box centre.
    Scene s = loadSceneFile(test::builtinSceneFile("cornell-mirror-glass"));
    const glm::vec3 centre(0.0f, 2.5f, 0.0f);
    const char* planes[] = {"floor", "ceiling", "back-wall", "left-wall", "right-wall"};
    for (const char* name : planes) {
        const SceneObject& o = s.objects[objectIndex(s, name)];
        const Mesh& m = s.meshes[o.meshes[0]];
        const glm::mat4 world = o.worldMatrix(0.0);
        glm::vec3 n = glm::normalize(normalMatrix(world) * m.normals[0]);
        glm::vec3 p = glm::vec3(world * glm::vec4(0, 0, 0, 1));
        EXPECT_VEC_NEAR(n, glm::normalize(centre - p), 1e-5f) << name;
        EXPECT_NEAR(glm::length(centre - p), 2.5f, 1e-5f) << name;
    }
}

TEST(CornellMirrorGlass, SpotLightCameraAndPath) {
    Scene s = loadSceneFile(test::builtinSceneFile("cornell-mirror-glass"));
    ASSERT_EQ(s.lights.size(), 1u);
    const Light& l = s.lights[0];
    EXPECT_EQ(l.name, "ceiling-spot");
    EXPECT_EQ(l.type, Light::Type::Spot);
    EXPECT_STREQ(lightTypeName(l.type), "spot");
    EXPECT_VEC_NEAR(l.position, glm::vec3(0.0f, 4.85f, 0.0f), 1e-6f);
    EXPECT_VEC_NEAR(l.direction, glm::vec3(0, -1, 0), 1e-6f);
    EXPECT_FLOAT_EQ(l.innerConeDegrees, 50.0f);
    EXPECT_FLOAT_EQ(l.outerConeDegrees, 65.0f);
    EXPECT_FLOAT_EQ(l.intensity, 22.0f);
    EXPECT_VEC_NEAR(l.color, glm::vec3(1.0f), 0.0f);

    EXPECT_VEC_NEAR(s.camera.position, glm::vec3(0.0f, 2.5f, 9.5f), 1e-6f);
    EXPECT_FLOAT_EQ(s.camera.fovYDegrees, 34.0f);
    ASSERT_EQ(s.cameraPaths.size(), 1u);
    const CameraPath& p = s.cameraPaths[0];
    EXPECT_EQ(p.name, "dolly");
    EXPECT_EQ(p.interpolation, Interpolation::Linear);
    EXPECT_EQ(p.times.size(), 2u);
    EXPECT_EQ(p.frameCount(), 31);
    Camera mid = p.evaluate(0.5, s.camera);
    EXPECT_VEC_NEAR(mid.position, glm::vec3(0.6f, 2.35f, 8.25f), 1e-5f);
    EXPECT_VEC_NEAR(mid.forward(), glm::normalize(glm::vec3(0.0f, 1.9f, 0.0f) - mid.position), 1e-5f);
}

TEST(SceneFile, MinimalFixtureLoadsAndErrorsArePrecise) {
    // Every fixture in bad/ is this file with one defect.
    Scene s = loadSceneFile(test::fixturesDir() / "minimal.toml");
    EXPECT_EQ(s.name, "minimal") << "the file name when there is no [scene] name";
    EXPECT_EQ(s.objects.size(), 1u);
    EXPECT_EQ(s.stats().triangles, 12u);
    EXPECT_TRUE(s.lights.empty());
    EXPECT_TRUE(s.cameraPaths.empty());

    // Errors name the file, line, column and key (the CLI tests cover them in depth).
    TempDir dir;
    writeTextFile(dir / "empty.toml", "[camera]\nposition = [0.0, 0.0, 1.0]\nlook_at = [0.0, 0.0, 0.0]\n");
    EXPECT_CONTAINS(loadError(dir / "empty.toml"), "empty.toml:1:1: the scene has no objects");
    EXPECT_CONTAINS(loadError(dir / "absent.toml"), "absent.toml: file not found");
    EXPECT_CONTAINS(loadError(test::fixturesDir() / "bad" / "out-of-range.toml"),
                    "out-of-range.toml:5:11: materials.grey.opacity: expected a number in [0, 1], got 1.5");
}

TEST(SceneFile, AnimationOrientationKeysAndLights) {
    TempDir dir;
    writeTextFile(dir / "anim.toml", R"(
[materials.m]
diffuse = [0.5, 0.5, 0.5]
casts_shadows = false

[[objects]]
name = "mover"
primitive = "cube"
material = "m"
position = [0.0, 1.0, 0.0]
scale = 2.0
[objects.animation]
interpolation = "linear"
keys = [
  { time = 0.0 },
  { time = 2.0, position = [4.0, 1.0, 0.0], rotation = [0.0, 90.0, 0.0] },
]

[[lights]]
type = "directional"
direction = [0.0, -2.0, 0.0]
casts_shadows = false

[[lights]]
type = "spot"
position = [0.0, 5.0, 0.0]
target = [3.0, 1.0, 0.0]

[camera]
projection = "orthographic"
height = 8.0
position = [0.0, 0.0, 10.0]
orientation = [0.0, 90.0, 0.0]

[camera_paths.turn]
interpolation = "linear"
keys = [
  { time = 0.0, position = [0.0, 0.0, 10.0], orientation = [0.0, 0.0, 0.0] },
  { time = 1.0, position = [0.0, 0.0, 10.0], orientation = [0.0, 90.0, 0.0] },
]
)");
    Scene s = loadSceneFile(dir / "anim.toml");
    ASSERT_EQ(s.objects.size(), 1u);
    const SceneObject& o = s.objects[0];
    ASSERT_TRUE(o.isAnimated());
    EXPECT_TRUE(s.isAnimated());
    EXPECT_EQ(o.animation.times.size(), 2u);
    // Key 0 gives no components: it keeps the object's placement.
    EXPECT_VEC_NEAR(o.animation.positions[0], glm::vec3(0, 1, 0), 0.0f);
    EXPECT_VEC_NEAR(o.animation.scales[1], glm::vec3(2.0f), 0.0f);
    EXPECT_VEC_NEAR(glm::vec3(o.worldMatrix(1.0) * glm::vec4(0, 0, 0, 1)), glm::vec3(2, 1, 0), 1e-5f);
    EXPECT_VEC_NEAR(glm::vec3(o.worldMatrix(2.0) * glm::vec4(0, 0, 0.5f, 1)), glm::vec3(5, 1, 0), 1e-5f);
    Aabb b = s.objectBounds(0, 2.0);
    EXPECT_VEC_NEAR(b.lo, glm::vec3(3, 0, -1), 1e-5f);
    EXPECT_FALSE(s.materials[0].castsShadows);

    ASSERT_EQ(s.lights.size(), 2u);
    EXPECT_EQ(s.lights[0].name, "directional0") << "unnamed lights are named by type and count";
    EXPECT_EQ(s.lights[1].name, "spot0");
    EXPECT_VEC_NEAR(s.lights[0].direction, glm::vec3(0, -1, 0), 0.0f) << "normalised";
    EXPECT_FALSE(s.lights[0].castsShadows);
    EXPECT_VEC_NEAR(s.lights[1].direction, glm::vec3(0.6f, -0.8f, 0.0f), 1e-6f) << "from the target";

    EXPECT_EQ(s.camera.projection, Camera::Projection::Orthographic);
    EXPECT_FLOAT_EQ(s.camera.orthoHeight, 8.0f);
    EXPECT_VEC_NEAR(s.camera.forward(), glm::vec3(-1, 0, 0), 1e-6f);
    ASSERT_EQ(s.cameraPaths.size(), 1u);
    const CameraPath& p = s.cameraPaths[0];
    EXPECT_FALSE(p.keysLookAt);
    EXPECT_DOUBLE_EQ(p.framesPerSecond, 30.0);
    EXPECT_EQ(p.interpolation, Interpolation::Linear);
    Camera mid = p.evaluate(0.5, s.camera);
    EXPECT_VEC_NEAR(mid.forward(), glm::normalize(glm::vec3(-1, 0, -1)), 1e-5f);
    EXPECT_EQ(mid.projection, Camera::Projection::Orthographic);
}

TEST(SceneFile, ModelWithMaterialsTexturesAndGltfCamera) {
    TempDir dir;
    std::filesystem::create_directories(dir / "models");
    test::GltfBuilder b;
    int pos = b.addFloats(test::kTrianglePositions, "VEC3");
    int red = b.addMaterial("red", {0.9, 0.1, 0.1, 1.0});
    int mesh = b.addMesh("tri", pos, -1, -1, red);
    int cam = b.addPerspectiveCamera(0.5, 0.2, 50.0, 1.0);
    b.setRoots({b.addNode({{"name", "geometry"}, {"mesh", mesh}}),
                b.addNode({{"name", "view"}, {"camera", cam}, {"translation", {0.0, 0.0, 4.0}}})});
    b.writeGltf(dir / "models" / "thing.gltf");
    // A 2 x 1 texture: sRGB (255, 0, 0) and (0, 0, 255) once written as a display PNG.
    Image img(2, 1);
    img.at(0, 0) = {1, 0, 0, 1};
    img.at(1, 0) = {0, 0, 1, 1};
    writeDisplayPng(dir / "stripes.png", img);
    writeTextFile(dir / "model.toml", R"(
[scene]
name = "model-scene"

[materials.painted]
diffuse_texture = "stripes.png"

[materials.also-painted]
diffuse_texture = "stripes.png"

[[objects]]
name = "thing"
model = "models/thing.gltf"
position = [10.0, 0.0, 0.0]
rotation = [0.0, 90.0, 0.0]

[[objects]]
name = "painted-thing"
model = "models/thing.gltf"
node = "geometry"
material = "painted"

[camera]
gltf_object = "thing"
gltf_camera = "view"
)");
    Scene s = loadSceneFile(dir / "model.toml");
    EXPECT_EQ(s.name, "model-scene");
    ASSERT_EQ(s.objects.size(), 2u);
    // Scene materials first, then the model's (default + red), named after the object.
    ASSERT_EQ(s.materials.size(), 4u);
    EXPECT_EQ(s.materials[2].name, "thing/default");
    EXPECT_EQ(s.materials[3].name, "thing/red");
    EXPECT_EQ(objectMaterial(s, "thing").name, "thing/red");
    EXPECT_EQ(objectMaterial(s, "painted-thing").name, "painted");
    // One texture for both materials that name the same file.
    ASSERT_EQ(s.textures.size(), 1u);
    EXPECT_EQ(s.materials[0].diffuseTexture, 0);
    EXPECT_EQ(s.materials[1].diffuseTexture, 0);
    ASSERT_EQ(s.textures[0].image.width(), 2);
    EXPECT_VEC_NEAR(s.textures[0].image.at(0, 0), glm::vec4(1, 0, 0, 1), 1e-6f) << "decoded from sRGB";
    EXPECT_VEC_NEAR(s.textures[0].image.at(1, 0), glm::vec4(0, 0, 1, 1), 1e-6f);
    // The glTF camera at (0, 0, 4) in the model moves with the object: turned 90 degrees about Y
    // (z -> x) and moved by (10, 0, 0).
    EXPECT_VEC_NEAR(s.camera.position, glm::vec3(14, 0, 0), 1e-5f);
    EXPECT_VEC_NEAR(s.camera.forward(), glm::vec3(-1, 0, 0), 1e-5f);
    EXPECT_NEAR(s.camera.fovYDegrees, glm::degrees(0.5f), 1e-4f);

    // Without texture decoding the texture is recorded but empty.
    Scene counts = loadSceneFile(dir / "model.toml", {.loadTextures = false});
    ASSERT_EQ(counts.textures.size(), 1u);
    EXPECT_TRUE(counts.textures[0].image.empty());
    EXPECT_EQ(counts.stats().triangles, 2u);
}

}  // namespace
}  // namespace hybridlab

namespace hybridlab {
namespace {

TEST(SceneFile, LensObjectsAndLensGroups) {
    TempDir dir;
    const std::string head =
        "[materials.glass]\nopacity = 0.0\nfresnel = true\n"
        "[camera]\nposition = [0.0, 0.0, 5.0]\nlook_at = [0.0, 0.0, 0.0]\n";
    writeTextFile(dir / "lens.toml", head +
        "[[objects]]\nname = \"pot\"\nprimitive = \"sphere\"\nmaterial = \"glass\"\nlens = true\nlens_group = \"pot-and-cup\"\n"
        "[[objects]]\nname = \"cup\"\nprimitive = \"cube\"\nmaterial = \"glass\"\nlens = true\nlens_group = \"pot-and-cup\"\n"
        "[[objects]]\nname = \"lone\"\nprimitive = \"cube\"\nmaterial = \"glass\"\nlens = true\n"
        "[[objects]]\nname = \"wall\"\nprimitive = \"cube\"\nmaterial = \"glass\"\n");
    Scene s = loadSceneFile(dir / "lens.toml", {.loadTextures = false});
    EXPECT_EQ(s.objects[objectIndex(s, "pot")].lensGroup, "pot-and-cup");
    EXPECT_EQ(s.objects[objectIndex(s, "cup")].lensGroup, "pot-and-cup");
    EXPECT_TRUE(s.objects[objectIndex(s, "lone")].lens);
    EXPECT_EQ(s.objects[objectIndex(s, "lone")].lensGroup, "");
    EXPECT_FALSE(s.objects[objectIndex(s, "wall")].lens);

    writeTextFile(dir / "nolens.toml", head + "[[objects]]\nname = \"pot\"\nprimitive = \"sphere\"\nmaterial = \"glass\"\nlens_group = \"g\"\n");
    EXPECT_CONTAINS(loadError(dir / "nolens.toml"), "nolens.toml:11:14: objects[0].lens_group: a lens group needs 'lens = true' on the object");
    writeTextFile(dir / "empty.toml", head + "[[objects]]\nname = \"pot\"\nprimitive = \"sphere\"\nmaterial = \"glass\"\nlens = true\nlens_group = \"\"\n");
    EXPECT_CONTAINS(loadError(dir / "empty.toml"), "empty.toml:12:14: objects[0].lens_group: expected a non-empty group name");
    writeTextFile(dir / "type.toml", head + "[[objects]]\nname = \"pot\"\nprimitive = \"sphere\"\nmaterial = \"glass\"\nlens = true\nlens_group = 3\n");
    EXPECT_CONTAINS(loadError(dir / "type.toml"), "type.toml:12:14: objects[0].lens_group: expected a string");
}

}  // namespace
}  // namespace hybridlab

namespace hybridlab {
namespace {

// [objects.copies]: copy k is copy 0 turned about the vertical axis through the centre by k steps,
// k * time_step seconds late in both its rigid animation and its deformation; each owns its meshes.
TEST(SceneFile, CopiesInARing) {
    TempDir dir;
    const std::string head =
        "[materials.grey]\ndiffuse = [0.5, 0.5, 0.5]\n"
        "[camera]\nposition = [0.0, 0.0, 5.0]\nlook_at = [0.0, 0.0, 0.0]\n";
    writeTextFile(dir / "ring.toml", head +
        "[[objects]]\nname = \"box\"\nprimitive = \"sphere\"\nmaterial = \"grey\"\n"
        "[objects.animation]\nkeys = [ { time = 0.0, position = [3.0, 0.0, 0.0] }, { time = 2.0, position = [3.0, 2.0, 1.0], rotation = [0.0, 40.0, 0.0] } ]\n"
        "[objects.deform]\namplitude = 0.05\nwavelength = 0.3\nspeed = 0.7\n"
        "[objects.copies]\ncount = 3\ncenter = [1.0, 0.0, 0.0]\nangle_step = 90.0\ntime_step = 0.5\n");
    const Scene s = loadSceneFile(dir / "ring.toml", {.loadTextures = false});
    ASSERT_EQ(s.objects.size(), 3u);
    const double t = 0.6;
    DeformedVertices first, late;
    deformMesh(s.objects[0].deformation, s.meshes[s.objects[0].meshes[0]], t, first);
    for (std::size_t k = 0; k < 3; ++k) {
        SCOPED_TRACE(k);
        const SceneObject& o = s.objects[k];
        EXPECT_EQ(o.name, "box-" + std::to_string(k));
        EXPECT_EQ(o.meshes, std::vector<std::uint32_t>{static_cast<std::uint32_t>(k)});
        const glm::mat4 turn = glm::translate(glm::mat4(1.0f), glm::vec3(1, 0, 0)) *
                               glm::mat4_cast(eulerDegreesToQuat(glm::vec3(0.0f, 90.0f * static_cast<float>(k), 0.0f))) *
                               glm::translate(glm::mat4(1.0f), glm::vec3(-1, 0, 0));
        const glm::vec4 p(0.2f, 0.1f, -0.3f, 1.0f);
        EXPECT_VEC_NEAR(glm::vec3(o.worldMatrix(t + 0.5 * static_cast<double>(k)) * p), glm::vec3(turn * s.objects[0].worldMatrix(t) * p), 1e-5f);
        deformMesh(o.deformation, s.meshes[o.meshes[0]], t + 0.5 * static_cast<double>(k), late);
        for (std::size_t v = 0; v < late.positions.size(); v += 97) EXPECT_VEC_NEAR(late.positions[v], first.positions[v], 1e-4f);
    }
    // Copy 1 starts when copy 0 does plus the time step.
    EXPECT_DOUBLE_EQ(s.objects[1].animation.times[0], 0.5);

    writeTextFile(dir / "clash.toml", head +
        "[[objects]]\nname = \"box-1\"\nprimitive = \"cube\"\nmaterial = \"grey\"\n"
        "[[objects]]\nname = \"box\"\nprimitive = \"cube\"\nmaterial = \"grey\"\n[objects.copies]\ncount = 2\n");
    EXPECT_CONTAINS(loadError(dir / "clash.toml"), "clash.toml:15:9: objects[1].copies.count: copy name 'box-1' is already an object's name");
}

}  // namespace
}  // namespace hybridlab
