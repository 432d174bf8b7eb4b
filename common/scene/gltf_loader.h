#pragma once
// glTF 2.0 (.gltf and .glb) through tinygltf: meshes with node transforms baked into object
// space, base-colour materials and textures, and cameras.
#include <filesystem>
#include <string>
#include <vector>

#include "common/scene/camera.h"
#include "common/scene/material.h"
#include "common/scene/mesh.h"
#include "common/scene/texture.h"

namespace hybridlab {

struct GltfCamera {
    std::string nodeName;
    Camera camera;  // in the file's space
};

struct GltfContent {
    std::vector<Mesh> meshes;          // Mesh::material indexes `materials`
    std::vector<Material> materials;   // texture indices index `textures`
    std::vector<Texture> textures;
    std::vector<GltfCamera> cameras;
    std::size_t droppedDegenerateTriangles = 0;
    std::vector<std::filesystem::path> sourceFiles;  // the file, its external buffers and images
};

struct GltfLoadOptions {
    std::string node;             // empty: every node of the default scene; else that node's subtree
    bool smoothNormals = false;   // for primitives without normals (glTF says flat)
    bool loadMaterials = true;    // false when the scene file overrides them
    bool decodeTextures = true;   // false: record texture paths only (listings that need counts)
};

// Throws InputError naming the file (and the mesh, primitive or node) on anything malformed:
// parse errors, missing buffers or images, out-of-range indices, non-finite vertex data,
// unsupported primitive modes or sparse accessors, an unknown node name.
GltfContent loadGltf(const std::filesystem::path& file, const GltfLoadOptions& options);

}  // namespace hybridlab
