#pragma once
// HDR-FLIP: Andersson, Nilsson, Shirley and Akenine-Möller, "Visualizing Errors in Rendered High
// Dynamic Range Images", Eurographics 2021 (short papers). LDR-FLIP (flip.h) of the two linear
// images exposure-compensated and tone mapped at a range of exposures, the per-pixel maximum over
// them. The range comes from the reference: the start exposure brings its largest luminance, the
// stop exposure its median luminance, to where the tone-mapping curve reaches t = 0.85; the
// exposures are spaced at most one stop apart (at least 2; 1 when start = stop). The procedure and
// its constants are those of NVIDIA's reference implementation (github.com/NVlabs/flip,
// python/flip_api.py compute_exposure_params, tone_map and compute_hdrflip; flip.py's exposure
// count), against whose values tests/metrics/test_metrics_hdr_flip.cpp checks it.
#include <opencv2/core.hpp>

#include "metrics/flip.h"

namespace hybridlab {

// The tone-mapping curves NVIDIA's implementation offers; ACES (Narkowicz's fit) is the paper's default.
enum class ToneMapper { Aces, Reinhard, Hable };

struct HdrFlipExposures {
    double start = 0.0;  // log2 of the exposure factor
    double stop = 0.0;
    int count = 1;
};

// The exposure range of `referenceLinear` (linear RGB, nonnegative) under `toneMapper`.
HdrFlipExposures hdrFlipExposures(const cv::Mat3f& referenceLinear, ToneMapper toneMapper = ToneMapper::Aces);

// The tone-mapped display sRGB image of `linear` at `exposure` (log2 factor), in [0, 1].
cv::Mat3f toneMapToDisplay(const cv::Mat3f& linear, double exposure, ToneMapper toneMapper = ToneMapper::Aces);

// The HDR-FLIP map of `testLinear` against `referenceLinear` (both linear RGB as rendered), in [0, 1].
cv::Mat1f hdrFlipMap(const cv::Mat3f& testLinear, const cv::Mat3f& referenceLinear,
                     double pixelsPerDegree = kDefaultPixelsPerDegree, ToneMapper toneMapper = ToneMapper::Aces);

}  // namespace hybridlab
