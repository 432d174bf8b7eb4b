// FLIP (Andersson et al., HPG 2020) against what its definition implies: zero for identical
// images, values in [0, 1], flat fields equal to the colour term worked out by hand from the
// paper's formulas, thin lines weighing more than a uniform shift of the same energy, errors that
// grow with noise; and its pooling (mean, value-weighted median and quartiles).
#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "metrics/flip.h"
#include "metrics/metric_input.h"
#include "tests/support/metric_test_images.h"

namespace hybridlab {
namespace {

using Color = std::array<double, 3>;

cv::Mat3f flat(int width, int height, const Color& c) {
    return cv::Mat3f(height, width, cv::Vec3f(static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2])));
}

double maxOf(const cv::Mat1f& m) {
    double largest = 0.0;
    cv::minMaxLoc(m, nullptr, &largest);
    return largest;
}

// The colour pipeline of the paper for one pair of flat colours, written out again in double
// precision. On a flat field the contrast sensitivity filters (normalised to sum 1) change
// nothing, so the filtered colour is the colour itself, and there are no edges or points, so the
// feature term is 0 and FLIP = the colour term.
namespace by_hand {

double decode(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

// Hunt-adjusted L*a*b* of a display sRGB colour; linear sRGB to XYZ as in the reference code.
Color huntLab(const Color& srgb, bool alreadyLinear = false) {
    const double m[3][3] = {{10135552.0 / 24577794.0, 8788810.0 / 24577794.0, 4435075.0 / 24577794.0},
                            {2613072.0 / 12288897.0, 8788810.0 / 12288897.0, 887015.0 / 12288897.0},
                            {1425312.0 / 73733382.0, 8788810.0 / 73733382.0, 70074185.0 / 73733382.0}};
    Color linear;
    for (int i = 0; i < 3; ++i) linear[i] = alreadyLinear ? srgb[i] : decode(srgb[i]);
    Color relative;  // XYZ over the white, which is XYZ of linear (1, 1, 1)
    for (int i = 0; i < 3; ++i) {
        double xyz = 0.0, white = 0.0;
        for (int j = 0; j < 3; ++j) xyz += m[i][j] * linear[j], white += m[i][j];
        relative[i] = xyz / white;
    }
    const double delta = 6.0 / 29.0;
    auto f = [&](double t) { return t > delta * delta * delta ? std::cbrt(t) : t / (3.0 * delta * delta) + 4.0 / 29.0; };
    const double l = 116.0 * f(relative[1]) - 16.0;
    const double a = 500.0 * (f(relative[0]) - f(relative[1])), b = 200.0 * (f(relative[1]) - f(relative[2]));
    return {l, 0.01 * l * a, 0.01 * l * b};
}

double hyab(const Color& p, const Color& q) { return std::abs(p[0] - q[0]) + std::hypot(p[1] - q[1], p[2] - q[2]); }

double colorTerm(const Color& test, const Color& reference) {
    const double qc = 0.7, pc = 0.4, pt = 0.95;
    const double cmax = std::pow(hyab(huntLab({0, 1, 0}, true), huntLab({0, 0, 1}, true)), qc);
    const double e = std::pow(hyab(huntLab(test), huntLab(reference)), qc);
    return e < pc * cmax ? pt / (pc * cmax) * e : pt + (e - pc * cmax) / (cmax - pc * cmax) * (1.0 - pt);
}

}  // namespace by_hand

void expectZeroForIdenticalImages() {
    const cv::Mat3f pattern = test::displayPattern(96, 64);
    EXPECT_EQ(maxOf(flipMap(pattern, pattern)), 0.0);
    const cv::Mat3f grey = flat(32, 32, {0.5, 0.5, 0.5});
    EXPECT_EQ(maxOf(flipMap(grey, grey)), 0.0);
    const FlipStats s = flipStats(flipMap(pattern, pattern), nullptr);
    EXPECT_EQ(s.mean, 0.0);
    EXPECT_EQ(s.weightedMedian, 0.0);
}

void expectValuesInTheUnitInterval() {
    auto expectInUnitInterval = [](const cv::Mat1f& m) {
        double lowest = 0.0, highest = 0.0;
        cv::minMaxLoc(m, &lowest, &highest);
        EXPECT_GE(lowest, 0.0);
        EXPECT_LE(highest, 1.0);
    };
    // Every pair of the RGB cube's corners as flat fields: the largest colour differences there are.
    for (int i = 0; i < 8; ++i) {
        for (int j = 0; j < 8; ++j) {
            SCOPED_TRACE(::testing::Message() << "corners " << i << " and " << j);
            expectInUnitInterval(flipMap(flat(16, 16, {double(i & 1), double(i >> 1 & 1), double(i >> 2 & 1)}),
                                         flat(16, 16, {double(j & 1), double(j >> 1 & 1), double(j >> 2 & 1)})));
        }
    }
    // Random images, and a black/white checkerboard against its inverse: the largest features.
    cv::Mat3f a(48, 48), b(48, 48), checker(48, 48), inverse(48, 48);
    cv::randu(a, 0.0f, 1.0f);
    cv::randu(b, 0.0f, 1.0f);
    for (int y = 0; y < 48; ++y) {
        for (int x = 0; x < 48; ++x) {
            const float v = (x + y) % 2 ? 1.0f : 0.0f;
            checker(y, x) = cv::Vec3f(v, v, v);
            inverse(y, x) = cv::Vec3f(1 - v, 1 - v, 1 - v);
        }
    }
    expectInUnitInterval(flipMap(a, b));
    expectInUnitInterval(flipMap(checker, inverse));
    expectInUnitInterval(flipMap(checker, flat(48, 48, {0.5, 0.5, 0.5})));
}

TEST(Flip, IsZeroForIdenticalImagesAndLiesInTheUnitInterval) {
    {
        SCOPED_TRACE("identical images");
        expectZeroForIdenticalImages();
    }
    {
        SCOPED_TRACE("extreme pairs");
        expectValuesInTheUnitInterval();
    }
}

TEST(Flip, FlatFieldsEqualTheColourTermComputedByHand) {
    const std::vector<std::pair<Color, Color>> pairs = {
        {{0.5, 0.5, 0.5}, {0.6, 0.6, 0.6}},     {{0.5, 0.5, 0.5}, {0.501, 0.5, 0.5}}, {{0.8, 0.2, 0.1}, {0.2, 0.7, 0.3}},
        {{0.05, 0.02, 0.1}, {0.1, 0.05, 0.02}}, {{0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}},   {{0.3, 0.4, 0.9}, {0.9, 0.8, 0.1}},
        {{0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}},  // the largest difference: exactly 1
    };
    for (const auto& [test, reference] : pairs) {
        SCOPED_TRACE(::testing::Message() << "test (" << test[0] << ", " << test[1] << ", " << test[2] << "), reference ("
                                          << reference[0] << ", " << reference[1] << ", " << reference[2] << ")");
        // The inputs are float, as in every image; work out the expected value from the same floats.
        const Color t{float(test[0]), float(test[1]), float(test[2])}, r{float(reference[0]), float(reference[1]), float(reference[2])};
        const double expected = by_hand::colorTerm(t, r);
        const cv::Mat1f map = flipMap(flat(24, 20, test), flat(24, 20, reference));
        double lowest = 0.0, highest = 0.0;
        cv::minMaxLoc(map, &lowest, &highest);
        EXPECT_NEAR(lowest, expected, 1e-5);
        EXPECT_NEAR(highest, expected, 1e-5);
    }
    EXPECT_NEAR(by_hand::colorTerm({0, 1, 0}, {0, 0, 1}), 1.0, 1e-12);
}

TEST(Flip, AOnePixelLineScoresHigherThanAUniformShiftOfTheSameEnergy) {
    // On a grey field, a line one pixel wide raised by a, against every pixel raised by s with
    // the same sum of squared differences: width a^2 = width height s^2.
    const int size = 64;
    const double a = 0.25, s = a / std::sqrt(double(size));
    const cv::Mat3f field = flat(size, size, {0.5, 0.5, 0.5});
    cv::Mat3f line = field.clone();
    line.row(size / 2).setTo(cv::Vec3f(float(0.5 + a), float(0.5 + a), float(0.5 + a)));
    const cv::Mat3f shifted = flat(size, size, {0.5 + s, 0.5 + s, 0.5 + s});
    const cv::Mat1f lineMap = flipMap(line, field), shiftMap = flipMap(shifted, field);
    EXPECT_GT(maxOf(lineMap), 2.0 * maxOf(shiftMap));
    double lowestOnLine = 0.0;
    cv::minMaxLoc(lineMap.row(size / 2), &lowestOnLine);
    EXPECT_GT(lowestOnLine, maxOf(shiftMap));  // every pixel of the line
}

TEST(Flip, ErrorGrowsMonotonicallyWithNoiseAmplitude) {
    // A smooth gradient in [0.35, 0.65] plus a fixed noise pattern in [-1, 1] times the
    // amplitude: nothing is clamped up to amplitude 0.3.
    cv::Mat3f base(64, 80), noise(64, 80);
    for (int y = 0; y < base.rows; ++y) {
        for (int x = 0; x < base.cols; ++x) base(y, x) = cv::Vec3f(0.35f + 0.3f * x / 79.0f, 0.5f, 0.65f - 0.3f * y / 63.0f);
    }
    cv::RNG random(7);
    random.fill(noise, cv::RNG::UNIFORM, -1.0, 1.0);
    double previous = 0.0;
    for (double amplitude : {0.0, 0.005, 0.01, 0.02, 0.04, 0.08, 0.16, 0.3}) {
        SCOPED_TRACE(amplitude);
        const cv::Mat3f noisy = base + noise * amplitude;
        const double mean = flipStats(flipMap(noisy, base), nullptr).mean;
        if (amplitude > 0.0) {
            EXPECT_GT(mean, previous);
        }
        previous = mean;
    }
}

// The definition of the value-weighted percentile, computed the slow way.
double weightedPercentileBySorting(std::vector<float> values, double p) {
    std::sort(values.begin(), values.end());
    double total = 0.0, cumulative = 0.0;
    for (float v : values) total += v;
    if (total == 0.0) return 0.0;
    for (float v : values) {
        cumulative += v;
        if (cumulative >= p * total) return v;
    }
    return values.back();
}

TEST(FlipPooling, WeightedPercentilesFollowTheirDefinitionAndMasksRestrictThem) {
    // By hand: total 1; cumulative 0.1, 0.3, 0.6, 1.0.
    const std::vector<double> p = valueWeightedPercentiles({0.4f, 0.1f, 0.3f, 0.2f}, {0.25, 0.5, 0.75});
    EXPECT_FLOAT_EQ(p[0], 0.2f);
    EXPECT_FLOAT_EQ(p[1], 0.3f);
    EXPECT_FLOAT_EQ(p[2], 0.4f);
    EXPECT_EQ(valueWeightedPercentiles({0.0f, 0.0f}, {0.5})[0], 0.0);
    // Large errors dominate: one pixel of 1 among 99 of 0.01 is half the weight.
    std::vector<float> mostlySmall(99, 0.01f);
    mostlySmall.push_back(1.0f);
    EXPECT_FLOAT_EQ(valueWeightedPercentiles(mostlySmall, {0.6})[0], 1.0f);

    std::mt19937 random(3);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    for (int trial = 0; trial < 20; ++trial) {
        std::vector<float> values(5000);
        for (float& v : values) v = trial % 2 ? uniform(random) : std::pow(uniform(random), 6.0f);  // skewed, as FLIP maps are
        for (double q : {0.25, 0.5, 0.75, 0.99}) {
            EXPECT_EQ(valueWeightedPercentiles(values, {q})[0], weightedPercentileBySorting(values, q)) << "trial " << trial << ", p " << q;
        }
    }

    // The left half differs, the right half is equal: away from the middle (further than the
    // filters reach), the right half's FLIP is exactly 0.
    const cv::Mat3f reference = flat(64, 32, {0.4, 0.5, 0.6});
    cv::Mat3f test = reference.clone();
    test(cv::Rect(0, 0, 32, 32)).setTo(cv::Vec3f(0.7f, 0.5f, 0.6f));
    cv::Mat1b right(32, 64, uchar(0));
    right(cv::Rect(48, 0, 16, 32)).setTo(1);
    const cv::Mat1f map = flipMap(test, reference);
    EXPECT_EQ(flipStats(map, &right).mean, 0.0);
    EXPECT_GT(flipStats(map, nullptr).mean, 0.1);
    cv::Mat1b left = 1 - right;
    EXPECT_NEAR(flipStats(map, &left).mean, regionMean(map, &left), 1e-12);
}

}  // namespace
}  // namespace hybridlab
