#pragma once
// Image files: linear EXR (any pixel type) and display PNG (8 or 16 bit sRGB) written; EXR, PNG,
// JPEG, BMP, TGA, GIF, PSD, PNM and Radiance HDR read, and through OpenImageIO TIFF, PFM, DDS, WebP,
// JPEG 2000, DPX, Cineon, SGI, FITS, HEIF and IFF, each recognised by its first bytes
// (image_codecs.h: the library behind each).
#include <filesystem>
#include <string>
#include <vector>

#include "common/image/image.h"

namespace hybridlab {

// How 8/16-bit colour channels are decoded. Tagged: as the file's metadata says, from PNG's cICP
// chunk (which overrides the others), sRGB chunk or gAMA chunk: linear (cICP transfer 8, gAMA 1) as
// stored, a gAMA of 1/g as v^g, sRGB or no such metadata as sRGB (for OpenImageIO's formats, its
// oiio:ColorSpace says). Float formats (EXR, HDR, PFM, float TIFF) are always taken as stored.
enum class ColorEncoding { Linear, Srgb, Tagged };

// Reads an image file. Pixel values are returned as stored; with `decode =
// ColorEncoding::Srgb` 8/16-bit colour channels are decoded from sRGB to linear, with Tagged as
// the file says. Grey images are expanded to RGB; missing alpha is 1. `assumed`, when given,
// receives what the values were taken as ("linear (float)", "sRGB (no colour-space metadata)", ...).
// Throws InputError naming the file on failure.
Image readImage(const std::filesystem::path& path, ColorEncoding decode = ColorEncoding::Linear, std::string* assumed = nullptr);

// What readImage checks before decoding, without decoding: the file is an image of a format read
// here, with pixels, within the size limit and no larger than its file can hold. With
// `requireFinite`, an image of floating-point samples (EXR: the format here that can hold NaN or
// infinities) is also decoded and refused as requireFiniteTexels (non_finite_pixels.h) refuses it. For commands that
// check a scene without rendering it. Returns the size its header states.
struct ImageSize {
    int width = 0;
    int height = 0;
};
ImageSize checkImageFile(const std::filesystem::path& path, bool requireFinite = false);

// Every writer writes the complete file or nothing (common/core/atomic_file.h; failures throw
// IoError), with no write time in it, so that the same pixels give the same bytes.

// Writes linear pixels as they are (EXR, 32-bit float).
void writeExr(const std::filesystem::path& path, const Image& linear);

// Writes the display image: clamp to [0, 1] and sRGB-encode (8-bit PNG unless bits == 16).
void writeDisplayPng(const std::filesystem::path& path, const Image& linear, int bits = 8);

// Writes values as they are, clamped to [0, 1], no transfer function (for masks and heat maps
// that are already display values).
void writePng(const std::filesystem::path& path, const Image& display, int bits = 8);
// The bytes writePng writes, for a writer that places the file itself (atomic_file.h's FileGroup).
std::vector<unsigned char> pngFileBytes(const Image& display, int bits = 8);

// Writes `linear` to `path` choosing by extension: .exr linear, .png display sRGB.
void writeImageAtomically(const std::filesystem::path& path, const Image& linear);

}  // namespace hybridlab

namespace hybridlab {
// Decodes an encoded image (PNG, JPEG, ...) held in memory, as readImage does for files; `name`
// is used in messages. The format is recognised by the first bytes, as for files.
Image readImageFromMemory(const unsigned char* bytes, std::size_t size, const std::string& name,
                          ColorEncoding decode = ColorEncoding::Linear);
}  // namespace hybridlab
