#pragma once
// How the ray tracer shades its hits, declared once for the techniques that trace from the camera
// or the G-buffer with shadow rays (the reference, rt_only, heuristic_rt): `shadows` and
// `texture_filter`.
#include "common/raytrace/whitted_tracer.h"
#include "techniques/parameter_binder.h"

namespace hybridlab {

struct TracedShadingParameters {
    bool shadows{};
    bool rayCones{};  // texture_filter = "cones"

    void applyTo(WhittedSettings& s) const {
        s.shadows = shadows;
        s.rayCones = rayCones;
    }
};

inline ParameterBinder<TracedShadingParameters> tracedShadingParameters() {
    ParameterBinder<TracedShadingParameters> b;
    b.bind(&TracedShadingParameters::shadows,
           ParamSpec::boolean("shadows", true, "trace shadow rays (false: every light unshadowed, to compare with raster shadows off)"));
    b.bind(&TracedShadingParameters::rayCones,
           ParamSpec::choice("texture_filter", "cones", {"cones", "none"},
                             "textures filtered over ray cones' footprints (as mip-mapping), or point lookups (as POV-Ray)"),
           {true, false});
    return b;
}

}  // namespace hybridlab
