#include "techniques/layered_em/lens_draw.h"

#include <algorithm>
#include <limits>

#include <glm/geometric.hpp>

#include "common/raytrace/shading.h"

namespace hybridlab {

LensDrawGeometry lensDrawGeometry(const TessellatedLens& lens, const std::vector<EmLayer>& layers, const Scene& scene,
                                  const Camera& camera, int width, int height, int emSize) {
    LensDrawGeometry g;
    g.positions.resize(lens.vertices.size());
    for (std::size_t i = 0; i < lens.vertices.size(); ++i) g.positions[i] = lens.vertices[i].position;
    // The back-face test of rasterizeLens, so that both draw the same triangles.
    for (const glm::uvec3& t : lens.triangles) {
        const glm::vec3 &p0 = g.positions[t[0]], &p1 = g.positions[t[1]], &p2 = g.positions[t[2]];
        if (glm::dot(glm::cross(p1 - p0, p2 - p0), lens.viewpoint - p0) > 0.0f) g.triangles.push_back(t);
    }
    const std::vector<glm::vec2> pixels = lensVertexPixels(lens, camera, width, height);
    for (int term = 0; term < kPathTerms; ++term) {
        const PathTerm pt = static_cast<PathTerm>(term);
        g.weights[term] = vertexPathWeights(lens, pt);
        g.skyWeights[term].assign(lens.vertices.size(), glm::vec3(0.0f));
        for (std::size_t i = 0; i < lens.vertices.size(); ++i) {
            const LensPath& p = lens.vertices[i].paths.terms[term];
            if (g.weights[term][i] != glm::vec3(0.0f)) g.skyWeights[term][i] = g.weights[term][i] * skyRadiance(scene, p.exitDirection);
        }
        const std::vector<ScreenEdge> edges = textureLodEdges(lens, pt, pixels);
        for (const EmLayer& layer : layers) g.indices[term].push_back(vertexTextureIndex(lens, pt, layer.shell, edges, emSize));
    }
    return g;
}

ViewpointBlend blendViewpoints(const LayeredEm& em, glm::vec3 eye, bool blend) {
    ViewpointBlend out;
    float da = std::numeric_limits<float>::infinity(), db = da;
    for (std::size_t v = 0; v < em.viewpoints.size(); ++v) {
        const float d = glm::length(em.viewpoints[v].camera.position - eye);
        if (d < da) {
            out.b = out.a;
            db = da;
            out.a = v;
            da = d;
        } else if (d < db) {
            out.b = v;
            db = d;
        }
    }
    if (!blend || em.viewpoints.size() < 2 || da + db <= 0.0f) return out;
    out.weightA = db / (da + db);
    out.weightB = da / (da + db);
    return out;
}

glm::vec3 compositeLensTerms(const std::array<std::vector<glm::vec4>, kPathTerms>& layerColors,
                             const std::array<glm::vec3, kPathTerms>& weights, const std::array<glm::vec3, kPathTerms>& skyWeights) {
    glm::vec3 sum(0.0f);
    for (int t = 0; t < kPathTerms; ++t) {
        glm::vec4 acc(0.0f);
        for (const glm::vec4& c : layerColors[t]) acc += (1.0f - acc.a) * c;
        sum += weights[t] * glm::vec3(acc) + (1.0f - acc.a) * skyWeights[t];
    }
    return sum;
}

std::vector<glm::vec4> drawLensOnCpu(const LensDrawGeometry& g, const LayeredEm& em, const ViewpointBlend& blend,
                                     const Camera& camera, int width, int height) {
    const LensRaster raster = rasterizeLens(g.positions, g.triangles, camera, width, height);
    std::vector<glm::vec4> out(raster.triangle.size(), glm::vec4(0.0f));
    const std::size_t layers = em.layers.size();
    for (std::size_t p = 0; p < out.size(); ++p) {
        if (!raster.covered(p)) continue;
        std::array<glm::vec3, kPathTerms> weights, sky;
        for (int t = 0; t < kPathTerms; ++t) {
            weights[t] = interpolateAtPixel(raster, p, g.triangles, g.weights[t]);
            sky[t] = interpolateAtPixel(raster, p, g.triangles, g.skyWeights[t]);
        }
        glm::vec3 c(0.0f);
        for (const auto& [viewpoint, w] : {std::pair(blend.a, blend.weightA), std::pair(blend.b, blend.weightB)}) {
            if (w <= 0.0f) continue;
            const EmViewpoint& v = em.viewpoints[viewpoint];
            std::array<std::vector<glm::vec4>, kPathTerms> colors;
            for (int t = 0; t < kPathTerms; ++t) {
                for (std::size_t l = 0; l < layers; ++l)
                    colors[t].push_back(v.maps[l].sample(pixelCubeMapLookup(raster, p, g.triangles, g.indices[t][l], v.maps[l].size)));
            }
            c += w * compositeLensTerms(colors, weights, sky);
        }
        out[p] = glm::vec4(c, 1.0f);
    }
    return out;
}

}  // namespace hybridlab
