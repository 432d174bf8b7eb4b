#pragma once
// The scene model: what the papers use and nothing more (Walewski 2019 §3 and Table 1;
// Hakura & Snyder 2001 §6 for lens objects). Loaded from a TOML scene file (scene_file.h).
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "common/scene/camera.h"
#include "common/scene/camera_path.h"
#include "common/scene/deformation.h"
#include "common/scene/light.h"
#include "common/scene/material.h"
#include "common/scene/mesh.h"
#include "common/scene/rigid_animation.h"
#include "common/scene/texture.h"
#include "common/scene/transform.h"

namespace hybridlab {

struct SceneObject {
    std::string name;
    std::string source;                 // primitive name, or the model path as written
    std::vector<std::uint32_t> meshes;  // into Scene::meshes, in object space
    Transform transform;                // placement when not animated
    RigidAnimation animation;           // keyframed placement (dynamic scenes); empty = static
    Deformation deformation;            // per-vertex deformation in object space; inactive = rigid
    float relevance = 1.0f;             // Walewski's static relevance K
    float cost = 1.0f;                  // Walewski's estimated cost E
    bool lens = false;                  // a lens object of the layered-EM technique (Hakura & Snyder)
    // Lens objects with the same non-empty group form one local lens system (Hakura & Snyder §1:
    // "multiple objects can be combined if they are close or one contains or surrounds another");
    // an empty group makes the object a system of its own.
    std::string lensGroup;

    bool isAnimated() const { return !animation.empty(); }
    bool isDeforming() const { return deformation.active(); }
    // Anything about the object changes with time: its placement or its vertices.
    bool isDynamic() const { return isAnimated() || isDeforming(); }
    glm::mat4 worldMatrix(double time) const;
};

// Sky seen by rays that miss: a constant colour, or a cube map (faces +X, -X, +Y, -Y, +Z, -Z in
// the OpenGL cube-map convention) when cubeFaces are set.
struct Sky {
    glm::vec3 color{0.0f};
    std::array<std::int32_t, 6> cubeFaces{kNoTexture, kNoTexture, kNoTexture, kNoTexture, kNoTexture, kNoTexture};
    bool hasCubeMap() const { return cubeFaces[0] != kNoTexture; }
};

// Walewski 2019 Table 4's rows. As there, the reflective and refractive counts are disjoint: an
// object that refracts (glass, which also reflects by Fresnel) counts as refractive only.
struct SceneStats {
    std::size_t objects = 0, vertices = 0, triangles = 0, lights = 0;
    std::size_t reflectiveObjects = 0, refractiveObjects = 0;
};

struct Scene {
    std::filesystem::path file;
    std::string name;
    std::string description;

    std::vector<Mesh> meshes;
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<SceneObject> objects;
    std::vector<Light> lights;
    Camera camera;
    std::vector<CameraPath> cameraPaths;
    Sky sky;
    glm::vec3 ambient{0.0f};   // global ambient colour
    float ambientIor = 1.0f;   // index of refraction of the medium around objects
    std::size_t droppedDegenerateTriangles = 0;  // zero-area triangles removed from models on load
    // Every file the scene was built from (the scene file, models, their buffers and images,
    // textures): what a cached reference image depends on.
    std::vector<std::filesystem::path> sourceFiles;

    const CameraPath* findCameraPath(const std::string& pathName) const;
    bool isAnimated() const;  // some object is dynamic (moves or deforms)

    // Some material of the object reflects (mirror or Fresnel) / transmits (opacity < 1).
    bool objectIsReflective(std::size_t object) const;
    bool objectIsRefractive(std::size_t object) const;
    std::size_t objectTriangleCount(std::size_t object) const;
    // Object space (scans every vertex); a deforming object's covers every time.
    Aabb objectLocalBounds(std::size_t object) const;
    Aabb objectBounds(std::size_t object, double time) const;  // world space
    Aabb bounds(double time = 0.0) const;                      // world space
    SceneStats stats() const;
};

}  // namespace hybridlab
