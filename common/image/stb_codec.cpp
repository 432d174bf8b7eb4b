// The formats with no library of their own here (BMP, TGA, GIF's first frame, PSD, PNM, PIC and
// Radiance HDR) on stb_image, and the recognition of every format by its first bytes.
#include <stb_image.h>

#include <climits>
#include <cstring>
#include <memory>

#include "common/image/image_codecs.h"

namespace hybridlab {

ImageFormat imageFormatOf(const unsigned char* bytes, std::size_t size) {
    auto startsWith = [&](std::initializer_list<unsigned char> magic) {
        return size >= magic.size() && std::memcmp(bytes, magic.begin(), magic.size()) == 0;
    };
    if (startsWith({0x76, 0x2F, 0x31, 0x01})) return ImageFormat::Exr;
    if (startsWith({0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'})) return ImageFormat::Png;
    if (startsWith({0xFF, 0xD8, 0xFF})) return ImageFormat::Jpeg;
    if (isOpenImageIoFormat(bytes, size)) return ImageFormat::OpenImageIo;
    return ImageFormat::Other;
}

namespace {

int lengthOf(std::size_t size) {
    if (size > static_cast<std::size_t>(INT_MAX)) throw ImageCodecError("file of over 2 GiB");
    return static_cast<int>(size);
}

[[noreturn]] void failed() {
    const char* reason = stbi_failure_reason();
    throw ImageCodecError(std::string("not an image in a format hybridlab reads (EXR, PNG, JPEG, BMP, TGA, GIF, PSD, PNM, HDR; "
                                      "TIFF, PFM, DDS, WebP, JPEG 2000, DPX, Cineon, SGI, FITS, HEIF, IFF through OpenImageIO)") +
                          (reason ? std::string(": ") + reason : std::string()));
}

}  // namespace

ImageHeader readStbHeader(const unsigned char* bytes, std::size_t size) {
    ImageHeader h;
    if (!stbi_info_from_memory(bytes, lengthOf(size), &h.width, &h.height, &h.channels)) failed();
    return h;
}

DecodedImage decodeStb(const unsigned char* bytes, std::size_t size) {
    const int length = lengthOf(size);
    DecodedImage image;
    // The values as decoded: their count from what the decoder returns, not from the header.
    auto take = [&](auto* p, int w, int h, int nc, auto convert) {
        if (!p) failed();
        const std::unique_ptr<void, void (*)(void*)> owned(p, stbi_image_free);
        image.header = {w, h, nc};
        image.values = convert(p, static_cast<std::size_t>(w) * h * nc);
    };
    int w = 0, h = 0, nc = 0;
    if (stbi_is_hdr_from_memory(bytes, length)) {
        // Radiance HDR: linear floats, as stored.
        float* p = stbi_loadf_from_memory(bytes, length, &w, &h, &nc, 0);
        take(p, w, h, nc, [](const float* v, std::size_t n) { return std::vector<float>(v, v + n); });
        return image;
    }
    image.integer = true;
    if (stbi_is_16_bit_from_memory(bytes, length)) {
        stbi_us* p = stbi_load_16_from_memory(bytes, length, &w, &h, &nc, 0);
        take(p, w, h, nc, [](const stbi_us* v, std::size_t n) { return unitFloats(v, n); });
        return image;
    }
    stbi_uc* p = stbi_load_from_memory(bytes, length, &w, &h, &nc, 0);
    take(p, w, h, nc, [](const stbi_uc* v, std::size_t n) { return unitFloats(v, n); });
    return image;
}

}  // namespace hybridlab
