#include "metrics/report_files.h"

#include <cmath>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <system_error>

#include "common/core/atomic_file.h"
#include "common/image/image_io.h"
#include "metrics/parallel_tasks.h"

namespace hybridlab {

namespace fs = std::filesystem;

namespace {

nlohmann::json numberOrNull(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json regionJson(const RegionMetrics& m, const MetricSelection& chosen) {
    nlohmann::json j = {{"pixels", m.pixels}};
    if (chosen.ssim) j["ssim"] = m.ssim;
    if (chosen.rmse) j["rmse"] = m.error.rmse;
    if (chosen.psnr) j["psnr_db"] = numberOrNull(m.error.psnr);
    if (chosen.flip) {
        j["flip"] = {{"mean", m.flip.mean},
                     {"weighted_median", m.flip.weightedMedian},
                     {"weighted_first_quartile", m.flip.weightedFirstQuartile},
                     {"weighted_third_quartile", m.flip.weightedThirdQuartile}};
    }
    if (chosen.flipHdr) {
        j["flip_hdr"] = {{"mean", m.flipHdr.mean},
                         {"weighted_median", m.flipHdr.weightedMedian},
                         {"weighted_first_quartile", m.flipHdr.weightedFirstQuartile},
                         {"weighted_third_quartile", m.flipHdr.weightedThirdQuartile}};
    }
    for (const auto& [key, value] : m.added) j[key] = numberOrNull(value);
    return j;
}

}  // namespace

double largestDifference(const MetricReport& report) {
    double largest = 0.0;
    if (!report.maps.absoluteDifference.empty()) cv::minMaxLoc(report.maps.absoluteDifference, nullptr, &largest);
    return largest;
}

std::vector<HeatmapSpec> reportHeatmaps(const MetricReport& report, std::optional<double> differenceHigh) {
    const MetricSelection& chosen = report.options.selection;
    std::vector<HeatmapSpec> maps;
    if (chosen.error()) {
        const double high = differenceHigh.value_or(largestDifference(report));
        // A legend from 0 to 0 says nothing; equal images show the bottom colour on 0 to 1.
        maps.push_back({"diff", "|T-R|", ColorMap::Viridis, {0.0, high > 0.0 ? high : 1.0}, &report.maps.absoluteDifference});
    }
    // Each metric of the table that has a map, in the table's colours and range.
    const auto values = [&](std::string_view key) -> const cv::Mat1f* {
        if (key == "ssim") return &report.maps.ssim;
        if (key == "flip") return &report.maps.flip;
        if (key == "flip_hdr") return &report.maps.flipHdr;
        return nullptr;
    };
    for (const MetricDefinition& m : kMetricTable) {
        if (!*m.colorMap || !chosen.chosen(m.key)) continue;
        maps.push_back({m.key, m.label, colorMapNamed(m.colorMap), {m.low, m.high}, values(m.key)});
    }
    return maps;
}

nlohmann::json reportJson(const MetricReport& report, const ReportSources& sources, std::optional<double> differenceHigh) {
    nlohmann::json j;
    j["test"] = sources.test;
    j["reference"] = sources.reference;
    j["mask"] = sources.mask ? nlohmann::json(*sources.mask) : nlohmann::json(nullptr);
    j["width"] = report.width;
    j["height"] = report.height;
    j["settings"] = {
        {"error_space", valueSpaceName(report.options.errorSpace)},
        {"ssim_channels", ssimChannelsName(report.options.ssimChannels)},
        {"flip_pixels_per_degree", report.options.pixelsPerDegree},
    };
    j["whole"] = regionJson(report.whole, report.options.selection);
    j["masked"] = report.masked ? regionJson(*report.masked, report.options.selection) : nlohmann::json(nullptr);
    nlohmann::json maps = nlohmann::json::object();
    for (const HeatmapSpec& h : reportHeatmaps(report, differenceHigh)) {
        maps[h.name] = {
            {"file", h.file()}, {"colormap", colorMapName(h.colorMap)}, {"range", {h.range.low, h.range.high}}};
    }
    j["maps"] = maps;
    return j;
}

void writeReportFiles(const fs::path& dir, const MetricReport& report, const ReportSources& sources, std::optional<double> differenceHigh) {
    createDirectories(dir);
    std::vector<std::function<void()>> maps;
    for (const HeatmapSpec& h : reportHeatmaps(report, differenceHigh)) {
        maps.push_back([&dir, h] { writePng(dir / h.file(), heatmapWithLegend(*h.values, h.range, h.colorMap, h.title)); });
    }
    runInParallel(maps);  // each PNG's encoding is serial
    const std::string text = reportJson(report, sources, differenceHigh).dump(2) + "\n";
    writeFileAtomically(dir / "metrics.json", text);
}

}  // namespace hybridlab
