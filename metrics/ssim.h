#pragma once
// SSIM exactly as Wang, Bovik, Sheikh and Simoncelli, "Image quality assessment: from error
// visibility to structural similarity", IEEE TIP 13(4), 2004: local statistics under an 11 x 11
// circular-symmetric Gaussian window with sigma 1.5 (their Sec. III-C), K1 = 0.01, K2 = 0.03,
// dynamic range L = 1, population (not sample) variances and covariance, and the mean of the map
// (their eq. 17, MSSIM). The numbers agree with scikit-image's
// structural_similarity(gaussian_weights=True, sigma=1.5, use_sample_covariance=False,
// data_range=1.0), which tests/metrics/test_metrics_skimage.cpp checks.
#include <opencv2/core.hpp>

namespace hybridlab {

enum class SsimChannels {
    Luma,        // one SSIM of the Rec. 709 luma of the sRGB values (default)
    PerChannel,  // SSIM of R, G and B separately, averaged (scikit-image's channel_axis)
};

const char* ssimChannelsName(SsimChannels channels);

// The window: 11 x 11, sigma 1.5. Its radius is also the border that the mean leaves out.
constexpr int kSsimWindowRadius = 5;
constexpr double kSsimSigma = 1.5;

// The per-pixel SSIM of one channel (values in [0, 1]). Throws InputError when the image is
// smaller than the 11 x 11 window.
cv::Mat1f ssimMap(const cv::Mat1d& test, const cv::Mat1d& reference);

// The SSIM map of two RGB images (values in [0, 1]): of their luma, or the mean of the three
// channel maps.
cv::Mat1f ssimMap(const cv::Mat3f& test, const cv::Mat3f& reference, SsimChannels channels);

// MSSIM: the mean of `map` over `region` (every pixel when null), leaving out the 5-pixel border
// where the window reaches past the image, as scikit-image does (crop(S, (win_size - 1) // 2)).
// A region that lies entirely within that border is averaged as it is (the map there uses
// mirrored pixels), so that a mask at the edge of the image still gets a value.
double ssimMean(const cv::Mat1f& map, const cv::Mat1b* region);

}  // namespace hybridlab
