#pragma once
// The shadow-map parameters of every technique that rasterizes its shadows, declared once: their
// specs and the ShadowSettings they give.
#include <cstdint>
#include <vector>

#include "common/raster/raster_options.h"
#include "techniques/parameters.h"

namespace hybridlab {

inline std::vector<ParamSpec> shadowMapParameterSpecs() {
    const ShadowSettings d;
    return {ParamSpec::integer("shadow_resolution", d.resolution, 64, 8192, "texels per side of each shadow-map layer"),
            ParamSpec::integer("pcf_radius", d.pcfRadius, 0, 4,
                               "percentage-closer filtering over (2r + 1)^2 bilinearly filtered taps (0: one tap, nearest to hard shadows)")};
}

inline ShadowSettings shadowMapSettings(const ParameterSet& p) {
    ShadowSettings s;
    s.resolution = static_cast<std::uint32_t>(p.getInt("shadow_resolution"));
    s.pcfRadius = static_cast<int>(p.getInt("pcf_radius"));
    return s;
}

}  // namespace hybridlab
