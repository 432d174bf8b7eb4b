#pragma once
// Vertex ray tracing and adaptive tessellation of a lens system (Hakura & Snyder 2001 §5): the two
// ray paths are traced at the lens mesh's vertices only; a triangle is subdivided where the paths
// at its vertices differ in topology or in outgoing direction by more than a few degrees, until
// its screen-projected edges are shorter than tau pixels; t-junctions are removed afterwards with
// the help of an edge hash table that also keeps a vertex from being traced twice.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "common/scene/camera.h"
#include "techniques/shared/lens_paths.h"
#include "techniques/shared/lens_system.h"

namespace hybridlab {

// The lens system's triangles in world space. Vertices with the same position and normal are
// welded, so a closed model is a closed mesh (UV seams, sphere poles).
struct LensMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;          // unit, interpolated vertex normals
    std::vector<std::uint32_t> materials;    // per vertex: into Scene::materials
    std::vector<glm::uvec3> triangles;
};
LensMesh buildLensMesh(const LensSystem& system, double time = 0.0);

struct TessellationSettings {
    float tauPixels = 3.0f;         // stop when every screen-projected edge is shorter (§5: 3 and 5)
    float maxAngleDegrees = 3.0f;   // outgoing directions further apart than this differ (§5)
    int maxLevels = 8;              // a bound on recursion (1-to-4 splits)
    LensPathSettings paths;
};

// A vertex of the tessellation with its two ray paths.
struct LensVertex {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f};
    std::uint32_t material = 0;
    bool traced = false;    // false for vertices whose triangles all face away
    bool visible = false;   // directly visible from the viewpoint (not hidden by the lens itself)
    TwoTermPaths paths;
};

struct TessellationStats {
    std::uint64_t tracedVertices = 0;
    std::uint64_t skippedVertices = 0;      // only on back-facing triangles: not traced
    std::uint64_t visibilityQueries = 0;
    std::uint64_t pathQueries = 0;
    std::uint64_t splits = 0;
    std::uint64_t tJunctionTriangles = 0;   // leaves re-triangulated to remove t-junctions
    double traceMilliseconds = 0.0;         // of the whole tessellation, the time spent tracing vertices
};

struct TessellatedLens {
    glm::vec3 viewpoint{0.0f};
    std::vector<LensVertex> vertices;
    std::vector<glm::uvec3> triangles;   // the final mesh, free of t-junctions
    std::vector<glm::uvec3> leaves;      // the adaptive triangles before t-junction removal
    std::vector<glm::uvec3> splits;      // every triangle that was subdivided
    TessellationStats stats;
};

// Paths differ in topology (existence, length, reflection/refraction at an interface) or in
// outgoing direction by more than maxAngleDegrees, in either term (§5).
bool pathsDiffer(const TwoTermPaths& a, const TwoTermPaths& b, float maxAngleDegrees);

// Pixel coordinates (x right, y down) of a world point for a width x height image.
glm::vec2 projectToPixels(const Camera& camera, int width, int height, glm::vec3 p);
// The same with the camera's projection times view for that image (viewProjection), made once.
glm::mat4 viewProjection(const Camera& camera, int width, int height);
glm::vec2 projectToPixels(const glm::mat4& viewProj, int width, int height, glm::vec3 p);

TessellatedLens tessellateLens(const LensSystem& system, const LensMesh& mesh, const Camera& camera, int width, int height,
                               const TessellationSettings& settings);

}  // namespace hybridlab
