#pragma once
// The heuristic's inputs per visible object this frame (Walewski 2019 §3.2): A from the visible-
// pixel counts, the bounding box's centre in NDC (for P) and its distance to the camera (D), the
// object's reflectivity and refractivity, its static relevance K and estimated cost E, and whether
// it was selected last frame (S).
#include <cstdint>
#include <vector>

#include "common/scene/camera.h"
#include "common/scene/scene.h"
#include "techniques/heuristic_rt/heuristic.h"

namespace hybridlab {

// One observation per object with A > 0 (objects that show no pixel are rejected, §3.2), in object
// order. `localBounds[o]` is Scene::objectLocalBounds(o), computed once per scene (it scans every
// vertex); `selectedLastFrame[o]` may be empty (no previous frame).
std::vector<ObjectObservation> observeVisibleObjects(const Scene& scene, const std::vector<Aabb>& localBounds, double time,
                                                     const Camera& camera, float aspect,
                                                     const std::vector<std::uint64_t>& visiblePixels,
                                                     const std::vector<bool>& selectedLastFrame);

}  // namespace hybridlab
