#pragma once
// The one call between the program and its OpenImageIO plugin (hybridlab_openimageio.so, built from
// openimageio_plugin.cpp): a C function, so that nothing of either side's C++ crosses the dlopen
// boundary. The program loads the plugin when it first meets a file of a format that only
// OpenImageIO reads (openimageio_codec.cpp).
#include <cstddef>

extern "C" {

// An image as the plugin decoded it: `values` interleaved, `channels` of them a pixel (at most 4:
// grey, grey and alpha, RGB, RGBA), integer channels scaled to [0, 1] as OpenImageIO scales them.
struct HybridlabOiioImage {
    int width;
    int height;
    int channels;
    int integer;           // 1 when the file's channels are integers
    char colorSpace[64];   // OpenImageIO's "oiio:ColorSpace" ("sRGB", "Linear", "Gamma2.2", ...; "" for none)
    float* values;         // allocated by the plugin (none when headerOnly); freed by hybridlab_oiio_free
};

// Reads `bytes` as an image of the format that `extension` ("tif", "pfm", ...) names: the header
// alone when headerOnly is non-zero, else every pixel. Returns 0 on success; otherwise writes
// OpenImageIO's message into `error` (at most errorSize bytes with the terminating zero).
typedef int (*HybridlabOiioRead)(const unsigned char* bytes, std::size_t size, const char* extension, int headerOnly,
                                 HybridlabOiioImage* image, char* error, std::size_t errorSize);
typedef void (*HybridlabOiioFree)(float* values);

}  // extern "C"

// Their names in the plugin, for dlsym.
inline constexpr const char* kHybridlabOiioReadSymbol = "hybridlab_oiio_read";
inline constexpr const char* kHybridlabOiioFreeSymbol = "hybridlab_oiio_free";
