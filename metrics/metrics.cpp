#include "metrics/metrics.h"

#include <stdexcept>
#include <string>

#include "common/core/input_error.h"

namespace hybridlab {

namespace {

// `test` and `reference` in the error space; `displayTest` and `displayReference` the display images.
RegionMetrics regionMetrics(const cv::Mat3f& test, const cv::Mat3f& reference, const cv::Mat3f& displayTest, const cv::Mat3f& displayReference,
                            const MetricMaps& maps, const cv::Mat1b* region, const MetricSelection& selection) {
    RegionMetrics m;
    m.pixels = region ? static_cast<std::size_t>(cv::countNonZero(*region)) : test.total();
    if (selection.ssim) m.ssim = ssimMean(maps.ssim, region);
    if (selection.error()) m.error = errorStats(test, reference, region);
    if (selection.flip) m.flip = flipStats(maps.flip, region);
    if (selection.flipHdr) m.flipHdr = flipStats(maps.flipHdr, region);
    for (const AddedMetric& a : addedMetrics()) m.added[a.definition.key] = a.value(displayTest, displayReference, region);
    return m;
}

}  // namespace

bool& MetricSelection::chosen(std::string_view key) {
    if (key == "ssim") return ssim;
    if (key == "flip") return flip;
    if (key == "flip_hdr") return flipHdr;
    if (key == "rmse") return rmse;
    if (key == "psnr") return psnr;
    throw std::out_of_range("no metric flag named '" + std::string(key) + "'");
}

MetricReport computeMetrics(const Image& test, const Image& reference, const MetricOptions& options, const PixelMask* mask) {
    requireSameSize(test, "the test image", reference, "the reference image");
    if (mask) requireUsableMask(*mask, "the mask", test.width(), test.height());
    MetricReport report;
    report.width = test.width();
    report.height = test.height();
    report.options = options;

    const cv::Mat3f displayTest = metricRgb(test, ValueSpace::Display), displayReference = metricRgb(reference, ValueSpace::Display);
    // Linear-light copies only for the error metrics that read them.
    const bool linear = options.errorSpace == ValueSpace::Linear && options.selection.error();
    const cv::Mat3f errorTest = linear ? metricRgb(test, ValueSpace::Linear) : displayTest;
    const cv::Mat3f errorReference = linear ? metricRgb(reference, ValueSpace::Linear) : displayReference;

    const MetricSelection& chosen = options.selection;
    if (chosen.ssim) report.maps.ssim = ssimMap(displayTest, displayReference, options.ssimChannels);
    if (chosen.flip) report.maps.flip = flipMap(displayTest, displayReference, options.pixelsPerDegree);
    if (chosen.flipHdr) {
        report.maps.flipHdr = hdrFlipMap(metricRgb(test, ValueSpace::Linear), metricRgb(reference, ValueSpace::Linear), options.pixelsPerDegree);
    }
    if (chosen.error()) report.maps.absoluteDifference = absoluteDifferenceMap(errorTest, errorReference);

    report.whole = regionMetrics(errorTest, errorReference, displayTest, displayReference, report.maps, nullptr, chosen);
    if (mask) report.masked = regionMetrics(errorTest, errorReference, displayTest, displayReference, report.maps, &mask->pixels(), chosen);
    return report;
}

std::vector<MetricReport> metricSeries(const std::vector<Image>& test, const std::vector<Image>& reference, const MetricOptions& options,
                                       const PixelMask* mask) {
    if (test.size() != reference.size()) {
        throw InputError("metric series: " + std::to_string(test.size()) + " test frames but " + std::to_string(reference.size()) +
                         " reference frames");
    }
    std::vector<MetricReport> series;
    for (std::size_t k = 0; k < test.size(); ++k) {
        MetricReport report = computeMetrics(test[k], reference[k], options, mask);
        report.maps = MetricMaps{};
        series.push_back(std::move(report));
    }
    return series;
}

}  // namespace hybridlab
