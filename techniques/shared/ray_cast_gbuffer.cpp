#include "techniques/shared/ray_cast_gbuffer.h"

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include "common/raytrace/ray_cone.h"
#include "common/raytrace/shading.h"
#include "techniques/shared/camera_ray_packet.h"

namespace hybridlab {

namespace {

// Octahedral encoding of a unit vector into [-1, 1]^2 (Cigolle et al., JCGT 2014): as
// octahedralEncode in shaders/gbuffer_encoding.glsl (GBufferRays in tests/ holds the two G-buffers
// equal), decoded by GBuffer::geometricNormal.
glm::vec2 octahedralEncode(glm::vec3 n) {
    n /= std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
    if (n.z >= 0.0f) return {n.x, n.y};
    return {(1.0f - std::abs(n.y)) * (n.x >= 0.0f ? 1.0f : -1.0f), (1.0f - std::abs(n.x)) * (n.y >= 0.0f ? 1.0f : -1.0f)};
}

// Every pixel is written (zero where the sky is), so nothing is cleared first.
template <class T>
void sized(std::vector<T>& v, bool wanted, std::size_t n) {
    if (wanted) v.resize(n);
    else v.clear();
}

}  // namespace

void rayCastGBuffer(const RayScene& rays, const Camera& camera, int width, int height, GBufferTargets targets, GBuffer& g,
                    RayStats& stats) {
    g.width = width;
    g.height = height;
    g.targets = targets;
    const std::size_t n = g.pixelCount();
    sized(g.position, g.has(kGBufferPosition), n);
    sized(g.normal, g.has(kGBufferNormal), n);
    sized(g.emission, (targets & kGBufferEmission) != 0, n);
    sized(g.ambient, (targets & kGBufferAmbient) != 0, n);
    sized(g.diffuse, g.has(kGBufferDiffuse), n);
    sized(g.specular, g.has(kGBufferSpecular), n);
    sized(g.optical, g.has(kGBufferOptical), n);
    sized(g.objectId, g.has(kGBufferObjectId), n);
    sized(g.depth, g.has(kGBufferDepth), n);

    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    const glm::mat4 viewProj = camera.projectionMatrix(aspect) * camera.view();
    const RayCone pixel = pixelCone(camera, height);
    const CameraRays cameraRays(camera, aspect);
    stats += forEachPixelBlockInParallel(width, height, [&](const PixelBlock& block, RayStats& st) {
        const CameraRayPacket packet(rays, cameraRays, block, width, height, st);
        for (int k = 0; k < block.count; ++k) {
            const std::size_t i = g.index(block.x[k], block.y[k]);
            if (!packet.found[k]) {  // the sky: all zero
                for (std::vector<glm::vec4>* t : {&g.position, &g.normal, &g.emission, &g.ambient, &g.diffuse, &g.specular, &g.optical})
                    if (!t->empty()) (*t)[i] = glm::vec4(0.0f);
                if (!g.objectId.empty()) g.objectId[i] = 0;
                if (!g.depth.empty()) g.depth[i] = 0.0f;
                continue;
            }
            const Ray& ray = packet.rays[k];
            const SurfaceHit& hit = packet.hits[k];
            const Material& m = *hit.material;
            // The diffuse texture through the primary ray's cone, as the reference's first hit reads it.
            glm::vec3 texel(1.0f);
            if (targets & (kGBufferAmbient | kGBufferDiffuse)) {
                const float lod = uvFootprintLod(hit.uvDensityLod, pixel.at(hit.t), ray.direction, hit.geometricNormal);
                texel = diffuseTextureValue(m, rays.diffuseTexture(m), hit.uv, lod);
            }
            const glm::vec2 ng = octahedralEncode(hit.geometricNormal);
            if (!g.position.empty()) g.position[i] = glm::vec4(hit.position, 1.0f);
            if (!g.normal.empty()) g.normal[i] = glm::vec4(hit.shadingNormal, glm::dot(ray.direction, hit.geometricNormal) < 0.0f ? 1.0f : -1.0f);
            if (!g.emission.empty()) g.emission[i] = glm::vec4(m.emission, ng.x);
            if (!g.ambient.empty()) g.ambient[i] = glm::vec4(m.ambient * texel, ng.y);
            if (!g.diffuse.empty()) g.diffuse[i] = glm::vec4(m.diffuse * texel, 0.0f);
            if (!g.specular.empty()) g.specular[i] = glm::vec4(m.specular, m.specularExponent);
            if (!g.optical.empty()) g.optical[i] = glm::vec4(m.reflectivity, m.ior, m.opacity, m.fresnel ? 1.0f : 0.0f);
            if (!g.objectId.empty()) g.objectId[i] = hit.object + 1;
            if (!g.depth.empty()) {
                const glm::vec4 clip = viewProj * glm::vec4(hit.position, 1.0f);
                g.depth[i] = clip.z / clip.w;  // reverse-Z: near 1, far 0
            }
        }
    });
}

}  // namespace hybridlab
