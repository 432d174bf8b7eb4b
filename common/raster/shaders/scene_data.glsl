// Scene data shared by the geometry passes (G-buffer, shadow maps, visible-pixel queries); the
// records are declared in raster_records.h, with GpuScene's C++.
#ifndef SCENE_DATA_GLSL
#define SCENE_DATA_GLSL

#include "raster_records.h"

// Per draw: the camera's (or light's) view-projection, and what is drawn.
layout(push_constant) uniform Draw { DrawConstants draw; };

// The draw's object and material: one record per draw in a dynamic uniform buffer, bound at the
// draw's offset. Uniform loads are what lavapipe does fast (storage-buffer loads cost it several
// times more per pixel).
layout(std140, set = 0, binding = 0) uniform DrawData { DrawRecord drawData; };

#endif
