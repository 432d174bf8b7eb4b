#pragma once
// Objects placed with negative scale factors. A mirror (an odd number of them) reverses the winding
// of every triangle it places, and every consumer of a scene takes a triangle's outside from its
// winding: Embree's and the Vulkan device's geometric normals, which decide entering and leaving
// glass, the rasterizer's front faces, the layered EM's lens meshes. So the signs are moved out of
// the placement into the object's own meshes once, on load, by transformMesh (which reverses the
// winding back and maps normals by the inverse transpose): afterwards every placement the
// consumers see scales by positive factors, and the world is as the scene file describes it.
#include <span>

#include <glm/vec3.hpp>

#include "common/scene/mesh.h"
#include "common/scene/scene.h"

namespace hybridlab {

// 1 or -1 for each scale factor's sign.
glm::vec3 scaleSigns(glm::vec3 scale);

// With D = diag(s) for the signs s of the object's scale (its first keyframe's when animated):
// applies D to `meshes` (the object's own) and to its deformation's direction and axis, and scales
// its placement and every keyframe by D. Each world matrix stays what it was (T R S = T R (S D) D,
// as D D = I), and so does each deformed vertex. Keyframes must share the first one's signs (the
// scene reader refuses others), or their factors stay negative. Returns s (all 1: nothing changed).
glm::vec3 moveMirrorIntoMeshes(SceneObject& object, std::span<Mesh> meshes);

}  // namespace hybridlab
