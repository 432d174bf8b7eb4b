#pragma once
// The geometric impostor of one EM layer (Hakura & Snyder 2001 §4.2, §5): a sphere around the EM
// origin by default, a quadrilateral for a sparsely occupied layer, a vertical cylinder for a ring
// of columns. An outgoing ray indexes the layer's cube map by the point where it meets the
// impostor minus the EM origin (§5 "Multipass Rendering with Layered EM Indexing"), so every kind
// shares one texture parameterisation.
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace hybridlab {

enum class ShellKind { Sphere, Quad, Cylinder };

struct Shell {
    ShellKind kind = ShellKind::Sphere;
    glm::vec3 center{0.0f};   // the EM origin (sphere centre; a point on the cylinder's axis)
    float radius = 1.0f;      // sphere, cylinder (axis along +Y)
    // Quad: a point, unit normal and in-plane axes, and the extent in (u, v) around planePoint.
    glm::vec3 planePoint{0.0f}, planeNormal{0.0f, 0.0f, 1.0f}, axisU{1.0f, 0.0f, 0.0f}, axisV{0.0f, 1.0f, 0.0f};
    glm::vec2 extentMin{-1.0f}, extentMax{1.0f};
    float farDistance = 1e4f;  // where rays that do not meet the impostor are sent (§4.2)
};

// The point on the impostor that the outgoing ray (origin, unit direction) indexes.
glm::vec3 shellPoint(const Shell& shell, glm::vec3 origin, glm::vec3 direction);

// The layer's cube-map index of that ray: shellPoint - centre (unnormalised, as a hardware cube
// map takes it).
inline glm::vec3 shellTextureDirection(const Shell& shell, glm::vec3 origin, glm::vec3 direction) {
    return shellPoint(shell, origin, direction) - shell.center;
}

// Least-squares plane through points: the centroid and the eigenvector of the smallest eigenvalue
// of their covariance (normal turned to face `viewer`).
struct Plane {
    glm::vec3 point{0.0f};
    glm::vec3 normal{0.0f, 0.0f, 1.0f};
};
Plane fitPlane(const std::vector<glm::vec3>& points, glm::vec3 viewer);

// A quad impostor for a layer: the plane fitted to the layer's intersection points, facing the EM
// origin, its extent the bounding rectangle of the layer's outgoing rays met with that plane.
struct OutgoingRay {
    glm::vec3 origin;
    glm::vec3 direction;
};
Shell fitQuadShell(glm::vec3 emOrigin, const std::vector<glm::vec3>& points, const std::vector<OutgoingRay>& rays);

// Whether the quad holds what a ray from the EM origin along `direction` indexes: the ray meets
// the plane in front, within the rectangle grown by `marginRadians` of angle at the hit. Rays
// that miss it (and rays travelling away from the plane, forced far off it) index texels no part
// of the quad's texture covers. A sphere or cylinder holds every direction.
bool shellHolds(const Shell& shell, glm::vec3 direction, float marginRadians);

// The kind a layer gets. A quad when its intersection points (seen from the EM origin) cover less
// than `quadCoverage` of the directions around the origin and lie within `quadConeDegrees` of
// their mean direction (a compact, sparsely occupied layer such as the cup seen from the teapot,
// §6). Otherwise a cylinder when the distance of `surface` (points spread over the layer's
// objects; the intersection points when empty) from the vertical axis through the origin varies
// relatively less than their distance from the origin (a ring of columns), a sphere when not.
ShellKind chooseShellKind(glm::vec3 emOrigin, const std::vector<glm::vec3>& points, const std::vector<glm::vec3>& surface,
                          double quadCoverage = 0.08, double quadConeDegrees = 50.0);

}  // namespace hybridlab
