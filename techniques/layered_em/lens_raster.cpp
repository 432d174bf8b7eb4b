#include "techniques/layered_em/lens_raster.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

namespace hybridlab {
namespace {

// Top-left rule for y-down screens with clockwise-positive area: an edge owns the pixels exactly
// on it when it is a top edge (horizontal, the triangle below it) or a left edge.
bool topLeft(glm::vec2 a, glm::vec2 b, float area) {
    glm::vec2 e = b - a;
    if (area < 0.0f) e = -e;
    return (e.y == 0.0f && e.x > 0.0f) || e.y < 0.0f;
}

}  // namespace

LensRaster rasterizeLens(const std::vector<glm::vec3>& positions, const std::vector<glm::uvec3>& triangles,
                         const Camera& camera, int width, int height) {
    LensRaster r;
    r.width = width;
    r.height = height;
    const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    r.triangle.assign(n, -1);
    r.barycentric.assign(n, glm::vec3(0.0f));
    std::vector<float> nearest(n, 0.0f);  // interpolated 1 / w: larger is nearer
    const glm::mat4 viewProj = viewProjection(camera, width, height);
    for (std::size_t ti = 0; ti < triangles.size(); ++ti) {
        const glm::uvec3& t = triangles[ti];
        const glm::vec3 &p0 = positions[t[0]], &p1 = positions[t[1]], &p2 = positions[t[2]];
        if (glm::dot(glm::cross(p1 - p0, p2 - p0), camera.position - p0) <= 0.0f) continue;  // back face
        glm::vec2 s[3];
        float invW[3];
        bool behind = false;
        for (int k = 0; k < 3; ++k) {
            glm::vec4 c = viewProj * glm::vec4(positions[t[k]], 1.0f);
            if (c.w <= camera.nearPlane * 0.5f) behind = true;
            invW[k] = 1.0f / c.w;
            s[k] = {(c.x * invW[k] * 0.5f + 0.5f) * static_cast<float>(width), (c.y * invW[k] * 0.5f + 0.5f) * static_cast<float>(height)};
        }
        if (behind) continue;
        const float area = (s[1].x - s[0].x) * (s[2].y - s[0].y) - (s[1].y - s[0].y) * (s[2].x - s[0].x);
        if (area == 0.0f) continue;
        const int x0 = std::max(0, static_cast<int>(std::floor(std::min({s[0].x, s[1].x, s[2].x}))));
        const int x1 = std::min(width - 1, static_cast<int>(std::ceil(std::max({s[0].x, s[1].x, s[2].x}))));
        const int y0 = std::max(0, static_cast<int>(std::floor(std::min({s[0].y, s[1].y, s[2].y}))));
        const int y1 = std::min(height - 1, static_cast<int>(std::ceil(std::max({s[0].y, s[1].y, s[2].y}))));
        const bool owns[3] = {topLeft(s[1], s[2], area), topLeft(s[2], s[0], area), topLeft(s[0], s[1], area)};
        for (int y = y0; y <= y1; ++y) {
            for (int x = x0; x <= x1; ++x) {
                const glm::vec2 p(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
                float l[3];
                bool inside = true;
                for (int k = 0; k < 3; ++k) {
                    const glm::vec2 &a = s[(k + 1) % 3], &b = s[(k + 2) % 3];
                    l[k] = ((b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x)) / area;
                    if (l[k] < 0.0f || (l[k] == 0.0f && !owns[k])) inside = false;
                }
                if (!inside) continue;
                const float w = l[0] * invW[0] + l[1] * invW[1] + l[2] * invW[2];
                const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
                if (r.triangle[i] >= 0 && w <= nearest[i]) continue;
                nearest[i] = w;
                r.triangle[i] = static_cast<std::int32_t>(ti);
                r.barycentric[i] = glm::vec3(l[0] * invW[0], l[1] * invW[1], l[2] * invW[2]) / w;
            }
        }
    }
    return r;
}

std::vector<glm::vec3> vertexTextureDirections(const TessellatedLens& lens, PathTerm term, const Shell& shell) {
    std::vector<glm::vec3> out(lens.vertices.size());
    for (std::size_t i = 0; i < lens.vertices.size(); ++i) {
        const LensVertex& v = lens.vertices[i];
        const LensPath& p = v.paths.terms[static_cast<int>(term)];
        out[i] = v.traced && p.exists ? shellTextureDirection(shell, p.exitOrigin, p.exitDirection) : v.normal;
    }
    return out;
}

std::vector<glm::vec3> vertexPathWeights(const TessellatedLens& lens, PathTerm term) {
    std::vector<glm::vec3> out(lens.vertices.size(), glm::vec3(0.0f));
    for (std::size_t i = 0; i < lens.vertices.size(); ++i) {
        const LensPath& p = lens.vertices[i].paths.terms[static_cast<int>(term)];
        if (lens.vertices[i].traced && p.exists) out[i] = p.weight();
    }
    return out;
}

std::vector<glm::vec2> lensVertexPixels(const TessellatedLens& lens, const Camera& camera, int width, int height) {
    const glm::mat4 viewProj = viewProjection(camera, width, height);
    std::vector<glm::vec2> pixels(lens.vertices.size());
    for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = projectToPixels(viewProj, width, height, lens.vertices[i].position);
    return pixels;
}

std::vector<ScreenEdge> textureLodEdges(const TessellatedLens& lens, PathTerm term, const std::vector<glm::vec2>& pixels) {
    auto path = [&](std::uint32_t i) -> const LensPath* {
        const LensVertex& v = lens.vertices[i];
        const LensPath& p = v.paths.terms[static_cast<int>(term)];
        return v.traced && p.exists ? &p : nullptr;
    };
    std::vector<ScreenEdge> edges;
    edges.reserve(3 * lens.triangles.size());
    for (const glm::uvec3& t : lens.triangles) {
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = t[k], b = t[(k + 1) % 3];
            const LensPath *pa = path(a), *pb = path(b);
            if (!pa || !pb || !pa->sameTopology(*pb)) continue;
            const float length = glm::length(pixels[a] - pixels[b]);
            if (length > 1e-3f) edges.push_back({a, b, length});
        }
    }
    return edges;
}

std::vector<float> vertexTextureLods(const std::vector<glm::vec3>& directions, const std::vector<ScreenEdge>& edges, int size) {
    std::vector<glm::vec3> unit(directions.size());
    for (std::size_t i = 0; i < unit.size(); ++i) unit[i] = glm::normalize(directions[i]);
    std::vector<float> rate(directions.size(), 0.0f);  // radians per pixel
    for (const ScreenEdge& e : edges) {
        const float r = std::acos(std::clamp(glm::dot(unit[e.a], unit[e.b]), -1.0f, 1.0f)) / e.pixels;
        rate[e.a] = std::max(rate[e.a], r);
        rate[e.b] = std::max(rate[e.b], r);
    }
    std::vector<float> lods(rate.size());
    for (std::size_t i = 0; i < lods.size(); ++i) lods[i] = cubeMapLod(rate[i], size);
    return lods;
}

LayerTextureIndex vertexTextureIndex(const TessellatedLens& lens, PathTerm term, const Shell& shell, const std::vector<ScreenEdge>& edges,
                                     int size) {
    LayerTextureIndex index;
    index.directions = vertexTextureDirections(lens, term, shell);
    index.lods = vertexTextureLods(index.directions, edges, size);
    return index;
}

CubeMapLookup pixelCubeMapLookup(const LensRaster& raster, std::size_t pixel, const std::vector<glm::uvec3>& triangles,
                                 const LayerTextureIndex& index, int size) {
    return cubeMapLookup(interpolateAtPixel(raster, pixel, triangles, index.directions), size,
                         interpolateAtPixel(raster, pixel, triangles, index.lods));
}

}  // namespace hybridlab
