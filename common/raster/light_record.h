#pragma once
// A scene light as the shaders read it (raster_records::LightData, shading.glsl's sampleLightRecord):
// one function for the raster lighting pass and the device ray tracer, which read the same record.
#include "common/raster/shaders/raster_records.h"
#include "common/scene/light.h"

namespace hybridlab {

// Colour times intensity and type (kLight*), position and direction with the spot cone's cosines
// (spotCone(): the ones the CPU ray tracer uses), and its shadow-map layers (`firstShadowLayer`
// -1: the light casts no shadow).
raster_records::LightData lightRecord(const Light& light, int firstShadowLayer, int shadowLayerCount);

}  // namespace hybridlab
