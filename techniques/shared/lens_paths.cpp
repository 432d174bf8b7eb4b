#include "techniques/shared/lens_paths.h"

#include <algorithm>
#include <limits>

#include "common/raytrace/ray_offset.h"
#include "common/raytrace/shading.h"

namespace hybridlab {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

Ray childRay(const SurfaceHit& hit, const InterfaceSplit& s, bool reflect) {
    return reflect ? Ray{offsetRayOrigin(hit.position, s.sideNormal), s.reflectDir}
                   : Ray{offsetRayOrigin(hit.position, -s.sideNormal), s.refractDir};
}

// The media of the child ray: a refraction enters or leaves the hit object (medium_stack.h).
void crossInterface(const SurfaceHit& hit, const InterfaceSplit& s, bool reflect, MediumStack& media, LensRayCounter& counter) {
    if (reflect) return;
    if (!(s.entering ? mediumEnter(media, {hit.object, hit.material->absorption}) : mediumLeave(media, hit.object))) ++counter.mediumErrors;
}

// Follows `path` from the child ray `ray` of interface number path.interfaces - 1, in `media`, greedily.
void propagate(const RayScene& lens, Ray ray, MediumStack media, const LensPathSettings& settings, LensRayCounter& counter,
               LensPath& path) {
    const Scene& scene = lens.scene();
    for (;;) {
        SurfaceHit hit;
        ++counter.queries;
        if (!lens.intersect(ray, 0.0f, kInfinity, hit)) {
            if (media.size > 0) ++counter.mediumErrors;
            path.exitOrigin = ray.origin;
            path.exitDirection = ray.direction;
            return;
        }
        // Beer-Lambert along the segment, the reference tracer's rule.
        if (mediumAbsorbs(media.absorption)) path.absorption *= segmentTransmittance(media.absorption, hit.t);
        if (path.interfaces >= settings.maxInterfaces) {
            path.truncated = true;
            path.exitOrigin = ray.origin;
            path.exitDirection = ray.direction;
            return;
        }
        const InterfaceSplit s = splitAtInterface(scene, hit, ray.direction);
        const bool reflect = s.reflected >= s.refracted;  // the child with the larger coefficient
        if (reflect) path.choices |= 1u << path.interfaces;
        ++path.interfaces;
        path.fresnel *= reflect ? s.reflected : s.refracted;
        crossInterface(hit, s, reflect, media, counter);
        ray = childRay(hit, s, reflect);
        if (path.fresnel <= 0.0f) {  // an opaque surface that neither reflects nor transmits ends it
            path.exitOrigin = ray.origin;
            path.exitDirection = ray.direction;
            return;
        }
    }
}

std::uint64_t treeQueries(const RayScene& lens, const Ray& ray, int interfaces, const LensPathSettings& settings) {
    SurfaceHit hit;
    if (!lens.intersect(ray, 0.0f, kInfinity, hit) || interfaces >= settings.maxInterfaces) return 1;
    const InterfaceSplit s = splitAtInterface(lens.scene(), hit, ray.direction);
    std::uint64_t n = 1;
    if (s.reflected > 0.0f) n += treeQueries(lens, childRay(hit, s, true), interfaces + 1, settings);
    if (s.refracted > 0.0f) n += treeQueries(lens, childRay(hit, s, false), interfaces + 1, settings);
    return n;
}

}  // namespace

InterfaceSplit splitAtInterface(const Scene& scene, const SurfaceHit& hit, glm::vec3 incoming) {
    // As WhittedTracer::shade: work on the side the ray arrives from; TIR sends everything to the
    // reflected child.
    const Material& m = *hit.material;
    InterfaceSplit s;
    s.entering = glm::dot(incoming, hit.geometricNormal) < 0.0f;
    s.sideNormal = s.entering ? hit.geometricNormal : -hit.geometricNormal;
    const glm::vec3 n = s.entering ? hit.shadingNormal : -hit.shadingNormal;
    const float n1 = s.entering ? scene.ambientIor : m.ior, n2 = s.entering ? m.ior : scene.ambientIor;
    const float cosi = std::max(-glm::dot(incoming, n), 0.0f);
    const float om = m.fresnel ? fresnelDielectric(cosi, n1, n2) : m.reflectivity;
    const float orr = 1.0f - m.opacity;
    s.reflectDir = reflectDirection(incoming, n);
    const bool tir = orr > 0.0f && !refractDirection(incoming, n, n1 / n2, s.refractDir);
    s.reflected = tir ? om + (1.0f - om) * orr : om;
    s.refracted = tir ? 0.0f : (1.0f - om) * orr;
    return s;
}

TwoTermPaths traceTwoTermPaths(const RayScene& lens, const SurfaceHit& first, glm::vec3 incoming,
                               const LensPathSettings& settings, LensRayCounter& counter) {
    TwoTermPaths paths;
    const InterfaceSplit s = splitAtInterface(lens.scene(), first, incoming);
    for (int term = 0; term < kPathTerms; ++term) {
        const bool reflect = term == static_cast<int>(PathTerm::Reflection);
        LensPath& p = paths.terms[term];
        p.fresnel = reflect ? s.reflected : s.refracted;
        if (p.fresnel <= 0.0f) continue;
        p.exists = true;
        p.interfaces = 1;
        p.choices = reflect ? 1u : 0u;
        MediumStack media;  // the viewpoint is outside the lens system
        crossInterface(first, s, reflect, media, counter);
        propagate(lens, childRay(first, s, reflect), media, settings, counter, p);
    }
    return paths;
}

bool traceTwoTermPaths(const RayScene& lens, const Ray& ray, const LensPathSettings& settings, LensRayCounter& counter,
                       TwoTermPaths& paths, SurfaceHit* firstHit) {
    SurfaceHit hit;
    ++counter.queries;
    if (!lens.intersect(ray, 0.0f, kInfinity, hit)) return false;
    paths = traceTwoTermPaths(lens, hit, ray.direction, settings, counter);
    if (firstHit) *firstHit = hit;
    return true;
}

std::uint64_t fullRayTreeQueries(const RayScene& lens, const Ray& ray, const LensPathSettings& settings) {
    return treeQueries(lens, ray, 0, settings);
}

RayQueryComparison compareRayQueries(const RayScene& lens, const Camera& camera, int width, int height,
                                     const LensPathSettings& settings) {
    RayQueryComparison c;
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const Ray ray = camera.rayThroughNdc(pixelCenterNdc(x, y, width, height), aspect);
            LensRayCounter counter;
            TwoTermPaths paths;
            ++c.cameraRays;
            if (traceTwoTermPaths(lens, ray, settings, counter, paths)) ++c.lensHits;
            c.pathQueries += counter.queries;
            c.treeQueries += fullRayTreeQueries(lens, ray, settings);
        }
    }
    return c;
}

}  // namespace hybridlab
