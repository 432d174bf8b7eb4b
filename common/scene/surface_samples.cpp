#include "common/scene/surface_samples.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include "common/scene/scene.h"

namespace hybridlab {

namespace {

struct WorldTriangle {
    glm::vec3 a, b, c;
};

// A double in [0, 1) from the generator's raw output: std::uniform_real_distribution differs
// between standard libraries, the engine's sequence does not.
double unitInterval(std::mt19937& rng) { return static_cast<double>(rng()) / 4294967296.0; }

}  // namespace

std::vector<glm::vec3> sampleObjectSurfaces(const Scene& scene, const std::vector<std::uint32_t>& objects, std::size_t count,
                                            std::uint32_t seed, double time) {
    std::vector<WorldTriangle> triangles;
    std::vector<double> cumulativeArea;
    double area = 0.0;
    for (std::uint32_t o : objects) {
        const SceneObject& object = scene.objects.at(o);
        const glm::mat4 world = object.worldMatrix(time);
        for (std::uint32_t m : object.meshes) {
            const Mesh& mesh = scene.meshes.at(m);
            for (const glm::uvec3& t : mesh.triangles) {
                const WorldTriangle w{glm::vec3(world * glm::vec4(mesh.positions[t.x], 1.0f)),
                                      glm::vec3(world * glm::vec4(mesh.positions[t.y], 1.0f)),
                                      glm::vec3(world * glm::vec4(mesh.positions[t.z], 1.0f))};
                const double a = 0.5 * static_cast<double>(glm::length(glm::cross(w.b - w.a, w.c - w.a)));
                if (!(a > 0.0)) continue;
                area += a;
                triangles.push_back(w);
                cumulativeArea.push_back(area);
            }
        }
    }
    std::vector<glm::vec3> points;
    if (triangles.empty()) return points;
    points.reserve(count);
    std::mt19937 rng(seed);
    for (std::size_t i = 0; i < count; ++i) {
        const double pick = unitInterval(rng) * area;
        const std::size_t k = std::min<std::size_t>(
            triangles.size() - 1, static_cast<std::size_t>(std::upper_bound(cumulativeArea.begin(), cumulativeArea.end(), pick) - cumulativeArea.begin()));
        // Uniform barycentrics (pbrt-v4's SampleUniformTriangle, square-root form).
        const double r = std::sqrt(unitInterval(rng));
        const double u = 1.0 - r, v = r * unitInterval(rng);
        const WorldTriangle& t = triangles[k];
        points.push_back(t.a * static_cast<float>(u) + t.b * static_cast<float>(v) + t.c * static_cast<float>(1.0 - u - v));
    }
    return points;
}

}  // namespace hybridlab
