#include "metrics/metric_table.h"

#include <algorithm>
#include <cmath>

namespace hybridlab {

namespace {

std::vector<AddedMetric>& added() {
    static std::vector<AddedMetric> metrics;
    return metrics;
}

}  // namespace

AddedMetricScope::AddedMetricScope(AddedMetric metric) : key_(metric.definition.key) {
    metric.definition.field = metric.definition.key;
    metric.definition.colorMap = "";
    metric.definition.cost = 0.0;
    added().push_back(std::move(metric));
}

AddedMetricScope::~AddedMetricScope() {
    std::erase_if(added(), [&](const AddedMetric& m) { return m.definition.key == key_; });
}

const std::vector<AddedMetric>& addedMetrics() { return added(); }

std::vector<MetricDefinition> metricTable() {
    std::vector<MetricDefinition> table(std::begin(kMetricTable), std::end(kMetricTable));
    for (const AddedMetric& m : added()) table.push_back(m.definition);
    return table;
}

nlohmann::json metricTableJson() {
    nlohmann::json table = nlohmann::json::array();
    const auto bound = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
    for (const MetricDefinition& m : metricTable()) {
        table.push_back({{"key", m.key},
                         {"label", m.label},
                         {"better", m.better == Better::Higher ? "higher" : "lower"},
                         {"range", {bound(m.low), bound(m.high)}},
                         {"field", m.field},
                         {"colormap", *m.colorMap ? nlohmann::json(m.colorMap) : nlohmann::json(nullptr)},
                         {"scored", m.scored},
                         {"summarised", m.summarised},
                         {"digits", m.digits}});
    }
    return table;
}

}  // namespace hybridlab
