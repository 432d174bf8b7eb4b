#include "common/scene/deformed_mesh_cache.h"

namespace hybridlab {

const std::vector<DeformedVertices>& DeformedMeshCache::vertices(std::size_t object, double time, Consumer consumer) {
    Entry& e = objects_[object];
    const bool computedForTheOther = e.served != 0 && !(e.served & consumer) && e.time == time;
    if (!computedForTheOther) {
        const SceneObject& o = scene_.objects[object];
        e.meshes.resize(o.meshes.size());
        for (std::size_t k = 0; k < o.meshes.size(); ++k) deformMesh(o.deformation, scene_.meshes[o.meshes[k]], time, e.meshes[k]);
        e.time = time;
        e.served = 0;
        ++deformations_;
    }
    e.served |= consumer;
    return e.meshes;
}

}  // namespace hybridlab
