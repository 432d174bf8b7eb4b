#include "metrics/temporal.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/core/input_error.h"

namespace hybridlab {

namespace {

// Every frame the same size (as the first), and the mask too; returns the frames in `space`.
std::vector<cv::Mat3f> framesIn(const std::vector<Image>& frames, const std::string& what, const PixelMask* mask, ValueSpace space) {
    if (frames.size() < 2) throw InputError(what + ": at least two frames are needed, got " + std::to_string(frames.size()));
    std::vector<cv::Mat3f> rgb;
    for (std::size_t i = 0; i < frames.size(); ++i) {
        requireSameSize(frames[i], what + " frame " + std::to_string(i), frames[0], what + " frame 0");
        rgb.push_back(metricRgb(frames[i], space));
    }
    if (mask) requireUsableMask(*mask, "the mask", frames[0].width(), frames[0].height());
    return rgb;
}

}  // namespace

TemporalError temporalError(const std::vector<Image>& test, const std::vector<Image>& reference, const PixelMask* mask, ValueSpace space) {
    if (test.size() != reference.size()) {
        throw InputError("temporal error: " + std::to_string(test.size()) + " test frames but " + std::to_string(reference.size()) +
                         " reference frames");
    }
    const std::vector<cv::Mat3f> t = framesIn(test, "test", mask, space), r = framesIn(reference, "reference", mask, space);
    requireSameSize(test[0], "the test frames", reference[0], "the reference frames");
    const cv::Mat1b* region = mask ? &mask->pixels() : nullptr;
    TemporalError result;
    for (std::size_t k = 1; k < t.size(); ++k) {
        cv::Mat3f change = (t[k] - t[k - 1]) - (r[k] - r[k - 1]);
        cv::Mat1f perPixel(change.rows, change.cols);
        for (int y = 0; y < change.rows; ++y) {
            for (int x = 0; x < change.cols; ++x) {
                const cv::Vec3f& d = change(y, x);
                perPixel(y, x) = (std::abs(d[0]) + std::abs(d[1]) + std::abs(d[2])) / 3.0f;
            }
        }
        result.perFrame.push_back(regionMean(perPixel, region));
    }
    for (double e : result.perFrame) result.mean += e;
    result.mean /= static_cast<double>(result.perFrame.size());
    return result;
}

Flicker flicker(const std::vector<Image>& frames, const PixelMask* mask, ValueSpace space) {
    const std::vector<cv::Mat3f> rgb = framesIn(frames, "flicker", mask, space);
    const double n = static_cast<double>(rgb.size());
    Flicker result;
    result.map.create(rgb[0].rows, rgb[0].cols);
    for (int y = 0; y < result.map.rows; ++y) {
        for (int x = 0; x < result.map.cols; ++x) {
            double deviation = 0.0;
            for (int c = 0; c < 3; ++c) {
                double sum = 0.0, squares = 0.0;
                for (const cv::Mat3f& f : rgb) {
                    const double v = f(y, x)[c];
                    sum += v;
                    squares += v * v;
                }
                const double mean = sum / n;
                deviation += std::sqrt(std::max(0.0, squares / n - mean * mean));
            }
            result.map(y, x) = static_cast<float>(deviation / 3.0);
        }
    }
    result.mean = regionMean(result.map, mask ? &mask->pixels() : nullptr);
    return result;
}

}  // namespace hybridlab
