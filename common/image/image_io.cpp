#include "common/image/image_io.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <system_error>
#include <vector>

#include <glm/common.hpp>
#include <glm/exponential.hpp>

#include "common/core/atomic_file.h"
#include "common/core/input_error.h"
#include "common/core/input_file.h"
#include "common/core/number_check.h"
#include "common/image/color.h"
#include "common/image/image_codecs.h"
#include "common/image/non_finite_pixels.h"

namespace hybridlab {
namespace fs = std::filesystem;

namespace {

// The transfer function of integer channels: none (linear), sRGB, or a power `gamma`.
struct Transfer {
    enum class Kind { Linear, Srgb, Power } kind = Transfer::Kind::Linear;
    float gamma = 1.0f;
    std::string description;
};

Transfer transferOf(const DecodedImage& image, ColorEncoding decode) {
    if (!image.integer) return {Transfer::Kind::Linear, 1.0f, "linear (floating point)"};
    if (decode == ColorEncoding::Linear) return {Transfer::Kind::Linear, 1.0f, "as stored"};
    if (decode == ColorEncoding::Srgb) return {Transfer::Kind::Srgb, 1.0f, "sRGB"};
    const ColorTag& tag = image.tag;
    switch (tag.kind) {
    case ColorTag::Kind::Linear: return {Transfer::Kind::Linear, 1.0f, "linear (colour-space metadata: " + tag.source + ")"};
    case ColorTag::Kind::Srgb: return {Transfer::Kind::Srgb, 1.0f, "sRGB (colour-space metadata: " + tag.source + ")"};
    case ColorTag::Kind::Gamma: {
        char text[96];
        std::snprintf(text, sizeof text, "gamma %.4g (colour-space metadata: %s)", tag.gamma, tag.source.c_str());
        return {Transfer::Kind::Power, tag.gamma, text};
    }
    case ColorTag::Kind::Unrecognised:
        return {Transfer::Kind::Srgb, 1.0f, "sRGB (unrecognised colour-space metadata: " + tag.source + ")"};
    case ColorTag::Kind::None: break;
    }
    return {Transfer::Kind::Srgb, 1.0f, "sRGB (no colour-space metadata)"};
}

Image toImage(const DecodedImage& decoded, ColorEncoding decode, std::string* assumed) {
    const int w = decoded.header.width, h = decoded.header.height, nc = decoded.header.channels;
    const Transfer transfer = transferOf(decoded, decode);
    if (assumed) *assumed = transfer.description;
    Image img(w, h);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const float* p = &decoded.values[(static_cast<std::size_t>(y) * w + x) * nc];
            glm::vec4 c(0.0f, 0.0f, 0.0f, 1.0f);
            if (nc < 3) {
                c.r = c.g = c.b = p[0];
                if (nc == 2) c.a = p[1];
            } else {
                c.r = p[0], c.g = p[1], c.b = p[2];
                if (nc > 3) c.a = p[3];
            }
            if (transfer.kind == Transfer::Kind::Srgb) c = glm::vec4(srgbToLinear(glm::vec3(c)), c.a);
            else if (transfer.kind == Transfer::Kind::Power) c = glm::vec4(glm::pow(glm::vec3(c), glm::vec3(transfer.gamma)), c.a);
            img.at(x, y) = c;
        }
    }
    return img;
}

// Checks a header against the limits; `name` for messages.
void checkHeader(const ImageHeader& h, const std::string& name) {
    if (h.width <= 0 || h.height <= 0 || h.channels <= 0) throw InputError(name + ": image has no pixels");
    if (h.width > limits::kImageSide || h.height > limits::kImageSide)
        throw InputError(name + ": image of " + std::to_string(h.width) + "x" + std::to_string(h.height) +
                         " pixels exceeds the limit of " + std::to_string(limits::kImageSide) + " a side");
}

ImageHeader readHeader(ImageFormat format, const unsigned char* bytes, std::size_t size) {
    switch (format) {
    case ImageFormat::Exr: return readExrHeader(bytes, size);
    case ImageFormat::Png: return readPngHeader(bytes, size);
    case ImageFormat::Jpeg: return readJpegHeader(bytes, size);
    case ImageFormat::OpenImageIo: return readOpenImageIoHeader(bytes, size);
    case ImageFormat::Other: break;
    }
    return readStbHeader(bytes, size);
}

// Reads the header of an image of `format` and checks it against the limits.
ImageHeader checkReadableHeader(ImageFormat format, const unsigned char* bytes, std::size_t size, const std::string& name) {
    try {
        const ImageHeader header = readHeader(format, bytes, size);
        checkHeader(header, name);
        return header;
    } catch (const ImageCodecError& e) {
        throw InputError(name + ": cannot read image (" + e.what() + ")");
    }
}

// The header is checked before the pixels are decoded, so that a header claiming a huge image is
// refused without the allocation.
Image decode(const unsigned char* bytes, std::size_t size, const std::string& name, ColorEncoding decode, std::string* assumed) {
    const ImageFormat format = imageFormatOf(bytes, size);
    checkReadableHeader(format, bytes, size, name);
    DecodedImage decoded;
    try {
        switch (format) {
        case ImageFormat::Exr: decoded = decodeExr(bytes, size); break;
        case ImageFormat::Png: decoded = decodePng(bytes, size); break;
        case ImageFormat::Jpeg: decoded = decodeJpeg(bytes, size); break;
        case ImageFormat::OpenImageIo: decoded = decodeOpenImageIo(bytes, size); break;
        case ImageFormat::Other: decoded = decodeStb(bytes, size); break;
        }
    } catch (const ImageCodecError& e) {
        throw InputError(name + ": cannot decode image (" + e.what() + ")");
    }
    checkHeader(decoded.header, name);
    const std::size_t expected = static_cast<std::size_t>(decoded.header.width) * decoded.header.height * decoded.header.channels;
    if (decoded.values.size() != expected) throw InputError(name + ": cannot decode image (fewer pixels than its header states)");
    return toImage(decoded, decode, assumed);
}

// The file's bytes: a regular file (a device or a pipe, /dev/zero, would never end).
std::string readImageBytes(const fs::path& path) {
    if (inputPathKind(path) == InputPathKind::Missing) throw InputError(path.string() + ": image file not found");
    return readInputFile(path, "an image file");
}

const unsigned char* unsignedBytes(const std::string& bytes) { return reinterpret_cast<const unsigned char*>(bytes.data()); }

}  // namespace

Image readImage(const fs::path& path, ColorEncoding decode, std::string* assumed) {
    const std::string bytes = readImageBytes(path);
    return hybridlab::decode(unsignedBytes(bytes), bytes.size(), path.string(), decode, assumed);
}

ImageSize checkImageFile(const fs::path& path, bool requireFinite) {
    const std::string bytes = readImageBytes(path);
    const ImageFormat format = imageFormatOf(unsignedBytes(bytes), bytes.size());
    const ImageHeader header = checkReadableHeader(format, unsignedBytes(bytes), bytes.size(), path.string());
    if (requireFinite && format == ImageFormat::Exr)
        requireFiniteTexels(hybridlab::decode(unsignedBytes(bytes), bytes.size(), path.string(), ColorEncoding::Linear, nullptr), path.string());
    return {header.width, header.height};
}

Image readImageFromMemory(const unsigned char* bytes, std::size_t size, const std::string& name, ColorEncoding decode) {
    return hybridlab::decode(bytes, size, name, decode, nullptr);
}

namespace {

// Encodes into memory, so that the bytes reach the disk through writeFileAtomically, which checks
// every step.
void writeBytes(const fs::path& path, const std::vector<unsigned char>& bytes) {
    writeFileAtomically(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

Image mapped(const Image& img, glm::vec4 (*map)(glm::vec4)) {
    Image out(img.width(), img.height());
    for (std::size_t i = 0; i < img.pixelCount(); ++i) out.data()[i] = map(img.data()[i]);
    return out;
}

// The bytes `encode()` returns, its failure named with `path`.
template <typename Encode>
std::vector<unsigned char> encoded(const fs::path& path, Encode&& encode) {
    try {
        return encode();
    } catch (const ImageCodecError& e) {
        throw std::runtime_error(path.string() + ": cannot encode image (" + e.what() + ")");
    }
}

}  // namespace

void writeExr(const fs::path& path, const Image& linear) {
    writeBytes(path, encoded(path, [&] { return encodeExr(linear); }));
}

void writeDisplayPng(const fs::path& path, const Image& linear, int bits) {
    const Image display = mapped(linear, linearToDisplay);
    writeBytes(path, encoded(path, [&] { return encodePng(display, bits); }));
}

void writePng(const fs::path& path, const Image& display, int bits) {
    // encodePng clamps to [0, 1].
    writeBytes(path, encoded(path, [&] { return encodePng(display, bits); }));
}

std::vector<unsigned char> pngFileBytes(const Image& display, int bits) {
    try {
        return encodePng(display, bits);
    } catch (const ImageCodecError& e) {
        throw std::runtime_error(std::string("cannot encode image (") + e.what() + ")");
    }
}

void writeImageAtomically(const fs::path& path, const Image& linear) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    if (ext != ".exr" && ext != ".png") {
        throw InputError(path.string() + ": unsupported image extension '" + ext + "' (expected .exr or .png)");
    }
    if (ext == ".exr") writeExr(path, linear);
    else writeDisplayPng(path, linear);
}

}  // namespace hybridlab
