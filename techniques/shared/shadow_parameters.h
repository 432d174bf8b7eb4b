#pragma once
// The shadow-map parameters of every technique that rasterizes its shadows, declared once:
// shadow_resolution and pcf_radius, the ShadowSettings they give.
#include <cstdint>

#include "common/raster/raster_options.h"
#include "techniques/parameter_binder.h"

namespace hybridlab {

struct ShadowMapParameters {
    std::uint32_t resolution{};
    int pcfRadius{};

    // ShadowSettings with these two, the others its defaults.
    ShadowSettings settings() const {
        ShadowSettings s;
        s.resolution = resolution;
        s.pcfRadius = pcfRadius;
        return s;
    }
};

inline ParameterBinder<ShadowMapParameters> shadowMapParameters() {
    const ShadowSettings d;
    ParameterBinder<ShadowMapParameters> b;
    b.bind(&ShadowMapParameters::resolution,
           ParamSpec::integer("shadow_resolution", d.resolution, 64, 8192, "texels per side of each shadow-map layer"));
    b.bind(&ShadowMapParameters::pcfRadius,
           ParamSpec::integer("pcf_radius", d.pcfRadius, 0, 4,
                              "percentage-closer filtering over (2r + 1)^2 bilinearly filtered taps (0: one tap, nearest to hard shadows)"));
    return b;
}

}  // namespace hybridlab
