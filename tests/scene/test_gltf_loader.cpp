// glTF loading (gltf_loader.h) from small files written by the tests: node transforms baked into
// positions, flat or smooth normals when NORMAL is missing, node selection, cameras, .glb, and
// clear errors for malformed files.
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "common/core/input_error.h"
#include "common/scene/gltf_loader.h"
#include "common/scene/transform.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

using test::GltfBuilder;
using test::kTrianglePositions;
using test::TempDir;

// A triangle with normals, in node "tri" translated by (1, 2, 3).
GltfBuilder translatedTriangle() {
    GltfBuilder b;
    int pos = b.addFloats(kTrianglePositions, "VEC3");
    int nrm = b.addFloats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
    int mesh = b.addMesh("triangle", pos, nrm);
    b.setRoots({b.addNode({{"name", "tri"}, {"mesh", mesh}, {"translation", {1.0, 2.0, 3.0}}})});
    return b;
}

// A unit quad in the XY plane folded along its diagonal (corner 3 lifted to z = 1), indexed, no
// normals: 4 vertices, 2 triangles.
GltfBuilder foldedQuadWithoutNormals() {
    GltfBuilder b;
    int pos = b.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 1}, "VEC3");
    int idx = b.addIndices({0, 1, 2, 1, 3, 2});
    int mesh = b.addMesh("quad", pos, -1, idx);
    b.setRoots({b.addNode({{"name", "quad"}, {"mesh", mesh}})});
    return b;
}

std::string loadError(const std::filesystem::path& file, const GltfLoadOptions& options = {}) {
    try {
        loadGltf(file, options);
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(GltfLoader, NodeTranslationIsBakedIntoPositions) {
    TempDir dir;
    translatedTriangle().writeGltf(dir / "tri.gltf");
    GltfContent c = loadGltf(dir / "tri.gltf", {});
    ASSERT_EQ(c.meshes.size(), 1u);
    const Mesh& m = c.meshes[0];
    EXPECT_EQ(m.name, "triangle");
    ASSERT_EQ(m.triangleCount(), 1u);
    ASSERT_EQ(m.vertexCount(), 3u);
    EXPECT_VEC_NEAR(m.positions[0], glm::vec3(1, 2, 3), 1e-6f);
    EXPECT_VEC_NEAR(m.positions[1], glm::vec3(2, 2, 3), 1e-6f);
    EXPECT_VEC_NEAR(m.positions[2], glm::vec3(1, 3, 3), 1e-6f);
    for (const auto& n : m.normals) EXPECT_VEC_NEAR(n, glm::vec3(0, 0, 1), 1e-6f);
    EXPECT_EQ(c.droppedDegenerateTriangles, 0u);
    EXPECT_TRUE(c.cameras.empty());
    // Without materials in the file, every mesh uses the default material 0.
    ASSERT_EQ(c.materials.size(), 1u);
    EXPECT_EQ(m.material, 0u);
}

TEST(GltfLoader, NodeTransformsCompose) {
    // parent: translate (10, 0, 0), rotate 90 degrees about Z; child: scale 2, translate (0, 1, 0).
    GltfBuilder b;
    int pos = b.addFloats(kTrianglePositions, "VEC3");
    int nrm = b.addFloats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
    int mesh = b.addMesh("triangle", pos, nrm);
    const double s = std::sqrt(0.5);
    int parent = b.addNode({{"name", "parent"}, {"translation", {10.0, 0.0, 0.0}}, {"rotation", {0.0, 0.0, s, s}}});
    int child = b.addNode({{"name", "child"}, {"mesh", mesh}, {"translation", {0.0, 1.0, 0.0}}, {"scale", {2.0, 2.0, 2.0}}});
    b.addChild(parent, child);
    b.setRoots({parent});
    TempDir dir;
    b.writeGltf(dir / "nested.gltf");
    GltfContent c = loadGltf(dir / "nested.gltf", {});
    ASSERT_EQ(c.meshes.size(), 1u);
    // world = T(10,0,0) Rz(90) T(0,1,0) S(2): local p -> (10,0,0) + Rz(90) ((0,1,0) + 2p).
    auto expected = [](glm::vec3 p) {
        glm::vec3 q = glm::vec3(0, 1, 0) + 2.0f * p;
        return glm::vec3(10, 0, 0) + glm::vec3(-q.y, q.x, q.z);
    };
    for (std::size_t i = 0; i < 3; ++i) {
        glm::vec3 local(kTrianglePositions[3 * i], kTrianglePositions[3 * i + 1], kTrianglePositions[3 * i + 2]);
        EXPECT_VEC_NEAR(c.meshes[0].positions[i], expected(local), 1e-5f);
        EXPECT_VEC_NEAR(c.meshes[0].normals[i], glm::vec3(0, 0, 1), 1e-6f);
    }

    // A node matrix (column-major): scale x by 3, translate by (0, 0, -4).
    GltfBuilder mb;
    int mmesh = mb.addMesh("triangle", mb.addFloats(kTrianglePositions, "VEC3"));
    mb.setRoots({mb.addNode({{"mesh", mmesh}, {"matrix", {3, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -4, 1}}})});
    mb.writeGltf(dir / "matrix.gltf");
    GltfContent mc = loadGltf(dir / "matrix.gltf", {});
    ASSERT_EQ(mc.meshes.size(), 1u);
    EXPECT_VEC_NEAR(mc.meshes[0].bounds().lo, glm::vec3(0, 0, -4), 1e-6f);
    EXPECT_VEC_NEAR(mc.meshes[0].bounds().hi, glm::vec3(3, 1, -4), 1e-6f);
}

TEST(GltfLoader, MissingNormalsGiveFlatOrSmoothNormals) {
    TempDir dir;
    foldedQuadWithoutNormals().writeGltf(dir / "quad.gltf");
    GltfContent c = loadGltf(dir / "quad.gltf", {});
    ASSERT_EQ(c.meshes.size(), 1u);
    const Mesh& m = c.meshes[0];
    ASSERT_EQ(m.triangleCount(), 2u);
    ASSERT_EQ(m.vertexCount(), 6u) << "glTF: without NORMAL every triangle is flat, with its own vertices";
    const glm::vec3 n1 = glm::normalize(glm::vec3(-1, -1, 1));
    for (int k = 0; k < 3; ++k) {
        EXPECT_VEC_NEAR(m.normals[m.triangles[0][k]], glm::vec3(0, 0, 1), 1e-6f);
        EXPECT_VEC_NEAR(m.normals[m.triangles[1][k]], n1, 1e-6f);
    }

    // With the smooth_normals option: shared vertices, area-weighted normals.
    GltfLoadOptions opt;
    opt.smoothNormals = true;
    GltfContent sc = loadGltf(dir / "quad.gltf", opt);
    ASSERT_EQ(sc.meshes.size(), 1u);
    const Mesh& sm = sc.meshes[0];
    ASSERT_EQ(sm.vertexCount(), 4u) << "smooth normals keep shared vertices";
    // Triangle 0 has cross product (0, 0, 1); triangle 1 has (-1, -1, 1).
    EXPECT_VEC_NEAR(sm.normals[0], glm::vec3(0, 0, 1), 1e-6f);
    EXPECT_VEC_NEAR(sm.normals[3], glm::normalize(glm::vec3(-1, -1, 1)), 1e-6f);
    EXPECT_VEC_NEAR(sm.normals[1], glm::normalize(glm::vec3(-1, -1, 2)), 1e-6f) << "shared: the area-weighted sum";
    EXPECT_VEC_NEAR(sm.normals[2], glm::normalize(glm::vec3(-1, -1, 2)), 1e-6f);
}

// Two top-level subtrees: "parent" (translate x by 10) holding "child" (translate y by 5) with
// the triangle, and "other" with a second mesh far away.
GltfBuilder twoSubtrees() {
    GltfBuilder b;
    int pos = b.addFloats(kTrianglePositions, "VEC3");
    int near = b.addMesh("near", pos);
    int far = b.addMesh("far", pos);
    int parent = b.addNode({{"name", "parent"}, {"translation", {10.0, 0.0, 0.0}}});
    int child = b.addNode({{"name", "child"}, {"mesh", near}, {"translation", {0.0, 5.0, 0.0}}});
    int other = b.addNode({{"name", "other"}, {"mesh", far}, {"translation", {0.0, 0.0, -100.0}}});
    b.addChild(parent, child);
    b.setRoots({parent, other});
    return b;
}

TEST(GltfLoader, NamedNodeSelection) {
    TempDir dir;
    twoSubtrees().writeGltf(dir / "two.gltf");
    EXPECT_EQ(loadGltf(dir / "two.gltf", {}).meshes.size(), 2u);

    GltfLoadOptions opt;
    opt.node = "child";
    GltfContent c = loadGltf(dir / "two.gltf", opt);
    ASSERT_EQ(c.meshes.size(), 1u);
    EXPECT_EQ(c.meshes[0].name, "near");
    // The node keeps its place: its parent's translation applies too.
    EXPECT_VEC_NEAR(c.meshes[0].positions[0], glm::vec3(10, 5, 0), 1e-6f);

    opt.node = "parent";
    c = loadGltf(dir / "two.gltf", opt);
    ASSERT_EQ(c.meshes.size(), 1u);
    EXPECT_EQ(c.meshes[0].name, "near");
    EXPECT_VEC_NEAR(c.meshes[0].positions[0], glm::vec3(10, 5, 0), 1e-6f);

    opt.node = "other";
    c = loadGltf(dir / "two.gltf", opt);
    ASSERT_EQ(c.meshes.size(), 1u);
    EXPECT_EQ(c.meshes[0].name, "far");
    EXPECT_VEC_NEAR(c.meshes[0].positions[0], glm::vec3(0, 0, -100), 1e-6f);

    opt.node = "nobody";
    std::string e = loadError(dir / "two.gltf", opt);
    EXPECT_CONTAINS(e, "two.gltf");
    EXPECT_CONTAINS(e, "no node named 'nobody' (nodes: parent, child, other)");
}

TEST(GltfLoader, PerspectiveCameraNode) {
    GltfBuilder b;
    int mesh = b.addMesh("triangle", b.addFloats(kTrianglePositions, "VEC3"));
    int cam = b.addPerspectiveCamera(0.8, 0.1, 250.0, 1.5);
    // Turned 90 degrees about Y (looking along -X) and tilted down 30 degrees about its own X.
    glm::quat q = eulerDegreesToQuat({0, 90, 0}) * eulerDegreesToQuat({-30, 0, 0});
    int rig = b.addNode({{"name", "rig"}, {"translation", {0.0, 2.0, 0.0}}});
    int camNode = b.addNode({{"name", "shot"}, {"camera", cam}, {"translation", {5.0, 1.0, 0.0}}, {"rotation", {q.x, q.y, q.z, q.w}}});
    b.addChild(rig, camNode);
    b.setRoots({b.addNode({{"mesh", mesh}}), rig});
    TempDir dir;
    b.writeGltf(dir / "camera.gltf");
    GltfContent c = loadGltf(dir / "camera.gltf", {});
    ASSERT_EQ(c.cameras.size(), 1u);
    const GltfCamera& gc = c.cameras[0];
    EXPECT_EQ(gc.nodeName, "shot");
    EXPECT_EQ(gc.camera.projection, Camera::Projection::Perspective);
    EXPECT_VEC_NEAR(gc.camera.position, glm::vec3(5, 3, 0), 1e-5f);
    EXPECT_NEAR(gc.camera.fovYDegrees, 0.8f * 180.0f / 3.14159265f, 1e-3f);
    EXPECT_NEAR(gc.camera.nearPlane, 0.1f, 1e-7f);
    EXPECT_NEAR(gc.camera.farPlane, 250.0f, 1e-4f);
    // glTF cameras look down their local -Z, as ours do.
    EXPECT_VEC_NEAR(gc.camera.forward(), glm::vec3(-std::cos(glm::radians(30.0f)), -0.5f, 0.0f), 1e-5f);
    EXPECT_VEC_NEAR(gc.camera.up(), q * glm::vec3(0, 1, 0), 1e-5f);
}

TEST(GltfLoader, BaseColorMaterialsFollowTheDefaultMaterial) {
    GltfBuilder b;
    int pos = b.addFloats(kTrianglePositions, "VEC3");
    b.addMaterial("red", {0.8, 0.1, 0.1, 1.0});
    int blue = b.addMaterial("blue", {0.1, 0.2, 0.9, 1.0});
    int mesh = b.addMesh("triangle", pos, -1, -1, blue);
    b.setRoots({b.addNode({{"mesh", mesh}})});
    TempDir dir;
    b.writeGltf(dir / "materials.gltf");
    GltfContent c = loadGltf(dir / "materials.gltf", {});
    ASSERT_EQ(c.materials.size(), 3u);  // the default, then the file's two
    EXPECT_EQ(c.materials[1].name, "red");
    EXPECT_EQ(c.materials[2].name, "blue");
    EXPECT_VEC_NEAR(c.materials[2].diffuse, glm::vec3(0.1f, 0.2f, 0.9f), 1e-6f);
    ASSERT_EQ(c.meshes.size(), 1u);
    EXPECT_EQ(c.meshes[0].material, 2u);

    GltfLoadOptions opt;
    opt.loadMaterials = false;
    c = loadGltf(dir / "materials.gltf", opt);
    EXPECT_EQ(c.materials.size(), 1u);
    EXPECT_EQ(c.meshes[0].material, 0u);
}

TEST(GltfLoader, BinaryGlbLoadsLikeGltf) {
    TempDir dir;
    GltfBuilder b = translatedTriangle();
    b.writeGlb(dir / "tri.glb");
    b.writeGltf(dir / "tri.gltf");
    GltfContent fromGlb = loadGltf(dir / "tri.glb", {});
    GltfContent fromGltf = loadGltf(dir / "tri.gltf", {});
    ASSERT_EQ(fromGlb.meshes.size(), 1u);
    EXPECT_EQ(fromGlb.meshes[0].positions, fromGltf.meshes[0].positions);
    EXPECT_EQ(fromGlb.meshes[0].normals, fromGltf.meshes[0].normals);
    EXPECT_EQ(fromGlb.meshes[0].triangles, fromGltf.meshes[0].triangles);
    EXPECT_VEC_NEAR(fromGlb.meshes[0].positions[2], glm::vec3(1, 3, 3), 1e-6f);
}

TEST(GltfLoader, DegenerateTrianglesAreDroppedAndCounted) {
    GltfBuilder b;
    // Triangle 1 repeats an index; triangle 2 is collinear.
    int pos = b.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0}, "VEC3");
    int idx = b.addIndices({0, 1, 2, 0, 0, 1, 0, 1, 3});
    b.setRoots({b.addNode({{"mesh", b.addMesh("bad", pos, -1, idx)}})});
    TempDir dir;
    b.writeGltf(dir / "degenerate.gltf");
    GltfContent c = loadGltf(dir / "degenerate.gltf", {});
    EXPECT_EQ(c.droppedDegenerateTriangles, 2u);
    ASSERT_EQ(c.meshes.size(), 1u);
    EXPECT_EQ(c.meshes[0].triangleCount(), 1u);
    for (const auto& n : c.meshes[0].normals) EXPECT_VEC_NEAR(n, glm::vec3(0, 0, 1), 1e-6f) << "no NaN normals from dropped triangles";
}

TEST(GltfLoader, OutOfRangeIndicesAreErrors) {
    TempDir dir;
    // A vertex index.
    GltfBuilder b;
    int pos = b.addFloats(kTrianglePositions, "VEC3");
    b.setRoots({b.addNode({{"mesh", b.addMesh("broken", pos, -1, b.addIndices({0, 1, 7}))}})});
    b.writeGltf(dir / "index.gltf");
    EXPECT_CONTAINS(loadError(dir / "index.gltf"), (dir / "index.gltf").string() +
                    ": mesh 'broken' primitive 0: index 7 at position 2 is out of range (the primitive has 3 vertices)");

    // A node's camera, a child node, the default scene: InputErrors naming the file, not
    // std::out_of_range (which the CLI reports as an internal error).
    GltfBuilder cam = translatedTriangle();
    cam.setRoots({0, cam.addNode({{"name", "eye"}, {"camera", 3}})});
    cam.writeGltf(dir / "camera.gltf");
    EXPECT_CONTAINS(loadError(dir / "camera.gltf"), (dir / "camera.gltf").string() + ": node 'eye': camera index out of range");
    GltfBuilder child = translatedTriangle();
    child.addChild(0, 9);
    child.writeGltf(dir / "child.gltf");
    EXPECT_CONTAINS(loadError(dir / "child.gltf"), (dir / "child.gltf").string() + ": node index out of range");
    GltfBuilder scene = translatedTriangle();
    scene.document()["scene"] = 4;
    scene.writeGltf(dir / "scene.gltf");
    EXPECT_CONTAINS(loadError(dir / "scene.gltf"), (dir / "scene.gltf").string() + ": default scene index out of range");
}

TEST(GltfLoader, NonFiniteVertexDataIsAnError) {
    std::vector<float> positions = kTrianglePositions;
    positions[4] = std::numeric_limits<float>::quiet_NaN();  // vertex 1, y
    GltfBuilder b;
    b.setRoots({b.addNode({{"mesh", b.addMesh("nan", b.addFloats(positions, "VEC3"))}})});
    TempDir dir;
    b.writeGltf(dir / "nan.gltf");
    std::string e = loadError(dir / "nan.gltf");
    EXPECT_CONTAINS(e, (dir / "nan.gltf").string());
    EXPECT_CONTAINS(e, "mesh 'nan' primitive 0 POSITION: element 1 is not finite (NaN or infinity)");

    positions[4] = 1.0f;
    std::vector<float> normals = {0, 0, 1, 0, 0, 1, 0, 0, std::numeric_limits<float>::infinity()};
    GltfBuilder b2;
    int pos = b2.addFloats(positions, "VEC3");
    b2.setRoots({b2.addNode({{"mesh", b2.addMesh("inf", pos, b2.addFloats(normals, "VEC3"))}})});
    b2.writeGltf(dir / "inf.gltf");
    EXPECT_CONTAINS(loadError(dir / "inf.gltf"), "mesh 'inf' primitive 0 NORMAL: element 2 is not finite");
}

TEST(GltfLoader, UnreadableFilesAreErrors) {
    TempDir dir;
    // An accessor that reads past the end of its buffer.
    GltfBuilder b;
    int pos = b.addFloats(kTrianglePositions, "VEC3");
    b.document()["accessors"][pos]["count"] = 300;
    b.setRoots({b.addNode({{"mesh", b.addMesh("short", pos)}})});
    b.writeGltf(dir / "short.gltf");
    EXPECT_CONTAINS(loadError(dir / "short.gltf"), (dir / "short.gltf").string() +
                                                       ": mesh 'short' primitive 0 POSITION: accessor's 300 elements of 12 bytes (stride 12, "
                                                       "offset 0) read past the end of its ");
    // A count that would allocate exabytes (2^60) is the same error, before any allocation.
    b.document()["accessors"][pos]["count"] = 1ULL << 60;
    b.writeGltf(dir / "huge.gltf");
    EXPECT_CONTAINS(loadError(dir / "huge.gltf"), "POSITION: accessor's 1152921504606846976 elements of 12 bytes");

    // Broken JSON.
    test::writeTextFile(dir / "broken.gltf", "{ \"asset\": { \"version\": \"2.0\" }, \"nodes\": [ ");
    std::string e = loadError(dir / "broken.gltf");
    EXPECT_CONTAINS(e, (dir / "broken.gltf").string() + ": not a valid glTF 2.0 file (");

    // No file, a format that is not glTF, a file without meshes.
    EXPECT_CONTAINS(loadError(dir / "absent.glb"), (dir / "absent.glb").string() + ": glTF file not found");
    test::writeTextFile(dir / "model.obj", "v 0 0 0\n");
    EXPECT_CONTAINS(loadError(dir / "model.obj"), "model.obj: unknown model format '.obj' (expected .gltf or .glb)");
    GltfBuilder empty;
    empty.setRoots({empty.addNode({{"name", "empty"}})});
    empty.writeGltf(dir / "empty.gltf");
    EXPECT_CONTAINS(loadError(dir / "empty.gltf"), (dir / "empty.gltf").string() + ": no triangle meshes");

    // Folders where files belong: a buffer's or an image's `uri`, and the model itself. tinygltf
    // read a folder as a file of 2^63 - 1 bytes (std::bad_alloc, exit 1 in the program); the glTF
    // fuzz target found them (tests/fuzz/corpus/gltf/regression-*).
    GltfBuilder named;
    const int material = named.addMaterial("textured", {1.0, 1.0, 1.0, 1.0});
    named.setRoots({named.addNode({{"mesh", named.addMesh("tri", named.addFloats(kTrianglePositions, "VEC3"), -1, -1, material)}})});
    const nlohmann::json original = nlohmann::json::parse(named.gltfText());
    nlohmann::json d = original;
    d["buffers"][0]["uri"] = ".";
    test::writeTextFile(dir / "buffer-folder.gltf", d.dump());
    EXPECT_CONTAINS(loadError(dir / "buffer-folder.gltf"), (dir / "buffer-folder.gltf").string() + ": not a valid glTF 2.0 file (");
    EXPECT_CONTAINS(loadError(dir / "buffer-folder.gltf"), "is not a regular file (a directory or a device)");
    d = original;
    d["images"] = {{{"uri", "."}}};
    d["textures"] = {{{"source", 0}}};
    d["materials"][material]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
    test::writeTextFile(dir / "image-folder.gltf", d.dump());
    EXPECT_CONTAINS(loadError(dir / "image-folder.gltf"), (dir / ".").string() + ": is a directory, expected an image file");
    std::filesystem::create_directory(dir / "folder.glb");
    EXPECT_CONTAINS(loadError(dir / "folder.glb"), (dir / "folder.glb").string() + ": is a directory, expected a glTF model (.gltf or .glb)");
}

}  // namespace
}  // namespace hybridlab
