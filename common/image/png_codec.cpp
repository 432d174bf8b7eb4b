// PNG on libpng. libpng reports errors by longjmp, so each entry point keeps the setjmp frame free
// of objects with destructors: buffers live in the caller's structs, and the C++ exception is
// thrown after the jump has landed.
#include <png.h>

#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstdint>
#include <cstring>

#include "common/image/image_codecs.h"

namespace hybridlab {

namespace {

struct PngMessages {
    char error[256] = "";
};

[[noreturn]] void onPngError(png_structp png, png_const_charp message) {
    auto* m = static_cast<PngMessages*>(png_get_error_ptr(png));
    std::snprintf(m->error, sizeof m->error, "%s", message);
    png_longjmp(png, 1);
}

void onPngWarning(png_structp, png_const_charp) {}  // ancillary-chunk complaints: the pixels are fine

struct MemoryReader {
    const unsigned char* bytes;
    std::size_t size;
    std::size_t at = 0;
};

void readFromMemory(png_structp png, png_bytep out, png_size_t n) {
    auto* r = static_cast<MemoryReader*>(png_get_io_ptr(png));
    if (n > r->size - r->at) png_error(png, "file ends early (truncated)");
    std::memcpy(out, r->bytes + r->at, n);
    r->at += n;
}

const png_byte kCicp[5] = {'c', 'I', 'C', 'P', '\0'};

// What decodePng fills between setjmp and the jump; no destructors run in that frame.
struct PngRead {
    ImageHeader header;
    int bitDepth = 8;
    ColorTag tag;
    std::vector<unsigned char> bytes;     // the rows, as libpng delivers them (16 bits: big-endian)
    std::vector<png_bytep> rows;
};

// The colour metadata: cICP's transfer characteristics (it overrides the rest), else an sRGB
// chunk, else gAMA.
ColorTag tagOf(png_structp png, png_infop info) {
    ColorTag tag;
    png_unknown_chunkp unknown = nullptr;
    const int n = png_get_unknown_chunks(png, info, &unknown);
    for (int i = 0; i < n; ++i) {
        if (std::memcmp(unknown[i].name, kCicp, 4) != 0 || unknown[i].size < 4) continue;
        const int transfer = unknown[i].data[1];
        tag.source = "cICP transfer " + std::to_string(transfer);
        tag.kind = transfer == 8 ? ColorTag::Kind::Linear : transfer == 13 ? ColorTag::Kind::Srgb : ColorTag::Kind::Unrecognised;
        return tag;
    }
    int intent = 0;
    if (png_get_sRGB(png, info, &intent)) return {ColorTag::Kind::Srgb, 1.0f, "sRGB chunk"};
    double fileGamma = 0.0;
    if (png_get_gAMA(png, info, &fileGamma) && fileGamma > 0.0) {
        char text[48];
        std::snprintf(text, sizeof text, "gAMA %.5g", fileGamma);
        // gAMA stores the encoding exponent (0.45455 for a display gamma of 2.2); 1.0 is linear.
        const float gamma = static_cast<float>(1.0 / fileGamma);
        if (std::abs(gamma - 1.0f) < 1e-4f) return {ColorTag::Kind::Linear, 1.0f, text};
        return {ColorTag::Kind::Gamma, gamma, text};
    }
    return tag;
}

// Returns false with messages.error set on a libpng error.
bool readPng(const unsigned char* bytes, std::size_t size, bool headerOnly, PngRead& out, PngMessages& messages) {
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &messages, onPngError, onPngWarning);
    if (!png) {
        std::snprintf(messages.error, sizeof messages.error, "libpng cannot start");
        return false;
    }
    png_infop info = png_create_info_struct(png);
    MemoryReader reader{bytes, size};
    if (!info || setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
        if (!messages.error[0]) std::snprintf(messages.error, sizeof messages.error, "libpng cannot start");
        return false;
    }
    png_set_read_fn(png, &reader, readFromMemory);
    png_set_keep_unknown_chunks(png, PNG_HANDLE_CHUNK_ALWAYS, kCicp, 1);
    png_read_info(png, info);
    // The rows as the file stores them (before the expansions below), which deflate packs at most
    // 1032:1 (a 258-byte match in two bits).
    const double fileRowBytes = static_cast<double>(png_get_rowbytes(png, info)) * png_get_image_height(png, info);
    if (claimExceedsFile(png_get_image_width(png, info), png_get_image_height(png, info), fileRowBytes / 1032.0, size,
                         "deflate packs at most 1032 bytes of rows into one", messages.error, sizeof messages.error)) {
        png_destroy_read_struct(&png, &info, nullptr);
        return false;
    }
    // Palettes to RGB, grey under 8 bits to 8, tRNS to an alpha channel; 16 bits stay 16.
    png_set_expand(png);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    out.header.width = static_cast<int>(png_get_image_width(png, info));
    out.header.height = static_cast<int>(png_get_image_height(png, info));
    out.header.channels = png_get_channels(png, info);
    out.bitDepth = png_get_bit_depth(png, info);
    out.tag = tagOf(png, info);
    if (!headerOnly) {
        const std::size_t rowBytes = png_get_rowbytes(png, info);
        out.bytes.resize(rowBytes * static_cast<std::size_t>(out.header.height));
        out.rows.resize(static_cast<std::size_t>(out.header.height));
        for (std::size_t y = 0; y < out.rows.size(); ++y) out.rows[y] = out.bytes.data() + y * rowBytes;
        png_read_image(png, out.rows.data());
        png_read_end(png, nullptr);
    }
    png_destroy_read_struct(&png, &info, nullptr);
    return true;
}

PngRead readPngOrThrow(const unsigned char* bytes, std::size_t size, bool headerOnly) {
    PngRead read;
    PngMessages messages;
    if (!readPng(bytes, size, headerOnly, read, messages)) throw ImageCodecError(std::string("PNG: ") + messages.error);
    return read;
}

struct PngWrite {
    std::vector<unsigned char> bytes;      // the encoded file
    std::vector<unsigned char> pixels;     // the rows to encode (16 bits: big-endian)
    std::vector<png_bytep> rows;
};

void appendToMemory(png_structp png, png_bytep data, png_size_t n) {
    auto* out = static_cast<PngWrite*>(png_get_io_ptr(png));
    out->bytes.insert(out->bytes.end(), data, data + n);
}

void flushNothing(png_structp) {}

bool writePngTo(PngWrite& out, int width, int height, int bits, ColorTag::Kind tag, PngMessages& messages) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &messages, onPngError, onPngWarning);
    if (!png) {
        std::snprintf(messages.error, sizeof messages.error, "libpng cannot start");
        return false;
    }
    png_infop info = png_create_info_struct(png);
    if (!info || setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, info ? &info : nullptr);
        if (!messages.error[0]) std::snprintf(messages.error, sizeof messages.error, "libpng cannot start");
        return false;
    }
    png_set_write_fn(png, &out, appendToMemory, flushNothing);
    // zlib's fastest level: a 1280x720 display PNG in about 140 ms instead of level 6's 470 ms,
    // 17% larger; a run writes several (the image, its error maps, debug images).
    png_set_compression_level(png, 1);
    png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), bits, PNG_COLOR_TYPE_RGB_ALPHA,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (tag == ColorTag::Kind::Linear) png_set_gAMA(png, info, 1.0);
    else if (tag == ColorTag::Kind::Srgb) png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(png, info);
    png_write_image(png, out.rows.data());
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return true;
}

}  // namespace

ImageHeader readPngHeader(const unsigned char* bytes, std::size_t size) { return readPngOrThrow(bytes, size, true).header; }

DecodedImage decodePng(const unsigned char* bytes, std::size_t size) {
    PngRead read = readPngOrThrow(bytes, size, false);
    DecodedImage image;
    image.header = read.header;
    image.integer = true;
    image.tag = read.tag;
    const std::size_t count = static_cast<std::size_t>(read.header.width) * read.header.height * read.header.channels;
    if (read.bitDepth != 16) {
        image.values = unitFloats(read.bytes.data(), count);
        return image;
    }
    std::vector<std::uint16_t> samples(count);  // PNG stores 16-bit samples big-endian
    for (std::size_t i = 0; i < count; ++i) samples[i] = static_cast<std::uint16_t>(read.bytes[2 * i] << 8 | read.bytes[2 * i + 1]);
    image.values = unitFloats(samples.data(), count);
    return image;
}

std::vector<unsigned char> encodePng(const Image& values, int bits, ColorTag::Kind tag) {
    if (bits != 8 && bits != 16) throw ImageCodecError("PNG: " + std::to_string(bits) + " bits a channel (expected 8 or 16)");
    PngWrite out;
    const int w = values.width(), h = values.height();
    const std::size_t bytesPerValue = bits / 8;
    const float steps = bits == 16 ? 65535.0f : 255.0f;
    out.pixels.resize(values.pixelCount() * 4 * bytesPerValue);
    for (std::size_t i = 0; i < values.pixelCount(); ++i) {
        for (int k = 0; k < 4; ++k) {
            // fmin/fmax send NaN to 0.
            const auto q = static_cast<unsigned>(std::round(std::fmin(std::fmax(values.data()[i][k], 0.0f), 1.0f) * steps));
            unsigned char* p = &out.pixels[(i * 4 + k) * bytesPerValue];
            if (bits == 16) p[0] = static_cast<unsigned char>(q >> 8), p[1] = static_cast<unsigned char>(q & 0xFF);
            else p[0] = static_cast<unsigned char>(q);
        }
    }
    out.rows.resize(static_cast<std::size_t>(h));
    const std::size_t rowBytes = static_cast<std::size_t>(w) * 4 * bytesPerValue;
    for (int y = 0; y < h; ++y) out.rows[static_cast<std::size_t>(y)] = out.pixels.data() + static_cast<std::size_t>(y) * rowBytes;
    PngMessages messages;
    if (!writePngTo(out, w, h, bits, tag, messages)) throw ImageCodecError(std::string("PNG: ") + messages.error);
    return std::move(out.bytes);
}

}  // namespace hybridlab
