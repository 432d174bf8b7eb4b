#pragma once
// What every metric reads: the RGB values of a test and a reference image of the same size, in
// the value space the metric is defined on, and an optional mask of the pixels to average over.
//
// Images arrive as the techniques produce them: linear HDR (common/image). By default metrics
// see them as the viewer shows them, display sRGB clamped to [0, 1] (DESIGN.md "The shading
// model": "Metrics are computed on the display image"); RMSE and PSNR may use the linear values.
#include <cstddef>
#include <string>

#include <opencv2/core.hpp>

#include "common/image/image.h"

namespace hybridlab {

enum class ValueSpace {
    Display,  // clamp to [0, 1], then sRGB-encode (as the viewer and the PNGs show it)
    Linear,   // the linear HDR values as rendered
};

const char* valueSpaceName(ValueSpace space);

// The R, G and B channels of `linear` in `space`, as a 3-channel float matrix (row 0 at the top,
// channels in R, G, B order). Alpha is not part of any metric.
cv::Mat3f metricRgb(const Image& linear, ValueSpace space);

// Luma of sRGB-encoded values with the Rec. 709 weights, Y' = 0.2126 R' + 0.7152 G' + 0.0722 B'
// (the weights are applied to the encoded values, as the issue asks for SSIM), in double.
cv::Mat1d rec709Luma(const cv::Mat3f& rgb);

// Throws InputError unless both images have the same size; the message names them.
void requireSameSize(const Image& test, const std::string& testName, const Image& reference,
                     const std::string& referenceName);

// The pixels a metric averages over. A pixel is inside when its value is nonzero.
class PixelMask {
public:
    PixelMask() = default;
    // Every pixel of a width x height image.
    static PixelMask everything(int width, int height);
    // A pixel of `image` is inside when its R, G or B value, as stored (no transfer function), is
    // above 0.5; alpha is ignored (an opaque PNG would otherwise select everything).
    static PixelMask fromImage(const Image& image);

    int width() const { return inside_.cols; }
    int height() const { return inside_.rows; }
    bool contains(int x, int y) const { return inside_(y, x) != 0; }
    std::size_t count() const { return count_; }
    const cv::Mat1b& pixels() const { return inside_; }

private:
    explicit PixelMask(cv::Mat1b inside);
    cv::Mat1b inside_;
    std::size_t count_ = 0;
};

// Throws InputError, naming `maskName`, when the mask's size differs from width x height or when
// it selects no pixel.
void requireUsableMask(const PixelMask& mask, const std::string& maskName, int width, int height);

// Mean of `map` over the pixels of `region` (every pixel when region is null), in double.
double regionMean(const cv::Mat1f& map, const cv::Mat1b* region);

}  // namespace hybridlab
