#include "tests/support/gbuffer_agreement.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "techniques/shared/ray_cast_gbuffer.h"

namespace hybridlab::test {

GBufferAgreement compareGBuffers(const GBuffer& g, const GBuffer& reference, double diagonal) {
    GBufferAgreement a;
    for (std::size_t i = 0; i < g.pixelCount(); ++i) {
        const std::uint32_t id = reference.objectId[i];
        if (id == kSkyObjectId && g.objectId[i] == kSkyObjectId) continue;
        ++a.covered;
        if (id != g.objectId[i]) continue;
        ++a.idMatches;
        const double positionError = glm::length(glm::vec3(g.position[i]) - glm::vec3(reference.position[i])) / diagonal;
        // Both normalised: a read-back normal is a unit vector rounded to 16-bit floats (its length off 1 by up to
        // about 1e-3, which alone reads as a degree or two near a dot product of 1).
        const glm::vec3 n = glm::normalize(glm::vec3(g.normal[i])), nr = glm::normalize(glm::vec3(reference.normal[i]));
        const float c = std::clamp(glm::dot(n, nr), -1.0f, 1.0f);
        const double normalDegrees = glm::degrees(std::acos(c));
        if (positionError >= kMaxGBufferPositionError || normalDegrees >= kMaxGBufferNormalDegrees) {
            ++a.outliers;
        } else {
            a.maxPositionError = std::max(a.maxPositionError, positionError);
            a.maxNormalDegrees = std::max(a.maxNormalDegrees, normalDegrees);
        }
        const float cg = std::clamp(glm::dot(g.geometricNormal(i), reference.geometricNormal(i)), -1.0f, 1.0f);
        a.geometricOutliers += glm::degrees(std::acos(cg)) > kMaxGBufferNormalDegrees;
        a.facingMatches += reference.frontFace(i) == g.frontFace(i);
    }
    return a;
}

GBufferAgreement compareWithPrimaryRays(const RayScene& rays, const GBuffer& g) {
    GBuffer cast;
    RayStats stats;
    const GBufferTargets targets = kGBufferPosition | kGBufferNormal | kGBufferGeometricNormal | kGBufferObjectId;
    rayCastGBuffer(rays, rays.scene().camera, g.width, g.height, targets, cast, stats);
    EXPECT_EQ(stats.primary, g.pixelCount());
    return compareGBuffers(g, cast, glm::length(rays.scene().bounds(rays.time()).extent()));
}

void expectGBuffersAgree(const GBufferAgreement& a) {
    EXPECT_GE(a.idAgreement(), 0.99);
    EXPECT_LE(a.outliers, a.idMatches / 1000);
    EXPECT_LT(a.maxPositionError, kMaxGBufferPositionError);
    EXPECT_LT(a.maxNormalDegrees, kMaxGBufferNormalDegrees);
}

const char* const kDeformingObjectScene = R"(
[materials.grey]
diffuse = [0.6, 0.6, 0.6]

[[objects]]
name = "floor"
primitive = "plane"
material = "grey"
scale = [8.0, 1.0, 8.0]

[[objects]]
name = "ball"
primitive = "sphere"
slices = 96
stacks = 48
material = "grey"
position = [0.0, 1.0, 0.0]
scale = 2.0
[objects.deform]
amplitude = 0.06
wavelength = 0.35
speed = 0.4
direction = [1.0, 0.0, 1.0]
axis = [0.0, 1.0, 0.0]

[[objects]]
name = "box"
primitive = "cube"
material = "grey"
[objects.animation]
keys = [ { time = 0.0, position = [-2.0, 0.5, 0.0] }, { time = 1.0, position = [2.0, 0.5, 1.0], rotation = [0.0, 90.0, 0.0] } ]

[camera]
position = [0.0, 2.5, 4.5]
look_at = [0.0, 0.8, 0.0]
)";

}  // namespace hybridlab::test
