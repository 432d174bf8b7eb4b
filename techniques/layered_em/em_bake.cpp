#include "techniques/layered_em/em_bake.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <unordered_set>

#include <glm/gtc/constants.hpp>

#include "common/core/wall_clock.h"
#include "common/raytrace/whitted_tracer.h"
#include "common/scene/surface_samples.h"
#include "techniques/layered_em/layer_clustering.h"
#include "techniques/layered_em/lens_raster.h"
#include "techniques/stage_clock.h"

namespace hybridlab {
namespace {

// Points over a layer's objects from which its round impostor's kind is chosen: enough for the
// radius spread to settle to a few parts in a thousand.
constexpr std::size_t kShellSurfaceSamples = 4096;
constexpr std::uint32_t kShellSurfaceSeed = 2001;

// Cells of side `cell` holding at least one point: "is there a lens record near this point".
class OccupancyGrid {
public:
    explicit OccupancyGrid(float cell) : cell_(cell) {}
    void add(glm::vec3 p) { cells_.insert(key(glm::floor(p / cell_))); }
    bool near(glm::vec3 p) const {
        const glm::vec3 c = glm::floor(p / cell_);
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    if (cells_.count(key(c + glm::vec3(dx, dy, dz)))) return true;
        return false;
    }

private:
    static std::uint64_t key(glm::vec3 c) {
        auto q = [](float v) { return static_cast<std::uint64_t>(static_cast<std::int64_t>(v) + (1 << 20)) & 0x1fffff; };
        return q(c.x) | (q(c.y) << 21) | (q(c.z) << 42);
    }
    float cell_;
    std::unordered_set<std::uint64_t> cells_;
};

// Per layer, the first record of each outgoing ray in that layer (records of one ray are
// contiguous and in order along it).
template <typename Visit>
void forFirstRecordPerLayer(const ViewpointRecords& recs, const std::vector<int>& objectLayer, Visit&& visit) {
    std::uint32_t currentRay = 0xffffffffu;
    std::uint64_t seen = 0;
    for (const OutgoingRecord& r : recs.records) {
        if (r.ray != currentRay) {
            currentRay = r.ray;
            seen = 0;
        }
        const int layer = objectLayer[r.object];
        if (layer < 0 || (seen >> layer) & 1u) continue;
        seen |= 1ull << layer;
        visit(r, layer);
    }
}

// A direct image of the environment as an observation of every layer (§4.3), with confidence 1
// where `keep(point, layer)` and 0 elsewhere. Where the pixel's ray meets the layer, the layer's
// first record at its point. Where the ray reached the sky without meeting the layer, the layer is
// empty along it (transparent black) at the point where the ray crosses the impostor: without it,
// only the "something here" half of an edge is observed, and the inference smears a layer's edge
// against the sky (the top of a wall) by the regulariser's reach.
template <typename Keep>
std::vector<EmObservation> directLayerObservations(const ViewpointRecords& direct, const Camera& camera, int width, int height,
                                                   const std::vector<EmLayer>& layers, const std::vector<int>& objectLayer, int size,
                                                   Keep&& keep) {
    const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    std::vector<std::vector<glm::vec4>> b(layers.size(), std::vector<glm::vec4>(pixels, glm::vec4(0.0f)));
    std::vector<std::vector<float>> confidence(layers.size(), std::vector<float>(pixels, 0.0f));
    std::vector<std::uint64_t> met(pixels, 0);  // per pixel: the layers its ray met
    forFirstRecordPerLayer(direct, objectLayer, [&](const OutgoingRecord& r, int layer) {
        met[r.pixel] |= 1ull << layer;
        if (!keep(r.position, layer)) return;
        b[static_cast<std::size_t>(layer)][r.pixel] = glm::vec4(r.radiance, 1.0f);
        confidence[static_cast<std::size_t>(layer)][r.pixel] = 1.0f;
    });
    for (std::size_t pixel = 0; pixel < pixels; ++pixel) {
        const std::size_t id = pixel * kPathTerms;  // one ray a pixel, term 0 (compileDirectRecords)
        if (!direct.rayExists[id] || !direct.rayEscaped[id]) continue;
        for (std::size_t l = 0; l < layers.size(); ++l) {
            if ((met[pixel] >> l) & 1u) continue;
            const OutgoingRay& ray = direct.rays[id];
            if (keep(shellPoint(layers[l].shell, ray.origin, ray.direction), static_cast<int>(l))) confidence[l][pixel] = 1.0f;
        }
    }
    std::vector<EmObservation> out;
    for (std::size_t l = 0; l < layers.size(); ++l) out.push_back(directObservation(camera, width, height, layers[l].shell, b[l], confidence[l], size));
    return out;
}

// A record as the layer clustering sees it, found along the outgoing ray `ray`.
ClusterSample clusterSampleOf(const OutgoingRecord& r, std::uint64_t ray) { return {r.distance, r.object, ray, r.order}; }

struct LayerSample {
    ClusterSample sample;
    glm::vec3 position;
    OutgoingRay ray;
};

Shell makeShell(glm::vec3 center, const std::vector<glm::vec3>& points, const std::vector<glm::vec3>& surface,
                const std::vector<OutgoingRay>& rays, double meanDistance) {
    Shell s;
    s.center = center;
    s.kind = chooseShellKind(center, points, surface);
    s.farDistance = static_cast<float>(1e3 * std::max(1.0, meanDistance));
    if (s.kind == ShellKind::Quad) return fitQuadShell(center, points, rays);
    if (s.kind == ShellKind::Cylinder) {
        double sum = 0.0;
        for (const glm::vec3& p : points) sum += std::hypot(p.x - center.x, p.z - center.z);
        s.radius = static_cast<float>(sum / static_cast<double>(points.size()));
        return s;
    }
    s.radius = static_cast<float>(meanDistance);
    return s;
}

// Per texel of the chain, whether the layer's impostor holds it (shellHolds at the level-0 texel
// centres, two texels' angle of margin for bilinear reads; a coarser texel when any texel below it
// does); empty for an impostor that holds every direction.
std::vector<bool> texelsTheShellHolds(const Shell& shell, int size) {
    if (shell.kind != ShellKind::Quad) return {};
    const std::vector<std::uint32_t> parents = cubeMapParents(size);
    std::vector<bool> holds(parents.size(), false);
    const float margin = 2.0f * glm::half_pi<float>() / static_cast<float>(size);
    const std::size_t level0 = cubeMapLevelOffset(size, 1);
    for (std::size_t t = 0; t < level0; ++t) holds[t] = shellHolds(shell, cubeMapTexelDirection(static_cast<std::uint32_t>(t), size), margin);
    for (std::size_t t = 0; t < holds.size(); ++t) {  // level after level: children before parents
        if (holds[t] && parents[t] != kNoParent) holds[parents[t]] = true;
    }
    return holds;
}

// Per texel of the chain, whether a row of `images` reads it (with positive confidence and weight).
std::vector<bool> texelsRead(const std::vector<EmObservation>& images, int size) {
    std::vector<bool> read(cubeMapTexelCount(size), false);
    for (const EmObservation& o : images) {
        for (std::size_t r = 0; r < o.lookups.size(); ++r) {
            if (o.confidence[r] <= 0.0f) continue;
            for (const CubeMapTap& t : o.lookups[r].taps) read[t.texel] = read[t.texel] || t.weight > 0.0f;
        }
    }
    return read;
}

// The rows of `fill` that read none of the `read` texels.
EmObservation rowsReadingNone(const EmObservation& fill, const std::vector<bool>& read) {
    EmObservation out;
    for (std::size_t r = 0; r < fill.lookups.size(); ++r) {
        const auto& taps = fill.lookups[r].taps;
        if (std::any_of(taps.begin(), taps.end(), [&](const CubeMapTap& t) { return t.weight > 0.0f && read[t.texel]; })) continue;
        out.lookups.push_back(fill.lookups[r]);
        out.targets.push_back(fill.targets[r]);
        out.confidence.push_back(fill.confidence[r]);
        out.pixels.push_back(fill.pixels[r]);
    }
    return out;
}

// Six 90-degree cameras at `center`, one looking through each cube-map face.
std::vector<Camera> cubeFaceCameras(glm::vec3 center) {
    std::vector<Camera> cameras;
    for (const glm::vec3 axis : {glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, -1, 0), glm::vec3(0, 0, 1),
                                 glm::vec3(0, 0, -1)}) {
        Camera c;
        c.position = center;
        c.fovYDegrees = 90.0f;
        c.orientation = Camera::lookAtOrientation(center, center + axis, axis.y != 0.0f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0));
        cameras.push_back(c);
    }
    return cameras;
}

// What every stage of one lens system's bake reads: the system, the full scene's rays for shading
// the records, the viewpoint samples, and the image sizes.
struct BakeInputs {
    BakeInputs(const Scene& s, const LensSystemInfo& i, const EmBakeSettings& b)
        : scene(s), info(i), settings(b), system(s, i), fullRays(s), shading(fullRays, WhittedSettings{}),
          cameras(viewpointSamples(s, system.center(), b.viewpoints)), views(static_cast<int>(cameras.size())) {}

    const Scene& scene;
    const LensSystemInfo& info;
    const EmBakeSettings& settings;
    LensSystem system;
    RayScene fullRays;
    WhittedTracer shading;
    std::vector<Camera> cameras;
    int views;
    int width() const { return settings.width; }
    int height() const { return settings.height; }
    int size() const { return settings.inference.size; }  // texels a cube-map face side
};

// The direct records of the six cube faces seen from the EM origin.
using OriginFaces = std::vector<std::pair<Camera, ViewpointRecords>>;

// §4.1 and §4.2: records at every viewpoint sample, to be clustered all at once. Rays are thinned
// by a fixed stride so that the sample count stays bounded.
std::vector<LayerSample> layerSamples(const BakeInputs& in, EmBakeStats& stats, const BakeProgress& progress) {
    const EmBakeSettings& settings = in.settings;
    const int n = settings.records.supersampling;
    const std::uint64_t expected = static_cast<std::uint64_t>(in.width()) * static_cast<std::uint64_t>(in.height()) *
                                   static_cast<std::uint64_t>(n * n) * kPathTerms * static_cast<std::uint64_t>(in.views) * 2u;
    const std::uint32_t stride = static_cast<std::uint32_t>(std::max<std::uint64_t>(1, expected / std::max<std::size_t>(1, settings.clusterSampleLimit)));
    std::vector<LayerSample> samples;
    for (int v = 0; v < in.views; ++v) {
        ViewpointRecords recs = compileOutgoingRecords(in.system, in.shading, in.cameras[v], in.width(), in.height(), settings.records);
        stats.records += recs.records.size();
        stats.lensQueries += recs.lensQueries;
        stats.environmentQueries += recs.environmentQueries;
        for (const OutgoingRecord& r : recs.records) {
            if ((r.ray / kPathTerms) % stride) continue;
            samples.push_back({clusterSampleOf(r, (static_cast<std::uint64_t>(v) << 32) | r.ray), r.position, recs.rays[r.ray]});
        }
        if (progress) progress("records", v + 1, in.views);
    }
    return samples;
}

LayerPartition clusterSamples(const BakeInputs& in, const std::vector<LayerSample>& samples) {
    std::vector<ClusterSample> clusterInput(samples.size());
    for (std::size_t i = 0; i < samples.size(); ++i) clusterInput[i] = samples[i].sample;
    const EmBakeSettings& settings = in.settings;
    return clusterLayers(clusterInput, in.scene.objects.size(), settings.layers, settings.maxLayers, settings.maxRelativeRms);
}

// Images of the environment from the EM origin, one a cube face at the maps' resolution, traced
// once. They are the direct images of a reflective system (§4.3). And, for every system, what no
// lens image of a window reads of a layer (the top of a column, seen only from above the samples'
// plane) is the environment as the origin sees it, not empty. What they see that no lens image
// met joins a layer first (in `partition`).
OriginFaces traceOriginFaces(const BakeInputs& in, LayerPartition& partition, EmBakeStats& stats) {
    OriginFaces faces;
    if (!in.settings.directImages) return faces;
    std::vector<ClusterSample> seen;
    for (const Camera& c : cubeFaceCameras(in.system.center())) {
        faces.emplace_back(c, compileDirectRecords(in.system, in.shading, c, in.size(), in.size(), in.settings.records));
        stats.environmentQueries += faces.back().second.environmentQueries;
        for (const OutgoingRecord& r : faces.back().second.records) seen.push_back(clusterSampleOf(r, r.ray));
    }
    assignObjectsOnlyDirectImagesSee(partition, seen);
    return faces;
}

// The layers: their objects, and the shell fitted to their frontmost samples and their objects' surfaces.
std::vector<EmLayer> layerShells(const BakeInputs& in, const std::vector<LayerSample>& samples, const LayerPartition& partition) {
    std::vector<EmLayer> layers;
    for (std::size_t l = 0; l < partition.shellRadius.size(); ++l) {
        std::vector<glm::vec3> points;
        std::vector<OutgoingRay> rays;
        for (std::size_t i = 0; i < samples.size(); ++i) {
            if (partition.sampleLayer[i] != static_cast<int>(l) || !partition.frontmost[i]) continue;
            points.push_back(samples[i].position);
            rays.push_back(samples[i].ray);
        }
        EmLayer layer;
        layer.meanDistance = partition.shellRadius[l];
        for (std::size_t o = 0; o < partition.objectLayer.size(); ++o) {
            if (partition.objectLayer[o] == static_cast<int>(l)) layer.objects.push_back(static_cast<std::uint32_t>(o));
        }
        const std::vector<glm::vec3> surface = sampleObjectSurfaces(in.scene, layer.objects, kShellSurfaceSamples, kShellSurfaceSeed);
        layer.shell = makeShell(in.system.center(), points, surface, rays, layer.meanDistance);
        layers.push_back(std::move(layer));
    }
    return layers;
}

// Per layer, the origin faces' direct images as observations (every point kept), when the bake uses them.
std::vector<std::vector<EmObservation>> originLayerImages(const BakeInputs& in, const OriginFaces& faces, const std::vector<EmLayer>& layers,
                                                          const std::vector<int>& objectLayer) {
    std::vector<std::vector<EmObservation>> images(layers.size());  // layer -> faces
    if (!in.settings.directImages || !in.settings.originImages) return images;
    for (const auto& [c, direct] : faces) {
        std::vector<EmObservation> face =
            directLayerObservations(direct, c, in.size(), in.size(), layers, objectLayer, in.size(), [](glm::vec3, int) { return true; });
        for (std::size_t l = 0; l < layers.size(); ++l) images[l].push_back(std::move(face[l]));
    }
    return images;
}

// §4.3 and §5: per viewpoint sample the tessellated lens, its raster and the layer images, as
// observations of every layer's cube map; computed on first use and kept while a window needs them.
class LayerObservations {
public:
    using PerLayer = std::vector<std::vector<EmObservation>>;  // layer -> images

    LayerObservations(const BakeInputs& in, const std::vector<EmLayer>& layers, const std::vector<int>& objectLayer,
                      const OriginFaces& originFaces, EmBakeStats& stats)
        : in_(in), layers_(layers), objectLayer_(objectLayer), originFaces_(originFaces), stats_(stats), mesh_(buildLensMesh(in.system)),
          directFromOrigin_(in.settings.directImages &&
                            directImageSourceFor(in.scene, in.info, in.settings.directImageSource) == DirectImageSource::Origin) {}

    const PerLayer& at(int v) {
        auto it = observations_.find(v);
        if (it != observations_.end()) return it->second;
        return observations_.emplace(v, observe(in_.cameras[static_cast<std::size_t>(v)])).first->second;
    }

    // Drops what no window after viewpoint v needs (a closed circle keeps the first ones).
    void dropBefore(int v) {
        const int reach = in_.settings.neighbourViewpoints;
        for (auto it = observations_.begin(); it != observations_.end();) {
            const bool wrapNeeded = in_.settings.viewpoints.closed() && it->first < reach;
            if (it->first < v - reach && !wrapNeeded) it = observations_.erase(it);
            else ++it;
        }
    }

    double tessellationMs = 0.0, imagesMs = 0.0;

private:
    PerLayer observe(const Camera& camera) {
        const int w = in_.width(), h = in_.height();
        auto t0 = WallClock::now();
        TessellatedLens lens = tessellateLens(in_.system, mesh_, camera, w, h, in_.settings.tessellation);
        std::vector<glm::vec3> positions(lens.vertices.size());
        for (std::size_t i = 0; i < positions.size(); ++i) positions[i] = lens.vertices[i].position;
        LensRaster raster = rasterizeLens(positions, lens.triangles, camera, w, h);
        stats_.tessellatedVertices += lens.vertices.size();
        stats_.tessellatedTriangles += lens.triangles.size();
        tessellationMs += millisecondsSince(t0);

        t0 = WallClock::now();
        std::vector<OccupancyGrid> lensPoints;
        PerLayer perLayer = lensImages(lens, raster, camera, lensPoints);
        if (in_.settings.directImages) addDirectImages(camera, lensPoints, perLayer);
        imagesMs += millisecondsSince(t0);
        return perLayer;
    }

    // The lens image of every layer and term, and (in lensPoints) where the lens records met each layer.
    PerLayer lensImages(const TessellatedLens& lens, const LensRaster& raster, const Camera& camera, std::vector<OccupancyGrid>& lensPoints) {
        const EmBakeSettings& settings = in_.settings;
        const int w = in_.width(), h = in_.height(), n = settings.records.supersampling, size = in_.size();
        const std::size_t layerCount = layers_.size();
        ViewpointRecords recs = compileOutgoingRecords(in_.system, in_.shading, camera, w, h, settings.records);
        PerLayer perLayer(layerCount);
        std::vector<LayerImageAccumulator> acc;
        for (std::size_t k = 0; k < layerCount * kPathTerms; ++k) acc.emplace_back(w, h, confidenceAngle(settings.records.confidenceAngleDegrees, h));
        const std::size_t raysPerPixel = static_cast<std::size_t>(n * n) * kPathTerms;
        for (std::size_t id = 0; id < recs.rayExists.size(); ++id) {
            if (!recs.rayExists[id]) continue;
            const int pixel = static_cast<int>(id / raysPerPixel), term = static_cast<int>(id % kPathTerms);
            for (std::size_t l = 0; l < layerCount; ++l) acc[l * kPathTerms + term].addRay(pixel % w, pixel / w, recs.rayDirection[id]);
        }
        for (std::size_t l = 0; l < layerCount; ++l) lensPoints.emplace_back(settings.directMissingDistance * static_cast<float>(layers_[l].meanDistance));
        forFirstRecordPerLayer(recs, objectLayer_, [&](const OutgoingRecord& r, int layer) {
            acc[static_cast<std::size_t>(layer) * kPathTerms + r.term].addColor(static_cast<int>(r.pixel) % w, static_cast<int>(r.pixel) / w, glm::vec4(r.radiance, 1.0f));
            lensPoints[static_cast<std::size_t>(layer)].add(r.position);
        });
        const std::vector<glm::vec2> pixels = lensVertexPixels(lens, camera, w, h);
        std::array<std::vector<ScreenEdge>, kPathTerms> edges;
        for (int term = 0; term < kPathTerms; ++term) edges[static_cast<std::size_t>(term)] = textureLodEdges(lens, static_cast<PathTerm>(term), pixels);
        for (std::size_t l = 0; l < layerCount; ++l) {
            for (int term = 0; term < kPathTerms; ++term) {
                std::vector<glm::vec4> b;
                std::vector<float> confidence;
                acc[l * kPathTerms + static_cast<std::size_t>(term)].finish(b, confidence);
                const LayerTextureIndex index =
                    vertexTextureIndex(lens, static_cast<PathTerm>(term), layers_[l].shell, edges[static_cast<std::size_t>(term)], size);
                perLayer[l].push_back(lensObservation(raster, lens.triangles, index, b, confidence, size));
            }
        }
        return perLayer;
    }

    // Direct images (§4.3), from the viewpoint or the EM origin: confidence 1 where the direct ray
    // meets a part of the layer no lens record came near, 0 elsewhere.
    void addDirectImages(const Camera& camera, const std::vector<OccupancyGrid>& lensPoints, PerLayer& perLayer) {
        auto addDirect = [&](const ViewpointRecords& direct, const Camera& from, int width, int height) {
            std::vector<EmObservation> image = directLayerObservations(direct, from, width, height, layers_, objectLayer_, in_.size(),
                                                                       [&](glm::vec3 point, int layer) {
                                                                           return !lensPoints[static_cast<std::size_t>(layer)].near(point);
                                                                       });
            for (std::size_t l = 0; l < layers_.size(); ++l) perLayer[l].push_back(std::move(image[l]));
        };
        if (directFromOrigin_) {
            for (const auto& [c, direct] : originFaces_) addDirect(direct, c, in_.size(), in_.size());
        } else {
            const ViewpointRecords direct = compileDirectRecords(in_.system, in_.shading, camera, in_.width(), in_.height(), in_.settings.records);
            stats_.environmentQueries += direct.environmentQueries;
            addDirect(direct, camera, in_.width(), in_.height());
        }
    }

    const BakeInputs& in_;
    const std::vector<EmLayer>& layers_;
    const std::vector<int>& objectLayer_;
    const OriginFaces& originFaces_;
    EmBakeStats& stats_;
    const LensMesh mesh_;
    const bool directFromOrigin_;
    std::map<int, PerLayer> observations_;  // viewpoint -> layer -> images
};

// The viewpoint samples whose observations viewpoint v's maps are inferred from: v and its
// neighbours (wrapping around a closed path), each once.
std::vector<int> windowAround(const EmBakeSettings& settings, int v, int views) {
    std::vector<int> window;
    for (int d = -settings.neighbourViewpoints; d <= settings.neighbourViewpoints; ++d) {
        int u = v + d;
        if (settings.viewpoints.closed()) u = ((u % views) + views) % views;
        if (u < 0 || u >= views || std::find(window.begin(), window.end(), u) != window.end()) continue;
        window.push_back(u);
    }
    return window;
}

// §4.3's inference of every layer's cube map at viewpoint v from its window's observations, and
// the origin's images where no row of the window reads.
EmViewpoint inferViewpoint(const BakeInputs& in, int v, LayerObservations& observations,
                           const std::vector<std::vector<EmObservation>>& originImages, const std::vector<std::vector<bool>>& layerHolds,
                           EmBakeStats& stats) {
    const std::vector<int> window = windowAround(in.settings, v, in.views);
    EmViewpoint out;
    out.camera = in.cameras[static_cast<std::size_t>(v)];
    const int size = in.size();
    for (std::size_t l = 0; l < layerHolds.size(); ++l) {
        std::vector<EmObservation> rows;
        for (int u : window) {
            const auto& obs = observations.at(u)[l];
            rows.insert(rows.end(), obs.begin(), obs.end());
        }
        if (!originImages[l].empty()) {
            const std::vector<bool> read = texelsRead(rows, size);
            for (const EmObservation& face : originImages[l]) rows.push_back(rowsReadingNone(face, read));
        }
        EmInferenceResult r = inferLayerEm(rows, in.settings.inference, layerHolds[l]);
        stats.inferenceRows += r.rows;
        stats.inferenceUnknowns += r.activeTexels;
        stats.maxIterations = std::max(stats.maxIterations, r.iterations);
        stats.maxRelativeResidual = std::max(stats.maxRelativeResidual, r.relativeResidual);
        out.unobservedTexels.push_back(cubeMapTexelCount(size) - r.observedTexels);
        out.maps.push_back(std::move(r.em));
    }
    return out;
}

}  // namespace

DirectImageSource directImageSourceNamed(const std::string& name) {
    if (name == "auto") return DirectImageSource::Automatic;
    if (name == "viewpoint") return DirectImageSource::Viewpoint;
    if (name == "origin") return DirectImageSource::Origin;
    throw std::invalid_argument("direct image source '" + name + "': expected auto, viewpoint or origin");
}

DirectImageSource directImageSourceFor(const Scene& scene, const LensSystemInfo& system, DirectImageSource requested) {
    if (requested != DirectImageSource::Automatic) return requested;
    for (std::uint32_t o : system.objects)
        if (scene.objectIsRefractive(o)) return DirectImageSource::Viewpoint;
    return DirectImageSource::Origin;
}

LayeredEm bakeLayeredEm(const Scene& scene, const LensSystemInfo& info, const EmBakeSettings& settings, EmBakeStats& stats,
                        const BakeProgress& progress) {
    StageClock clock(stats.stages);
    const BakeInputs in(scene, info, settings);
    clock.lap("setup");

    std::vector<LayerSample> samples = layerSamples(in, stats, progress);
    clock.lap("records");

    LayerPartition partition = clusterSamples(in, samples);
    const OriginFaces originFaces = traceOriginFaces(in, partition, stats);
    LayeredEm em;
    em.system = info.name;
    em.center = in.system.center();
    em.layers = layerShells(in, samples, partition);
    samples.clear();
    samples.shrink_to_fit();
    clock.lap("clustering");

    LayerObservations observations(in, em.layers, partition.objectLayer, originFaces, stats);  // builds the lens mesh
    clock.lap("tessellation");
    const std::vector<std::vector<EmObservation>> originImages = originLayerImages(in, originFaces, em.layers, partition.objectLayer);
    clock.lap("layer images");
    std::vector<std::vector<bool>> layerHolds;
    for (const EmLayer& layer : em.layers) layerHolds.push_back(texelsTheShellHolds(layer.shell, in.size()));
    for (int v = 0; v < in.views; ++v) {
        // The window's observations first: their time is the images', not the inference's.
        for (int u : windowAround(settings, v, in.views)) observations.at(u);
        em.viewpoints.push_back(inferViewpoint(in, v, observations, originImages, layerHolds, stats));
        observations.dropBefore(v);
        if (progress) progress("inference", v + 1, in.views);
    }
    // Every viewpoint's observations were timed inside; the rest is the inference.
    clock.lap({{"tessellation", observations.tessellationMs}, {"layer images", observations.imagesMs}}, "inference");
    return em;
}

}  // namespace hybridlab
