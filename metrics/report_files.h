#pragma once
// A metric report as files: the error maps as PNG heat maps with legends, and the numbers as JSON.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "metrics/heatmap.h"
#include "metrics/metrics.h"

namespace hybridlab {

// Where the compared images came from, for the record.
struct ReportSources {
    std::string test;
    std::string reference;
    std::optional<std::string> mask;
};

// One heat map of a report: its name (the metric's key, or "diff"), colour map and range.
struct HeatmapSpec {
    std::string name;
    std::string title;
    ColorMap colorMap;
    LegendRange range;
    const cv::Mat1f* values;

    std::string file() const { return name + ".png"; }
};

// diff.png (|test - reference|, viridis, 0 to `differenceHigh`, by default the largest difference),
// and the map of each selected metric that has one, as metric_table.h colours it (ssim.png,
// flip.png, flip_hdr.png). A fixed `differenceHigh` lets the maps of several
// tests against one reference be read on one scale.
std::vector<HeatmapSpec> reportHeatmaps(const MetricReport& report, std::optional<double> differenceHigh = std::nullopt);

// The largest |test - reference| of a report's difference map (0 for equal images).
double largestDifference(const MetricReport& report);

// The numbers: sources, size, settings, whole-image (and masked) metrics, the maps' files and
// ranges. An infinite PSNR (equal images) is written as null, which JSON has for it.
nlohmann::json reportJson(const MetricReport& report, const ReportSources& sources, std::optional<double> differenceHigh = std::nullopt);

// Writes the heat maps and metrics.json into `dir` (created if missing). Each file is written to
// a temporary name beside it and renamed, so no half-written file is ever left.
void writeReportFiles(const std::filesystem::path& dir, const MetricReport& report, const ReportSources& sources,
                      std::optional<double> differenceHigh = std::nullopt);

}  // namespace hybridlab
