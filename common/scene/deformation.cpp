#include "common/scene/deformation.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace hybridlab {

Aabb Deformation::envelope(const Aabb& rest) const {
    if (!active() || !rest.valid()) return rest;
    const glm::vec3 reach = std::abs(amplitude) * glm::abs(axis);
    return {rest.lo - reach, rest.hi + reach};
}

void deformMesh(const Deformation& d, const Mesh& rest, double time, DeformedVertices& out) {
    const std::size_t n = rest.positions.size();
    out.positions.resize(n);
    out.normals.resize(n);
    out.tangents.resize(rest.tangents.size());
    const double k = d.wavenumber();
    const double omegaT = d.angularFrequency() * time;
    for (std::size_t i = 0; i < n; ++i) {
        const glm::vec3 p = rest.positions[i];
        const double s = k * static_cast<double>(glm::dot(p, d.direction)) - omegaT + static_cast<double>(d.phaseRadians);
        const auto displacement = static_cast<float>(static_cast<double>(d.amplitude) * std::sin(s));
        const auto c = static_cast<float>(static_cast<double>(d.amplitude) * k * std::cos(s));  // slope of the wave
        out.positions[i] = p + displacement * d.axis;
        const glm::vec3 nrm = rest.normals.empty() ? glm::vec3(0.0f, 1.0f, 0.0f) : rest.normals[i];
        out.normals[i] = glm::normalize(nrm - c * glm::dot(d.axis, nrm) * d.direction);
        if (!rest.tangents.empty()) {
            const glm::vec4 t = rest.tangents[i];
            const glm::vec3 tx(t);
            out.tangents[i] = glm::vec4(glm::normalize(tx + c * glm::dot(d.direction, tx) * d.axis), t.w);
        }
    }
}

}  // namespace hybridlab
