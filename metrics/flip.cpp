#include "metrics/flip.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "common/image/color.h"
#include "metrics/metric_input.h"
#include "metrics/parallel_tasks.h"

// The steps below are the paper's, in its order: the colour pipeline (spatial filtering with the
// contrast sensitivity functions in YCxCz, clamping to the RGB cube, Hunt-adjusted L*a*b*, HyAB
// distance, redistribution to [0, 1]), the feature pipeline (edge and point detectors on the
// achromatic channel), and their combination. The constants were checked against NVIDIA's
// reference code (NVlabs/flip: python/flip_api.py, functions generate_spatial_filter,
// spatial_filter, hunt_adjustment, hyab, redistribute_errors, feature_detection, compute_ldrflip;
// and the same numbers in cpp/FLIP.h).

namespace hybridlab {
namespace {

constexpr double kPi = std::numbers::pi;

// Colour difference: HyAB^qc is remapped so that the fraction pc of the largest possible difference
// maps to pt, and the rest of the range to (pt, 1].
constexpr double kQc = 0.7;
constexpr double kPc = 0.4;
constexpr double kPt = 0.95;
// Feature detection: w is the peak-to-trough width, in degrees, of the edge detector (twice the
// Gaussian's standard deviation); the feature difference is raised to qf.
constexpr double kW = 0.082;
constexpr double kQf = 0.5;

// Contrast sensitivity of the achromatic (A), red-green (RG) and blue-yellow (BY) channels, in the
// spatial domain, as a sum of two Gaussians of the visual angle x (degrees):
//   S(x) = a1 sqrt(pi / b1) exp(-pi^2 x^2 / b1) + a2 sqrt(pi / b2) exp(-pi^2 x^2 / b2).
// A and RG have one Gaussian (a2 = 0; b2 only enters the support radius below).
struct ContrastSensitivity {
    double a1, b1, a2, b2;
};
constexpr ContrastSensitivity kCsf[3] = {
    {1.0, 0.0047, 0.0, 1e-5},    // A, filters Y
    {1.0, 0.0053, 0.0, 1e-5},    // RG, filters Cx
    {34.1, 0.04, 13.5, 0.025},   // BY, filters Cz
};
constexpr double kLargestCsfB = 0.04;

// Linear sRGB to CIE XYZ (D65), as exact fractions (the reference code's constants).
const cv::Matx33d kLinearRgbToXyz(10135552.0 / 24577794.0, 8788810.0 / 24577794.0, 4435075.0 / 24577794.0,
                                  2613072.0 / 12288897.0, 8788810.0 / 12288897.0, 887015.0 / 12288897.0,
                                  1425312.0 / 73733382.0, 8788810.0 / 73733382.0, 70074185.0 / 73733382.0);
// The reference white, XYZ of linear RGB (1, 1, 1): (0.950428545, 1, 1.088900371).
const cv::Vec3d kWhite = kLinearRgbToXyz * cv::Vec3d(1.0, 1.0, 1.0);
// XYZ divided by the white, the common start of YCxCz and L*a*b*, in one matrix, and back.
const cv::Matx33d kLinearRgbToRelativeXyz =
    cv::Matx33d::diag(cv::Vec3d(1.0 / kWhite[0], 1.0 / kWhite[1], 1.0 / kWhite[2])) * kLinearRgbToXyz;
const cv::Matx33d kRelativeXyzToLinearRgb = kLinearRgbToRelativeXyz.inv();

cv::Vec3d relativeXyz(const cv::Vec3d& linearRgb) { return kLinearRgbToRelativeXyz * linearRgb; }

// YCxCz (Johnson and Fairchild's linearised L*a*b*, the opponent space where FLIP filters):
// Y = 116 y - 16, Cx = 500 (x - y), Cz = 200 (y - z) of the white-relative XYZ.
cv::Vec3d ycxczFromLinearRgb(const cv::Vec3d& linearRgb) {
    const cv::Vec3d n = relativeXyz(linearRgb);
    return {116.0 * n[1] - 16.0, 500.0 * (n[0] - n[1]), 200.0 * (n[1] - n[2])};
}

cv::Vec3d linearRgbFromYcxcz(const cv::Vec3d& o) {
    const double y = (o[0] + 16.0) / 116.0;
    return kRelativeXyzToLinearRgb * cv::Vec3d(y + o[1] / 500.0, y, y - o[2] / 200.0);
}

// The cube root of t > 0 to double precision, four times faster than std::cbrt (which dominated
// FLIP's time): a first guess from the bit pattern (dividing the exponent by 3, within about 3%),
// then two Halley steps x <- x (x^3 + 2t) / (2x^3 + t), each of which cubes the relative error.
double cubeRoot(double t) {
    std::uint64_t bits = std::bit_cast<std::uint64_t>(t);
    double x = std::bit_cast<double>(bits / 3 + 0x2A9F7893782DA1CEull);
    for (int i = 0; i < 2; ++i) {
        const double x3 = x * x * x;
        x *= (x3 + 2.0 * t) / (2.0 * x3 + t);
    }
    return x;
}

// CIE L*a*b* with the Hunt adjustment: a* and b* scaled by 0.01 L*, so that chroma differences
// count less in dark colours (the Hunt effect).
cv::Vec3d huntAdjustedLab(const cv::Vec3d& linearRgb) {
    constexpr double d = 6.0 / 29.0;
    // Both branches are computed and one is selected, so that the three cube roots overlap.
    auto f = [](double t) {
        const double root = cubeRoot(std::max(t, d * d * d));
        return t > d * d * d ? root : t / (3.0 * d * d) + 4.0 / 29.0;
    };
    const cv::Vec3d n = relativeXyz(linearRgb);
    const double fx = f(n[0]), fy = f(n[1]), fz = f(n[2]);
    const double l = 116.0 * fy - 16.0;
    return {l, 0.01 * l * 500.0 * (fx - fy), 0.01 * l * 200.0 * (fy - fz)};
}

// HyAB (Abasi et al.): city-block in lightness, Euclidean in the chromatic plane.
double hyab(const cv::Vec3d& p, const cv::Vec3d& q) {
    const double da = p[1] - q[1], db = p[2] - q[2];
    return std::abs(p[0] - q[0]) + std::sqrt(da * da + db * db);
}

// cmax: the largest colour difference in the RGB cube, that between green and blue, raised to qc.
double maxColorDifference() {
    static const double cmax = std::pow(hyab(huntAdjustedLab({0.0, 1.0, 0.0}), huntAdjustedLab({0.0, 0.0, 1.0})), kQc);
    return cmax;
}

// The colour error in [0, 1]: e = HyAB^qc, then e < pc cmax maps linearly to [0, pt) and the rest
// linearly to [pt, 1].
double redistributedColorError(double distance) {
    // In float: powf is twice as fast, and its 1e-7 relative error is far below what matters.
    const double e = std::pow(static_cast<float>(distance), static_cast<float>(kQc));
    const double cmax = maxColorDifference(), knee = kPc * cmax;
    return e < knee ? kPt / knee * e : kPt + (e - knee) / (cmax - knee) * (1.0 - kPt);
}

using Planes = std::vector<cv::Mat>;  // three single-channel planes of one image

// sRGB decoding (srgbToLinear) through a table of 4097 samples with linear interpolation: three
// times faster than its powf, which dominated the conversion below, and as precise as float
// allows (the interpolation error is below max|f''| h^2 / 8 = 3 / (8 * 4096^2) = 2e-8; measured
// against double precision, the result is within 2.4e-7, a few float ulps). Values outside [0, 1]
// take the exact function.
constexpr int kDecodeSteps = 4096;
const std::array<float, kDecodeSteps + 1> kSrgbDecodeTable = [] {
    std::array<float, kDecodeSteps + 1> table;
    for (int i = 0; i <= kDecodeSteps; ++i) table[i] = srgbToLinear(static_cast<float>(static_cast<double>(i) / kDecodeSteps));
    return table;
}();

float decodeSrgb(float c) {
    if (!(c >= 0.0f && c < 1.0f)) return srgbToLinear(c);
    const float position = c * kDecodeSteps;
    const int i = static_cast<int>(position);
    const float t = position - static_cast<float>(i);
    return kSrgbDecodeTable[i] + t * (kSrgbDecodeTable[i + 1] - kSrgbDecodeTable[i]);
}

// Display sRGB -> linear RGB -> XYZ -> YCxCz, as three float planes.
Planes ycxczPlanes(const cv::Mat3f& srgb) {
    Planes planes{cv::Mat1f(srgb.size()), cv::Mat1f(srgb.size()), cv::Mat1f(srgb.size())};
    forEachRowInParallel(srgb.rows, [&](int y) {
        const cv::Vec3f* in = srgb[y];
        float* out[3] = {planes[0].ptr<float>(y), planes[1].ptr<float>(y), planes[2].ptr<float>(y)};
        for (int x = 0; x < srgb.cols; ++x) {
            const cv::Vec3d o = ycxczFromLinearRgb({decodeSrgb(in[x][0]), decodeSrgb(in[x][1]), decodeSrgb(in[x][2])});
            for (int c = 0; c < 3; ++c) out[c][x] = static_cast<float>(o[c]);
        }
    });
    return planes;
}

// Filters one YCxCz plane with its contrast sensitivity function, sampled at 1 / ppd degrees on a
// square of radius ceil(3 sqrt(b_max / (2 pi^2)) ppd) (three standard deviations of the widest
// Gaussian) and normalised to sum 1. Each Gaussian exp(-pi^2 (x^2 + y^2) / b) is the product of
// two 1-D ones, so the 2-D filter is a weighted sum of separable passes; the edge is replicated.
cv::Mat csfFilter(const cv::Mat& plane, const ContrastSensitivity& csf, double ppd) {
    const int radius = static_cast<int>(std::ceil(3.0 * std::sqrt(kLargestCsfB / (2.0 * kPi * kPi)) * ppd));
    struct Term {
        cv::Mat1d profile;  // exp(-pi^2 (i / ppd)^2 / b), i = -radius..radius
        double amplitude;   // a sqrt(pi / b)
    };
    std::vector<Term> terms;
    for (auto [a, b] : {std::pair{csf.a1, csf.b1}, std::pair{csf.a2, csf.b2}}) {
        if (a == 0.0) continue;
        cv::Mat1d profile(1, 2 * radius + 1);
        for (int i = -radius; i <= radius; ++i) {
            const double x = i / ppd;
            profile(0, i + radius) = std::exp(-kPi * kPi * x * x / b);
        }
        terms.push_back({profile, a * std::sqrt(kPi / b)});
    }
    double total = 0.0;  // the sum of the 2-D kernel
    for (const Term& t : terms) total += t.amplitude * cv::sum(t.profile)[0] * cv::sum(t.profile)[0];
    cv::Mat filtered = cv::Mat::zeros(plane.size(), plane.type());
    for (const Term& t : terms) {
        cv::Mat pass;
        cv::sepFilter2D(plane, pass, -1, t.profile * (t.amplitude / total), t.profile, cv::Point(-1, -1), 0.0, cv::BORDER_REPLICATE);
        filtered += pass;
    }
    return filtered;
}

// Per pixel, the redistributed colour error of the CSF-filtered images.
cv::Mat1f colorError(const Planes& test, const Planes& reference, double ppd) {
    Planes t(3), r(3);
    std::vector<std::function<void()>> passes;
    for (int c = 0; c < 3; ++c) {
        passes.push_back([&, c] { t[c] = csfFilter(test[c], kCsf[c], ppd); });
        passes.push_back([&, c] { r[c] = csfFilter(reference[c], kCsf[c], ppd); });
    }
    runInParallel(passes);
    cv::Mat1f error(test[0].size());
    // Filtering can leave the RGB cube; the paper clamps there before going to L*a*b*.
    auto perceptual = [](const Planes& p, int y, int x) {
        cv::Vec3d rgb = linearRgbFromYcxcz({p[0].at<float>(y, x), p[1].at<float>(y, x), p[2].at<float>(y, x)});
        for (int c = 0; c < 3; ++c) rgb[c] = std::clamp(rgb[c], 0.0, 1.0);
        return huntAdjustedLab(rgb);
    };
    forEachRowInParallel(error.rows, [&](int y) {
        for (int x = 0; x < error.cols; ++x) {
            error(y, x) = static_cast<float>(redistributedColorError(hyab(perceptual(t, y, x), perceptual(r, y, x))));
        }
    });
    return error;
}

// The feature detectors: the first (edges) and second (points) derivative of a Gaussian with
// standard deviation sd = w ppd / 2 pixels, across one axis, times the Gaussian along the other,
// on a square of radius ceil(3 sd). Each is normalised so that its positive weights sum to 1 and
// its negative weights to -1; for the separable form that is the derivative profile normalised
// that way times the Gaussian profile normalised to sum 1.
struct FeatureDetectors {
    cv::Mat1d gaussian, firstDerivative, secondDerivative;  // 1 x (2 radius + 1) profiles

    explicit FeatureDetectors(double ppd) {
        const double sd = 0.5 * kW * ppd;
        const int radius = static_cast<int>(std::ceil(3.0 * sd));
        gaussian.create(1, 2 * radius + 1);
        firstDerivative.create(1, 2 * radius + 1);
        secondDerivative.create(1, 2 * radius + 1);
        for (int i = -radius; i <= radius; ++i) {
            const double g = std::exp(-(i * i) / (2.0 * sd * sd));
            gaussian(0, i + radius) = g;
            firstDerivative(0, i + radius) = -i * g;
            secondDerivative(0, i + radius) = (i * i / (sd * sd) - 1.0) * g;
        }
        gaussian /= cv::sum(gaussian)[0];
        normalizeSigned(firstDerivative);
        normalizeSigned(secondDerivative);
    }

    static void normalizeSigned(cv::Mat1d& k) {
        double positive = 0.0, negative = 0.0;
        for (double v : k) (v > 0.0 ? positive : negative) += v;
        for (double& v : k) v /= v > 0.0 ? positive : -negative;
    }
};

// One pass of a 1-D profile along x (as a row) or y (as a column), the edge replicated. The 2-D
// detectors are separable and replication commutes with filtering along the other axis, so two
// passes equal the 2-D filter; the Gaussian pass is shared by the edge and the point detector.
cv::Mat1d filterAlong(const cv::Mat1d& image, const cv::Mat1d& profile, bool alongX) {
    cv::Mat1d out;
    cv::filter2D(image, out, -1, alongX ? profile : cv::Mat1d(profile.t()), cv::Point(-1, -1), 0.0, cv::BORDER_REPLICATE);
    return out;
}

struct FeatureResponses {
    cv::Mat1d edges, points;  // per pixel, |(response along x, response along y)|
};

FeatureResponses detectFeatures(const cv::Mat1d& luminance, const FeatureDetectors& d) {
    cv::Mat1d smoothedAlongY, smoothedAlongX, edgeX, edgeY, pointX, pointY;
    runInParallel({[&] { smoothedAlongY = filterAlong(luminance, d.gaussian, false); },
                   [&] { smoothedAlongX = filterAlong(luminance, d.gaussian, true); }});
    runInParallel({[&] { edgeX = filterAlong(smoothedAlongY, d.firstDerivative, true); },
                   [&] { edgeY = filterAlong(smoothedAlongX, d.firstDerivative, false); },
                   [&] { pointX = filterAlong(smoothedAlongY, d.secondDerivative, true); },
                   [&] { pointY = filterAlong(smoothedAlongX, d.secondDerivative, false); }});
    FeatureResponses r;
    cv::magnitude(edgeX, edgeY, r.edges);
    cv::magnitude(pointX, pointY, r.points);
    return r;
}

// Per pixel, the feature difference raised to qf: (max(||edge_r| - |edge_t||, ||point_r| -
// |point_t||) / sqrt(2))^qf, in [0, 1]. The detectors run on the achromatic channel of the
// unfiltered images, normalised to [0, 1] as (Y + 16) / 116. Double precision keeps a flat
// field's response at zero: the detectors sum to zero, and qf = 0.5 would turn float round-off
// of 1e-8 into a feature difference of 1e-4.
cv::Mat1f featureDifference(const cv::Mat& testY, const cv::Mat& referenceY, double ppd) {
    const FeatureDetectors detectors(ppd);
    cv::Mat1d t, r;
    testY.convertTo(t, CV_64F, 1.0 / 116.0, 16.0 / 116.0);
    referenceY.convertTo(r, CV_64F, 1.0 / 116.0, 16.0 / 116.0);
    const FeatureResponses ft = detectFeatures(t, detectors), fr = detectFeatures(r, detectors);
    cv::Mat1f difference(t.size());
    forEachRowInParallel(difference.rows, [&](int y) {
        for (int x = 0; x < difference.cols; ++x) {
            const double d = std::max(std::abs(fr.edges(y, x) - ft.edges(y, x)), std::abs(fr.points(y, x) - ft.points(y, x)));
            static_assert(kQf == 0.5, "d^qf is a square root");
            difference(y, x) = static_cast<float>(std::sqrt(d / std::numbers::sqrt2));
        }
    });
    return difference;
}

}  // namespace

cv::Mat1f flipMap(const cv::Mat3f& test, const cv::Mat3f& reference, double pixelsPerDegree) {
    if (test.size() != reference.size()) throw std::invalid_argument("flipMap: the images differ in size");
    if (!(pixelsPerDegree >= kSmallestPixelsPerDegree && pixelsPerDegree <= kLargestPixelsPerDegree))
        throw std::invalid_argument("flipMap: pixels per degree outside [kSmallestPixelsPerDegree, kLargestPixelsPerDegree]");
    const Planes t = ycxczPlanes(test), r = ycxczPlanes(reference);
    const cv::Mat1f color = colorError(t, r, pixelsPerDegree);
    const cv::Mat1f feature = featureDifference(t[0], r[0], pixelsPerDegree);
    // FLIP = colour error ^ (1 - feature difference): features push the colour error towards 1.
    cv::Mat1f flip(test.size());
    forEachRowInParallel(flip.rows, [&](int y) {
        for (int x = 0; x < flip.cols; ++x) flip(y, x) = std::pow(color(y, x), 1.0f - feature(y, x));
    });
    return flip;
}

std::vector<double> valueWeightedPercentiles(const std::vector<float>& values, const std::vector<double>& ps) {
    std::vector<double> result(ps.size(), 0.0);
    double total = 0.0;
    float largest = 0.0f;
    for (float v : values) {
        total += v;
        largest = std::max(largest, v);
    }
    if (!(total > 0.0)) return result;
    // Sorting a megapixel took longer than the rest of the pooling: instead, the value sums of
    // 4096 buckets (by value) locate the bucket where each percentile lies, and only that
    // bucket's values are sorted and walked.
    constexpr int kBuckets = 4096;
    auto bucketOf = [&](float v) { return std::clamp(static_cast<int>(v / largest * kBuckets), 0, kBuckets - 1); };
    std::vector<double> bucketSum(kBuckets, 0.0);
    for (float v : values) bucketSum[bucketOf(v)] += v;
    for (std::size_t i = 0; i < ps.size(); ++i) {
        const double target = ps[i] * total;
        double below = 0.0;  // the sum of the values in the buckets before `b`
        int b = 0;
        while (b < kBuckets - 1 && below + bucketSum[b] < target) below += bucketSum[b++];
        std::vector<float> inBucket;
        for (float v : values) {
            if (bucketOf(v) == b) inBucket.push_back(v);
        }
        std::sort(inBucket.begin(), inBucket.end());
        result[i] = inBucket.empty() ? 0.0 : inBucket.back();
        for (float v : inBucket) {
            below += v;
            if (below >= target) {
                result[i] = v;
                break;
            }
        }
    }
    return result;
}

FlipStats flipStats(const cv::Mat1f& map, const cv::Mat1b* region) {
    std::vector<float> values;
    values.reserve(map.total());
    for (int y = 0; y < map.rows; ++y) {
        for (int x = 0; x < map.cols; ++x) {
            if (!region || (*region)(y, x)) values.push_back(map(y, x));
        }
    }
    const std::vector<double> p = valueWeightedPercentiles(values, {0.5, 0.25, 0.75});
    FlipStats s;
    s.mean = regionMean(map, region);
    s.weightedMedian = p[0];
    s.weightedFirstQuartile = p[1];
    s.weightedThirdQuartile = p[2];
    return s;
}

}  // namespace hybridlab
