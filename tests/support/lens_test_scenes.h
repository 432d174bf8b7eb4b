#pragma once
// Small lens systems for the layered-EM tests: a glass slab and a glass sphere.
#include <cmath>

#include "common/scene/camera.h"
#include "tests/support/scene_fixtures.h"

namespace hybridlab::test {

inline Material glassWithAbsorption(glm::vec3 absorption) {
    Material g;
    g.name = "glass";
    g.ior = 1.5f;
    g.opacity = 0.0f;
    g.fresnel = true;
    g.absorption = absorption;
    return g;
}

// Clear glass (Fresnel, IOR 1.5) that lets shadow rays through unattenuated at its surfaces
// (diffuse 1: occluderTransmittance 1), so that only its absorption darkens them.
inline Material absorbingGlass(glm::vec3 absorption) {
    Material g = glassWithAbsorption(absorption);
    g.diffuse = glm::vec3(1.0f);
    g.ambient = glm::vec3(0.0f);
    g.specular = glm::vec3(0.0f);
    return g;
}

// Exact unpolarised Fresnel reflectance, written out from the s and p amplitudes (Hecht) so that
// the tests do not lean on the function they check.
inline double handFresnel(double thetaI, double n1, double n2) {
    double s = n1 / n2 * std::sin(thetaI);
    if (s >= 1.0) return 1.0;
    double thetaT = std::asin(s), ci = std::cos(thetaI), ct = std::cos(thetaT);
    double rs = (n1 * ci - n2 * ct) / (n1 * ci + n2 * ct), rp = (n2 * ci - n1 * ct) / (n2 * ci + n1 * ct);
    return 0.5 * (rs * rs + rp * rp);
}

// A perspective camera at `eye` looking at `target`.
inline Camera lookingAt(glm::vec3 eye, glm::vec3 target, float fov) {
    Camera c;
    c.position = eye;
    c.orientation = Camera::lookAtOrientation(eye, target);
    c.fovYDegrees = fov;
    return c;
}

// A glass sphere of radius `radius` at `center` (a UV sphere fine enough for 1e-3 agreement).
inline Scene glassSphereScene(glm::vec3 center, float radius, glm::vec3 absorption, int slices = 256, int stacks = 128) {
    SceneBuilder b;
    auto glass = b.material(glassWithAbsorption(absorption));
    b.object("ball", makeSphere(slices, stacks), glass, placed(center, glm::vec3(2.0f * radius)));
    b.scene().objects[0].lens = true;
    return b.scene();
}

}  // namespace hybridlab::test
