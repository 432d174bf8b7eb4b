#pragma once
// Error maps as pictures: a perceptually uniform colour map (OpenCV's viridis or magma) over a
// stated value range, with a legend strip below the map that shows the colour bar and the range,
// for the viewer and the report.
#include <string>
#include <string_view>

#include <opencv2/core.hpp>

#include "common/image/image.h"

namespace hybridlab {

enum class ColorMap { Viridis, Magma };

const char* colorMapName(ColorMap map);
// The colour map colorMapName calls `name`; throws std::out_of_range for another name.
ColorMap colorMapNamed(std::string_view name);

// The values shown from the first colour of the map (low) to the last (high); values outside
// are clamped.
struct LegendRange {
    double low = 0.0;
    double high = 1.0;
};

// The colours of `values`: display RGB in [0, 1] (write it with writePng, no transfer function),
// alpha 1, the same size as `values`.
Image colorize(const cv::Mat1f& values, LegendRange range, ColorMap map);

// Height in pixels of the legend strip that heatmapWithLegend adds below a map `width` wide.
int legendHeight(int width);

// colorize(values) with a legend strip below it: `title`, the low value, the colour bar from low
// to high, the high value.
Image heatmapWithLegend(const cv::Mat1f& values, LegendRange range, ColorMap map, const std::string& title);

}  // namespace hybridlab
