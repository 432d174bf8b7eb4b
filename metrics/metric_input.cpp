#include "metrics/metric_input.h"

#include <utility>

#include "common/core/input_error.h"
#include "common/image/color.h"
#include "metrics/parallel_tasks.h"

namespace hybridlab {

const char* valueSpaceName(ValueSpace space) { return space == ValueSpace::Display ? "display" : "linear"; }

cv::Mat3f metricRgb(const Image& linear, ValueSpace space) {
    cv::Mat3f rgb(linear.height(), linear.width());
    // In parallel: the sRGB encoding's powf makes this as slow as SSIM otherwise.
    forEachRowInParallel(linear.height(), [&](int y) {
        cv::Vec3f* row = rgb[y];
        for (int x = 0; x < linear.width(); ++x) {
            const glm::vec4 c = space == ValueSpace::Display ? linearToDisplay(linear.at(x, y)) : linear.at(x, y);
            row[x] = cv::Vec3f(c.r, c.g, c.b);
        }
    });
    return rgb;
}

cv::Mat1d rec709Luma(const cv::Mat3f& rgb) {
    cv::Mat1d luma(rgb.rows, rgb.cols);
    for (int y = 0; y < rgb.rows; ++y) {
        const cv::Vec3f* in = rgb[y];
        double* out = luma[y];
        for (int x = 0; x < rgb.cols; ++x) out[x] = 0.2126 * in[x][0] + 0.7152 * in[x][1] + 0.0722 * in[x][2];
    }
    return luma;
}

namespace {

std::string sizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

}  // namespace

void requireSameSize(const Image& test, const std::string& testName, const Image& reference, const std::string& referenceName) {
    if (test.width() != reference.width() || test.height() != reference.height()) {
        throw InputError(testName + " is " + sizeText(test.width(), test.height()) + " but " + referenceName + " is " +
                         sizeText(reference.width(), reference.height()) + ": the images compared must be the same size");
    }
}

PixelMask::PixelMask(cv::Mat1b inside) : inside_(std::move(inside)), count_(static_cast<std::size_t>(cv::countNonZero(inside_))) {}

PixelMask PixelMask::everything(int width, int height) { return PixelMask(cv::Mat1b(height, width, uchar(1))); }

PixelMask PixelMask::fromImage(const Image& image) {
    cv::Mat1b inside(image.height(), image.width());
    for (int y = 0; y < image.height(); ++y) {
        for (int x = 0; x < image.width(); ++x) {
            const glm::vec4& c = image.at(x, y);
            inside(y, x) = c.r > 0.5f || c.g > 0.5f || c.b > 0.5f ? 1 : 0;
        }
    }
    return PixelMask(std::move(inside));
}

void requireUsableMask(const PixelMask& mask, const std::string& maskName, int width, int height) {
    if (mask.width() != width || mask.height() != height) {
        throw InputError(maskName + " is " + sizeText(mask.width(), mask.height()) + " but the images are " +
                         sizeText(width, height) + ": the mask must be the same size as the images");
    }
    if (mask.count() == 0) {
        throw InputError(maskName + ": the mask selects no pixel (a pixel is in the mask when its R, G or B value is above 0.5)");
    }
}

double regionMean(const cv::Mat1f& map, const cv::Mat1b* region) {
    double sum = 0.0;
    std::size_t n = 0;
    for (int y = 0; y < map.rows; ++y) {
        const float* values = map[y];
        const uchar* inside = region ? (*region)[y] : nullptr;
        for (int x = 0; x < map.cols; ++x) {
            if (inside && !inside[x]) continue;
            sum += values[x];
            ++n;
        }
    }
    return n ? sum / static_cast<double>(n) : 0.0;
}

}  // namespace hybridlab
