#include "techniques/layered_em/layer_shells.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include <Eigen/Eigenvalues>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace hybridlab {
namespace {

// Farthest positive root of |o + t d - c|^2 = r^2 (the exit point for an origin inside), the
// nearest positive one for an origin outside; false when the ray misses.
bool sphereHit(glm::vec3 c, float r, glm::vec3 o, glm::vec3 d, float& t) {
    glm::vec3 oc = o - c;
    float b = glm::dot(oc, d), cc = glm::dot(oc, oc) - r * r;
    float disc = b * b - cc;
    if (disc < 0.0f) return false;
    float s = std::sqrt(disc);
    t = cc <= 0.0f ? -b + s : -b - s;
    return t > 0.0f;
}

}  // namespace

glm::vec3 shellPoint(const Shell& shell, glm::vec3 origin, glm::vec3 direction) {
    float t = 0.0f;
    switch (shell.kind) {
    case ShellKind::Sphere:
        if (sphereHit(shell.center, shell.radius, origin, direction, t)) return origin + t * direction;
        break;
    case ShellKind::Cylinder: {
        // |(o + t d - c)_xz| = r in the horizontal plane; a vertical ray never meets it.
        glm::vec2 o2(origin.x - shell.center.x, origin.z - shell.center.z), d2(direction.x, direction.z);
        float a = glm::dot(d2, d2);
        if (a > 1e-8f) {
            float b = glm::dot(o2, d2), cc = glm::dot(o2, o2) - shell.radius * shell.radius;
            float disc = b * b - a * cc;
            if (disc >= 0.0f) {
                float s = std::sqrt(disc);
                t = cc <= 0.0f ? (-b + s) / a : (-b - s) / a;
                if (t > 0.0f) return origin + t * direction;
            }
        }
        break;
    }
    case ShellKind::Quad: {
        float dn = glm::dot(direction, shell.planeNormal);
        float dist = glm::dot(shell.planePoint - origin, shell.planeNormal);
        if (dn != 0.0f && dist / dn > 0.0f) return origin + (dist / dn) * direction;
        // §4.2: a ray travelling away from the plane is forced onto it: its tangential component,
        // scaled to lie very far from the impostor centre.
        glm::vec3 tangential = direction - dn * shell.planeNormal;
        float len = glm::length(tangential);
        glm::vec3 dir = len > 1e-8f ? tangential / len : shell.axisU;
        return shell.planePoint + shell.farDistance * dir;
    }
    }
    return shell.center + shell.farDistance * direction;  // misses the impostor: the direction alone
}

bool shellHolds(const Shell& shell, glm::vec3 direction, float marginRadians) {
    if (shell.kind != ShellKind::Quad) return true;
    const glm::vec3 d = glm::normalize(direction);
    const float dn = glm::dot(d, shell.planeNormal), dist = glm::dot(shell.planePoint - shell.center, shell.planeNormal);
    if (dn == 0.0f || dist / dn <= 0.0f) return false;
    const float t = dist / dn;
    const glm::vec3 q = shell.center + t * d - shell.planePoint;
    // An angle at distance t covers t * angle across the ray, and more along an oblique plane.
    const float margin = t * marginRadians / std::max(std::abs(dn), 0.1f);
    const glm::vec2 uv(glm::dot(q, shell.axisU), glm::dot(q, shell.axisV));
    return glm::all(glm::greaterThanEqual(uv, shell.extentMin - margin)) && glm::all(glm::lessThanEqual(uv, shell.extentMax + margin));
}

Plane fitPlane(const std::vector<glm::vec3>& points, glm::vec3 viewer) {
    Plane p;
    if (points.empty()) return p;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const glm::vec3& q : points) mean += Eigen::Vector3d(q.x, q.y, q.z);
    mean /= static_cast<double>(points.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const glm::vec3& q : points) {
        Eigen::Vector3d d = Eigen::Vector3d(q.x, q.y, q.z) - mean;
        cov += d * d.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    Eigen::Vector3d n = eig.eigenvectors().col(0);  // eigenvalues ascending
    p.point = glm::vec3(static_cast<float>(mean.x()), static_cast<float>(mean.y()), static_cast<float>(mean.z()));
    p.normal = glm::normalize(glm::vec3(static_cast<float>(n.x()), static_cast<float>(n.y()), static_cast<float>(n.z())));
    if (glm::dot(p.normal, viewer - p.point) < 0.0f) p.normal = -p.normal;
    return p;
}

Shell fitQuadShell(glm::vec3 emOrigin, const std::vector<glm::vec3>& points, const std::vector<OutgoingRay>& rays) {
    Shell s;
    s.kind = ShellKind::Quad;
    s.center = emOrigin;
    Plane plane = fitPlane(points, emOrigin);
    s.planePoint = plane.point;
    s.planeNormal = plane.normal;
    glm::vec3 helper = std::abs(plane.normal.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    s.axisU = glm::normalize(glm::cross(helper, plane.normal));
    s.axisV = glm::cross(plane.normal, s.axisU);
    s.farDistance = 1e3f * std::max(1.0f, glm::length(plane.point - emOrigin));
    glm::vec2 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
    for (const OutgoingRay& r : rays) {
        float dn = glm::dot(r.direction, s.planeNormal);
        if (dn == 0.0f) continue;
        float t = glm::dot(s.planePoint - r.origin, s.planeNormal) / dn;
        if (t <= 0.0f) continue;
        glm::vec3 q = r.origin + t * r.direction - s.planePoint;
        glm::vec2 uv(glm::dot(q, s.axisU), glm::dot(q, s.axisV));
        lo = glm::min(lo, uv);
        hi = glm::max(hi, uv);
    }
    if (lo.x <= hi.x) {
        s.extentMin = lo;
        s.extentMax = hi;
    }
    return s;
}

namespace {

// Relative standard deviation of the points' distance from the origin (3D) and from the vertical
// axis through it (horizontal): how far each impostor's single radius is from the geometry.
struct RadialSpread {
    double spherical = 0.0, cylindrical = 0.0;
};

RadialSpread radialSpread(glm::vec3 origin, const std::vector<glm::vec3>& points) {
    double mean3 = 0.0, mean2 = 0.0, square3 = 0.0, square2 = 0.0;
    for (const glm::vec3& p : points) {
        const double d3 = glm::length(glm::dvec3(p - origin));
        const double d2 = std::hypot(p.x - origin.x, p.z - origin.z);
        mean3 += d3;
        mean2 += d2;
        square3 += d3 * d3;
        square2 += d2 * d2;
    }
    const double n = static_cast<double>(points.size());
    mean3 /= n;
    mean2 /= n;
    auto relative = [n](double mean, double square) { return mean > 0.0 ? std::sqrt(std::max(0.0, square / n - mean * mean)) / mean : 0.0; };
    return {relative(mean3, square3), relative(mean2, square2)};
}

}  // namespace

ShellKind chooseShellKind(glm::vec3 emOrigin, const std::vector<glm::vec3>& points, const std::vector<glm::vec3>& surface,
                          double quadCoverage, double quadConeDegrees) {
    if (points.empty()) return ShellKind::Sphere;
    // Coverage: occupied cells of a 16 x 32 latitude-longitude grid of directions, weighted by
    // their solid angle.
    constexpr int kRows = 16, kCols = 32;
    std::set<int> cells;
    glm::dvec3 meanDirection(0.0);
    for (const glm::vec3& p : points) {
        glm::vec3 d = p - emOrigin;
        float len = glm::length(d);
        if (len <= 0.0f) continue;
        d /= len;
        int row = std::min(kRows - 1, static_cast<int>((std::acos(std::clamp(d.y, -1.0f, 1.0f)) / M_PI) * kRows));
        int col = std::min(kCols - 1, static_cast<int>((std::atan2(d.z, d.x) / (2.0 * M_PI) + 0.5) * kCols));
        cells.insert(row * kCols + col);
        meanDirection += glm::dvec3(d);
    }
    if (cells.empty()) return ShellKind::Sphere;
    double covered = 0.0;
    for (int c : cells) {
        int row = c / kCols;
        covered += (std::cos(row * M_PI / kRows) - std::cos((row + 1) * M_PI / kRows)) / (2.0 * kCols);
    }
    // A plane holds the layer only when the layer lies to one side of the origin: thin objects spread
    // around it (a ring of columns seen in a convex mirror) cover few directions too, but rays
    // leaving away from a plane meet it nowhere near what they hit.
    const glm::dvec3 axis = glm::normalize(meanDirection);
    double widest = 0.0;
    for (const glm::vec3& p : points) {
        const glm::dvec3 d = glm::dvec3(p - emOrigin);
        if (glm::length(d) > 0.0) widest = std::max(widest, std::acos(std::clamp(glm::dot(glm::normalize(d), axis), -1.0, 1.0)));
    }
    if (covered < quadCoverage && widest < glm::radians(quadConeDegrees)) return ShellKind::Quad;
    // The round impostor whose radius varies less over the objects' surfaces: the points seen from
    // the viewpoint samples lie in a band of elevations, over which a sphere and a cylinder differ
    // little, while a view above the band sees the column tops a sphere puts too near (§2:
    // cylinders "may be substituted where they more accurately match the actual geometry").
    const RadialSpread spread = radialSpread(emOrigin, surface.empty() ? points : surface);
    return spread.cylindrical < spread.spherical ? ShellKind::Cylinder : ShellKind::Sphere;
}

}  // namespace hybridlab
