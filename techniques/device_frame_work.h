#pragma once
// What a frame cost the Vulkan devices outside the technique's own work, as counters of the frame:
// device_submissions (queue submissions, each a fence wait and a CPU round trip),
// device_readback_bytes (what the host read of memory the device wrote: the image, counters, query
// results, debug records) and device_allocations (device memory, descriptor sets and command
// buffers created during the frame; 0 in a steady state), and apart from them the submissions and
// bytes of the frame's diagnostics read after its timed stages (device_diagnostic_submissions,
// device_diagnostic_readback_bytes: debug images, statistics). Counted by VulkanDevice (DeviceWork) over
// the frame, for every technique: createTechnique() hands each one out wrapped in this. Recorded
// only for frames that used a device. One frame at a time: the counts are the process's.
#include <memory>

#include "techniques/technique.h"

namespace hybridlab {

// `technique`, its frames counting their device work.
std::unique_ptr<Technique> countingDeviceWork(std::unique_ptr<Technique> technique);

}  // namespace hybridlab
