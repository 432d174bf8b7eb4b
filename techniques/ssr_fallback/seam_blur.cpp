#include "techniques/ssr_fallback/seam_blur.h"

#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace hybridlab {

namespace {

// One direction of a separable dilation: out[i] is set where `in` is set within `radius` texels
// along x (dx = 1) or y (dx = 0).
std::vector<std::uint8_t> dilate(const std::vector<std::uint8_t>& in, int width, int height, int radius, bool alongX) {
    std::vector<std::uint8_t> out(in.size(), 0);
    tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y) {
            for (int x = 0; x < width; ++x) {
                const int lo = std::max(0, (alongX ? x : y) - radius), hi = std::min((alongX ? width : height) - 1, (alongX ? x : y) + radius);
                for (int k = lo; k <= hi; ++k) {
                    if (in[alongX ? static_cast<std::size_t>(y) * width + k : static_cast<std::size_t>(k) * width + x]) {
                        out[static_cast<std::size_t>(y) * width + x] = 1;
                        break;
                    }
                }
            }
        }
    });
    return out;
}

// c / (1 + c) per channel: colour differences on a bounded scale, whatever the radiance.
glm::vec3 compressed(const glm::vec3& c) { return c / (glm::vec3(1.0f) + glm::max(c, glm::vec3(0.0f))); }

}  // namespace

std::size_t blurReflectionSeams(std::vector<glm::vec3>& reflection, const std::vector<ReflectionSource>& source, int width, int height,
                                int radius, float rangeSigma) {
    if (radius <= 0) return 0;
    auto at = [width](int x, int y) { return static_cast<std::size_t>(y) * width + x; };
    // The seam: reflecting texels with a reflecting 4-neighbour from another path. With it, the range
    // kernel's colours, once per reflecting texel rather than once per window it falls in.
    std::vector<std::uint8_t> seam(source.size(), 0);
    std::vector<glm::vec3> range(rangeSigma > 0.0f ? reflection.size() : 0);
    tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y) {
            for (int x = 0; x < width; ++x) {
                const ReflectionSource s = source[at(x, y)];
                if (s == ReflectionSource::None) continue;
                auto differs = [&](int nx, int ny) {
                    if (nx < 0 || ny < 0 || nx >= width || ny >= height) return false;
                    const ReflectionSource n = source[at(nx, ny)];
                    return n != ReflectionSource::None && n != s;
                };
                seam[at(x, y)] = differs(x + 1, y) || differs(x - 1, y) || differs(x, y + 1) || differs(x, y - 1);
                if (!range.empty()) range[at(x, y)] = compressed(reflection[at(x, y)]);
            }
        }
    });
    const std::vector<std::uint8_t> band = dilate(dilate(seam, width, height, radius, true), width, height, radius, false);

    const float sigma = 0.5f * static_cast<float>(radius);
    std::vector<float> kernel(2 * radius + 1);
    for (int k = -radius; k <= radius; ++k) kernel[k + radius] = std::exp(-0.5f * k * k / (sigma * sigma));
    const std::vector<glm::vec3> input = reflection;
    std::vector<std::size_t> blurredPerRow(height, 0);
    tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y) {
            for (int x = 0; x < width; ++x) {
                if (!band[at(x, y)] || source[at(x, y)] == ReflectionSource::None) continue;
                glm::vec3 sum(0.0f);
                float weight = 0.0f;
                for (int dy = -radius; dy <= radius; ++dy) {
                    const int ny = y + dy;
                    if (ny < 0 || ny >= height) continue;
                    for (int dx = -radius; dx <= radius; ++dx) {
                        const int nx = x + dx;
                        if (nx < 0 || nx >= width || source[at(nx, ny)] == ReflectionSource::None) continue;
                        float w = kernel[dx + radius] * kernel[dy + radius];
                        if (rangeSigma > 0.0f) {
                            const glm::vec3 d = range[at(nx, ny)] - range[at(x, y)];
                            w *= std::exp(-0.5f * glm::dot(d, d) / (rangeSigma * rangeSigma));
                        }
                        sum += w * input[at(nx, ny)];
                        weight += w;
                    }
                }
                reflection[at(x, y)] = sum / weight;
                ++blurredPerRow[y];
            }
        }
    });
    std::size_t blurred = 0;
    for (std::size_t n : blurredPerRow) blurred += n;
    return blurred;
}

}  // namespace hybridlab
