#include "metrics/hdr_flip.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/parallel_for.h>

#include "metrics/parallel_tasks.h"

namespace hybridlab {
namespace {

// The tone mapper as a rational polynomial (k0 x^2 + k1 x + k2) / (k3 x^2 + k4 x + k5) of the
// exposed linear value x (the HDR-FLIP paper, eq. 2, with the pre-exposure of each curve folded in).
struct Rational {
    double k0, k1, k2, k3, k4, k5;
};

Rational curve(ToneMapper t) {
    switch (t) {
        case ToneMapper::Reinhard:
            return {0.0, 1.0, 0.0, 0.0, 1.0, 1.0};  // on luminance: x / (1 + Y), see toneMapToDisplay
        case ToneMapper::Hable: {
            const double A = 0.15, B = 0.50, C = 0.10, D = 0.20, E = 0.02, F = 0.30, W = 11.2;
            Rational r{A * F - A * E, C * B * F - B * E, 0.0, A * F, B * F, D * F * F};
            const double whiteScale = (r.k3 * W * W + r.k4 * W + r.k5) / (r.k0 * W * W + r.k1 * W + r.k2);
            return {4.0 * r.k0 * whiteScale, 2.0 * r.k1 * whiteScale, r.k2 * whiteScale, 4.0 * r.k3, 2.0 * r.k4, r.k5};
        }
        case ToneMapper::Aces:
        default:
            return {0.6 * 0.6 * 2.51, 0.6 * 0.03, 0.0, 0.6 * 0.6 * 2.43, 0.6 * 0.59, 0.14};
    }
}

// The exposed value x at which the curve reaches t (the paper's x for t = 0.85).
double valueReaching(ToneMapper toneMapper, double t) {
    const Rational k = curve(toneMapper);
    if (toneMapper == ToneMapper::Reinhard) return t * k.k5 / (k.k1 - t * k.k4);
    const double c0 = (k.k1 - k.k4 * t) / (k.k0 - k.k3 * t), c1 = (k.k2 - k.k5 * t) / (k.k0 - k.k3 * t);
    return -0.5 * c0 + std::sqrt(0.25 * c0 * c0 - c1);
}

double luminance(const cv::Vec3f& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

float encodeSrgb(float c) { return c > 0.0031308f ? 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f : 12.92f * c; }

}  // namespace

HdrFlipExposures hdrFlipExposures(const cv::Mat3f& reference, ToneMapper toneMapper) {
    constexpr double kT = 0.85;
    std::vector<double> y;
    y.reserve(reference.total());
    for (auto it = reference.begin(); it != reference.end(); ++it) y.push_back(luminance(*it));
    HdrFlipExposures e;
    if (y.empty()) return e;
    const double yMax = *std::max_element(y.begin(), y.end());
    if (yMax == 0.0) return e;
    // The median as numpy's 50th percentile: linear between the two middle values.
    const double position = 0.5 * static_cast<double>(y.size() - 1);
    const std::size_t lo = static_cast<std::size_t>(std::floor(position));
    std::nth_element(y.begin(), y.begin() + static_cast<std::ptrdiff_t>(lo), y.end());
    const double yLo = y[lo];
    const double yHi = lo + 1 < y.size() ? *std::min_element(y.begin() + static_cast<std::ptrdiff_t>(lo) + 1, y.end()) : yLo;
    const double median = yLo + (position - static_cast<double>(lo)) * (yHi - yLo);
    const double x = valueReaching(toneMapper, kT);
    e.start = std::log2(x / yMax);
    e.stop = std::log2(x / median);
    e.count = e.start == e.stop ? 1 : std::max(2, static_cast<int>(std::ceil(e.stop - e.start)));
    return e;
}

cv::Mat3f toneMapToDisplay(const cv::Mat3f& linear, double exposure, ToneMapper toneMapper) {
    const Rational k = curve(toneMapper);
    const float scale = static_cast<float>(std::exp2(exposure));
    cv::Mat3f out(linear.size());
    forEachRowInParallel(linear.rows, [&](int r) {
        for (int c = 0; c < linear.cols; ++c) {
            cv::Vec3f x = linear(r, c);
            for (int i = 0; i < 3; ++i) x[i] = std::max(x[i], 0.0f) * scale;
            cv::Vec3f y;
            if (toneMapper == ToneMapper::Reinhard) {
                const float Y = static_cast<float>(luminance(x));
                for (int i = 0; i < 3; ++i) y[i] = x[i] / (1.0f + Y);
            } else {
                for (int i = 0; i < 3; ++i) {
                    const double v = x[i];
                    const double denominator = k.k3 * v * v + k.k4 * v + k.k5;
                    // A value so bright that the polynomials overflow tone maps to 1.
                    y[i] = std::isinf(denominator) ? 1.0f : static_cast<float>((k.k0 * v * v + k.k1 * v + k.k2) / denominator);
                }
            }
            for (int i = 0; i < 3; ++i) y[i] = encodeSrgb(std::clamp(y[i], 0.0f, 1.0f));
            out(r, c) = y;
        }
    });
    return out;
}

cv::Mat1f hdrFlipMap(const cv::Mat3f& test, const cv::Mat3f& reference, double pixelsPerDegree, ToneMapper toneMapper) {
    const HdrFlipExposures e = hdrFlipExposures(reference, toneMapper);
    const double step = (e.stop - e.start) / std::max(e.count - 1, 1);
    // The exposures side by side (each FLIP's filter passes leave threads idle), then their maximum,
    // which no order changes.
    std::vector<cv::Mat1f> ldr(static_cast<std::size_t>(std::max(e.count, 0)));
    tbb::parallel_for(0, e.count, [&](int i) {
        const double exposure = e.start + i * step;
        ldr[static_cast<std::size_t>(i)] = flipMap(toneMapToDisplay(test, exposure, toneMapper),
                                                   toneMapToDisplay(reference, exposure, toneMapper), pixelsPerDegree);
    });
    cv::Mat1f result(reference.size(), 0.0f);
    forEachRowInParallel(result.rows, [&](int r) {
        for (const cv::Mat1f& map : ldr)
            for (int c = 0; c < result.cols; ++c) result(r, c) = std::max(result(r, c), map(r, c));
    });
    return result;
}

}  // namespace hybridlab
