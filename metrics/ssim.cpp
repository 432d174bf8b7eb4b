#include "metrics/ssim.h"

#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "common/core/input_error.h"
#include "metrics/metric_input.h"
#include "metrics/parallel_tasks.h"

namespace hybridlab {

const char* ssimChannelsName(SsimChannels channels) { return channels == SsimChannels::Luma ? "luma" : "per_channel"; }

namespace {

// Wang et al. 2004, eq. 7 with C1 = (K1 L)^2 and C2 = (K2 L)^2, L = 1 (values in [0, 1]).
constexpr double kC1 = 0.01 * 0.01;
constexpr double kC2 = 0.03 * 0.03;

// The Gaussian-weighted local mean. cv::BORDER_REFLECT repeats the edge pixel (fedcba|abcdef),
// which is scipy.ndimage's mode 'reflect' that scikit-image uses; it only matters for the map's
// 5-pixel border, which MSSIM leaves out anyway. The kernel is OpenCV's sampled, normalised
// Gaussian of 11 taps, the same weights as scipy's gaussian_filter(sigma=1.5, truncate=3.5).
cv::Mat1d localMean(const cv::Mat1d& values) {
    cv::Mat1d mean;
    const int size = 2 * kSsimWindowRadius + 1;
    cv::GaussianBlur(values, mean, cv::Size(size, size), kSsimSigma, kSsimSigma, cv::BORDER_REFLECT);
    return mean;
}

}  // namespace

cv::Mat1f ssimMap(const cv::Mat1d& test, const cv::Mat1d& reference) {
    const int window = 2 * kSsimWindowRadius + 1;
    if (test.rows < window || test.cols < window) {
        throw InputError("SSIM needs images of at least " + std::to_string(window) + "x" + std::to_string(window) +
                         " pixels (its window), not " + std::to_string(test.cols) + "x" + std::to_string(test.rows));
    }
    cv::Mat1d muX, muY, xx, yy, xy;
    runInParallel({[&] { muX = localMean(test); },
                   [&] { muY = localMean(reference); },
                   [&] { xx = localMean(test.mul(test)); },
                   [&] { yy = localMean(reference.mul(reference)); },
                   [&] { xy = localMean(test.mul(reference)); }});
    cv::Mat1f map(test.rows, test.cols);
    forEachRowInParallel(map.rows, [&](int y) {
        for (int x = 0; x < map.cols; ++x) {
            const double mx = muX(y, x), my = muY(y, x);
            // Population moments under the window: E[X^2] - E[X]^2 (eqs. 14-16, weights sum to 1).
            const double varX = xx(y, x) - mx * mx, varY = yy(y, x) - my * my, cov = xy(y, x) - mx * my;
            // Eq. 13.
            map(y, x) = static_cast<float>(((2.0 * mx * my + kC1) * (2.0 * cov + kC2)) /
                                           ((mx * mx + my * my + kC1) * (varX + varY + kC2)));
        }
    });
    return map;
}

cv::Mat1f ssimMap(const cv::Mat3f& test, const cv::Mat3f& reference, SsimChannels channels) {
    if (channels == SsimChannels::Luma) return ssimMap(rec709Luma(test), rec709Luma(reference));
    std::vector<cv::Mat> testPlanes, referencePlanes;
    cv::split(test, testPlanes);
    cv::split(reference, referencePlanes);
    cv::Mat1f sum(test.rows, test.cols, 0.0f);
    for (int c = 0; c < 3; ++c) {
        cv::Mat1d t, r;
        testPlanes[c].convertTo(t, CV_64F);
        referencePlanes[c].convertTo(r, CV_64F);
        sum += ssimMap(t, r);
    }
    // The mean over the region of the mean map is the mean of the per-channel MSSIMs.
    return sum / 3.0f;
}

double ssimMean(const cv::Mat1f& map, const cv::Mat1b* region) {
    const int r = kSsimWindowRadius;
    cv::Mat1b interior(map.rows, map.cols, uchar(0));
    if (map.rows > 2 * r && map.cols > 2 * r) interior(cv::Rect(r, r, map.cols - 2 * r, map.rows - 2 * r)).setTo(1);
    if (region) {
        cv::Mat1b inside = interior & *region;
        return regionMean(map, cv::countNonZero(inside) > 0 ? &inside : region);
    }
    return regionMean(map, &interior);
}

}  // namespace hybridlab
