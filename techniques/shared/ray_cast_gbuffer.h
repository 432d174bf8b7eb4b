#pragma once
// The G-buffer from primary rays instead of the rasterizer (Falcor's GBufferRT beside its
// GBufferRaster): one camera ray through every pixel centre, the hit written into the same targets,
// in the same units and conventions, as the G-buffer pass writes them (common/raster/gbuffer.h,
// shaders/gbuffer.frag), so that every later stage is unchanged. Textured colours are filtered
// with the primary ray's cone (as the reference filters them) instead of screen-space gradients.
// On a machine whose raster is a software rasterizer the G-buffer pass is a hybrid frame's fixed
// cost; the rays pay per pixel what they hit.
#include "common/raster/gbuffer.h"
#include "common/raytrace/ray_scene.h"
#include "common/raytrace/ray_stats.h"
#include "common/scene/camera.h"

namespace hybridlab {

// Fills `targets` of `out` (width x height, reusing its storage) from `rays` seen by `camera`;
// the sky's texels are all zero, as the G-buffer pass clears them. Counts one primary ray a pixel
// in `stats`. Deterministic; parallel over tiles.
void rayCastGBuffer(const RayScene& rays, const Camera& camera, int width, int height, GBufferTargets targets, GBuffer& out,
                    RayStats& stats);

}  // namespace hybridlab
