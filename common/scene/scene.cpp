#include "common/scene/scene.h"

namespace hybridlab {

const char* lightTypeName(Light::Type type) {
    switch (type) {
    case Light::Type::Directional: return "directional";
    case Light::Type::Point: return "point";
    case Light::Type::Spot: return "spot";
    }
    return "?";
}

glm::mat4 SceneObject::worldMatrix(double time) const {
    return isAnimated() ? animation.at(time).matrix() : transform.matrix();
}

const CameraPath* Scene::findCameraPath(const std::string& pathName) const {
    for (const auto& p : cameraPaths)
        if (p.name == pathName) return &p;
    return nullptr;
}

bool Scene::isAnimated() const {
    for (const auto& o : objects)
        if (o.isDynamic()) return true;
    return false;
}

bool Scene::objectIsReflective(std::size_t object) const {
    for (auto m : objects[object].meshes)
        if (materials[meshes[m].material].isReflective()) return true;
    return false;
}

bool Scene::objectIsRefractive(std::size_t object) const {
    for (auto m : objects[object].meshes)
        if (materials[meshes[m].material].isRefractive()) return true;
    return false;
}

std::size_t Scene::objectTriangleCount(std::size_t object) const {
    std::size_t n = 0;
    for (auto m : objects[object].meshes) n += meshes[m].triangleCount();
    return n;
}

Aabb Scene::objectLocalBounds(std::size_t object) const {
    Aabb local;
    for (auto m : objects[object].meshes) local.extend(meshes[m].bounds());
    return objects[object].deformation.envelope(local);
}

Aabb Scene::objectBounds(std::size_t object, double time) const {
    return objectLocalBounds(object).transformed(objects[object].worldMatrix(time));
}

Aabb Scene::bounds(double time) const {
    Aabb b;
    for (std::size_t i = 0; i < objects.size(); ++i) b.extend(objectBounds(i, time));
    return b;
}

SceneStats Scene::stats() const {
    SceneStats s;
    s.objects = objects.size();
    s.lights = lights.size();
    for (std::size_t i = 0; i < objects.size(); ++i) {
        for (auto m : objects[i].meshes) {
            s.triangles += meshes[m].triangleCount();
            s.vertices += meshes[m].vertexCount();
        }
        const bool refractive = objectIsRefractive(i);
        s.refractiveObjects += refractive;
        s.reflectiveObjects += !refractive && objectIsReflective(i);
    }
    return s;
}

}  // namespace hybridlab
