#pragma once
// The two-term greedy ray-path model (Hakura & Snyder 2001 §3, Figure 3): where a ray from the
// viewpoint first strikes the lens system two paths start, one with the reflection and one with
// the refraction; at every later interface a path continues along the child with the larger
// Fresnel coefficient until it leaves the system. Each path carries the product F of the Fresnel
// coefficients it took and the transparency attenuation G of the glass it crossed (Kay &
// Greenberg: a per-channel constant to the power of the thickness, here exp(-absorption * d) along
// every segment inside, the reference tracer's rule of medium_stack.h). The shading is
// T F_T G_T + R F_R G_R.
#include <cstdint>

#include <glm/vec3.hpp>

#include "common/raytrace/medium_stack.h"
#include "common/raytrace/ray_scene.h"

namespace hybridlab {

enum class PathTerm : std::uint8_t { Reflection = 0, Refraction = 1 };
inline constexpr int kPathTerms = 2;

struct LensPathSettings {
    int maxInterfaces = 10;  // as the reference's depth limit: a path still inside after it ends there
};

// One greedy ray path from the first interface out of the lens system.
struct LensPath {
    bool exists = false;        // false when its first child has zero weight (a refraction into an opaque mirror, TIR)
    glm::vec3 exitOrigin{0.0f};
    glm::vec3 exitDirection{0.0f};  // unit; the outgoing ray into the environment
    float fresnel = 0.0f;           // F: product of the coefficients taken
    glm::vec3 absorption{1.0f};     // G
    int interfaces = 0;             // surfaces met, the first included (path length)
    std::uint32_t choices = 0;      // bit i set: reflection at interface i (the path's topology)
    bool truncated = false;         // still inside the system at maxInterfaces

    glm::vec3 weight() const { return fresnel * absorption; }
    bool sameTopology(const LensPath& o) const {
        return exists == o.exists && interfaces == o.interfaces && choices == o.choices;
    }
};

struct TwoTermPaths {
    LensPath terms[kPathTerms];  // indexed by PathTerm
    const LensPath& reflection() const { return terms[0]; }
    const LensPath& refraction() const { return terms[1]; }
};

// Ray queries made into the lens system's scene.
struct LensRayCounter {
    std::uint64_t queries = 0;
    std::uint64_t mediumErrors = 0;  // as RayStats::mediumErrors
};

// The two paths starting at a known first interface `first` (a hit, or a lens vertex with its
// normal as hit.shadingNormal) met along unit `incoming`.
TwoTermPaths traceTwoTermPaths(const RayScene& lens, const SurfaceHit& first, glm::vec3 incoming,
                               const LensPathSettings& settings, LensRayCounter& counter);

// The same from a ray: false (and no paths) when the ray misses the lens system.
bool traceTwoTermPaths(const RayScene& lens, const Ray& ray, const LensPathSettings& settings, LensRayCounter& counter,
                       TwoTermPaths& paths, SurfaceHit* firstHit = nullptr);

// For comparison (§3, Figure 2): the number of lens-system ray queries the full binary ray tree
// makes for the same ray (every interface spawns both children that carry weight, to the same
// interface limit). The first query (finding the first interface) is counted as in the paths.
std::uint64_t fullRayTreeQueries(const RayScene& lens, const Ray& ray, const LensPathSettings& settings);

// Figure 2's comparison over the pixel centres of a width x height view: the lens-system ray
// queries of the two greedy paths and of the full binary tree on the same camera rays.
struct RayQueryComparison {
    std::uint64_t cameraRays = 0, lensHits = 0, pathQueries = 0, treeQueries = 0;
    double ratio() const { return pathQueries ? static_cast<double>(treeQueries) / static_cast<double>(pathQueries) : 0.0; }
};
RayQueryComparison compareRayQueries(const RayScene& lens, const Camera& camera, int width, int height,
                                     const LensPathSettings& settings);

// The Fresnel split at one interface (the composition rule of DESIGN.md without the local colour):
// coefficient of the reflected child, of the refracted child, and the refracted direction.
struct InterfaceSplit {
    float reflected = 0.0f;
    float refracted = 0.0f;
    glm::vec3 reflectDir{0.0f}, refractDir{0.0f};
    glm::vec3 sideNormal{0.0f};  // geometric normal on the incoming side
    bool entering = true;
};
InterfaceSplit splitAtInterface(const Scene& scene, const SurfaceHit& hit, glm::vec3 incoming);

}  // namespace hybridlab
