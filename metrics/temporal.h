#pragma once
// Temporal stability along a camera path. A technique can match each reference frame fairly well
// and still shimmer: what the eye sees in motion is how each frame changes from the last.
#include <vector>

#include <opencv2/core.hpp>

#include "common/image/image.h"
#include "metrics/metric_input.h"

namespace hybridlab {

struct TemporalError {
    // perFrame[k] compares the change into frame k + 1: the mean over the region's pixels and the
    // R, G, B channels of |(T_(k+1) - T_k) - (R_(k+1) - R_k)|. Zero when the technique changes
    // exactly as the reference does (even if it is off by the same amount in every frame).
    std::vector<double> perFrame;
    double mean = 0.0;  // of perFrame
};

// `test` and `reference` are the technique's and the reference's frames (linear, as rendered),
// the same number (at least two) of the same size; `mask` selects the pixels (every pixel when
// null). Throws InputError on mismatched sequences.
TemporalError temporalError(const std::vector<Image>& test, const std::vector<Image>& reference,
                            const PixelMask* mask = nullptr, ValueSpace space = ValueSpace::Display);

struct Flicker {
    // Per pixel, the population standard deviation over the frames, averaged over R, G and B.
    cv::Mat1f map;
    double mean = 0.0;  // of the map over the region
};

// For a static camera over repeated frames (at least two) of one technique: how much each pixel
// varies from frame to frame.
Flicker flicker(const std::vector<Image>& frames, const PixelMask* mask = nullptr, ValueSpace space = ValueSpace::Display);

}  // namespace hybridlab
