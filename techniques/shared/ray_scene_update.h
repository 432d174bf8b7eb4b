#pragma once
// The `bvh_update` stage of every technique that traces rays: moves the shared RayScene to the
// frame's time (instances re-placed, deforming objects' BVHs refitted: ray_scene.h), times it as
// its own stage (de Macedo & Rodrigues, Tables I-II), and reports what the update touched.
#include "techniques/scene_context.h"
#include "techniques/stage_clock.h"

namespace hybridlab {

inline const RayScene& updateRayScene(SceneContext& context, double time, StageClock& clock, FrameResult& result) {
    const RayScene& rays = context.rayScene(time);
    clock.lap("bvh_update");
    result.counters["bvh_triangles"] = static_cast<double>(rays.triangleCount());
    // Triangles moved as rigid instances (a top-level re-commit) and refitted in place (deformed).
    result.counters["bvh_moving_triangles"] = static_cast<double>(rays.rigidMovingTriangles());
    result.counters["bvh_refit_triangles"] = static_cast<double>(rays.deformingTriangles());
    return rays;
}

}  // namespace hybridlab
