#pragma once
// Local lens systems (Hakura & Snyder 2001 §1, §3): the lens objects of a scene grouped by their
// `lens_group`, each with a separate Embree scene holding only its own geometry (ray paths are
// traced through a system of one or a few objects) and a scene of everything else, the
// environment that its layered EMs approximate.
#include <memory>
#include <string>
#include <vector>

#include "common/raytrace/ray_scene.h"
#include "common/scene/scene.h"

namespace hybridlab {

// The objects of `scene` for which keep[object] is true, with their meshes, materials, textures,
// lights, sky and camera. Object order is kept; objectMap[i] is the original index of object i.
struct SceneSubset {
    Scene scene;
    std::vector<std::uint32_t> objectMap;
};
SceneSubset makeSceneSubset(const Scene& scene, const std::vector<bool>& keep);

// A lens system as found in a scene (objects in scene order).
struct LensSystemInfo {
    std::string name;                    // the group, or the object's name for a lone lens object
    std::vector<std::uint32_t> objects;  // indices into Scene::objects
};
std::vector<LensSystemInfo> findLensSystems(const Scene& scene);

// One lens system ready for tracing at `time`: its own ray scene and the environment's.
class LensSystem {
public:
    LensSystem(const Scene& scene, LensSystemInfo info, double time = 0.0);

    const LensSystemInfo& info() const { return info_; }
    const Scene& scene() const { return scene_; }
    const RayScene& lensRays() const { return *lensRays_; }
    const RayScene& environmentRays() const { return *environmentRays_; }
    // Original scene object index of an object id in lensRays() / environmentRays() hits.
    std::uint32_t lensObject(std::uint32_t id) const { return lens_.objectMap[id]; }
    std::uint32_t environmentObject(std::uint32_t id) const { return environment_.objectMap[id]; }
    // The EM origin: the centre of the system's world bounds (§4.2 "the centroid of the local object").
    glm::vec3 center() const { return center_; }

private:
    const Scene& scene_;
    LensSystemInfo info_;
    SceneSubset lens_, environment_;
    std::unique_ptr<RayScene> lensRays_, environmentRays_;
    glm::vec3 center_{0.0f};
};

}  // namespace hybridlab
