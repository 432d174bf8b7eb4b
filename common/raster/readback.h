#pragma once
// Read-back of GPU images to host-visible buffers: the copies a pass records at the end of a frame,
// and the one barrier that makes them visible to the host after the frame completed.
#include "common/raster/gpu_buffer.h"
#include "common/raster/gpu_image.h"

namespace hybridlab {

// Copies mip 0, layer 0 of `image` (in GENERAL; `aspect` of it) into `buffer`, tightly packed.
void recordCopyToBuffer(VkCommandBuffer cb, const GpuImage& image, VkImageAspectFlags aspect, const GpuBuffer& buffer);

// Makes the transfer writes recorded before it visible to the host.
void recordHostReadBarrier(VkCommandBuffer cb);

}  // namespace hybridlab
