#include "metrics/error_stats.h"

#include <cmath>
#include <limits>

namespace hybridlab {

ErrorStats errorStats(const cv::Mat3f& test, const cv::Mat3f& reference, const cv::Mat1b* region) {
    double sum = 0.0;
    std::size_t n = 0;
    for (int y = 0; y < test.rows; ++y) {
        const cv::Vec3f* t = test[y];
        const cv::Vec3f* r = reference[y];
        const uchar* inside = region ? (*region)[y] : nullptr;
        for (int x = 0; x < test.cols; ++x) {
            if (inside && !inside[x]) continue;
            for (int c = 0; c < 3; ++c) {
                const double d = static_cast<double>(t[x][c]) - static_cast<double>(r[x][c]);
                sum += d * d;
            }
            n += 3;
        }
    }
    ErrorStats s;
    s.mse = n ? sum / static_cast<double>(n) : 0.0;
    s.rmse = std::sqrt(s.mse);
    s.psnr = s.mse > 0.0 ? 10.0 * std::log10(kPsnrPeak * kPsnrPeak / s.mse) : std::numeric_limits<double>::infinity();
    return s;
}

cv::Mat1f absoluteDifferenceMap(const cv::Mat3f& test, const cv::Mat3f& reference) {
    cv::Mat1f map(test.rows, test.cols);
    for (int y = 0; y < test.rows; ++y) {
        const cv::Vec3f* t = test[y];
        const cv::Vec3f* r = reference[y];
        for (int x = 0; x < test.cols; ++x) {
            map(y, x) = (std::abs(t[x][0] - r[x][0]) + std::abs(t[x][1] - r[x][1]) + std::abs(t[x][2] - r[x][2])) / 3.0f;
        }
    }
    return map;
}

}  // namespace hybridlab
