#include "common/scene/gltf_loader.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "common/core/input_error.h"
#include "common/core/input_file.h"
#include "common/core/number_check.h"
#include "common/core/log.h"
#include "common/image/image_io.h"
#include "common/image/non_finite_pixels.h"

namespace hybridlab {
namespace fs = std::filesystem;

namespace {

class Reader {
public:
    Reader(const tinygltf::Model& model, fs::path file) : model_(model), file_(std::move(file)) {}

    [[noreturn]] void fail(const std::string& what) const { throw InputError(file_.string() + ": " + what); }

    // Reads accessor `index` as `components` floats per element (normalised integers allowed).
    std::vector<float> floats(int index, int components, const std::string& what) const {
        const auto& acc = accessor(index, what);
        if (tinygltf::GetNumComponentsInType(acc.type) != components) fail(what + ": wrong accessor type");
        std::vector<float> out(elementCount(acc, what) * components);
        forEachElement(acc, what, [&](std::size_t i, const unsigned char* p) {
            for (int c = 0; c < components; ++c) {
                float v = 0.0f;
                switch (acc.componentType) {
                case TINYGLTF_COMPONENT_TYPE_FLOAT: std::memcpy(&v, p + 4 * c, 4); break;
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: v = p[c] / 255.0f; break;
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                    std::uint16_t s;
                    std::memcpy(&s, p + 2 * c, 2);
                    v = s / 65535.0f;
                    break;
                }
                default: fail(what + ": unsupported component type " + std::to_string(acc.componentType));
                }
                if (!std::isfinite(v)) fail(what + ": element " + std::to_string(i) + " is not finite (NaN or infinity)");
                out[i * components + c] = v;
            }
        });
        return out;
    }

    std::vector<std::uint32_t> indices(int index, const std::string& what) const {
        const auto& acc = accessor(index, what);
        std::vector<std::uint32_t> out(elementCount(acc, what));
        forEachElement(acc, what, [&](std::size_t i, const unsigned char* p) {
            switch (acc.componentType) {
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: out[i] = p[0]; break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { std::uint16_t s; std::memcpy(&s, p, 2); out[i] = s; break; }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: std::memcpy(&out[i], p, 4); break;
            default: fail(what + ": indices must be unsigned integers");
            }
        });
        return out;
    }

private:
    const tinygltf::Accessor& accessor(int index, const std::string& what) const {
        if (index < 0 || index >= static_cast<int>(model_.accessors.size())) fail(what + ": accessor index out of range");
        const auto& acc = model_.accessors[index];
        if (acc.sparse.isSparse) fail(what + ": sparse accessors are not supported");
        if (acc.bufferView < 0) fail(what + ": accessor has no buffer view");
        return acc;
    }

    // The accessor's element count, once its elements are known to lie inside its buffer: the
    // count comes from the file, and it sizes the allocation (a count of 2^60 is an error here,
    // not std::bad_alloc). The arithmetic cannot overflow: count - 1 <= (size - start - elemSize) / stride.
    std::size_t elementCount(const tinygltf::Accessor& acc, const std::string& what) const {
        if (acc.bufferView >= static_cast<int>(model_.bufferViews.size())) fail(what + ": buffer view out of range");
        const auto& view = model_.bufferViews[acc.bufferView];
        if (view.buffer < 0 || view.buffer >= static_cast<int>(model_.buffers.size())) fail(what + ": buffer out of range");
        const std::size_t size = model_.buffers[view.buffer].data.size();
        const int componentSize = tinygltf::GetComponentSizeInBytes(acc.componentType);
        const int components = tinygltf::GetNumComponentsInType(acc.type);
        if (componentSize <= 0 || components <= 0) fail(what + ": unsupported accessor component type or type");
        const std::size_t elemSize = static_cast<std::size_t>(componentSize) * components;
        const std::size_t stride = view.byteStride ? view.byteStride : elemSize;
        const std::size_t start = view.byteOffset + acc.byteOffset;
        if (acc.count == 0) return 0;
        const bool fits = start <= size && elemSize <= size - start && (acc.count - 1) <= (size - start - elemSize) / stride;
        if (!fits) {
            fail(what + ": accessor's " + std::to_string(acc.count) + " elements of " + std::to_string(elemSize) + " bytes (stride " +
                 std::to_string(stride) + ", offset " + std::to_string(start) + ") read past the end of its " + std::to_string(size) +
                 "-byte buffer");
        }
        return acc.count;
    }

    template <typename F>
    void forEachElement(const tinygltf::Accessor& acc, const std::string& what, F&& f) const {
        const std::size_t count = elementCount(acc, what);
        const auto& view = model_.bufferViews[acc.bufferView];
        const auto& buf = model_.buffers[view.buffer].data;
        const std::size_t elemSize = static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(acc.componentType)) *
                                     tinygltf::GetNumComponentsInType(acc.type);
        const std::size_t stride = view.byteStride ? view.byteStride : elemSize;
        const std::size_t start = view.byteOffset + acc.byteOffset;
        for (std::size_t i = 0; i < count; ++i) f(i, buf.data() + start + stride * i);
    }

    const tinygltf::Model& model_;
    fs::path file_;
};

glm::mat4 nodeLocalMatrix(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) {
        glm::dmat4 m = glm::make_mat4(node.matrix.data());
        return glm::mat4(m);
    }
    glm::mat4 m(1.0f);
    if (node.translation.size() == 3) m = glm::translate(m, glm::vec3(node.translation[0], node.translation[1], node.translation[2]));
    if (node.rotation.size() == 4) {
        glm::quat q(static_cast<float>(node.rotation[3]), static_cast<float>(node.rotation[0]),
                    static_cast<float>(node.rotation[1]), static_cast<float>(node.rotation[2]));
        m *= glm::mat4_cast(q);
    }
    if (node.scale.size() == 3) m = glm::scale(m, glm::vec3(node.scale[0], node.scale[1], node.scale[2]));
    return m;
}

std::vector<glm::uvec3> assembleTriangles(const std::vector<std::uint32_t>& idx, int mode, const Reader& r,
                                          const std::string& what) {
    std::vector<glm::uvec3> tris;
    switch (mode) {
    case TINYGLTF_MODE_TRIANGLES:
        if (idx.size() % 3 != 0) r.fail(what + ": index count is not a multiple of 3");
        for (std::size_t i = 0; i + 2 < idx.size(); i += 3) tris.emplace_back(idx[i], idx[i + 1], idx[i + 2]);
        break;
    case TINYGLTF_MODE_TRIANGLE_STRIP:
        for (std::size_t i = 0; i + 2 < idx.size(); ++i)
            tris.push_back(i % 2 == 0 ? glm::uvec3(idx[i], idx[i + 1], idx[i + 2]) : glm::uvec3(idx[i + 1], idx[i], idx[i + 2]));
        break;
    case TINYGLTF_MODE_TRIANGLE_FAN:
        for (std::size_t i = 1; i + 1 < idx.size(); ++i) tris.emplace_back(idx[0], idx[i], idx[i + 1]);
        break;
    default: r.fail(what + ": primitive mode " + std::to_string(mode) + " is not supported (expected triangles)");
    }
    return tris;
}

class Loader {
public:
    Loader(const tinygltf::Model& model, const fs::path& file, const GltfLoadOptions& opt)
        : model_(model), file_(file), opt_(opt), reader_(model, file) {}

    GltfContent run() {
        out_.sourceFiles.push_back(file_);
        for (const auto& b : model_.buffers)
            if (!b.uri.empty() && b.uri.rfind("data:", 0) != 0) out_.sourceFiles.push_back(file_.parent_path() / b.uri);
        if (opt_.loadMaterials) loadMaterials();
        else out_.materials.push_back(Material{"default"});
        std::vector<int> roots;
        if (!opt_.node.empty()) {
            roots.push_back(findNode(opt_.node));
            // The node keeps its place in the file: apply its ancestors' transforms.
            visit(roots[0], ancestorsMatrix(roots[0]));
        } else {
            int s = model_.defaultScene >= 0 ? model_.defaultScene : 0;
            if (!model_.scenes.empty()) {
                if (s >= static_cast<int>(model_.scenes.size())) reader_.fail("default scene index out of range");
                for (int n : model_.scenes[s].nodes) visit(n, glm::mat4(1.0f));
            } else {
                for (std::size_t n = 0; n < model_.nodes.size(); ++n) visit(static_cast<int>(n), glm::mat4(1.0f));
            }
        }
        if (out_.meshes.empty()) reader_.fail(opt_.node.empty() ? "no triangle meshes" : "node '" + opt_.node + "' holds no triangle meshes");
        return std::move(out_);
    }

private:
    int findNode(const std::string& name) const {
        std::string names;
        for (std::size_t i = 0; i < model_.nodes.size(); ++i) {
            if (model_.nodes[i].name == name) return static_cast<int>(i);
            if (i < 20) names += (i ? ", " : "") + model_.nodes[i].name;
        }
        reader_.fail("no node named '" + name + "' (nodes: " + names + ")");
    }

    glm::mat4 ancestorsMatrix(int node) const {
        for (std::size_t p = 0; p < model_.nodes.size(); ++p) {
            for (int c : model_.nodes[p].children)
                if (c == node) return ancestorsMatrix(static_cast<int>(p)) * nodeLocalMatrix(model_.nodes[p]);
        }
        return glm::mat4(1.0f);
    }

    void visit(int nodeIndex, const glm::mat4& parent) {
        if (nodeIndex < 0 || nodeIndex >= static_cast<int>(model_.nodes.size())) reader_.fail("node index out of range");
        if (++depth_ > 256) reader_.fail("node hierarchy deeper than 256 (a cycle?)");
        const auto& node = model_.nodes[nodeIndex];
        // glTF 2.0's node properties, whole: a short matrix would be passed over as if absent.
        const auto whole = [&](const std::vector<double>& values, std::size_t count, const char* key) {
            if (!values.empty() && values.size() != count)
                reader_.fail("node '" + node.name + "': " + key + " has " + std::to_string(values.size()) + " numbers, expected " +
                             std::to_string(count));
        };
        whole(node.matrix, 16, "matrix");
        whole(node.translation, 3, "translation");
        whole(node.rotation, 4, "rotation");
        whole(node.scale, 3, "scale");
        glm::mat4 world = parent * nodeLocalMatrix(node);
        if (node.mesh >= 0) addMesh(node.mesh, world);
        if (node.camera >= 0) addCamera(node, world);
        for (int c : node.children) visit(c, world);
        --depth_;
    }

    void addMesh(int meshIndex, const glm::mat4& world) {
        if (meshIndex >= static_cast<int>(model_.meshes.size())) reader_.fail("mesh index out of range");
        const auto& gm = model_.meshes[meshIndex];
        for (std::size_t p = 0; p < gm.primitives.size(); ++p) {
            const auto& prim = gm.primitives[p];
            const std::string what = "mesh '" + gm.name + "' primitive " + std::to_string(p);
            auto pos = prim.attributes.find("POSITION");
            if (pos == prim.attributes.end()) reader_.fail(what + ": no POSITION attribute");
            Mesh m;
            m.name = gm.name.empty() ? "mesh" + std::to_string(meshIndex) : gm.name;
            auto P = reader_.floats(pos->second, 3, what + " POSITION");
            for (std::size_t i = 0; i < P.size(); i += 3) m.positions.emplace_back(P[i], P[i + 1], P[i + 2]);
            const std::size_t nv = m.positions.size();
            if (auto it = prim.attributes.find("TEXCOORD_0"); it != prim.attributes.end()) {
                auto T = reader_.floats(it->second, 2, what + " TEXCOORD_0");
                if (T.size() / 2 != nv) reader_.fail(what + ": TEXCOORD_0 count differs from POSITION count");
                for (std::size_t i = 0; i < T.size(); i += 2) m.uvs.emplace_back(T[i], T[i + 1]);
            }
            bool hasNormals = false;
            if (auto it = prim.attributes.find("NORMAL"); it != prim.attributes.end()) {
                auto N = reader_.floats(it->second, 3, what + " NORMAL");
                if (N.size() / 3 != nv) reader_.fail(what + ": NORMAL count differs from POSITION count");
                for (std::size_t i = 0; i < N.size(); i += 3) m.normals.push_back(glm::normalize(glm::vec3(N[i], N[i + 1], N[i + 2])));
                hasNormals = true;
            }
            std::vector<std::uint32_t> idx;
            if (prim.indices >= 0) {
                idx = reader_.indices(prim.indices, what + " indices");
            } else {
                idx.resize(nv);
                for (std::size_t i = 0; i < nv; ++i) idx[i] = static_cast<std::uint32_t>(i);
            }
            for (std::size_t i = 0; i < idx.size(); ++i) {
                if (idx[i] >= nv) reader_.fail(what + ": index " + std::to_string(idx[i]) + " at position " + std::to_string(i) +
                                               " is out of range (the primitive has " + std::to_string(nv) + " vertices)");
            }
            m.triangles = assembleTriangles(idx, prim.mode, reader_, what);
            std::size_t dropped = dropDegenerateTriangles(m);
            if (dropped) {
                warn(file_.string() + ": " + what + ": dropped " + std::to_string(dropped) + " degenerate triangle(s)");
                out_.droppedDegenerateTriangles += dropped;
            }
            if (!hasNormals) {
                if (opt_.smoothNormals) makeSmoothNormals(m);
                else makeFlatNormals(m);
            }
            m.material = opt_.loadMaterials && prim.material >= 0 ? static_cast<std::uint32_t>(prim.material) + 1 : 0;
            if (m.material >= out_.materials.size()) reader_.fail(what + ": material index out of range");
            transformMesh(m, world);
            if (!m.uvs.empty() && m.material < out_.materials.size() && out_.materials[m.material].normalTexture != kNoTexture) {
                computeTangents(m);
            }
            out_.meshes.push_back(std::move(m));
        }
    }

    void addCamera(const tinygltf::Node& node, const glm::mat4& world) {
        if (node.camera >= static_cast<int>(model_.cameras.size())) reader_.fail("node '" + node.name + "': camera index out of range");
        const auto& gc = model_.cameras[node.camera];
        const std::string what = "camera node '" + node.name + "'";
        // Its placement: axes neither zero nor non-finite (a scale of 0 leaves no view direction).
        for (int axis = 0; axis < 3; ++axis) {
            const float length = glm::length(glm::vec3(world[axis]));
            if (!(length > 0.0f) || !std::isfinite(length)) reader_.fail(what + ": its transform scales an axis to 0 or to infinity");
        }
        Camera cam;
        cam.position = glm::vec3(world[3]);
        glm::mat3 rot(glm::normalize(glm::vec3(world[0])), glm::normalize(glm::vec3(world[1])), glm::normalize(glm::vec3(world[2])));
        cam.orientation = glm::normalize(glm::quat_cast(rot));
        // The glTF 2.0 camera's properties, in the ranges a scene file's [camera] takes.
        const auto within = [&](const std::string& key, double v, NumberRange range) {
            if (!(v >= range.min && v <= range.max))
                reader_.fail(what + ": " + key + " " + formatNumber(v) + " is outside [" + formatNumber(range.min) + ", " +
                             formatNumber(range.max) + "]");
            return static_cast<float>(v);
        };
        if (gc.type == "orthographic") {
            cam.projection = Camera::Projection::Orthographic;
            const NumberRange magnification{limits::kOrthoHeight.min / 2.0, limits::kOrthoHeight.max / 2.0};  // half the view
            within("orthographic.xmag", gc.orthographic.xmag, magnification);
            cam.orthoHeight = 2.0f * within("orthographic.ymag", gc.orthographic.ymag, magnification);
            // glTF allows an orthographic near plane at 0; a scene's camera takes at least kNearPlane.min.
            cam.nearPlane = std::max(within("orthographic.znear", gc.orthographic.znear, {0.0, limits::kNearPlane.max}),
                                     static_cast<float>(limits::kNearPlane.min));
            cam.farPlane = within("orthographic.zfar", gc.orthographic.zfar, limits::kFarPlane);
        } else {
            cam.fovYDegrees = within("perspective.yfov (in degrees)", glm::degrees(gc.perspective.yfov), limits::kFovYDegrees);
            cam.nearPlane = within("perspective.znear", gc.perspective.znear, limits::kNearPlane);
            if (gc.perspective.zfar > 0.0) cam.farPlane = within("perspective.zfar", gc.perspective.zfar, limits::kFarPlane);
        }
        if (cam.farPlane <= cam.nearPlane) reader_.fail(what + ": expected zfar > znear");
        out_.cameras.push_back({node.name, cam});
    }

    void loadMaterials() {
        // Material 0 is the default for primitives without one.
        out_.materials.push_back(Material{"default"});
        std::vector<std::int32_t> textureSlot(model_.textures.size(), kNoTexture);
        for (const auto& gm : model_.materials) {
            Material m;
            m.name = gm.name;
            const auto& pbr = gm.pbrMetallicRoughness;
            m.diffuse = glm::vec3(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2]);
            m.ambient = m.diffuse;  // so that the scene's global ambient colour lights it
            m.specular = glm::vec3(0.0f);
            if (gm.alphaMode == "BLEND") m.opacity = static_cast<float>(pbr.baseColorFactor[3]);
            m.emission = glm::vec3(gm.emissiveFactor[0], gm.emissiveFactor[1], gm.emissiveFactor[2]);
            if (pbr.baseColorTexture.index >= 0) {
                m.diffuseTexture = texture(pbr.baseColorTexture.index, true, textureSlot);
            }
            if (gm.normalTexture.index >= 0) m.normalTexture = texture(gm.normalTexture.index, false, textureSlot);
            out_.materials.push_back(m);
        }
    }

    std::int32_t texture(int index, bool srgb, std::vector<std::int32_t>& slot) {
        if (index >= static_cast<int>(model_.textures.size())) reader_.fail("texture index out of range");
        if (slot[index] != kNoTexture) return slot[index];
        int src = model_.textures[index].source;
        if (src < 0 || src >= static_cast<int>(model_.images.size())) reader_.fail("texture " + std::to_string(index) + " has no image");
        const auto& img = model_.images[src];
        Texture t;
        t.srgb = srgb;
        if (!img.uri.empty()) {
            if (img.uri.rfind("data:", 0) == 0) reader_.fail("image " + std::to_string(src) + ": data URIs are not supported");
            fs::path p = file_.parent_path() / img.uri;
            if (inputPathKind(p) == InputPathKind::Missing) reader_.fail("image '" + img.uri + "' not found (looked for " + p.string() + ")");
            out_.sourceFiles.push_back(p);
            if (opt_.decodeTextures) {
                t = loadTexture(p, srgb);
            } else {
                checkImageFile(p, true);  // not decoded (unless it may hold NaN), but checked
                t.source = p.string();
            }
        } else if (img.bufferView >= 0 && img.bufferView < static_cast<int>(model_.bufferViews.size())) {
            const auto& view = model_.bufferViews[img.bufferView];
            const auto& buf = model_.buffers.at(view.buffer).data;
            if (view.byteOffset > buf.size() || view.byteLength > buf.size() - view.byteOffset) reader_.fail("image " + std::to_string(src) + " reads past its buffer");
            t.source = file_.string() + "#image" + std::to_string(src);
            t.image = readImageFromMemory(buf.data() + view.byteOffset, view.byteLength, t.source,
                                          srgb ? ColorEncoding::Srgb : ColorEncoding::Linear);
            requireFiniteTexels(t.image, t.source);
        } else {
            reader_.fail("image " + std::to_string(src) + " has neither a uri nor a buffer view");
        }
        slot[index] = static_cast<std::int32_t>(out_.textures.size());
        out_.textures.push_back(std::move(t));
        return slot[index];
    }

    const tinygltf::Model& model_;
    fs::path file_;
    GltfLoadOptions opt_;
    Reader reader_;
    GltfContent out_;
    int depth_ = 0;
};

// Images are decoded by us (image_io.h, with sRGB decoding and clear errors), not by tinygltf.
bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
    return true;
}

// tinygltf's own file reading, for regular files only: it opens a folder (a buffer or image `uri`
// of "." or "textures/", or a .glb that is one) as a file of 2^63 - 1 bytes and allocates that.
bool readRegularFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) {
        if (err) *err += "'" + path + "' is " + (fs::exists(path, ec) ? "not a regular file (a directory or a device)" : "missing") + "\n";
        return false;
    }
    return tinygltf::ReadWholeFile(out, err, path, user);
}

}  // namespace

GltfContent loadGltf(const fs::path& file, const GltfLoadOptions& options) {
    if (inputPathKind(file) == InputPathKind::Missing) throw InputError(file.string() + ": glTF file not found");
    requireInputFile(file, "a glTF model (.gltf or .glb)");
    tinygltf::TinyGLTF gltf;
    gltf.SetImageLoader(skipImage, nullptr);
    gltf.SetFsCallbacks({&tinygltf::FileExists, &tinygltf::ExpandFilePath, &readRegularFile, &tinygltf::WriteWholeFile, nullptr});
    tinygltf::Model model;
    std::string err, warnings;
    std::string ext = file.extension().string();
    for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    bool ok = false;
    if (ext == ".glb") ok = gltf.LoadBinaryFromFile(&model, &err, &warnings, file.string());
    else if (ext == ".gltf") ok = gltf.LoadASCIIFromFile(&model, &err, &warnings, file.string());
    else throw InputError(file.string() + ": unknown model format '" + ext + "' (expected .gltf or .glb)");
    if (!ok) {
        while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
        throw InputError(file.string() + ": not a valid glTF 2.0 file (" + (err.empty() ? "unknown error" : err) + ")");
    }
    return Loader(model, file, options).run();
}

}  // namespace hybridlab
