#include "techniques/shared/lens_system.h"

#include <map>

namespace hybridlab {

SceneSubset makeSceneSubset(const Scene& scene, const std::vector<bool>& keep) {
    SceneSubset out;
    Scene& s = out.scene;
    s.file = scene.file;
    s.name = scene.name;
    s.description = scene.description;
    s.materials = scene.materials;
    s.textures = scene.textures;
    s.lights = scene.lights;
    s.camera = scene.camera;
    s.cameraPaths = scene.cameraPaths;
    s.sky = scene.sky;
    s.ambient = scene.ambient;
    s.ambientIor = scene.ambientIor;
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        if (!keep[i]) continue;
        SceneObject o = scene.objects[i];
        o.meshes.clear();
        for (std::uint32_t m : scene.objects[i].meshes) {
            o.meshes.push_back(static_cast<std::uint32_t>(s.meshes.size()));
            s.meshes.push_back(scene.meshes[m]);
        }
        s.objects.push_back(std::move(o));
        out.objectMap.push_back(static_cast<std::uint32_t>(i));
    }
    return out;
}

std::vector<LensSystemInfo> findLensSystems(const Scene& scene) {
    std::vector<LensSystemInfo> systems;
    std::map<std::string, std::size_t> byGroup;
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& o = scene.objects[i];
        if (!o.lens) continue;
        if (o.lensGroup.empty()) {
            systems.push_back({o.name, {static_cast<std::uint32_t>(i)}});
            continue;
        }
        auto [it, added] = byGroup.emplace(o.lensGroup, systems.size());
        if (added) systems.push_back({o.lensGroup, {}});
        systems[it->second].objects.push_back(static_cast<std::uint32_t>(i));
    }
    return systems;
}

LensSystem::LensSystem(const Scene& scene, LensSystemInfo info, double time) : scene_(scene), info_(std::move(info)) {
    std::vector<bool> inSystem(scene.objects.size(), false);
    for (std::uint32_t o : info_.objects) inSystem[o] = true;
    std::vector<bool> outside(inSystem.size());
    for (std::size_t i = 0; i < inSystem.size(); ++i) outside[i] = !inSystem[i];
    lens_ = makeSceneSubset(scene, inSystem);
    environment_ = makeSceneSubset(scene, outside);
    lensRays_ = std::make_unique<RayScene>(lens_.scene, time);
    environmentRays_ = std::make_unique<RayScene>(environment_.scene, time);
    const Aabb box = lens_.scene.bounds(time);
    center_ = 0.5f * (box.lo + box.hi);
}

}  // namespace hybridlab
