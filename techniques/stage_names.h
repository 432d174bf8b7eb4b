#pragma once
// The stage vocabulary: every technique names the stages of its frame (FrameResult::stages) from
// this table, so that the report's stage chart has one entry per kind of work whichever technique
// did it. A stage may add a detail after a dot (`gbuffer.rays`); charts sum it under the name
// before the dot. report/results.py reads this table (one {"name", "meaning"} a line) and
// experiments/README.md lists it.
#include <string>
#include <string_view>

namespace hybridlab {

struct StageName {
    const char* name;
    const char* meaning;
};

// In the order of a frame.
inline constexpr StageName kStageNames[] = {
    {"bvh_update", "acceleration structures moved to the frame's time (instances re-placed, deformed meshes refitted)"},
    {"shadow_maps", "shadow-map passes (near 0 when the maps were kept)"},
    {"gbuffer", "primary visibility into the G-buffer: the raster pass, or primary rays (.rays) and their upload (.upload)"},
    {"heuristic", "choosing what to ray trace: object observations, selection, the pixel mask (.visible_pixels: occlusion queries)"},
    {"lighting", "deferred shading of the G-buffer with shadow maps and environment mapping (the P-buffer; .cpu: on the host, shadow rays for maps)"},
    {"ssr", "screen-space reflections: depth pyramid and march"},
    {"lens", "layered-EM lens geometry: .tessellation, .texture_coordinates, .draw (the lens pass)"},
    {"trace", "rays traced for shading: Whitted trees, fallback rays, layered-EM lens vertices (.lens_vertices)"},
    {"blend", "composing traced, SSR or lens colours over the rasterized image (.seam_blur: SSR seams smoothed)"},
    {"readback", "the rasterizer's targets, or a device trace's image, copied to the host and unpacked"},
    {"overhead", "recording and submitting the rasterizer's or a device launch's commands and waiting: the wall clock its GPU timestamps miss"},
};

// The part of a stage name before its first dot: the kind of work it is charted under.
inline std::string_view stageKind(std::string_view stage) { return stage.substr(0, stage.find('.')); }

// Whether `stage` is a vocabulary name, or one with a detail after a dot (a nonempty one).
inline bool isStageName(std::string_view stage) {
    const std::size_t dot = stage.find('.');
    if (dot != std::string_view::npos && dot + 1 == stage.size()) return false;
    for (const StageName& s : kStageNames)
        if (stageKind(stage) == s.name) return true;
    return false;
}

}  // namespace hybridlab
