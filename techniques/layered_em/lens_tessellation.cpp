#include "techniques/layered_em/lens_tessellation.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include <glm/geometric.hpp>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>
#include <glm/mat4x4.hpp>

#include "common/core/wall_clock.h"
#include "common/raytrace/ray_task_context.h"
#include "common/scene/transform.h"

namespace hybridlab {
namespace {

std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) {
    if (a > b) std::swap(a, b);
    return (static_cast<std::uint64_t>(a) << 32) | b;
}

float angleDegrees(glm::vec3 a, glm::vec3 b) {
    return glm::degrees(std::acos(std::clamp(glm::dot(a, b), -1.0f, 1.0f)));
}

class Tessellator {
public:
    Tessellator(const LensSystem& system, const LensMesh& mesh, const Camera& camera, int width, int height,
                const TessellationSettings& settings)
        : system_(system), camera_(camera), viewProj_(viewProjection(camera, width, height)), width_(width), height_(height),
          settings_(settings) {
        out_.viewpoint = camera.position;
        for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
            LensVertex v;
            v.position = mesh.positions[i];
            v.normal = mesh.normals[i];
            v.material = mesh.materials[i];
            out_.vertices.push_back(v);
        }
        // §5: a pass through the faces marks the vertices of front-facing triangles "to be ray
        // traced"; the others are not.
        std::vector<bool> marked(mesh.positions.size(), false);
        for (const glm::uvec3& t : mesh.triangles) {
            if (!frontFacing(t)) continue;
            for (int k = 0; k < 3; ++k) marked[t[k]] = true;
        }
        // The mesh's own vertices are independent: traced in parallel (midpoints, during refinement,
        // one at a time).
        std::vector<std::uint32_t> toTrace;
        for (std::uint32_t i = 0; i < marked.size(); ++i) {
            if (marked[i]) toTrace.push_back(i);
            else ++out_.stats.skippedVertices;
        }
        const auto start = WallClock::now();
        tbb::combinable<TessellationStats> perThread;
        RayTaskContext context;
        tbb::parallel_for(std::size_t{0}, toTrace.size(), [&](std::size_t k) { traceVertex(out_.vertices[toTrace[k]], perThread.local()); }, context);
        perThread.combine_each([&](const TessellationStats& t) {
            out_.stats.tracedVertices += t.tracedVertices;
            out_.stats.visibilityQueries += t.visibilityQueries;
            out_.stats.pathQueries += t.pathQueries;
        });
        out_.stats.traceMilliseconds += millisecondsSince(start);
        for (const glm::uvec3& t : mesh.triangles) refine(t[0], t[1], t[2], 0);
        removeTJunctions();
    }

    TessellatedLens result() { return std::move(out_); }

private:
    bool frontFacing(const glm::uvec3& t) const {
        const glm::vec3& a = out_.vertices[t[0]].position;
        glm::vec3 n = glm::cross(out_.vertices[t[1]].position - a, out_.vertices[t[2]].position - a);
        return glm::dot(n, camera_.position - a) > 0.0f;
    }

    // Visibility from the viewpoint and the two paths through the vertex (its first interface is
    // the vertex itself, with its interpolated normal turned to face the viewer if it does not).
    void trace(std::uint32_t i) {
        if (out_.vertices[i].traced) return;
        const auto start = WallClock::now();
        traceVertex(out_.vertices[i], out_.stats);
        out_.stats.traceMilliseconds += millisecondsSince(start);
    }
    void traceVertex(LensVertex& v, TessellationStats& stats) const {
        v.traced = true;
        ++stats.tracedVertices;
        const glm::vec3 toVertex = v.position - camera_.position;
        const float dist = glm::length(toVertex);
        const glm::vec3 incoming = toVertex / dist;
        SurfaceHit blocker;
        ++stats.visibilityQueries;
        v.visible = !system_.lensRays().intersect(Ray{camera_.position, incoming}, 0.0f, dist * (1.0f - 1e-4f), blocker);
        glm::vec3 n = v.normal;
        const float facing = glm::dot(n, incoming);
        if (facing >= 0.0f) n = glm::normalize(n - (facing + 1e-3f) * incoming);
        SurfaceHit first;
        first.position = v.position;
        first.geometricNormal = n;
        first.shadingNormal = n;
        first.material = &system_.lensRays().scene().materials[v.material];
        LensRayCounter counter;
        v.paths = traceTwoTermPaths(system_.lensRays(), first, incoming, settings_.paths, counter);
        stats.pathQueries += counter.queries;
    }

    std::uint32_t midpoint(std::uint32_t a, std::uint32_t b) {
        auto [it, added] = midpoints_.emplace(edgeKey(a, b), 0u);
        if (!added) return it->second;  // computed from a neighbour: no second ray query
        LensVertex m;
        const LensVertex &va = out_.vertices[a], &vb = out_.vertices[b];
        m.position = 0.5f * (va.position + vb.position);
        glm::vec3 n = va.normal + vb.normal;
        m.normal = glm::length(n) > 1e-12f ? glm::normalize(n) : va.normal;
        m.material = va.material;
        it->second = static_cast<std::uint32_t>(out_.vertices.size());
        out_.vertices.push_back(m);
        trace(it->second);
        return it->second;
    }

    bool edgeLong(std::uint32_t a, std::uint32_t b) const {
        glm::vec2 pa = projectToPixels(viewProj_, width_, height_, out_.vertices[a].position);
        glm::vec2 pb = projectToPixels(viewProj_, width_, height_, out_.vertices[b].position);
        return glm::length(pa - pb) >= settings_.tauPixels;
    }

    bool differ(std::uint32_t a, std::uint32_t b) const {
        return pathsDiffer(out_.vertices[a].paths, out_.vertices[b].paths, settings_.maxAngleDegrees);
    }

    void refine(std::uint32_t a, std::uint32_t b, std::uint32_t c, int level) {
        const glm::uvec3 t(a, b, c);
        auto leaf = [&] { out_.leaves.push_back(t); };
        if (!frontFacing(t)) return leaf();
        const auto& v = out_.vertices;
        // Hidden by the lens itself at all three vertices: not subdivided further (its vertices are
        // still traced, in case part of its interior shows).
        if (!v[a].visible && !v[b].visible && !v[c].visible) return leaf();
        if (level >= settings_.maxLevels) return leaf();
        if (!differ(a, b) && !differ(b, c) && !differ(c, a)) return leaf();
        const bool lab = edgeLong(a, b), lbc = edgeLong(b, c), lca = edgeLong(c, a);
        const int longEdges = lab + lbc + lca;
        if (longEdges == 0) return leaf();
        out_.splits.push_back(t);
        ++out_.stats.splits;
        if (longEdges == 3) {  // 1-to-4
            std::uint32_t mab = midpoint(a, b), mbc = midpoint(b, c), mca = midpoint(c, a);
            refine(a, mab, mca, level + 1);
            refine(mab, b, mbc, level + 1);
            refine(mca, mbc, c, level + 1);
            refine(mab, mbc, mca, level + 1);
            return;
        }
        // Rotate so that the split edges come first: (a, b) always, (b, c) too for 1-to-3.
        std::uint32_t p = a, q = b, r = c;
        if (longEdges == 1) {
            if (lbc) std::tie(p, q, r) = std::tuple(b, c, a);
            else if (lca) std::tie(p, q, r) = std::tuple(c, a, b);
            std::uint32_t m = midpoint(p, q);  // 1-to-2
            refine(p, m, r, level + 1);
            refine(m, q, r, level + 1);
            return;
        }
        if (!lab) std::tie(p, q, r) = std::tuple(b, c, a);       // long: bc, ca
        else if (!lbc) std::tie(p, q, r) = std::tuple(c, a, b);  // long: ca, ab
        std::uint32_t mpq = midpoint(p, q), mqr = midpoint(q, r);  // 1-to-3
        refine(mpq, q, mqr, level + 1);
        refine(p, mpq, mqr, level + 1);
        refine(p, mqr, r, level + 1);
    }

    // All vertices strictly inside edge (a, b), in order from a: recursive queries of the hash.
    void edgeInterior(std::uint32_t a, std::uint32_t b, std::vector<std::uint32_t>& out) const {
        auto it = midpoints_.find(edgeKey(a, b));
        if (it == midpoints_.end()) return;
        edgeInterior(a, it->second, out);
        out.push_back(it->second);
        edgeInterior(it->second, b, out);
    }

    // §5, Figure 6c: each leaf with vertices inside its edges becomes a convex polygon of all its
    // boundary vertices, triangulated by clipping ears that have area (corners and the vertices
    // next to a clipped corner), which never makes a sliver of collinear points.
    void removeTJunctions() {
        for (const glm::uvec3& t : out_.leaves) {
            std::vector<std::uint32_t> poly;
            for (int k = 0; k < 3; ++k) {
                poly.push_back(t[k]);
                edgeInterior(t[k], t[(k + 1) % 3], poly);
            }
            if (poly.size() == 3) {
                out_.triangles.push_back(t);
                continue;
            }
            ++out_.stats.tJunctionTriangles;
            const glm::vec3 normal = glm::cross(out_.vertices[t[1]].position - out_.vertices[t[0]].position,
                                                out_.vertices[t[2]].position - out_.vertices[t[0]].position);
            const float minArea = 1e-6f * glm::length(normal);
            while (poly.size() > 3) {
                std::size_t best = 0;
                float bestArea = -1.0f;
                for (std::size_t i = 0; i < poly.size(); ++i) {
                    const glm::vec3& p0 = out_.vertices[poly[(i + poly.size() - 1) % poly.size()]].position;
                    const glm::vec3& p1 = out_.vertices[poly[i]].position;
                    const glm::vec3& p2 = out_.vertices[poly[(i + 1) % poly.size()]].position;
                    float area = glm::dot(glm::cross(p1 - p0, p2 - p0), normal) / glm::length(normal);
                    if (area > minArea && area > bestArea) {
                        bestArea = area;
                        best = i;
                    }
                }
                const std::size_t n = poly.size();
                out_.triangles.emplace_back(poly[(best + n - 1) % n], poly[best], poly[(best + 1) % n]);
                poly.erase(poly.begin() + static_cast<std::ptrdiff_t>(best));
            }
            out_.triangles.emplace_back(poly[0], poly[1], poly[2]);
        }
    }

    const LensSystem& system_;
    const Camera& camera_;
    glm::mat4 viewProj_;
    int width_, height_;
    TessellationSettings settings_;
    TessellatedLens out_;
    std::unordered_map<std::uint64_t, std::uint32_t> midpoints_;  // the edge hash table
};

}  // namespace

LensMesh buildLensMesh(const LensSystem& system, double time) {
    const Scene& scene = system.lensRays().scene();
    LensMesh out;
    std::map<std::tuple<float, float, float, float, float, float, std::uint32_t>, std::uint32_t> weld;
    for (const SceneObject& o : scene.objects) {
        const glm::mat4 toWorld = o.worldMatrix(time);
        const glm::mat3 nm = normalMatrix(toWorld);
        for (std::uint32_t meshIndex : o.meshes) {
            const Mesh& mesh = scene.meshes[meshIndex];
            std::vector<std::uint32_t> index(mesh.positions.size());
            for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
                glm::vec3 p = glm::vec3(toWorld * glm::vec4(mesh.positions[i], 1.0f));
                glm::vec3 n = glm::normalize(nm * mesh.normals[i]);
                auto [it, added] = weld.emplace(std::tuple(p.x, p.y, p.z, n.x, n.y, n.z, mesh.material),
                                                static_cast<std::uint32_t>(out.positions.size()));
                if (added) {
                    out.positions.push_back(p);
                    out.normals.push_back(n);
                    out.materials.push_back(mesh.material);
                }
                index[i] = it->second;
            }
            for (const glm::uvec3& t : mesh.triangles) {
                glm::uvec3 w(index[t[0]], index[t[1]], index[t[2]]);
                if (w[0] != w[1] && w[1] != w[2] && w[2] != w[0]) out.triangles.push_back(w);
            }
        }
    }
    return out;
}

bool pathsDiffer(const TwoTermPaths& a, const TwoTermPaths& b, float maxAngleDegrees) {
    for (int term = 0; term < kPathTerms; ++term) {
        const LensPath &p = a.terms[term], &q = b.terms[term];
        if (!p.sameTopology(q)) return true;
        if (p.exists && angleDegrees(p.exitDirection, q.exitDirection) > maxAngleDegrees) return true;
    }
    return false;
}

glm::vec2 projectToPixels(const Camera& camera, int width, int height, glm::vec3 p) {
    return projectToPixels(viewProjection(camera, width, height), width, height, p);
}

glm::mat4 viewProjection(const Camera& camera, int width, int height) {
    return camera.projectionMatrix(static_cast<float>(width) / static_cast<float>(height)) * camera.view();
}

glm::vec2 projectToPixels(const glm::mat4& viewProj, int width, int height, glm::vec3 p) {
    glm::vec4 clip = viewProj * glm::vec4(p, 1.0f);
    glm::vec2 ndc = glm::vec2(clip) / clip.w;
    return {(ndc.x * 0.5f + 0.5f) * static_cast<float>(width), (ndc.y * 0.5f + 0.5f) * static_cast<float>(height)};
}

TessellatedLens tessellateLens(const LensSystem& system, const LensMesh& mesh, const Camera& camera, int width, int height,
                               const TessellationSettings& settings) {
    Tessellator t(system, mesh, camera, width, height, settings);
    return t.result();
}

}  // namespace hybridlab
