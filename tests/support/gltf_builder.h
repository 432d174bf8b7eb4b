#pragma once
// Writes small glTF 2.0 files for tests: .gltf with the buffer as a base64 data URI, or .glb
// (12-byte header, JSON chunk, BIN chunk). Values are written as given, so a test can put NaN in
// a buffer or an index past the end of its vertices.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace hybridlab::test {

class GltfBuilder {
public:
    GltfBuilder();

    // Accessors over new buffer views; return the accessor index. `type` is "VEC2", "VEC3", ...
    int addFloats(const std::vector<float>& values, const std::string& type);
    int addIndices(const std::vector<std::uint32_t>& indices);

    // A mesh of one triangle-list primitive; -1 leaves out normals, indices or the material.
    int addMesh(const std::string& name, int positions, int normals = -1, int indices = -1, int material = -1);
    int addMaterial(const std::string& name, const std::vector<double>& baseColorFactor);
    int addPerspectiveCamera(double yfov, double znear, double zfar, double aspectRatio);
    // `node` is the glTF node object (name, mesh, camera, translation, rotation, scale, matrix...).
    int addNode(const nlohmann::json& node);
    void addChild(int parent, int child);
    // The default scene's root nodes.
    void setRoots(const std::vector<int>& roots);

    nlohmann::json& document() { return doc_; }
    std::string gltfText() const;
    std::vector<std::uint8_t> glbBytes() const;
    void writeGltf(const std::filesystem::path& path) const;
    void writeGlb(const std::filesystem::path& path) const;

private:
    int addView(const void* bytes, std::size_t size);
    nlohmann::json document(bool embedBufferUri) const;

    nlohmann::json doc_;
    std::vector<std::uint8_t> bin_;
};

// A single triangle in the XY plane, counter-clockwise seen from +Z: (0,0,0), (1,0,0), (0,1,0).
inline const std::vector<float> kTrianglePositions = {0, 0, 0, 1, 0, 0, 0, 1, 0};

}  // namespace hybridlab::test
