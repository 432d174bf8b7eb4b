#pragma once
// The first hits of a block of pixels' camera rays (through the pixel centres), traced as one
// coherent packet (RayScene::intersectCoherent): the primary visibility of the reference's pixel
// loop and of the ray-cast G-buffer.
#include "common/raytrace/ray_scene.h"
#include "common/raytrace/ray_stats.h"
#include "common/scene/camera.h"
#include "techniques/shared/pixel_loop.h"

namespace hybridlab {

struct CameraRayPacket {
    static constexpr int kSize = PixelBlock::kWidth * PixelBlock::kHeight;
    static_assert(kSize <= RayScene::kCoherentRays, "a block of pixels is one packet of camera rays");

    // Traces the camera rays of `block` in a width x height image; counts them as primary rays.
    CameraRayPacket(const RayScene& scene, const CameraRays& camera, const PixelBlock& block, int width, int height, RayStats& stats) {
        for (int k = 0; k < block.count; ++k) rays[k] = camera.throughNdc(pixelCenterNdc(block.x[k], block.y[k], width, height));
        scene.intersectCoherent(rays, block.count, hits, found);
        stats.primary += static_cast<std::uint64_t>(block.count);
    }

    // Pixel k's first hit; null where its ray left the scene.
    const SurfaceHit* hit(int k) const { return found[k] ? &hits[k] : nullptr; }

    Ray rays[kSize];
    SurfaceHit hits[kSize];
    bool found[kSize];
};

}  // namespace hybridlab
