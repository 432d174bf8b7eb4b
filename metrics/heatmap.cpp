#include "metrics/heatmap.h"

#include <stdexcept>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <opencv2/imgproc.hpp>

namespace hybridlab {

const char* colorMapName(ColorMap map) { return map == ColorMap::Viridis ? "viridis" : "magma"; }

ColorMap colorMapNamed(std::string_view name) {
    for (ColorMap map : {ColorMap::Viridis, ColorMap::Magma})
        if (name == colorMapName(map)) return map;
    throw std::out_of_range("no colour map named '" + std::string(name) + "'");
}

namespace {

int openCvColorMap(ColorMap map) { return map == ColorMap::Viridis ? cv::COLORMAP_VIRIDIS : cv::COLORMAP_MAGMA; }

// The colour map's index, 0..255, of each value.
cv::Mat1b mapIndices(const cv::Mat1f& values, LegendRange range) {
    cv::Mat1b indices(values.size());
    const double span = range.high > range.low ? range.high - range.low : 1.0;
    for (int y = 0; y < values.rows; ++y) {
        for (int x = 0; x < values.cols; ++x) {
            const double t = (static_cast<double>(values(y, x)) - range.low) / span;
            indices(y, x) = std::isnan(t) ? 0 : static_cast<uchar>(std::lround(std::clamp(t, 0.0, 1.0) * 255.0));
        }
    }
    return indices;
}

// BGR as OpenCV draws it.
cv::Mat3b colorizeBgr(const cv::Mat1f& values, LegendRange range, ColorMap map) {
    cv::Mat3b bgr;
    cv::applyColorMap(mapIndices(values, range), bgr, openCvColorMap(map));
    return bgr;
}

Image toImage(const cv::Mat3b& bgr) {
    Image image(bgr.cols, bgr.rows);
    for (int y = 0; y < bgr.rows; ++y) {
        for (int x = 0; x < bgr.cols; ++x) {
            const cv::Vec3b& c = bgr(y, x);
            image.at(x, y) = glm::vec4(c[2] / 255.0f, c[1] / 255.0f, c[0] / 255.0f, 1.0f);
        }
    }
    return image;
}

std::string formatValue(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", v);
    return text;
}

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
double fontScale(int width) { return width >= 640 ? 0.5 : 0.35; }

// Draws `title  low [colour bar] high` into the strip; parts that do not fit are left out, the bar
// last of all.
void drawLegend(cv::Mat3b& strip, LegendRange range, ColorMap map, const std::string& title) {
    strip.setTo(cv::Scalar(0, 0, 0));
    const double scale = fontScale(strip.cols);
    const int margin = 4, gap = 6;
    auto textWidth = [&](const std::string& s) {
        int baseline = 0;
        return cv::getTextSize(s, kFont, scale, 1, &baseline).width;
    };
    const std::string low = formatValue(range.low), high = formatValue(range.high);
    const int minBar = 16;
    bool showTitle = !title.empty(), showValues = true;
    auto barWidth = [&] {
        int used = 2 * margin;
        if (showTitle) used += textWidth(title) + gap;
        if (showValues) used += textWidth(low) + textWidth(high) + 2 * gap;
        return strip.cols - used;
    };
    if (barWidth() < minBar) showTitle = false;
    if (barWidth() < minBar) showValues = false;
    int baseline = 0;
    const int textHeight = cv::getTextSize("0", kFont, scale, 1, &baseline).height;
    const int textY = (strip.rows + textHeight) / 2;
    const cv::Scalar white(255, 255, 255);
    int x = margin;
    if (showTitle) {
        cv::putText(strip, title, {x, textY}, kFont, scale, white, 1, cv::LINE_AA);
        x += textWidth(title) + gap;
    }
    if (showValues) {
        cv::putText(strip, low, {x, textY}, kFont, scale, white, 1, cv::LINE_AA);
        x += textWidth(low) + gap;
    }
    const int bar = std::max(1, barWidth());
    const int barTop = strip.rows / 4, barHeight = std::max(1, strip.rows - 2 * barTop);
    cv::Mat1f ramp(barHeight, bar);
    for (int i = 0; i < bar; ++i) {
        ramp.col(i).setTo(bar > 1 ? range.low + (range.high - range.low) * i / (bar - 1.0) : range.high);
    }
    const cv::Rect barRect(x, barTop, std::min(bar, strip.cols - x), barHeight);
    colorizeBgr(ramp, range, map)(cv::Rect(0, 0, barRect.width, barRect.height)).copyTo(strip(barRect));
    if (showValues) cv::putText(strip, high, {x + bar + gap, textY}, kFont, scale, white, 1, cv::LINE_AA);
}

}  // namespace

Image colorize(const cv::Mat1f& values, LegendRange range, ColorMap map) { return toImage(colorizeBgr(values, range, map)); }

int legendHeight(int width) { return width >= 640 ? 28 : 18; }

Image heatmapWithLegend(const cv::Mat1f& values, LegendRange range, ColorMap map, const std::string& title) {
    cv::Mat3b canvas(values.rows + legendHeight(values.cols), values.cols);
    colorizeBgr(values, range, map).copyTo(canvas(cv::Rect(0, 0, values.cols, values.rows)));
    cv::Mat3b strip = canvas(cv::Rect(0, values.rows, values.cols, canvas.rows - values.rows));
    drawLegend(strip, range, map, title);
    return toImage(canvas);
}

}  // namespace hybridlab
