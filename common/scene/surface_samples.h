#pragma once
// Points spread uniformly by area over objects' surfaces: what a fit to an object's shape (the
// sphere or cylinder impostor of a layered EM's layer) measures, rather than the parts of it some
// sample of views happened to see.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace hybridlab {

struct Scene;

// `count` world-space points at `time`, area-uniform over the union of the objects' triangles
// (deformations ignored: rigid placement only). Deterministic for a seed on every platform; empty
// when the objects have no area.
std::vector<glm::vec3> sampleObjectSurfaces(const Scene& scene, const std::vector<std::uint32_t>& objects, std::size_t count,
                                            std::uint32_t seed, double time = 0.0);

}  // namespace hybridlab
