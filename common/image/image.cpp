#include "common/image/image.h"

namespace hybridlab {

Image::Image(int width, int height, glm::vec4 fill)
    : width_(width), height_(height),
      pixels_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), fill) {}

}  // namespace hybridlab
