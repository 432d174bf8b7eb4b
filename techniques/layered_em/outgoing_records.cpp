#include "techniques/layered_em/outgoing_records.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/parallel_for.h>

#include "common/raytrace/ray_offset.h"
#include "common/raytrace/ray_task_context.h"

namespace hybridlab {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Follows one outgoing ray through the environment recording its front-facing intersections.
// Whether the ray left the scene with every surface along it recorded (it reached the sky).
bool followIntoEnvironment(const LensSystem& system, const WhittedTracer& shading, Ray ray, std::uint32_t pixel,
                           std::uint32_t rayId, std::uint8_t term, const RecordSettings& settings,
                           std::vector<OutgoingRecord>& out, std::uint64_t& queries) {
    const int maxHits = settings.continueRays ? settings.maxHitsPerRay : 1;
    std::uint16_t order = 0;
    for (int step = 0; step < 4 * settings.maxHitsPerRay && order < maxHits; ++step) {
        SurfaceHit hit;
        ++queries;
        if (!system.environmentRays().intersect(ray, 0.0f, kInfinity, hit)) return true;
        const bool front = glm::dot(ray.direction, hit.geometricNormal) < 0.0f;
        if (front) {
            OutgoingRecord r;
            r.pixel = pixel;
            r.ray = rayId;
            r.order = order++;
            r.term = term;
            r.object = system.environmentObject(hit.object);
            r.position = hit.position;
            r.distance = glm::length(hit.position - system.center());
            RayStats stats;
            r.radiance = shading.shade(hit, ray.direction, 1, 1.0f, stats);
            out.push_back(r);
            if (!settings.continueRays) return false;
        }
        // Continue through the surface.
        ray.origin = offsetRayOrigin(hit.position, front ? -hit.geometricNormal : hit.geometricNormal);
    }
    return false;
}

template <typename PerRow>
ViewpointRecords compileRows(const Camera& camera, int width, int height, int n, PerRow&& perRow) {
    ViewpointRecords v;
    v.camera = camera;
    v.width = width;
    v.height = height;
    v.supersampling = n;
    const std::size_t rays = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * static_cast<std::size_t>(n * n) * kPathTerms;
    v.rayExists.assign(rays, 0);
    v.rayDirection.assign(rays, glm::vec3(0.0f));
    v.rays.assign(rays, OutgoingRay{glm::vec3(0.0f), glm::vec3(0.0f)});
    v.rayEscaped.assign(rays, 0);
    std::vector<std::vector<OutgoingRecord>> rows(static_cast<std::size_t>(height));
    std::vector<std::uint64_t> lensQueries(static_cast<std::size_t>(height), 0), envQueries(static_cast<std::size_t>(height), 0);
    RayTaskContext context;
    tbb::parallel_for(0, height, [&](int y) { perRow(v, y, rows[static_cast<std::size_t>(y)], lensQueries[static_cast<std::size_t>(y)], envQueries[static_cast<std::size_t>(y)]); }, context);
    for (int y = 0; y < height; ++y) {
        v.records.insert(v.records.end(), rows[static_cast<std::size_t>(y)].begin(), rows[static_cast<std::size_t>(y)].end());
        v.lensQueries += lensQueries[static_cast<std::size_t>(y)];
        v.environmentQueries += envQueries[static_cast<std::size_t>(y)];
    }
    return v;
}

}  // namespace

glm::vec2 subpixelNdc(int x, int y, int k, int n, int width, int height) {
    const float sx = static_cast<float>(x) + (static_cast<float>(k % n) + 0.5f) / static_cast<float>(n);
    const float sy = static_cast<float>(y) + (static_cast<float>(k / n) + 0.5f) / static_cast<float>(n);
    return {sx / static_cast<float>(width) * 2.0f - 1.0f, sy / static_cast<float>(height) * 2.0f - 1.0f};
}

float confidenceAngle(float degrees, int height) { return degrees > 0.0f ? degrees : 5.0f * 480.0f / static_cast<float>(height); }

float rayConfidence(float maxAngle, float thetaC) {
    return 1.0f - std::min(maxAngle * maxAngle, thetaC * thetaC) / (thetaC * thetaC);
}

ViewpointRecords compileOutgoingRecords(const LensSystem& system, const WhittedTracer& shading, const Camera& camera,
                                        int width, int height, const RecordSettings& settings) {
    const int n = settings.supersampling;
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    return compileRows(camera, width, height, n, [&](ViewpointRecords& v, int y, std::vector<OutgoingRecord>& out,
                                                     std::uint64_t& lensQueries, std::uint64_t& envQueries) {
        for (int x = 0; x < width; ++x) {
            const std::uint32_t pixel = static_cast<std::uint32_t>(y * width + x);
            for (int k = 0; k < n * n; ++k) {
                const Ray ray = camera.rayThroughNdc(subpixelNdc(x, y, k, n, width, height), aspect);
                LensRayCounter counter;
                TwoTermPaths paths;
                SurfaceHit first;
                const bool hit = traceTwoTermPaths(system.lensRays(), ray, settings.paths, counter, paths, &first);
                lensQueries += counter.queries;
                if (!hit) continue;
                if (!settings.continueRays) {  // without continuation an occluder in front hides the lens
                    SurfaceHit occluder;
                    ++envQueries;
                    if (system.environmentRays().intersect(ray, 0.0f, first.t, occluder)) continue;
                }
                for (int term = 0; term < kPathTerms; ++term) {
                    const LensPath& p = paths.terms[term];
                    if (!p.exists || p.fresnel <= 0.0f) continue;
                    const std::uint32_t id = (pixel * static_cast<std::uint32_t>(n * n) + static_cast<std::uint32_t>(k)) * kPathTerms + static_cast<std::uint32_t>(term);
                    v.rayExists[id] = 1;
                    v.rayDirection[id] = p.exitDirection;
                    v.rays[id] = {p.exitOrigin, p.exitDirection};
                    v.rayEscaped[id] = followIntoEnvironment(system, shading, Ray{p.exitOrigin, p.exitDirection}, pixel, id,
                                                             static_cast<std::uint8_t>(term), settings, out, envQueries);
                }
            }
        }
    });
}

ViewpointRecords compileDirectRecords(const LensSystem& system, const WhittedTracer& shading, const Camera& camera, int width,
                                      int height, const RecordSettings& settings) {
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    return compileRows(camera, width, height, 1, [&](ViewpointRecords& v, int y, std::vector<OutgoingRecord>& out,
                                                     std::uint64_t&, std::uint64_t& envQueries) {
        for (int x = 0; x < width; ++x) {
            const std::uint32_t pixel = static_cast<std::uint32_t>(y * width + x);
            const Ray ray = camera.rayThroughNdc(pixelCenterNdc(x, y, width, height), aspect);
            const std::uint32_t id = pixel * kPathTerms;
            v.rayExists[id] = 1;
            v.rayDirection[id] = ray.direction;
            v.rays[id] = {ray.origin, ray.direction};
            v.rayEscaped[id] = followIntoEnvironment(system, shading, ray, pixel, id, 0, settings, out, envQueries);
        }
    });
}

LayerImageAccumulator::LayerImageAccumulator(int width, int height, float confidenceAngleDegrees)
    : width_(width), thetaC_(glm::radians(confidenceAngleDegrees)),
      sum_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), glm::vec4(0.0f)),
      directions_(sum_.size()) {}

void LayerImageAccumulator::addRay(int x, int y, glm::vec3 d) {
    directions_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x)].push_back(d);
}

void LayerImageAccumulator::addColor(int x, int y, glm::vec4 c) {
    sum_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x)] += c;
}

void LayerImageAccumulator::finish(std::vector<glm::vec4>& b, std::vector<float>& confidence) const {
    b.assign(sum_.size(), glm::vec4(0.0f));
    confidence.assign(sum_.size(), 0.0f);
    for (std::size_t i = 0; i < sum_.size(); ++i) {
        const auto& d = directions_[i];
        if (d.empty()) continue;
        b[i] = sum_[i] / static_cast<float>(d.size());
        float maxAngle = 0.0f;
        for (std::size_t a = 0; a < d.size(); ++a) {
            for (std::size_t c = a + 1; c < d.size(); ++c) {
                maxAngle = std::max(maxAngle, std::acos(std::clamp(glm::dot(d[a], d[c]), -1.0f, 1.0f)));
            }
        }
        confidence[i] = rayConfidence(maxAngle, thetaC_);
    }
}

}  // namespace hybridlab
