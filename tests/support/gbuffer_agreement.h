#pragma once
// Two G-buffers of one view held to each other (DESIGN.md "Invariants that tests hold"): the
// rasterized one against primary rays' (test_raster_gbuffer.cpp, Embree's cast), and the device's
// ray-cast one against both (test_device_gbuffer_rays.cpp). At every pixel centre the object id,
// world position, shading normal and geometric normal agree, except for a thin band of silhouette
// pixels: the ids on at least 99% of the covered pixels; where they match, the position within
// 1e-3 of the scene's bounding-box diagonal and the normals within 0.5 degree. Where the ids match,
// the only pixels allowed outside those bounds are those where the two can legitimately pick
// different triangles of one object: pixel centres on a crease between flat faces or on an edge
// between two triangles (the normal jumps), on a silhouette inside one object (Sponza is one
// object), or on coincident faces; at most 0.1% of them.
#include <cstddef>

#include "common/raster/gbuffer.h"
#include "common/raytrace/ray_scene.h"

namespace hybridlab::test {

inline constexpr double kMaxGBufferPositionError = 1e-3;  // of the bounding-box diagonal
inline constexpr double kMaxGBufferNormalDegrees = 0.5;

struct GBufferAgreement {
    std::size_t covered = 0, idMatches = 0, facingMatches = 0;
    std::size_t outliers = 0;       // pixels whose ids match but whose position or normal is out of bounds
    double maxPositionError = 0.0;  // over the other pixels whose ids match, relative to the bounding-box diagonal
    double maxNormalDegrees = 0.0;
    std::size_t geometricOutliers = 0;  // pixels whose ids match but whose triangles' normals differ by over 0.5 degree
                                        // (a pixel centre on an edge between two triangles)
    double idAgreement() const { return covered ? static_cast<double>(idMatches) / covered : 1.0; }
};

// `g` against `reference` (both holding position, normal, the geometric normal and object ids, of
// one size), positions relative to `diagonal`.
GBufferAgreement compareGBuffers(const GBuffer& g, const GBuffer& reference, double diagonal);

// `g` against the G-buffer primary rays cast from `rays` (at the time `g` was rendered): the
// ray-cast G-buffer (techniques/shared/ray_cast_gbuffer.h) is the primary rays' hits in the
// G-buffer's form, so this is both `g` against the reference's camera rays and against Embree's
// ray-cast G-buffer.
GBufferAgreement compareWithPrimaryRays(const RayScene& rays, const GBuffer& g);

// Adds googletest failures where `a` breaks the bounds above.
void expectGBuffersAgree(const GBufferAgreement& a);

// A deforming object (a `deform` block, deformation.h) beside a rigidly moving one and a floor.
extern const char* const kDeformingObjectScene;

}  // namespace hybridlab::test
