// What every shader of a device ray launch reads without the ray-tracing extension: the frame's
// uniforms, the launch's counters and its radiance output (set 0 of DeviceRayPipeline). The
// ray-generation shaders read them through device_rays.glsl; a compacted launch's classification
// pass (a compute shader, texel_list.glsl) reads them too.
#ifndef DEVICE_FRAME_GLSL
#define DEVICE_FRAME_GLSL

#include "device_ray_records.h"

layout(std140, set = 0, binding = 1) uniform Frame { DeviceFrame frame; };
// Counted on the device: rays by kind (primary, shadow, reflection, refraction), medium errors
// (RayStats' order and mediumErrors), then the invocations launched and those that traced a ray.
layout(std430, set = 0, binding = 7) buffer Counters { uint rayCounts[kRayCounterCount]; };
layout(std430, set = 0, binding = 8) writeonly buffer Output { vec4 radianceOut[]; };

// Every invocation of a launch counts itself, and once more where it traced a ray: rays per
// launched invocation, and how many were launched only to return.
void countLaunched() { atomicAdd(rayCounts[kLaunchedInvocations], 1u); }
void countTraced() { atomicAdd(rayCounts[kTracingInvocations], 1u); }

#endif
