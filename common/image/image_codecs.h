#pragma once
// The image formats behind image_io.h, each on the library that defines it: EXR on OpenEXR, PNG on
// libpng, JPEG on libjpeg(-turbo), BMP, TGA, GIF, PSD, PNM and Radiance HDR on stb_image, and the
// rest that OpenImageIO reads (TIFF, PFM, DDS, WebP, ...) through a plugin loaded on demand. They
// decode from and encode to memory, so that a file, an image embedded in a glTF buffer and an
// atomic write all go through the same code. Errors throw ImageCodecError with the library's words;
// image_io.cpp names the file.
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/image/image.h"

namespace hybridlab {

class ImageCodecError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// What a file says of the transfer function of its integer channels.
struct ColorTag {
    enum class Kind { None, Srgb, Linear, Gamma, Unrecognised } kind = Kind::None;
    float gamma = 1.0f;   // Gamma: decode as v^gamma
    std::string source;   // the metadata, in words: "sRGB chunk", "gAMA 0.45455", "cICP transfer 8"
};

// Size and channel count, read from the header alone.
struct ImageHeader {
    int width = 0;
    int height = 0;
    int channels = 0;
};

// Pixels as stored: channels interleaved (1 grey, 2 grey and alpha, 3 RGB, 4 RGBA); integer
// channels scaled to [0, 1] by v * (1 / (2^bits - 1)), floating-point channels as they are.
struct DecodedImage {
    ImageHeader header;
    bool integer = false;
    ColorTag tag;
    std::vector<float> values;
};

// Integer samples to [0, 1]: v * (1 / (2^bits - 1)), the product OpenImageIO computes (the
// quotient differs from it in the last bit for 126 of the 256 8-bit values), so that textures
// decode to the values they did when OpenImageIO read them.
template <typename Sample>
std::vector<float> unitFloats(const Sample* samples, std::size_t count) {
    constexpr float scale = 1.0f / static_cast<float>(std::numeric_limits<Sample>::max());
    std::vector<float> values(count);
    for (std::size_t i = 0; i < count; ++i) values[i] = static_cast<float>(samples[i]) * scale;
    return values;
}

// A header's claim against the file that holds it, where the compression has a greatest ratio: a
// 1 KB PNG whose header claims 16384 x 16384 pixels would otherwise be refused only after the
// decoder allocated them. True, with `message` filled, when the claim of width x height pixels
// needs `leastFileBytes` (its samples over the greatest ratio, which `why` states) and the file
// is smaller. C-style, for the codecs whose error handling jumps over destructors.
inline bool claimExceedsFile(long long width, long long height, double leastFileBytes, std::size_t fileSize, const char* why,
                             char* message, std::size_t messageSize) {
    if (leastFileBytes <= static_cast<double>(fileSize)) return false;
    std::snprintf(message, messageSize, "header claims %lldx%lld pixels, which take at least %.0f bytes (%s), more than the file's %zu",
                  width, height, std::ceil(leastFileBytes), why, fileSize);
    return true;
}

enum class ImageFormat { Exr, Png, Jpeg, OpenImageIo, Other };
// By the file's first bytes, not its name.
ImageFormat imageFormatOf(const unsigned char* bytes, std::size_t size);

// Each reader: the header (without decoding) or the whole image. A decoder allocates what the
// header states: image_io.cpp reads the header first and refuses one without pixels or over
// limits::kImageSide a side, so that only a header that passed is decoded.
ImageHeader readExrHeader(const unsigned char* bytes, std::size_t size);
DecodedImage decodeExr(const unsigned char* bytes, std::size_t size);
ImageHeader readPngHeader(const unsigned char* bytes, std::size_t size);
DecodedImage decodePng(const unsigned char* bytes, std::size_t size);
ImageHeader readJpegHeader(const unsigned char* bytes, std::size_t size);
DecodedImage decodeJpeg(const unsigned char* bytes, std::size_t size);
ImageHeader readStbHeader(const unsigned char* bytes, std::size_t size);
DecodedImage decodeStb(const unsigned char* bytes, std::size_t size);
// TIFF, PFM, DDS, WebP, JPEG 2000, DPX, Cineon, SGI, FITS, HEIF and IFF, by their first bytes; read
// by OpenImageIO in a plugin that the first such file loads (openimageio_codec.cpp).
bool isOpenImageIoFormat(const unsigned char* bytes, std::size_t size);
ImageHeader readOpenImageIoHeader(const unsigned char* bytes, std::size_t size);
DecodedImage decodeOpenImageIo(const unsigned char* bytes, std::size_t size);

// 32-bit float RGBA, ZIP-compressed, with no attribute beyond the required ones (no capDate).
std::vector<unsigned char> encodeExr(const Image& image);

// RGBA, 8 or 16 bits, each value clamped to [0, 1] and rounded to the nearest step (NaN as 0), at
// zlib's fastest level, with no tIME chunk. `tag` Linear writes gAMA 1.0, Srgb an sRGB chunk, None
// nothing (readers then assume sRGB).
std::vector<unsigned char> encodePng(const Image& values, int bits, ColorTag::Kind tag = ColorTag::Kind::None);

}  // namespace hybridlab
