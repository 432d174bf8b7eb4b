#include "common/raytrace/whitted_tracer.h"

#include <cmath>
#include <limits>

#include <glm/exponential.hpp>
#include <glm/geometric.hpp>

#include "common/raytrace/ray_offset.h"

namespace hybridlab {

WhittedTracer::WhittedTracer(const RayScene& rays, WhittedSettings settings) : rays_(rays), settings_(settings) {
    for (const Light& l : rays.scene().lights) cones_.push_back(spotCone(l));
}

glm::vec3 WhittedTracer::radiance(const Ray& ray, int depth, float importance, RayStats& stats) const {
    SurfaceHit hit;
    if (!rays_.intersect(ray, 0.0f, std::numeric_limits<float>::infinity(), hit)) return skyRadiance(rays_.scene(), ray.direction);
    glm::vec3 L = shade(hit, ray.direction, depth, importance, stats);
    // A ray that meets the back of a surface travelled inside its object: Beer-Lambert absorption
    // of thick glass (Hakura & Snyder's G).
    const glm::vec3& a = hit.material->absorption;
    if ((a.x > 0.0f || a.y > 0.0f || a.z > 0.0f) && glm::dot(ray.direction, hit.geometricNormal) > 0.0f) {
        L *= glm::exp(-a * hit.t);
    }
    return L;
}

glm::vec3 WhittedTracer::localColor(const SurfaceHit& hit, glm::vec3 normal, glm::vec3 geometricNormal, glm::vec3 toViewer,
                                    RayStats& stats) const {
    const Scene& scene = rays_.scene();
    const SurfacePoint sp{hit.position, normal, hit.uv, hit.material};
    const glm::vec3 tex = diffuseTextureValue(scene, *hit.material, hit.uv);
    glm::vec3 c = unlitTerm(scene, sp, tex);
    const glm::vec3 shadowOrigin = offsetRayOrigin(hit.position, geometricNormal);
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& light = scene.lights[i];
        LightSample ls = sampleLight(light, cones_[i], hit.position);
        glm::vec3 direct = blinnPhong(sp, tex, toViewer, ls);
        if (direct == glm::vec3(0.0f)) continue;  // facing away, or outside a spot cone: no ray needed
        if (light.castsShadows && settings_.shadows) {
            ++stats.shadow;
            direct *= rays_.transmittance(shadowOrigin, ls.toLight, ls.distance);
        }
        c += direct;
    }
    return c;
}

glm::vec3 WhittedTracer::shade(const SurfaceHit& hit, glm::vec3 incoming, int depth, float importance, RayStats& stats) const {
    const Material& m = *hit.material;
    const Scene& scene = rays_.scene();
    // Work on the side the ray arrives from.
    const bool entering = glm::dot(incoming, hit.geometricNormal) < 0.0f;
    const glm::vec3 ng = entering ? hit.geometricNormal : -hit.geometricNormal;
    glm::vec3 n = entering ? hit.shadingNormal : -hit.shadingNormal;

    const glm::vec3 C = localColor(hit, n, ng, -incoming, stats);
    const float orr = 1.0f - m.opacity;
    const float n1 = entering ? scene.ambientIor : m.ior, n2 = entering ? m.ior : scene.ambientIor;
    const float cosi = std::max(-glm::dot(incoming, n), 0.0f);
    float om = m.fresnel ? fresnelDielectric(cosi, n1, n2) : m.reflectivity;
    if (om <= 0.0f && orr <= 0.0f) return C;
    if (depth >= settings_.maxDepth) return C;  // the depth limit returns the local colour

    glm::vec3 refracted;
    const bool tir = orr > 0.0f && !refractDirection(incoming, n, n1 / n2, refracted);
    // Total internal reflection sends everything to the reflected ray.
    const float weightM = tir ? om + (1.0f - om) * orr : om;
    const float weightR = tir ? 0.0f : (1.0f - om) * orr;
    auto worthTracing = [&](float w) { return w > 0.0f && importance * w >= settings_.importanceCutoff; };

    glm::vec3 M = C, R = C;
    if (worthTracing(weightM)) {
        ++stats.reflection;
        M = radiance({offsetRayOrigin(hit.position, ng), reflectDirection(incoming, n)}, depth + 1, importance * weightM, stats);
    }
    if (tir) {
        R = M;
    } else if (worthTracing(weightR)) {
        ++stats.refraction;
        R = radiance({offsetRayOrigin(hit.position, -ng), refracted}, depth + 1, importance * weightR, stats);
    }
    return compose(om, orr, M, R, C, settings_.blend);
}

}  // namespace hybridlab
