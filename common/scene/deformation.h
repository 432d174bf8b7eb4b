#pragma once
// Procedural per-vertex deformation of an object (the deformable Utah teapots of de Macedo &
// Rodrigues, Table II): a transverse travelling wave in object space,
//   p'(p, t) = p + A sin(k (p . d) - w t + phase) a,   k = 2 pi / wavelength,  w = k * speed,
// with propagation direction d and displacement axis a (unit, perpendicular). deformMesh() is the
// one function that computes deformed vertices: the rasterizer's vertex upload and the Embree scene
// both take them from it (through DeformedMeshCache, deformed_mesh_cache.h), so rasterization and
// ray tracing see the same surface.
#include <numbers>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "common/scene/mesh.h"
#include "common/scene/transform.h"

namespace hybridlab {

struct Deformation {
    float amplitude = 0.0f;             // object-space units; 0: no deformation
    float wavelength = 1.0f;            // object-space units
    float speed = 0.0f;                 // object-space units per second, along direction
    float phaseRadians = 0.0f;
    glm::vec3 direction{1.0f, 0.0f, 0.0f};  // propagation, unit
    glm::vec3 axis{0.0f, 1.0f, 0.0f};       // displacement, unit, perpendicular to direction

    bool active() const { return amplitude != 0.0f; }
    double wavenumber() const { return 2.0 * std::numbers::pi / static_cast<double>(wavelength); }  // k
    double angularFrequency() const { return wavenumber() * static_cast<double>(speed); }          // w = k v
    // Object-space bounds of the deformed mesh at any time, from its rest bounds.
    Aabb envelope(const Aabb& rest) const;
};

// A mesh's vertex attributes at one time (the attributes a deformation changes).
struct DeformedVertices {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;   // unit
    std::vector<glm::vec4> tangents;  // empty when the mesh has none
};

// Deforms `rest` at `time` into `out` (resized). Normals are exact: with the Jacobian
// J = I + c a d^T (c = A k cos(...)) and a perpendicular to d, J^-T n = n - c (a . n) d; tangents
// go with J.
void deformMesh(const Deformation& deformation, const Mesh& rest, double time, DeformedVertices& out);

}  // namespace hybridlab
