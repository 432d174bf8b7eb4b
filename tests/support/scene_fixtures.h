#pragma once
// Small scenes built in code for analytic ray-tracing tests.
#include <string>

#include "common/scene/primitives.h"
#include "common/scene/scene.h"

namespace hybridlab::test {

class SceneBuilder {
public:
    SceneBuilder() { scene_.name = "test"; }

    std::uint32_t material(Material m) {
        scene_.materials.push_back(std::move(m));
        return static_cast<std::uint32_t>(scene_.materials.size() - 1);
    }

    // Adds a primitive object placed by `transform`.
    SceneBuilder& object(const std::string& name, Mesh mesh, std::uint32_t material, Transform transform = {}) {
        mesh.material = material;
        SceneObject o;
        o.name = name;
        o.source = mesh.name;
        o.transform = transform;
        o.meshes.push_back(static_cast<std::uint32_t>(scene_.meshes.size()));
        scene_.meshes.push_back(std::move(mesh));
        scene_.objects.push_back(std::move(o));
        return *this;
    }

    SceneBuilder& light(Light l) {
        scene_.lights.push_back(std::move(l));
        return *this;
    }

    Scene& scene() { return scene_; }

private:
    Scene scene_;
};

inline Transform placed(glm::vec3 position, glm::vec3 scale, glm::vec3 rotationDegrees = glm::vec3(0.0f)) {
    Transform t;
    t.position = position;
    t.scale = scale;
    t.rotation = eulerDegreesToQuat(rotationDegrees);
    return t;
}

inline Material matte(glm::vec3 diffuse) {
    Material m;
    m.name = "matte";
    m.diffuse = diffuse;
    m.specular = glm::vec3(0.0f);
    return m;
}

inline Material emissive(glm::vec3 emission) {
    Material m = matte(glm::vec3(0.0f));
    m.name = "emissive";
    m.emission = emission;
    return m;
}

}  // namespace hybridlab::test
