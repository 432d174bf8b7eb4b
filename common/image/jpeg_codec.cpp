// JPEG on libjpeg(-turbo), decoded with the library's defaults (integer IDCT, fancy upsampling) to
// 8-bit RGB or grey. libjpeg reports errors through error_exit, which must not return: it jumps
// back here, and the setjmp frame holds no objects with destructors.
#include <cstdio>
// jpeglib.h needs FILE and size_t declared first.
#include <jpeglib.h>

#include <cmath>
#include <csetjmp>

#include "common/image/image_codecs.h"

namespace hybridlab {

namespace {

struct JpegErrors {
    jpeg_error_mgr manager;  // first: libjpeg hands error_exit a pointer to it
    std::jmp_buf jump;
    char message[JMSG_LENGTH_MAX] = "";
};

[[noreturn]] void onJpegError(j_common_ptr info) {
    auto* errors = reinterpret_cast<JpegErrors*>(info->err);
    (*info->err->format_message)(info, errors->message);
    std::longjmp(errors->jump, 1);
}

void onJpegMessage(j_common_ptr, int) {}  // warnings (corrupt but decodable data) are not errors

struct JpegRead {
    ImageHeader header;
    bool cmyk = false;
    bool adobeInverted = false;
    std::vector<unsigned char> bytes;
};

bool readJpeg(const unsigned char* bytes, std::size_t size, bool headerOnly, JpegRead& out, JpegErrors& errors) {
    jpeg_decompress_struct info;
    info.err = jpeg_std_error(&errors.manager);
    errors.manager.error_exit = onJpegError;
    errors.manager.emit_message = onJpegMessage;
    if (setjmp(errors.jump)) {
        jpeg_destroy_decompress(&info);
        return false;
    }
    jpeg_create_decompress(&info);
    jpeg_mem_src(&info, bytes, static_cast<unsigned long>(size));
    jpeg_read_header(&info, TRUE);
    // Huffman coding spends at least a bit on each 8 x 8 block of a full-resolution component (its
    // DC difference); arithmetic coding has no such floor.
    const double blocks = std::ceil(info.image_width / 8.0) * std::ceil(info.image_height / 8.0);
    if (!info.arith_code && claimExceedsFile(info.image_width, info.image_height, blocks / 8.0, size,
                                             "Huffman coding spends a bit at least on each 8x8 block", errors.message, sizeof errors.message)) {
        jpeg_destroy_decompress(&info);
        return false;
    }
    out.cmyk = info.jpeg_color_space == JCS_CMYK || info.jpeg_color_space == JCS_YCCK;
    out.adobeInverted = info.saw_Adobe_marker;
    info.out_color_space = out.cmyk ? JCS_CMYK : info.jpeg_color_space == JCS_GRAYSCALE ? JCS_GRAYSCALE : JCS_RGB;
    out.header.width = static_cast<int>(info.image_width);
    out.header.height = static_cast<int>(info.image_height);
    out.header.channels = out.cmyk ? 3 : info.out_color_space == JCS_GRAYSCALE ? 1 : 3;
    if (!headerOnly) {
        jpeg_start_decompress(&info);
        const std::size_t rowBytes = static_cast<std::size_t>(info.output_width) * info.output_components;
        out.bytes.resize(rowBytes * info.output_height);
        while (info.output_scanline < info.output_height) {
            JSAMPROW row = out.bytes.data() + static_cast<std::size_t>(info.output_scanline) * rowBytes;
            jpeg_read_scanlines(&info, &row, 1);
        }
        jpeg_finish_decompress(&info);
    }
    jpeg_destroy_decompress(&info);
    return true;
}

JpegRead readJpegOrThrow(const unsigned char* bytes, std::size_t size, bool headerOnly) {
    JpegRead read;
    JpegErrors errors;
    if (!readJpeg(bytes, size, headerOnly, read, errors)) throw ImageCodecError(std::string("JPEG: ") + errors.message);
    return read;
}

}  // namespace

ImageHeader readJpegHeader(const unsigned char* bytes, std::size_t size) { return readJpegOrThrow(bytes, size, true).header; }

DecodedImage decodeJpeg(const unsigned char* bytes, std::size_t size) {
    JpegRead read = readJpegOrThrow(bytes, size, false);
    DecodedImage image;
    image.header = read.header;
    image.integer = true;
    const std::size_t pixels = static_cast<std::size_t>(read.header.width) * read.header.height;
    if (!read.cmyk) {
        image.values = unitFloats(read.bytes.data(), pixels * read.header.channels);
        return image;
    }
    // Four channels to RGB: R = (1 - C)(1 - K) on the stored values, which Adobe's files store
    // inverted (the common case for CMYK JPEGs).
    image.values.resize(pixels * read.header.channels);
    for (std::size_t i = 0; i < pixels; ++i) {
        const unsigned char* p = &read.bytes[i * 4];
        auto ink = [&](int k) { return read.adobeInverted ? p[k] / 255.0f : 1.0f - p[k] / 255.0f; };
        for (int c = 0; c < 3; ++c) image.values[i * 3 + c] = ink(c) * ink(3);
    }
    return image;
}

}  // namespace hybridlab
