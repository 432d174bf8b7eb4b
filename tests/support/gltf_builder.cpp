#include "tests/support/gltf_builder.h"

#include <cstring>

#include "tests/support/test_support.h"

namespace hybridlab::test {

namespace {

std::string base64(const std::vector<std::uint8_t>& data) {
    static const char* const kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    std::size_t i = 0;
    for (; i + 2 < data.size(); i += 3) {
        std::uint32_t v = (data[i] << 16) | (data[i + 1] << 8) | data[i + 2];
        for (int k = 3; k >= 0; --k) out += kAlphabet[(v >> (6 * k)) & 63];
    }
    if (std::size_t rest = data.size() - i; rest > 0) {
        std::uint32_t v = data[i] << 16;
        if (rest == 2) v |= data[i + 1] << 8;
        out += kAlphabet[(v >> 18) & 63];
        out += kAlphabet[(v >> 12) & 63];
        out += rest == 2 ? kAlphabet[(v >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

void appendU32(std::vector<std::uint8_t>& out, std::uint32_t v) {
    for (int k = 0; k < 4; ++k) out.push_back(static_cast<std::uint8_t>(v >> (8 * k)));
}

}  // namespace

GltfBuilder::GltfBuilder() {
    doc_ = {{"asset", {{"version", "2.0"}, {"generator", "hybridlab tests"}}},
            {"scene", 0},
            {"scenes", nlohmann::json::array({{{"nodes", nlohmann::json::array()}}})},
            {"nodes", nlohmann::json::array()},
            {"meshes", nlohmann::json::array()},
            {"accessors", nlohmann::json::array()},
            {"bufferViews", nlohmann::json::array()}};
}

int GltfBuilder::addView(const void* bytes, std::size_t size) {
    while (bin_.size() % 4) bin_.push_back(0);
    std::size_t offset = bin_.size();
    bin_.resize(offset + size);
    std::memcpy(bin_.data() + offset, bytes, size);
    doc_["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}});
    return static_cast<int>(doc_["bufferViews"].size()) - 1;
}

int GltfBuilder::addFloats(const std::vector<float>& values, const std::string& type) {
    const std::size_t components = type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : 4;
    int view = addView(values.data(), values.size() * sizeof(float));
    doc_["accessors"].push_back(
        {{"bufferView", view}, {"componentType", 5126}, {"count", values.size() / components}, {"type", type}});
    return static_cast<int>(doc_["accessors"].size()) - 1;
}

int GltfBuilder::addIndices(const std::vector<std::uint32_t>& indices) {
    int view = addView(indices.data(), indices.size() * sizeof(std::uint32_t));
    doc_["accessors"].push_back({{"bufferView", view}, {"componentType", 5125}, {"count", indices.size()}, {"type", "SCALAR"}});
    return static_cast<int>(doc_["accessors"].size()) - 1;
}

int GltfBuilder::addMesh(const std::string& name, int positions, int normals, int indices, int material) {
    nlohmann::json prim = {{"attributes", {{"POSITION", positions}}}, {"mode", 4}};
    if (normals >= 0) prim["attributes"]["NORMAL"] = normals;
    if (indices >= 0) prim["indices"] = indices;
    if (material >= 0) prim["material"] = material;
    doc_["meshes"].push_back({{"name", name}, {"primitives", nlohmann::json::array({prim})}});
    return static_cast<int>(doc_["meshes"].size()) - 1;
}

int GltfBuilder::addMaterial(const std::string& name, const std::vector<double>& baseColorFactor) {
    doc_["materials"].push_back({{"name", name}, {"pbrMetallicRoughness", {{"baseColorFactor", baseColorFactor}}}});
    return static_cast<int>(doc_["materials"].size()) - 1;
}

int GltfBuilder::addPerspectiveCamera(double yfov, double znear, double zfar, double aspectRatio) {
    doc_["cameras"].push_back(
        {{"type", "perspective"}, {"perspective", {{"yfov", yfov}, {"znear", znear}, {"zfar", zfar}, {"aspectRatio", aspectRatio}}}});
    return static_cast<int>(doc_["cameras"].size()) - 1;
}

int GltfBuilder::addNode(const nlohmann::json& node) {
    doc_["nodes"].push_back(node);
    return static_cast<int>(doc_["nodes"].size()) - 1;
}

void GltfBuilder::addChild(int parent, int child) { doc_["nodes"][parent]["children"].push_back(child); }

void GltfBuilder::setRoots(const std::vector<int>& roots) { doc_["scenes"][0]["nodes"] = roots; }

nlohmann::json GltfBuilder::document(bool embedBufferUri) const {
    nlohmann::json d = doc_;
    if (bin_.empty()) return d;  // no data, no buffer (an empty data URI does not decode)
    nlohmann::json buffer = {{"byteLength", bin_.size()}};
    if (embedBufferUri) buffer["uri"] = "data:application/octet-stream;base64," + base64(bin_);
    d["buffers"] = nlohmann::json::array({buffer});
    return d;
}

std::string GltfBuilder::gltfText() const { return document(true).dump(2); }

std::vector<std::uint8_t> GltfBuilder::glbBytes() const {
    std::string json = document(false).dump();
    while (json.size() % 4) json += ' ';
    std::vector<std::uint8_t> bin = bin_;
    while (bin.size() % 4) bin.push_back(0);
    std::vector<std::uint8_t> out;
    appendU32(out, 0x46546C67);  // "glTF"
    appendU32(out, 2);
    appendU32(out, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
    appendU32(out, static_cast<std::uint32_t>(json.size()));
    appendU32(out, 0x4E4F534A);  // "JSON"
    out.insert(out.end(), json.begin(), json.end());
    appendU32(out, static_cast<std::uint32_t>(bin.size()));
    appendU32(out, 0x004E4942);  // "BIN\0"
    out.insert(out.end(), bin.begin(), bin.end());
    return out;
}

void GltfBuilder::writeGltf(const std::filesystem::path& path) const { writeTextFile(path, gltfText()); }
void GltfBuilder::writeGlb(const std::filesystem::path& path) const { writeBinaryFile(path, glbBytes()); }

}  // namespace hybridlab::test
