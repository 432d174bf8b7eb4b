#pragma once
// Built-in primitives (Walewski 2019 §3: plane, cube, sphere with slices and stacks; plus a
// cylinder). Each fits the unit box [-0.5, 0.5]^3, so an object's scale is its size. Triangles
// are counter-clockwise seen from outside; normals point out; uvs in [0, 1].
#include "common/scene/mesh.h"

namespace hybridlab {

// Square in the XZ plane, normal +Y: 2 triangles.
Mesh makePlane();
// Cube with one flat-shaded quad per face: 12 triangles, 24 vertices.
Mesh makeCube();
// UV sphere of radius 0.5 with smooth normals: 2 * slices * (stacks - 1) triangles (a fan at each
// pole, quads between). slices >= 3, stacks >= 2.
Mesh makeSphere(int slices, int stacks);
// Cylinder of radius 0.5 and height 1 along Y, smooth sides and flat caps: 4 * slices triangles.
Mesh makeCylinder(int slices);

}  // namespace hybridlab
