#include "experiments/runner/resolution_scale.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <tuple>
#include <utility>

#include "common/core/input_error.h"

namespace hybridlab {

double parseResolutionScale(const std::string& text) {
    // strtod alone would take "0.25abc", " 0.25", "nan" and "inf".
    char* end = nullptr;
    const double scale = text.empty() || std::isspace(static_cast<unsigned char>(text[0])) ? 0.0 : std::strtod(text.c_str(), &end);
    const bool number = end && end != text.c_str() && *end == '\0' && std::isfinite(scale);
    if (!number || !(scale > 0.0) || scale > 1.0) {
        throw InputError("--scale " + text + ": expected a number greater than 0 and at most 1 (the fraction of every configured " +
                         "resolution to render at, e.g. 0.25 for 1280x720 at 320x180)");
    }
    return scale;
}

int scaledSide(int side, double scale) {
    constexpr int kMinimumSide = 16;
    const int even = 2 * static_cast<int>(std::lround(0.5 * side * scale));
    return std::min(side, std::max(even, kMinimumSide));
}

std::string formatScale(double scale) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", scale);
    if (std::strtod(text, nullptr) != scale) std::snprintf(text, sizeof text, "%.17g", scale);
    return text;
}

namespace {
std::string sizeText(std::pair<int, int> size) { return std::to_string(size.first) + "x" + std::to_string(size.second); }
}  // namespace

void scaleResolutions(ExperimentConfig& config, double scale) {
    config.resolutionScale = scale;
    if (scale == 1.0) return;
    for (SceneSpec& scene : config.scenes) {
        std::map<std::pair<int, int>, std::pair<int, int>> configured;  // scaled size -> the size configured
        for (auto& [w, h] : scene.resolutions) {
            const std::pair<int, int> size{scaledSide(w, scale), scaledSide(h, scale)};
            if (const auto [first, added] = configured.emplace(size, std::make_pair(w, h)); !added)
                throw InputError(config.file.string() + ": --scale " + formatScale(scale) + " makes " + sizeText(first->second) + " and " +
                                 sizeText({w, h}) + " of scene '" + scene.name + "' both " + sizeText(size) +
                                 ": every run of them would be rendered twice (list one of them)");
            std::tie(w, h) = size;
        }
    }
}

}  // namespace hybridlab
