#include "common/scene/scene_file.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vector_relational.hpp>

#include "common/core/input_error.h"
#include "common/core/input_file.h"
#include "common/core/number_check.h"
#include "common/core/log.h"
#include "common/core/toml_reader.h"
#include "common/image/image_io.h"
#include "common/scene/assets.h"
#include "common/scene/bounds_fit.h"
#include "common/scene/gltf_loader.h"
#include "common/scene/placement_mirror.h"
#include "common/scene/primitives.h"

namespace hybridlab {
namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kInterpolations = {"linear", "catmull-rom"};

Interpolation toInterpolation(const std::string& s) {
    return s == "linear" ? Interpolation::Linear : Interpolation::CatmullRom;
}

class SceneFileReader {
public:
    SceneFileReader(const fs::path& file, const SceneLoadOptions& options) : doc_(file), options_(options) {
        scene_.file = file;
        scene_.sourceFiles.push_back(file);
    }

    Scene read() {
        TomlTable root = doc_.root();
        readHeader(root);
        readSky(root);
        readMaterials(root);
        readObjects(root);
        readLights(root);
        readCamera(root);
        readCameraPaths(root);
        root.rejectUnknownKeys();
        if (scene_.objects.empty()) root.failHere("the scene has no objects (expected at least one [[objects]] entry)");
        return std::move(scene_);
    }

private:
    // A point the camera is at or looks at (withinSceneReach).
    static glm::vec3 pointInReach(const TomlTable& t, const std::string& key) {
        const glm::vec3 p = t.requiredVec3(key);
        if (!withinSceneReach(p))
            t.fail(key, "expected each coordinate within " + formatNumber(limits::kSceneCoordinate) + " of the origin, got [" +
                            formatNumber(p.x) + ", " + formatNumber(p.y) + ", " + formatNumber(p.z) + "]");
        return p;
    }

    // A direction that must not be zero (an up vector).
    static glm::vec3 nonZeroVec3(const TomlTable& t, const std::string& key, glm::vec3 fallback) {
        const glm::vec3 v = t.vec3(key, fallback);
        if (!(glm::length(v) > 0.0f)) t.fail(key, "expected a non-zero vector");
        return v;
    }

    // Checks that a file named in the scene exists, with the asset explanation when not.
    fs::path existingPath(const TomlTable& t, const std::string& key, const std::string& written) const {
        fs::path p = resolveScenePath(written, doc_.file());
        std::string reason;
        switch (inputPathKind(p, &reason)) {
        case InputPathKind::Missing: t.fail(key, missingAssetExplanation(written, p));
        case InputPathKind::Directory: t.fail(key, "'" + written + "' is a directory (" + p.string() + "), expected a file");
        case InputPathKind::Unreadable: t.fail(key, "'" + written + "' cannot be read (" + p.string() + ": " + reason + ")");
        case InputPathKind::RegularFile:
        case InputPathKind::Special: break;  // the reader says what a device or a pipe is not
        }
        return p;
    }

    void readHeader(const TomlTable& root) {
        scene_.name = doc_.file().stem().string();
        if (auto s = root.table("scene")) {
            scene_.name = s->string("name", scene_.name);
            scene_.description = s->string("description", "");
            scene_.ambient = s->vec3("ambient", glm::vec3(0.0f));
            scene_.ambientIor = static_cast<float>(s->number("ambient_ior", 1.0, {1e-3, 10.0}));
            s->rejectUnknownKeys();
        }
    }

    void readSky(const TomlTable& root) {
        auto s = root.table("sky");
        if (!s) return;
        scene_.sky.color = s->vec3("color", glm::vec3(0.0f));
        auto faces = s->stringArray("cube_map");
        if (!faces.empty()) {
            if (faces.size() != 6) s->fail("cube_map", "expected 6 images (+X, -X, +Y, -Y, +Z, -Z), got " + std::to_string(faces.size()));
            for (int i = 0; i < 6; ++i) scene_.sky.cubeFaces[i] = texture(*s, "cube_map", faces[i], true);
            // One cube image: six square faces of one size (what a Vulkan cube image is).
            const ImageSize first = textureSize(scene_.sky.cubeFaces[0]);
            for (int i = 0; i < 6; ++i) {
                const ImageSize face = textureSize(scene_.sky.cubeFaces[i]);
                if (face.width != face.height || face.width != first.width)
                    s->fail("cube_map", "expected six square faces of one size, got " + faces[i] + " at " + std::to_string(face.width) +
                                            " x " + std::to_string(face.height) + " beside " + faces[0] + " at " +
                                            std::to_string(first.width) + " x " + std::to_string(first.height));
            }
        }
        s->rejectUnknownKeys();
    }

    std::int32_t texture(const TomlTable& t, const std::string& key, const std::string& written, bool srgb) {
        std::string id = written + (srgb ? "" : "#linear");
        if (auto it = textureIds_.find(id); it != textureIds_.end()) return it->second;
        Texture tex;
        if (isBuiltinTexture(written)) {
            tex = makeBuiltinTexture(written);
        } else if (written.rfind("builtin:", 0) == 0) {
            t.fail(key, "unknown built-in texture '" + written + "' (expected builtin:checker)");
        } else {
            fs::path p = existingPath(t, key, written);
            scene_.sourceFiles.push_back(p);
            if (options_.loadTextures) {
                try {
                    tex = loadTexture(p, srgb);
                } catch (const InputError& e) {
                    t.fail(key, e.what());
                }
            } else {
                // Not decoded, but checked: a scene that passes scene-info also renders.
                try {
                    headerSizes_[static_cast<std::int32_t>(scene_.textures.size())] = checkImageFile(p, true);
                } catch (const InputError& e) {
                    t.fail(key, e.what());
                }
                tex.source = p.string();
            }
        }
        auto idx = static_cast<std::int32_t>(scene_.textures.size());
        scene_.textures.push_back(std::move(tex));
        textureIds_[id] = idx;
        return idx;
    }

    // A texture's size: its image's, or where it was not decoded its header's.
    ImageSize textureSize(std::int32_t index) const {
        if (const auto it = headerSizes_.find(index); it != headerSizes_.end()) return it->second;
        const Image& image = scene_.textures[static_cast<std::size_t>(index)].image;
        return {image.width(), image.height()};
    }

    void readMaterials(const TomlTable& root) {
        for (const auto& [name, t] : root.namedTables("materials")) {
            Material m;
            m.name = name;
            m.emission = t.vec3("emission", m.emission);
            m.ambient = t.vec3("ambient", m.ambient);
            m.diffuse = t.vec3("diffuse", m.diffuse);
            m.specular = t.vec3("specular", m.specular);
            m.specularExponent = static_cast<float>(t.number("specular_exponent", m.specularExponent, {1.0, 255.0}));
            m.reflectivity = static_cast<float>(t.number("reflectivity", m.reflectivity, {0.0, 1.0}));
            m.ior = static_cast<float>(t.number("ior", m.ior, {1e-3, 10.0}));
            m.opacity = static_cast<float>(t.number("opacity", m.opacity, {0.0, 1.0}));
            m.fresnel = t.boolean("fresnel", m.fresnel);
            m.absorption = t.vec3("absorption", m.absorption);
            m.castsShadows = t.boolean("casts_shadows", m.castsShadows);
            if (t.has("diffuse_texture")) m.diffuseTexture = texture(t, "diffuse_texture", t.string("diffuse_texture", ""), true);
            if (t.has("normal_texture")) m.normalTexture = texture(t, "normal_texture", t.string("normal_texture", ""), false);
            m.textureTiling = t.vec2("texture_tiling", m.textureTiling);
            m.textureOffset = t.vec2("texture_offset", m.textureOffset);
            for (int c = 0; c < 3; ++c) {
                if (m.emission[c] < 0 || m.ambient[c] < 0 || m.diffuse[c] < 0 || m.specular[c] < 0 || m.absorption[c] < 0)
                    t.failHere("colours must not be negative");
            }
            t.rejectUnknownKeys();
            materialIds_[name] = static_cast<std::uint32_t>(scene_.materials.size());
            scene_.materials.push_back(m);
        }
    }

    std::uint32_t materialId(const TomlTable& t, const std::string& key) const {
        std::string name = t.string(key, "");
        auto it = materialIds_.find(name);
        if (it == materialIds_.end()) {
            std::string known;
            for (const auto& [n, i] : materialIds_) known += (known.empty() ? "" : ", ") + n;
            t.fail(key, "unknown material '" + name + "'" + (known.empty() ? " (the scene defines no [materials])" : " (defined: " + known + ")"));
        }
        return it->second;
    }

    Transform readTransform(const TomlTable& t, const Transform& fallback) const {
        Transform tr;
        tr.position = t.vec3("position", fallback.position);
        tr.rotation = t.has("rotation") ? eulerDegreesToQuat(t.vec3("rotation", glm::vec3(0.0f))) : fallback.rotation;
        tr.scale = t.scalarOrVec3("scale", fallback.scale);
        // Factors of 1e-30 leave extents whose products underflow, and Embree's spatial splits
        // abort on such triangles; 1e-9 of a kilometre is still a micrometre.
        constexpr float kSmallestScale = 1e-9f;
        if (glm::any(glm::lessThan(glm::abs(tr.scale), glm::vec3(kSmallestScale))))
            t.fail("scale", "expected non-zero scale factors, each at least " + formatNumber(kSmallestScale) + " in magnitude, got [" +
                                formatNumber(tr.scale.x) + ", " + formatNumber(tr.scale.y) + ", " + formatNumber(tr.scale.z) + "]");
        return tr;
    }

    // [objects.fit]: the object scaled to a height or a size and moved so that its bounds' bottom or
    // centre lands at `at` (default: `position`, which it then replaces).
    Transform readFit(const TomlTable& fit, const TomlTable& object, const std::vector<Mesh>& meshes, const Transform& placement) const {
        if (fit.has("at") && object.has("position")) fit.fail("at", "the object's 'position' and fit's 'at' both place it: give one");
        if (fit.has("height") && fit.has("size")) fit.fail("size", "expected 'height' or 'size', not both");
        BoundsFit f;
        constexpr NumberRange kPositive{1e-6, 1e6};
        if (fit.has("height")) f.height = static_cast<float>(fit.requiredNumber("height", kPositive));
        if (fit.has("size")) f.size = static_cast<float>(fit.requiredNumber("size", kPositive));
        f.at = fit.vec3("at", placement.position);
        f.anchor = fit.choice("anchor", "center", {"center", "bottom"}) == "bottom" ? BoundsFit::Anchor::Bottom : BoundsFit::Anchor::Center;
        fit.rejectUnknownKeys();
        Aabb local;
        for (const Mesh& m : meshes) local.extend(m.bounds());
        if (!local.valid()) fit.failHere("the object has no vertices to fit");
        Transform rest = placement;
        rest.position = glm::vec3(0.0f);
        const glm::vec3 extent = placedBounds(local, rest).extent();
        if (f.height && !(extent.y > 0.0f)) fit.fail("height", "the object's bounds have no height (a flat object): fit its 'size' instead");
        return fitToBounds(local, placement, f);
    }

    void readObjects(const TomlTable& root) {
        std::map<std::string, int> names;
        for (const auto& t : root.tableArray("objects")) {
            SceneObject o;
            o.name = t.requiredString("name");
            if (names.count(o.name)) t.fail("name", "duplicate object name '" + o.name + "'");
            names[o.name] = 1;
            const bool isPrimitive = t.has("primitive"), isModel = t.has("model");
            if (isPrimitive == isModel) t.failHere("expected exactly one of 'primitive' or 'model'");
            std::vector<Mesh> meshes;
            if (isPrimitive) {
                o.source = t.choice("primitive", "", {"plane", "cube", "sphere", "cylinder"});
                if (o.source == "plane") meshes.push_back(makePlane());
                else if (o.source == "cube") meshes.push_back(makeCube());
                else if (o.source == "sphere") {
                    const int slices = t.integer("slices", 64, 3, limits::kTessellation), stacks = t.integer("stacks", 32, 2, limits::kTessellation);
                    // Each side is bounded, and so is their product: it is the memory and the build time.
                    const long long vertices = static_cast<long long>(slices + 1) * (stacks + 1);
                    if (vertices > limits::kPrimitiveVertices)
                        t.fail("stacks", "slices " + std::to_string(slices) + " x stacks " + std::to_string(stacks) + " make " +
                                             std::to_string(vertices) + " vertices, more than the limit of " +
                                             std::to_string(limits::kPrimitiveVertices));
                    meshes.push_back(makeSphere(slices, stacks));
                } else meshes.push_back(makeCylinder(t.integer("slices", 64, 3, limits::kTessellation)));
                if (!t.has("material")) t.fail("material", "missing (a primitive needs a material)");
                meshes[0].material = materialId(t, "material");
            } else {
                o.source = t.string("model", "");
                fs::path p = existingPath(t, "model", o.source);
                GltfLoadOptions opt;
                opt.node = t.string("node", "");
                opt.smoothNormals = t.boolean("smooth_normals", false);
                const bool overrideMaterial = t.has("material");
                opt.loadMaterials = !overrideMaterial;
                opt.decodeTextures = options_.loadTextures;
                GltfContent content;
                try {
                    content = loadGltf(p, opt);
                } catch (const InputError& e) {
                    t.fail("model", e.what());
                }
                std::uint32_t base = static_cast<std::uint32_t>(scene_.materials.size());
                if (overrideMaterial) {
                    std::uint32_t id = materialId(t, "material");
                    for (auto& m : content.meshes) m.material = id;
                } else {
                    auto texBase = static_cast<std::int32_t>(scene_.textures.size());
                    for (auto& m : content.materials) {
                        m.name = o.name + "/" + m.name;
                        if (m.diffuseTexture != kNoTexture) m.diffuseTexture += texBase;
                        if (m.normalTexture != kNoTexture) m.normalTexture += texBase;
                        scene_.materials.push_back(m);
                    }
                    for (auto& tex : content.textures) scene_.textures.push_back(std::move(tex));
                    for (auto& m : content.meshes) m.material += base;
                }
                for (auto& c : content.cameras) gltfCameras_[o.name].push_back(c);
                scene_.droppedDegenerateTriangles += content.droppedDegenerateTriangles;
                scene_.sourceFiles.insert(scene_.sourceFiles.end(), content.sourceFiles.begin(), content.sourceFiles.end());
                meshes = std::move(content.meshes);
            }
            o.transform = readTransform(t, Transform{});
            if (auto f = t.table("fit")) o.transform = readFit(*f, t, meshes, o.transform);
            o.relevance = static_cast<float>(t.number("relevance", 1.0, {0.0, 1e6}));
            o.cost = static_cast<float>(t.number("cost", 1.0, {1e-6, 1e6}));
            o.lens = t.boolean("lens", false);
            o.lensGroup = t.string("lens_group", "");
            if (t.has("lens_group") && !o.lens) t.fail("lens_group", "a lens group needs 'lens = true' on the object");
            if (t.has("lens_group") && o.lensGroup.empty()) t.fail("lens_group", "expected a non-empty group name");
            if (auto a = t.table("animation")) o.animation = readAnimation(*a, o.transform);
            if (auto d = t.table("deform")) o.deformation = readDeformation(*d);
            mirrorCameras(o.name, moveMirrorIntoMeshes(o, meshes));
            checkPlacementReach(t, o, meshes);
            std::vector<SceneObject> copies;
            if (auto c = t.table("copies")) copies = readCopies(*c, o, names);
            else copies.push_back(std::move(o));
            t.rejectUnknownKeys();
            // Every copy owns its meshes (a deforming copy rewrites them); the last takes the loaded
            // meshes rather than a copy of them.
            for (std::size_t k = 0; k < copies.size(); ++k) {
                SceneObject& copy = copies[k];
                for (Mesh& m : meshes) {
                    copy.meshes.push_back(static_cast<std::uint32_t>(scene_.meshes.size()));
                    scene_.meshes.push_back(k + 1 == copies.size() ? std::move(m) : m);
                }
                objectIds_[copy.name] = scene_.objects.size();
                scene_.objects.push_back(std::move(copy));
            }
        }
    }

    // The cameras of a model whose mirror moved into its meshes (placement_mirror.h) move with it:
    // a camera cannot be mirrored, so it looks along the mirrored direction with the mirrored up.
    void mirrorCameras(const std::string& object, glm::vec3 signs) {
        if (signs == glm::vec3(1.0f)) return;
        for (GltfCamera& c : gltfCameras_[object]) {
            const glm::vec3 forward = signs * c.camera.forward(), up = signs * c.camera.up();
            c.camera.position *= signs;
            c.camera.orientation = Camera::lookAtOrientation(c.camera.position, c.camera.position + forward, up);
        }
    }

    // Every vertex of the object, at rest and at each keyframe (deformed at most by its amplitude),
    // within limits::kSceneCoordinate of the origin: a scale of 1e38 makes bounds of inf, a
    // rasterizer that draws nothing and rays that find nothing.
    void checkPlacementReach(const TomlTable& t, const SceneObject& o, const std::vector<Mesh>& meshes) const {
        Aabb local;
        for (const Mesh& m : meshes) local.extend(m.bounds());
        local = o.deformation.envelope(local);
        if (!local.valid()) return;
        const auto check = [&](const Transform& placement, const std::string& key, const std::string& which) {
            const Aabb world = local.transformed(placement.matrix());
            const glm::vec3 far = glm::max(glm::abs(world.lo), glm::abs(world.hi));
            const float reach = std::max({far.x, far.y, far.z});
            const auto finite = [](glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
            if (finite(world.lo) && finite(world.hi) && reach <= limits::kSceneCoordinate) return;
            t.fail(key, which + "places the object's vertices up to " + formatNumber(reach) + " from the origin, beyond the limit of " +
                            formatNumber(limits::kSceneCoordinate) + " (a camera's far plane reaches no farther)");
        };
        if (!o.isAnimated()) {
            // Named at what put it there: the position, else the scale, else the model's own coordinates.
            const glm::vec3 far = glm::abs(o.transform.position);
            const bool byPosition = std::max({far.x, far.y, far.z}) > limits::kSceneCoordinate && t.has("position");
            check(o.transform, byPosition ? "position" : t.has("scale") ? "scale" : t.has("model") ? "model" : "primitive", "");
            return;
        }
        for (std::size_t k = 0; k < o.animation.times.size(); ++k)
            check({o.animation.positions[k], o.animation.rotations[k], o.animation.scales[k]}, "animation",
                  "keyframe " + std::to_string(k) + " ");
    }

    // `count` copies of `o` in a ring: copy k turned about the vertical axis through `center` by
    // k * angle_step degrees, its animation and deformation running k * time_step seconds late
    // (the populations of de Macedo & Rodrigues' Tables I-II: N bunnies, N teapots).
    std::vector<SceneObject> readCopies(const TomlTable& t, const SceneObject& o, std::map<std::string, int>& names) const {
        const int count = t.integer("count", 1, 1, 10000);
        const glm::vec3 center = t.vec3("center", glm::vec3(0.0f));
        const auto angleStep = static_cast<float>(t.number("angle_step", 360.0 / count, {-360.0, 360.0}));
        const double timeStep = t.number("time_step", 0.0, {0.0, 1e6});
        t.rejectUnknownKeys();
        std::vector<SceneObject> copies;
        for (int k = 0; k < count; ++k) {
            SceneObject c = o;
            c.name = o.name + "-" + std::to_string(k);
            if (names.count(c.name)) t.fail("count", "copy name '" + c.name + "' is already an object's name");
            names[c.name] = 1;
            const glm::quat turn = eulerDegreesToQuat(glm::vec3(0.0f, angleStep * static_cast<float>(k), 0.0f));
            auto place = [&](glm::vec3& position, glm::quat& rotation) {
                position = center + turn * (position - center);
                rotation = turn * rotation;
            };
            place(c.transform.position, c.transform.rotation);
            for (std::size_t i = 0; i < c.animation.times.size(); ++i) {
                place(c.animation.positions[i], c.animation.rotations[i]);
                c.animation.times[i] += k * timeStep;
            }
            // Late by k * time_step: sin(k_w x - w (t - k dt)) = sin(k_w x - w t + w k dt).
            c.deformation.phaseRadians += static_cast<float>(c.deformation.angularFrequency() * k * timeStep);
            copies.push_back(std::move(c));
        }
        return copies;
    }

    // Key times must increase, by at least kKeySpacing; at least two keys. Keys closer than that
    // make the interpolation's tangents (differences over the keys' interval) overflow.
    static constexpr double kKeySpacing = 1e-6;
    std::vector<TomlTable> readKeys(const TomlTable& t, const std::string& what, std::vector<double>& times) const {
        auto keys = t.tableArray("keys");
        if (keys.size() < 2) t.fail("keys", what + " needs at least two keyframes, got " + std::to_string(keys.size()));
        for (const auto& k : keys) {
            double time = k.requiredNumber("time", {0.0, 1e6});
            if (!times.empty() && time <= times.back()) k.fail("time", "keyframe times must increase (previous key is at " + std::to_string(times.back()) + ")");
            if (!times.empty() && time < times.back() + kKeySpacing)
                k.fail("time", "keyframe times must be at least " + formatNumber(kKeySpacing) + " s apart (previous key is at " +
                                   formatNumber(times.back()) + ", this one at " + formatNumber(time) + ")");
            times.push_back(time);
        }
        return keys;
    }

    RigidAnimation readAnimation(const TomlTable& t, const Transform& rest) const {
        RigidAnimation a;
        a.interpolation = toInterpolation(t.choice("interpolation", "linear", kInterpolations));
        for (const auto& k : readKeys(t, "an animation", a.times)) {
            Transform tr = readTransform(k, rest);  // missing components keep the object's placement
            // A factor whose sign changes between keys scales through zero: the object flattens
            // and turns inside out (placement_mirror.h moves one set of signs into its meshes).
            if (!a.scales.empty() && scaleSigns(tr.scale) != scaleSigns(a.scales.front()))
                k.fail("scale", "expected each scale factor to keep the sign it has at the first keyframe (scaling through zero "
                                "would flatten the object and turn it inside out)");
            a.positions.push_back(tr.position);
            a.rotations.push_back(tr.rotation);
            a.scales.push_back(tr.scale);
            k.rejectUnknownKeys();
        }
        t.rejectUnknownKeys();
        return a;
    }

    // A travelling wave (deformation.h); direction and axis are normalised and must be perpendicular.
    Deformation readDeformation(const TomlTable& t) const {
        Deformation d;
        t.choice("type", "wave", {"wave"});
        d.amplitude = static_cast<float>(t.requiredNumber("amplitude", {0.0, 1e6}));
        d.wavelength = static_cast<float>(t.requiredNumber("wavelength", {1e-6, 1e9}));
        d.speed = static_cast<float>(t.number("speed", 0.0, {-1e9, 1e9}));
        d.phaseRadians = glm::radians(static_cast<float>(t.number("phase", 0.0, {-1e6, 1e6})));
        auto unit = [&](const std::string& key, glm::vec3 fallback) { return glm::normalize(nonZeroVec3(t, key, fallback)); };
        d.direction = unit("direction", d.direction);
        d.axis = unit("axis", d.axis);
        if (std::abs(glm::dot(d.direction, d.axis)) > 1e-4f)
            t.fail("axis", "expected the displacement axis perpendicular to the wave's direction (a transverse wave)");
        t.rejectUnknownKeys();
        return d;
    }

    void readLights(const TomlTable& root) {
        int counts[3] = {0, 0, 0};
        const int limits[3] = {kMaxDirectionalLights, kMaxPointLights, kMaxSpotLights};
        for (const auto& t : root.tableArray("lights")) {
            Light l;
            std::string type = t.choice("type", "", {"directional", "point", "spot"});
            l.type = type == "directional" ? Light::Type::Directional : type == "point" ? Light::Type::Point : Light::Type::Spot;
            int& count = counts[static_cast<int>(l.type)];
            if (++count > limits[static_cast<int>(l.type)]) {
                t.fail("type", "too many " + type + " lights: at most " + std::to_string(limits[static_cast<int>(l.type)]) + " are allowed");
            }
            l.name = t.string("name", type + std::to_string(count - 1));
            l.color = t.vec3("color", l.color);
            if (glm::any(glm::lessThan(l.color, glm::vec3(0.0f)))) t.fail("color", "colours must not be negative");
            l.intensity = static_cast<float>(t.number("intensity", 1.0, {0.0, 1e12}));
            l.castsShadows = t.boolean("casts_shadows", true);
            if (l.type != Light::Type::Directional) l.position = t.requiredVec3("position");
            if (l.type != Light::Type::Point) {
                glm::vec3 d;
                if (t.has("target") == t.has("direction")) t.failHere("a " + type + " light needs exactly one of 'direction' or 'target'");
                if (t.has("target")) d = t.vec3("target", {}) - l.position;
                else d = t.vec3("direction", {});
                if (glm::length(d) == 0.0f) t.failHere("light direction has zero length");
                l.direction = glm::normalize(d);
            }
            if (l.type == Light::Type::Spot) {
                l.innerConeDegrees = static_cast<float>(t.number("inner_cone", l.innerConeDegrees, {0.0, 90.0}));
                l.outerConeDegrees = static_cast<float>(t.number("outer_cone", l.outerConeDegrees, {0.0, 90.0}));
                if (l.outerConeDegrees < l.innerConeDegrees) t.fail("outer_cone", "expected outer_cone >= inner_cone");
            }
            t.rejectUnknownKeys();
            scene_.lights.push_back(l);
        }
    }

    void readLens(const TomlTable& t, Camera& c) const {
        std::string proj = t.choice("projection", c.projection == Camera::Projection::Perspective ? "perspective" : "orthographic",
                                    {"perspective", "orthographic"});
        c.projection = proj == "perspective" ? Camera::Projection::Perspective : Camera::Projection::Orthographic;
        c.fovYDegrees = static_cast<float>(t.number("fov_y", c.fovYDegrees, limits::kFovYDegrees));
        c.orthoHeight = static_cast<float>(t.number("height", c.orthoHeight, limits::kOrthoHeight));
        c.nearPlane = static_cast<float>(t.number("near", c.nearPlane, limits::kNearPlane));
        c.farPlane = static_cast<float>(t.number("far", c.farPlane, limits::kFarPlane));
        if (c.farPlane <= c.nearPlane) t.fail("far", "expected far > near");
    }

    void readCamera(const TomlTable& root) {
        auto t = root.table("camera");
        if (!t) root.failHere("missing [camera] table");
        Camera& c = scene_.camera;
        if (t->has("gltf_object")) {
            std::string obj = t->string("gltf_object", "");
            std::string node = t->string("gltf_camera", "");
            auto it = gltfCameras_.find(obj);
            if (it == gltfCameras_.end()) t->fail("gltf_object", "object '" + obj + "' is not a model with a glTF camera");
            const GltfCamera* found = nullptr;
            for (const auto& gc : it->second)
                if (node.empty() || gc.nodeName == node) { found = &gc; break; }
            if (!found) t->fail("gltf_camera", "model of object '" + obj + "' has no camera node '" + node + "'");
            c = found->camera;
            // The camera moves with the object that holds it.
            glm::mat4 m = scene_.objects[objectIds_.at(obj)].transform.matrix();
            c.position = glm::vec3(m * glm::vec4(c.position, 1.0f));
            glm::mat3 r(m);
            c.orientation = glm::normalize(glm::quat_cast(glm::mat3(glm::normalize(r[0]), glm::normalize(r[1]), glm::normalize(r[2])))) * c.orientation;
            if (!c.placementUsable())
                t->fail("gltf_object", "object '" + obj + "' places its glTF camera '" + found->nodeName +
                                           "' at a degenerate or far placement (a scale of 0, or beyond " +
                                           formatNumber(limits::kSceneCoordinate) + " from the origin)");
        } else {
            c.position = pointInReach(*t, "position");
            c.orientation = readOrientation(*t, c.position, nonZeroVec3(*t, "up", glm::vec3(0, 1, 0)));
        }
        readLens(*t, c);
        t->rejectUnknownKeys();
    }

    glm::quat readOrientation(const TomlTable& t, glm::vec3 position, glm::vec3 up) const {
        if (t.has("look_at") == t.has("orientation")) t.failHere("expected exactly one of 'look_at' or 'orientation'");
        if (t.has("orientation")) return eulerDegreesToQuat(t.vec3("orientation", {}));
        glm::vec3 target = pointInReach(t, "look_at");
        if (glm::length(target - position) == 0.0f) t.fail("look_at", "look_at equals the camera position");
        return Camera::lookAtOrientation(position, target, up);
    }

    void readCameraPaths(const TomlTable& root) {
        for (const auto& [name, t] : root.namedTables("camera_paths")) {
            CameraPath p;
            p.name = name;
            p.interpolation = toInterpolation(t.choice("interpolation", "catmull-rom", kInterpolations));
            p.framesPerSecond = t.number("fps", 30.0, {1e-3, 1e4});
            p.up = nonZeroVec3(t, "up", p.up);
            auto keys = readKeys(t, "a camera path", p.times);
            // Frame numbers are ints; a path's frame count must fit one with room to spare.
            if (p.duration() * p.framesPerSecond >= limits::kFrame)
                t.fail("fps", "the path's " + formatNumber(p.duration()) + " s at " + formatNumber(p.framesPerSecond) +
                                  " fps make more frames than the limit of " + std::to_string(limits::kFrame));
            p.keysLookAt = keys[0].has("look_at");
            for (const auto& k : keys) {
                glm::vec3 pos = pointInReach(k, "position");
                p.positions.push_back(pos);
                if (k.has("look_at") != p.keysLookAt) k.failHere("all keys of a path must use 'look_at', or all 'orientation'");
                if (p.keysLookAt) {
                    p.targets.push_back(pointInReach(k, "look_at"));
                    if (glm::length(p.targets.back() - pos) == 0.0f) k.fail("look_at", "look_at equals the key's position");
                } else {
                    p.orientations.push_back(readOrientation(k, pos, p.up));
                }
                k.rejectUnknownKeys();
            }
            t.rejectUnknownKeys();
            scene_.cameraPaths.push_back(std::move(p));
        }
    }

    TomlDocument doc_;
    SceneLoadOptions options_;
    Scene scene_;
    std::map<std::string, std::uint32_t> materialIds_;
    std::map<std::string, std::int32_t> textureIds_;
    std::map<std::int32_t, ImageSize> headerSizes_;  // of the textures not decoded
    std::map<std::string, std::size_t> objectIds_;
    std::map<std::string, std::vector<GltfCamera>> gltfCameras_;
};

}  // namespace

Scene loadSceneFile(const fs::path& file, const SceneLoadOptions& options) {
    return SceneFileReader(file, options).read();
}

}  // namespace hybridlab
