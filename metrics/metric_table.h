#pragma once
// The metric vocabulary: every score of an image against its reference, declared once with what
// its readers need to show it (name, direction, range, error map's colours), as
// techniques/stage_names.h declares the stages. The runner writes the table into each result set
// (experiment.json's "metric_table"), and the report, the paper tables and the viewer loop over
// it; report/results.py reads kMetricTable below (one {...} a line) for result sets written before
// they carried it.
#include <functional>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

namespace hybridlab {

enum class Better { Higher, Lower };

inline constexpr double kUnbounded = std::numeric_limits<double>::infinity();

struct MetricDefinition {
    const char* key;       // the config's `metrics` name, and its error map's name
    const char* label;     // what tables and read-outs call it
    Better better;
    double low, high;      // the range of its values (high may be kUnbounded)
    const char* field;     // where a region's value lies in a record's metrics: "ssim", "flip.mean"
    const char* colorMap;  // its error map's colour map (heatmap.h's names); "" without a map
    bool scored;           // the verdict ranks settings by it; the others are shown beside
    bool summarised;       // the summary and verdict tables show it (each run's row shows every one)
    int digits;            // decimals a table shows
    double cost;           // scoring a pixel, relative to SSIM (the shards' estimated costs)
};

// In the order tables list them. FLIP on the display images and HDR-FLIP (Andersson et al. 2021)
// on the linear ones are told apart wherever both are shown; HDR-FLIP is several LDR-FLIPs (one
// per exposure), RMSE and PSNR a subtraction.
inline constexpr MetricDefinition kMetricTable[] = {
    {"ssim", "SSIM", Better::Higher, 0.0, 1.0, "ssim", "viridis", true, true, 4, 1.0},
    {"flip", "FLIP (LDR)", Better::Lower, 0.0, 1.0, "flip.mean", "magma", true, true, 4, 2.0},
    {"flip_hdr", "HDR-FLIP", Better::Lower, 0.0, 1.0, "flip_hdr.mean", "magma", false, true, 4, 5.0},
    {"rmse", "RMSE", Better::Lower, 0.0, kUnbounded, "rmse", "", false, false, 4, 0.0},
    {"psnr", "PSNR dB", Better::Higher, 0.0, kUnbounded, "psnr_db", "", false, false, 2, 0.0},
};

// A metric added at run time by its definition and its value over a region of the display images
// (`region`: null for the whole image): a new score in one place, which tests use to hold every
// reader to the table. Its field is its key; it has no error map and is computed whenever images
// are scored.
struct AddedMetric {
    MetricDefinition definition;
    std::function<double(const cv::Mat3f& test, const cv::Mat3f& reference, const cv::Mat1b* region)> value;
};

// Adds `metric` to metricTable() until the returned guard is destroyed.
class AddedMetricScope {
public:
    explicit AddedMetricScope(AddedMetric metric);
    ~AddedMetricScope();
    AddedMetricScope(const AddedMetricScope&) = delete;
    AddedMetricScope& operator=(const AddedMetricScope&) = delete;

private:
    std::string key_;
};

// kMetricTable, then the metrics added.
std::vector<MetricDefinition> metricTable();
const std::vector<AddedMetric>& addedMetrics();

// The table as a result set carries it: [{"key", "label", "better": "higher"|"lower", "range":
// [low, high or null], "field", "colormap": name or null, "scored", "summarised", "digits"}, ...].
nlohmann::json metricTableJson();

}  // namespace hybridlab
