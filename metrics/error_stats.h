#pragma once
// Pixel-wise errors: RMSE and PSNR over the R, G and B values, and the absolute-difference map.
#include <opencv2/core.hpp>

namespace hybridlab {

struct ErrorStats {
    double mse = 0.0;   // mean over the region's pixels and the three channels of (test - reference)^2
    double rmse = 0.0;  // sqrt(mse)
    double psnr = 0.0;  // 10 log10(peak^2 / mse) in dB; +infinity when the images are equal
};

// The peak of PSNR: display white. In the linear space this is the linear value of display
// white, 1, too, so that PSNR stays comparable between the two spaces for LDR content.
constexpr double kPsnrPeak = 1.0;

// Over `region` (every pixel when null).
ErrorStats errorStats(const cv::Mat3f& test, const cv::Mat3f& reference, const cv::Mat1b* region);

// Per pixel, the mean over R, G and B of |test - reference|.
cv::Mat1f absoluteDifferenceMap(const cv::Mat3f& test, const cv::Mat3f& reference);

}  // namespace hybridlab
