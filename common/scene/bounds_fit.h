#pragma once
// Placing a model by its bounds (a scene object's `fit` table, scenes/README.md): scaled uniformly
// to a height or to a size, and moved so that a point of its bounds lands on a given point (its
// bottom on a floor, or its centre), so that no one reads a model's bounds and does the arithmetic.
#include <optional>

#include "common/scene/transform.h"

namespace hybridlab {

struct BoundsFit {
    enum class Anchor { Center, Bottom };
    std::optional<float> height;  // the placed bounds' extent along y
    std::optional<float> size;    // the placed bounds' largest side
    glm::vec3 at{0.0f};           // where the anchor lands
    Anchor anchor = Anchor::Center;
};

// The anchor of `bounds`: its centre, or the centre of its bottom face (lowest y).
glm::vec3 anchorPoint(const Aabb& bounds, BoundsFit::Anchor anchor);

// `placement` (its rotation, and its scale times the fit's factor) with the position that puts the
// anchor of the placed bounds at `fit.at`. `local` is the object's bounds in its own space and must
// have the extent the fit divides by (checked by the caller, which can name the key).
Transform fitToBounds(const Aabb& local, Transform placement, const BoundsFit& fit);

// The object's bounds in world space under `placement`: its local bounds' eight corners, placed.
Aabb placedBounds(const Aabb& local, const Transform& placement);

}  // namespace hybridlab
