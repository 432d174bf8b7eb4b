#include "common/image/non_finite_pixels.h"

#include <sstream>

#include "common/core/input_error.h"

namespace hybridlab {

NonFinitePixels findNonFinite(const Image& image) {
    NonFinitePixels found;
    for (int y = 0; y < image.height(); ++y) {
        for (int x = 0; x < image.width(); ++x) {
            const glm::vec4& c = image.at(x, y);
            if (isFinitePixel(c)) continue;
            if (found.count++ == 0) found.x = x, found.y = y, found.value = c;
        }
    }
    return found;
}

std::string NonFinitePixels::description(const char* pixelWord) const {
    if (count == 0) return {};
    std::ostringstream s;
    s << count << " non-finite " << pixelWord << (count == 1 ? "" : "s") << " (NaN or infinite), the first at (" << x << ", " << y
      << "): (" << value.r << ", " << value.g << ", " << value.b << ", " << value.a << ")";
    return s.str();
}

void requireFiniteTexels(const Image& image, const std::string& name) {
    const NonFinitePixels found = findNonFinite(image);
    if (found.count > 0) throw InputError(name + ": " + found.description("texel") + "; a texture must hold finite values");
}

std::size_t blackOutNonFinite(Image& test, Image& reference) {
    std::size_t changed = 0;
    for (std::size_t i = 0; i < test.pixelCount() && i < reference.pixelCount(); ++i) {
        if (isFinitePixel(test.data()[i]) && isFinitePixel(reference.data()[i])) continue;
        test.data()[i] = reference.data()[i] = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
        ++changed;
    }
    return changed;
}

}  // namespace hybridlab
