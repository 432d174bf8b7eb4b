#pragma once
// The Embree 3 scene of a Scene (DESIGN.md "A frame, as data"). Static geometry lives in one BVH
// in world space; each dynamic object is an instance of its own object-space BVH, so a new frame
// re-commits only the top level. A deforming object's BVH is refitted each frame, not rebuilt
// (RTC_BUILD_QUALITY_REFIT on its geometry, in a two-level RTC_BUILD_QUALITY_LOW scene): the
// deformation moves vertices but keeps the topology, and a refit costs a pass over the nodes
// where a rebuild sorts the triangles again (de Macedo & Rodrigues' Table II times this update).
// Geometry and instance ids map back to objects and meshes.
#include <functional>
#include <limits>
#include <memory>
#include <vector>

#include <embree3/rtcore.h>

#include "common/image/mip_chain.h"
#include "common/raytrace/embree_call_clock.h"
#include "common/raytrace/ray_log.h"
#include "common/raytrace/shading.h"
#include "common/scene/camera.h"
#include "common/scene/deformed_mesh_cache.h"
#include "common/scene/scene.h"

namespace hybridlab {

// A ray-surface intersection, resolved to the scene.
struct SurfaceHit {
    float t = 0.0f;
    glm::vec3 position;         // world space, interpolated from the triangle's vertices
    glm::vec3 geometricNormal;  // world space, unit, by the triangle's winding
    glm::vec3 shadingNormal;    // world space, unit: interpolated vertex normal, normal-mapped
    glm::vec2 uv{0.0f};
    // The triangle's 0.5 log2(uv area / world area) (ray cones' Delta_0, ray_cone.h); -inf without uvs.
    float uvDensityLod = -std::numeric_limits<float>::infinity();
    std::uint32_t object = 0;
    std::uint32_t mesh = 0;     // index into Scene::meshes
    std::uint32_t primitive = 0;
    const Material* material = nullptr;
};

// A shadow ray's running state while Embree traces it: its transmittance, which the occlusion
// filter of transparent geometry multiplies.
struct ShadowLane {
    glm::vec3 transmittance;
    // Beer-Lambert absorption (medium_stack.h): the ray's length, and the optical depth that the
    // absorbing surfaces it crosses add (entering ones +a (tmax - t), leaving ones -a (tmax - t);
    // towards a light at infinity -a t and +a t).
    float tmax;
    glm::vec3 opticalDepth;
    // Surfaces already counted, so that a ray through an edge shared by two triangles (which a
    // watertight intersector reports twice) is attenuated once.
    static constexpr int kMaxCrossings = 16;
    int crossings;
    unsigned geometry[kMaxCrossings];
    unsigned instance[kMaxCrossings];
    float distance[kMaxCrossings];

    // Before a ray of length `rayTmax` is traced (the crossings' records are written before they are read).
    void start(float rayTmax) {
        transmittance = glm::vec3(1.0f);
        tmax = rayTmax;
        opticalDepth = glm::vec3(0.0f);
        crossings = 0;
    }
};

// Embree's intersection context extended with the shadow rays' states; shadow rays must be traced
// with it, since the occlusion filter of transparent geometry writes to them. A ray's id is its
// lane: 0 for a single ray, k for lane k of a packet.
struct ShadowRayContext {
    RTCIntersectContext base;  // first: Embree hands the filter a pointer to it
    ShadowLane* lanes;

    explicit ShadowRayContext(ShadowLane* states) : lanes(states) { rtcInitIntersectContext(&base); }
};

// A shadow ray: from `origin` along unit `direction` up to `tmax`, starting in media of absorption
// `startAbsorption` (RayScene::transmittance).
struct ShadowQuery {
    glm::vec3 origin;
    glm::vec3 direction;
    float tmax;
    glm::vec3 startAbsorption{0.0f};
};

class RayScene {
public:
    // Deformed vertices come from `deformedMeshes` when given (shared with the rasterizer, see
    // deformed_mesh_cache.h; it must outlive this), else from a cache of its own.
    explicit RayScene(const Scene& scene, double time = 0.0, DeformedMeshCache* deformedMeshes = nullptr);
    ~RayScene();
    RayScene(const RayScene&) = delete;
    RayScene& operator=(const RayScene&) = delete;

    const Scene& scene() const { return scene_; }

    // Moves animated objects to `time`, deforms and refits deforming ones (their vertices from the
    // DeformedMeshCache, which the rasterizer can share), and re-commits the top level (a no-op for static scenes). Also at
    // an unchanged time: every frame of an animation pays its update, and so do the repeats that
    // time one frame.
    void setTime(double time);
    double time() const { return time_; }

    // Closest hit along the ray within (tmin, tmax); false when it misses.
    bool intersect(const Ray& ray, float tmin, float tmax, SurfaceHit& hit) const;

    // intersect() for up to kCoherentRays rays that leave one point in nearly one direction (a
    // block of camera rays), from tmin 0 to infinity: one Embree packet with the coherent flag,
    // whose frustum traversal casts sponza-spheres' primary rays in half the time of one ray at a
    // time. The same hits, except where a ray meets an edge shared by two triangles at exactly
    // the same distance: the traversal order then picks which (10 of 921600 primary rays there).
    // found[k] is false where rays[k] missed.
    static constexpr int kCoherentRays = 8;
    void intersectCoherent(const Ray* rays, int count, SurfaceHit* hits, bool* found) const;
    // The Embree call under intersectCoherent, for benchmarks that time Embree alone: rays[0, count)
    // into `packet` (idle lanes masked off), traced in `scene`.
    static void traceCoherentPacket(RTCScene scene, const Ray* rays, int count, RTCRayHit8& packet);

    // Shadow ray: the transmittance from `origin` along unit `dir` up to `tmax`. Opaque shadow
    // casters stop it (0); transparent ones multiply it by their occluderTransmittance (the any-hit
    // rule of Walewski 2019 Listing 8b); materials that cast no shadow are ignored. Absorbing media
    // attenuate the part of the ray inside them (medium_stack.h), `startAbsorption` being that of
    // the media around `origin`. The vectors by reference: by value, GCC spills a vec3's two
    // registers apart and reloads (y, z) as one 8-byte load across both stores, a failed
    // store-to-load forwarding that cost half of this function's time.
    glm::vec3 transmittance(const glm::vec3& origin, const glm::vec3& dir, float tmax,
                            const glm::vec3& startAbsorption = glm::vec3(0.0f)) const;

    // transmittance() for up to kCoherentRays shadow rays towards one light from nearby points (a
    // block of pixels' first hits): one Embree packet with the coherent flag, which traces
    // sponza-spheres' first-hit shadow rays in 0.35-0.4 of their time one at a time. The same
    // values, except where a ray crosses several transparent surfaces: the packet may meet them in
    // another order, and their product may round differently in the last bit.
    void transmittanceCoherent(const ShadowQuery* rays, int count, glm::vec3* transmittances) const;
    // The Embree call under transmittanceCoherent, for benchmarks that time Embree alone: rays[0,
    // count) into `packet` (idle lanes masked off), traced in `scene` with `context`, whose lanes
    // it starts (ShadowLane::start; a lane's tfar is -inf where it was stopped: an opaque caster, or its light used up).
    static void traceShadowPacket(RTCScene scene, const ShadowQuery* rays, int count, ShadowRayContext& context, RTCRay8& packet);

    // For benchmarks that trace the same rays with bare rtcIntersect1 / rtcOccluded1: the
    // top-level scene, and a log that records every ray traced while it is set (null: off).
    RTCScene embreeScene() const { return top_; }
    void setRayLog(RayLog* log) { log_ = log; }
    // Times every Embree call while set (null: off); embree_call_clock.h.
    void setCallClock(EmbreeCallClock* clock) { callClock_ = clock; }

    // Texture `index`'s mip chain (the reference's filtered lookups), null for kNoTexture.
    const MipChain* textureMips(std::int32_t index) const {
        return index == kNoTexture ? nullptr : &textureMips_[static_cast<std::size_t>(index)];
    }
    // A material's diffuse texture (shading.h): made once for the scene's materials, on the spot for
    // a copy of one (a G-buffer texel's).
    DiffuseTexture diffuseTexture(const Material& material) const {
        if (material.diffuseTexture == kNoTexture) return {};
        const Material* first = scene_.materials.data();
        if (std::less_equal<>{}(first, &material) && std::less<>{}(&material, first + scene_.materials.size()))
            return diffuseTextures_[static_cast<std::size_t>(&material - first)];
        return makeDiffuseTexture(material, textureMips(material.diffuseTexture));
    }

    double buildMilliseconds() const { return buildMs_; }
    double lastUpdateMilliseconds() const { return updateMs_; }
    // Triangles that a frame update touches: of rigidly moving instances (the top level moves
    // them) and of deforming objects (their BVHs are refitted).
    std::size_t rigidMovingTriangles() const { return rigidMovingTriangles_; }
    std::size_t deformingTriangles() const { return deformingTriangles_; }
    std::size_t triangleCount() const { return triangles_; }  // every object's

private:
    void resolveHit(const RTCRayHit& rh, SurfaceHit& hit) const;
    // `positions` are the mesh's (or its deformed ones), placed by `toWorld` when given.
    RTCGeometry makeTriangleGeometry(const Mesh& mesh, const std::vector<glm::vec3>& positions, const glm::mat4* toWorld, bool refit);
    // Writes the deformed vertices of `object` at `time` into its geometries (commit the object's scene after).
    void deformObject(std::size_t object, double time);

    const Scene& scene_;
    RTCDevice device_ = nullptr;
    RTCScene top_ = nullptr;
    RTCScene static_ = nullptr;  // == top_ when nothing is animated
    std::vector<RTCScene> objectScenes_;               // per object: its instanced BVH, or null
    std::vector<std::uint32_t> instanceObject_;        // by instance geomID in top_
    std::vector<std::uint32_t> instanceGeometry_;      // per object: its instance geomID in top_
    std::vector<glm::mat4> toWorld_;                   // per object, at time_
    std::vector<glm::mat3> normalToWorld_;             // per object, at time_
    // A static mesh's triangle as resolving a hit reads it: its vertices' positions and
    // (unnormalised) normals already in world space and its uvs, together in two cache lines (not
    // an index and three vertices in each of three arrays, which Embree's traversal has left cold),
    // and what depends on the triangle alone computed once.
    struct alignas(64) StaticTriangle {
        glm::vec3 position[3];
        glm::vec3 normal[3];
        glm::vec2 uv[3];
        glm::vec3 geometricNormal;
        float uvDensityLod;
        glm::uvec3 vertices;  // indices (tangents)
    };
    // A geometry of static_: its object and mesh, and its triangles' records, so that resolving a
    // hit reaches the record in one dependent load from the geometry id. Per geometry, not per
    // mesh: two static objects sharing a mesh have triangles in two places.
    struct GeometryRef {
        std::uint32_t object;
        std::uint32_t mesh;
        const Material* material;  // the mesh's: a hit needs no load of the Mesh itself
        bool hasUvs;
        std::vector<StaticTriangle> triangles;
    };
    std::vector<GeometryRef> staticGeometry_;          // by geomID in static_
    // A static mesh's triangles placed in the world by its object's matrices.
    static std::vector<StaticTriangle> worldTriangles(const Mesh& mesh, const glm::mat4& toWorld, const glm::mat3& normalToWorld);
    std::unique_ptr<DeformedMeshCache> ownDeformedMeshes_;  // when none is shared
    DeformedMeshCache* deformedMeshes_ = nullptr;
    std::vector<DeformedVertices> deformed_;           // by mesh: vertices at time_ (deforming objects only)
    std::size_t rigidMovingTriangles_ = 0, deformingTriangles_ = 0, triangles_ = 0;
    std::vector<MipChain> textureMips_;                // per scene texture
    std::vector<DiffuseTexture> diffuseTextures_;      // per material
    RayLog* log_ = nullptr;
    EmbreeCallClock* callClock_ = nullptr;
    double time_ = 0.0;
    double buildMs_ = 0.0;
    double updateMs_ = 0.0;
};

}  // namespace hybridlab
