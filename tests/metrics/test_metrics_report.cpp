// The metric report (metrics.h) on analytic cases: SSIM of flat fields, RMSE and PSNR of uniform
// shifts, the display and linear value spaces, masks, per-frame series, bad input; and the heat
// maps with their legends.
#include <cmath>
#include <limits>
#include <vector>

#include <glm/common.hpp>
#include <gtest/gtest.h>

#include "common/core/input_error.h"
#include "metrics/heatmap.h"
#include "metrics/metrics.h"
#include "metrics/report_files.h"
#include "tests/support/metric_test_images.h"

namespace hybridlab {
namespace {

using test::flatDisplay;

void expectIdenticalImagesScorePerfectly() {
    const Image image = test::fromDisplay(test::displayPattern(48, 40));
    const MetricReport r = computeMetrics(image, image);
    EXPECT_EQ(r.width, 48);
    EXPECT_EQ(r.height, 40);
    EXPECT_EQ(r.whole.pixels, 48u * 40u);
    EXPECT_NEAR(r.whole.ssim, 1.0, 1e-12);
    EXPECT_EQ(r.whole.error.rmse, 0.0);
    EXPECT_EQ(r.whole.error.psnr, std::numeric_limits<double>::infinity());
    EXPECT_EQ(r.whole.flip.mean, 0.0);
    EXPECT_FALSE(r.masked.has_value());
}

void expectSsimOfFlatFieldsIsTheLuminanceTerm() {
    // No variance: SSIM = (2 a b + C1) / (a^2 + b^2 + C1) (Wang et al. 2004, eq. 13, with the
    // structure term (0 + C2) / (0 + C2) = 1), for luma a and b; grey, so luma = value.
    for (auto [a, b] : {std::pair{0.5f, 0.6f}, std::pair{0.1f, 0.9f}, std::pair{0.3f, 0.31f}}) {
        SCOPED_TRACE(::testing::Message() << a << " vs " << b);
        const Image test = flatDisplay(20, 16, glm::vec3(a)), reference = flatDisplay(20, 16, glm::vec3(b));
        const MetricReport r = computeMetrics(test, reference);
        const double c1 = 0.01 * 0.01;
        EXPECT_NEAR(r.whole.ssim, (2.0 * a * b + c1) / (double(a) * a + double(b) * b + c1), 1e-6);
        // Per channel, a grey image has three equal channel maps, each equal to the luma map.
        MetricOptions perChannel;
        perChannel.ssimChannels = SsimChannels::PerChannel;
        EXPECT_NEAR(computeMetrics(test, reference, perChannel).whole.ssim, r.whole.ssim, 1e-6);
    }
}

void expectRmseAndPsnrOfAUniformShift() {
    const MetricReport r = computeMetrics(flatDisplay(16, 16, glm::vec3(0.55f)), flatDisplay(16, 16, glm::vec3(0.5f)));
    EXPECT_NEAR(r.whole.error.rmse, 0.05, 1e-6);
    EXPECT_NEAR(r.whole.error.psnr, -20.0 * std::log10(0.05), 1e-4);
    double lowest = 0.0, highest = 0.0;
    cv::minMaxLoc(r.maps.absoluteDifference, &lowest, &highest);
    EXPECT_NEAR(lowest, 0.05, 1e-6);
    EXPECT_NEAR(highest, 0.05, 1e-6);
}

void expectDisplayValuesClampWhileTheLinearSpaceKeepsHdrValues() {
    // Linear 2 and 1 both show as display white.
    const Image bright(16, 16, glm::vec4(2.0f, 2.0f, 2.0f, 1.0f)), white(16, 16, glm::vec4(1.0f));
    EXPECT_EQ(computeMetrics(bright, white).whole.error.rmse, 0.0);
    MetricOptions linear;
    linear.errorSpace = ValueSpace::Linear;
    const MetricReport r = computeMetrics(bright, white, linear);
    EXPECT_NEAR(r.whole.error.rmse, 1.0, 1e-7);
    EXPECT_NEAR(r.whole.error.psnr, 0.0, 1e-6);
    EXPECT_NEAR(r.whole.ssim, 1.0, 1e-12);  // SSIM and FLIP stay on the display image
    EXPECT_EQ(r.whole.flip.mean, 0.0);
}

TEST(MetricReport, AnalyticValues) {
    {
        SCOPED_TRACE("identical images");
        expectIdenticalImagesScorePerfectly();
    }
    {
        SCOPED_TRACE("SSIM of flat fields");
        expectSsimOfFlatFieldsIsTheLuminanceTerm();
    }
    {
        SCOPED_TRACE("RMSE and PSNR of a uniform shift");
        expectRmseAndPsnrOfAUniformShift();
    }
    {
        SCOPED_TRACE("display and linear value spaces");
        expectDisplayValuesClampWhileTheLinearSpaceKeepsHdrValues();
    }
}

TEST(MetricReport, MaskRestrictsEveryMetric) {
    // The left half differs, the right half is equal; the mask takes the right quarter, further
    // from the middle than SSIM's window and FLIP's filters reach.
    const Image reference = flatDisplay(64, 32, glm::vec3(0.4f, 0.5f, 0.6f));
    Image test = reference;
    for (int y = 0; y < 32; ++y) {
        for (int x = 0; x < 32; ++x) test.at(x, y) = glm::vec4(0.9f, 0.8f, 0.1f, 1.0f);
    }
    Image maskImage(64, 32, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));  // opaque: alpha does not count
    for (int y = 0; y < 32; ++y) {
        for (int x = 48; x < 64; ++x) maskImage.at(x, y) = glm::vec4(0.0f, 0.6f, 0.0f, 1.0f);
    }
    const PixelMask mask = PixelMask::fromImage(maskImage);
    EXPECT_EQ(mask.count(), 16u * 32u);
    const MetricReport r = computeMetrics(test, reference, {}, &mask);
    ASSERT_TRUE(r.masked.has_value());
    EXPECT_EQ(r.masked->pixels, 16u * 32u);
    EXPECT_NEAR(r.masked->ssim, 1.0, 1e-12);
    EXPECT_EQ(r.masked->error.rmse, 0.0);
    EXPECT_EQ(r.masked->flip.mean, 0.0);
    EXPECT_LT(r.whole.ssim, 0.9);
    EXPECT_GT(r.whole.error.rmse, 0.1);
    EXPECT_GT(r.whole.flip.mean, 0.1);

    // MSSIM leaves out the 5-pixel border; a mask lying only there is averaged as it is.
    const Image a = flatDisplay(32, 32, glm::vec3(0.5f)), b = flatDisplay(32, 32, glm::vec3(0.6f));
    Image cornerImage(32, 32, glm::vec4(0.0f));
    cornerImage.at(0, 0) = glm::vec4(1.0f);
    const PixelMask corner = PixelMask::fromImage(cornerImage);
    const MetricReport flat = computeMetrics(a, b, {}, &corner);
    EXPECT_NEAR(flat.masked->ssim, flat.whole.ssim, 1e-6);  // flat: the map is the same everywhere
}

TEST(MetricReport, SelectedMetricsAloneAreComputedWithTheSameValues) {
    const Image test = test::fromDisplay(test::displayPattern(40, 32)), reference = flatDisplay(40, 32, glm::vec3(0.4f));
    const MetricReport all = computeMetrics(test, reference);
    MetricOptions ssimOnly;
    ssimOnly.selection = {.ssim = true, .flip = false, .flipHdr = false, .rmse = false, .psnr = false};
    const MetricReport r = computeMetrics(test, reference, ssimOnly);
    EXPECT_EQ(r.whole.ssim, all.whole.ssim);
    EXPECT_TRUE(r.maps.flip.empty());
    EXPECT_TRUE(r.maps.absoluteDifference.empty());
    ASSERT_EQ(reportHeatmaps(r).size(), 1u);
    EXPECT_EQ(reportHeatmaps(r)[0].file(), "ssim.png");
    const nlohmann::json j = reportJson(r, {"t.exr", "r.exr", std::nullopt});
    EXPECT_TRUE(j.at("whole").contains("ssim"));
    for (const char* absent : {"flip", "flip_hdr", "rmse", "psnr_db"}) EXPECT_FALSE(j.at("whole").contains(absent)) << absent;
    EXPECT_FALSE(j.at("maps").contains("flip"));

    MetricOptions flipAndPsnr;
    flipAndPsnr.selection = {.ssim = false, .flip = true, .flipHdr = false, .rmse = false, .psnr = true};
    const MetricReport f = computeMetrics(test, reference, flipAndPsnr);
    EXPECT_EQ(f.whole.flip.mean, all.whole.flip.mean);
    EXPECT_EQ(f.whole.error.psnr, all.whole.error.psnr);
    EXPECT_TRUE(f.maps.ssim.empty());
    const nlohmann::json k = reportJson(f, {"t.exr", "r.exr", std::nullopt});
    EXPECT_TRUE(k.at("whole").contains("psnr_db"));
    EXPECT_FALSE(k.at("whole").contains("rmse"));
    EXPECT_FALSE(k.at("whole").contains("ssim"));
    EXPECT_EQ(reportHeatmaps(f).size(), 2u);  // diff.png (PSNR's difference) and flip.png
}

TEST(MetricReport, BadInputIsAnInputError) {
    const Image a(32, 32), b(32, 24);
    EXPECT_THROW(computeMetrics(a, b), InputError);
    const PixelMask wrongSize = PixelMask::everything(16, 16);
    EXPECT_THROW(computeMetrics(a, a, {}, &wrongSize), InputError);
    const PixelMask empty = PixelMask::fromImage(Image(32, 32, glm::vec4(0.5f, 0.5f, 0.5f, 1.0f)));  // 0.5 is not above 0.5
    EXPECT_EQ(empty.count(), 0u);
    EXPECT_THROW(computeMetrics(a, a, {}, &empty), InputError);
    EXPECT_THROW(computeMetrics(Image(10, 40), Image(10, 40)), InputError);  // narrower than SSIM's window
    try {
        computeMetrics(a, b);
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "the test image is 32x32 but the reference image is 32x24: the images compared must be the same size");
    }
}

TEST(MetricSeries, IsTheReportOfEachFrameWithoutMaps) {
    std::vector<Image> test, reference;
    for (int k = 0; k < 3; ++k) {
        reference.push_back(flatDisplay(16, 16, glm::vec3(0.5f)));
        test.push_back(flatDisplay(16, 16, glm::vec3(0.5f + 0.1f * static_cast<float>(k))));
    }
    const std::vector<MetricReport> series = metricSeries(test, reference);
    ASSERT_EQ(series.size(), 3u);
    for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(series[k].whole.error.rmse, computeMetrics(test[k], reference[k]).whole.error.rmse);
        EXPECT_TRUE(series[k].maps.flip.empty());
    }
    EXPECT_LT(series[2].whole.ssim, series[1].whole.ssim);
    EXPECT_THROW(metricSeries(test, {reference[0]}), InputError);
}

TEST(Heatmap, ColoursFollowTheColourMapAndTheLegendShowsTheRange) {
    cv::Mat1f samples(1, 4);
    samples << -1.0f, 0.0f, 0.5f, 2.0f;
    // OpenCV's viridis runs from (68, 1, 84) to (253, 231, 37); magma from (0, 0, 4) to (252, 253, 191).
    const Image viridis = colorize(samples, {0.0, 0.5}, ColorMap::Viridis);
    EXPECT_EQ(glm::round(glm::vec3(viridis.at(0, 0)) * 255.0f), glm::vec3(68, 1, 84));   // clamped below
    EXPECT_EQ(glm::round(glm::vec3(viridis.at(1, 0)) * 255.0f), glm::vec3(68, 1, 84));
    EXPECT_EQ(glm::round(glm::vec3(viridis.at(2, 0)) * 255.0f), glm::vec3(253, 231, 37));
    EXPECT_EQ(glm::round(glm::vec3(viridis.at(3, 0)) * 255.0f), glm::vec3(253, 231, 37));  // clamped above
    const Image magma = colorize(samples, {0.0, 0.5}, ColorMap::Magma);
    EXPECT_EQ(glm::round(glm::vec3(magma.at(1, 0)) * 255.0f), glm::vec3(0, 0, 4));
    EXPECT_EQ(glm::round(glm::vec3(magma.at(2, 0)) * 255.0f), glm::vec3(252, 253, 191));

    // The legend strip below the map.
    cv::Mat1f values(90, 160);
    cv::randu(values, 0.0f, 1.0f);
    const Image map = colorize(values, {0.0, 1.0}, ColorMap::Magma);
    const Image withLegend = heatmapWithLegend(values, {0.0, 1.0}, ColorMap::Magma, "FLIP");
    ASSERT_EQ(withLegend.width(), 160);
    ASSERT_EQ(withLegend.height(), 90 + legendHeight(160));
    for (int y = 0; y < 90; ++y) {
        for (int x = 0; x < 160; ++x) ASSERT_EQ(withLegend.at(x, y), map.at(x, y));
    }
    // The strip has the colour bar, ending in the map's top colour, and white (anti-aliased) text.
    bool topColour = false, text = false;
    for (int y = 90; y < withLegend.height(); ++y) {
        for (int x = 0; x < 160; ++x) {
            const glm::vec3 c = glm::round(glm::vec3(withLegend.at(x, y)) * 255.0f);
            topColour = topColour || c == glm::vec3(252, 253, 191);
            text = text || (c.r > 160.0f && c.r == c.g && c.g == c.b);
        }
    }
    EXPECT_TRUE(topColour);
    EXPECT_TRUE(text);
}

}  // namespace
}  // namespace hybridlab
