#pragma once
// Every metric of one test image against its reference, over the whole image and over an
// optional mask (for example the pixels of reflective objects, or those a technique ray traced):
// the numbers behind every chart (DESIGN.md "Experiments and results").
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <opencv2/core.hpp>

#include "common/image/image.h"
#include "metrics/error_stats.h"
#include "metrics/flip.h"
#include "metrics/hdr_flip.h"
#include "metrics/metric_input.h"
#include "metrics/metric_table.h"
#include "metrics/ssim.h"

namespace hybridlab {

// Which metrics a report holds. SSIM and FLIP each need a map of the whole image (the costly part
// of scoring an image); one not chosen is not computed, and neither its values nor its heat map
// appear in the report's files.
struct MetricSelection {
    bool ssim = true;
    bool flip = true;     // LDR-FLIP on the display images
    bool flipHdr = true;  // HDR-FLIP on the linear images (hdr_flip.h)
    bool rmse = true;
    bool psnr = true;

    bool error() const { return rmse || psnr; }  // both come from the difference (errorStats)
    bool any() const { return ssim || flip || flipHdr || error(); }
    // The flag of kMetricTable's metric `key` (metric_table.h); throws std::out_of_range for another.
    bool& chosen(std::string_view key);
    bool chosen(std::string_view key) const { return const_cast<MetricSelection&>(*this).chosen(key); }
};

struct MetricOptions {
    // RMSE, PSNR and the difference map: display values (default) or the linear HDR values.
    // SSIM and FLIP always see the display image, HDR-FLIP the linear one.
    ValueSpace errorSpace = ValueSpace::Display;
    SsimChannels ssimChannels = SsimChannels::Luma;
    double pixelsPerDegree = kDefaultPixelsPerDegree;  // FLIP's viewing condition
    MetricSelection selection;
};

struct RegionMetrics {
    std::size_t pixels = 0;
    double ssim = 0.0;  // MSSIM over the region (ssimMean)
    ErrorStats error;   // RMSE, PSNR
    FlipStats flip;     // LDR-FLIP
    FlipStats flipHdr;  // HDR-FLIP
    std::map<std::string, double> added;  // the metrics added at run time (metric_table.h), by key
};

// A metric not selected is left at its default (zero), its map empty.
struct MetricMaps {
    cv::Mat1f absoluteDifference;  // mean |test - reference| over R, G, B, in the error space
    cv::Mat1f ssim;
    cv::Mat1f flip;
    cv::Mat1f flipHdr;
};

struct MetricReport {
    int width = 0;
    int height = 0;
    MetricOptions options;
    RegionMetrics whole;
    std::optional<RegionMetrics> masked;  // when a mask was given
    MetricMaps maps;
};

// `test` and `reference` are linear, as rendered. Throws InputError when their sizes differ, when
// the mask's size differs or it selects no pixel, or when the images are smaller than SSIM's
// 11 x 11 window.
MetricReport computeMetrics(const Image& test, const Image& reference, const MetricOptions& options = {},
                            const PixelMask* mask = nullptr);

// Per-frame metrics along a camera path (frame k of `test` against frame k of `reference`), so
// that a chart can show where quality drops. The reports carry no maps: a long path's maps would
// not fit in memory.
std::vector<MetricReport> metricSeries(const std::vector<Image>& test, const std::vector<Image>& reference,
                                       const MetricOptions& options = {}, const PixelMask* mask = nullptr);

}  // namespace hybridlab
