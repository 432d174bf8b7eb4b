// The OpenImageIO plugin: the formats that no codec of the program reads (TIFF, PFM, DDS, WebP,
// JPEG 2000, DPX, ...), decoded by OpenImageIO. A shared library of its own that the program
// dlopens when it meets such a file, so that a run that reads none pays neither OpenImageIO's
// start-up (it links every codec there is) nor its place in the portable bundle.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <type_traits>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "common/image/openimageio_plugin_api.h"

namespace {

void say(char* error, std::size_t size, const std::string& message) {
    if (size == 0) return;
    std::snprintf(error, size, "%s", message.empty() ? "OpenImageIO gave no reason" : message.c_str());
}

// Bytes on disk for a reader that takes no memory proxy: a temporary file, removed when done.
class TemporaryFile {
public:
    TemporaryFile(const unsigned char* bytes, std::size_t size, const std::string& extension) {
        const char* dir = std::getenv("TMPDIR");
        std::string name = std::string(dir && *dir ? dir : "/tmp") + "/hybridlab-oiio-XXXXXX." + extension;
        const int fd = ::mkstemps(name.data(), static_cast<int>(extension.size() + 1));
        if (fd < 0) return;
        path_ = name;
        std::size_t written = 0;
        while (written < size) {
            const ssize_t n = ::write(fd, bytes + written, size - written);
            if (n <= 0) break;
            written += static_cast<std::size_t>(n);
        }
        ::close(fd);
        if (written != size) {
            ::unlink(path_.c_str());
            path_.clear();
        }
    }
    ~TemporaryFile() {
        if (!path_.empty()) ::unlink(path_.c_str());
    }
    TemporaryFile(const TemporaryFile&) = delete;
    TemporaryFile& operator=(const TemporaryFile&) = delete;
    const std::string& path() const { return path_; }

private:
    std::string path_;
};

int read(const unsigned char* bytes, std::size_t size, const char* extension, int headerOnly, HybridlabOiioImage* image, char* error,
         std::size_t errorSize) {
    using namespace OIIO;
    // From memory; a reader that takes no memory proxy gets the bytes as a temporary file. The name
    // says the format (OpenImageIO goes by the extension first).
    const std::string name = std::string("image.") + extension;
    Filesystem::IOMemReader memory(bytes, size);
    std::unique_ptr<TemporaryFile> file;
    std::unique_ptr<ImageInput> in = ImageInput::open(name, nullptr, &memory);
    if (!in) {
        const std::string fromMemory = OIIO::geterror();
        file = std::make_unique<TemporaryFile>(bytes, size, extension);
        if (!file->path().empty()) in = ImageInput::open(file->path());
        if (!in) {
            say(error, errorSize, fromMemory);
            return 1;
        }
    }
    const ImageSpec& spec = in->spec();
    image->width = spec.width;
    image->height = spec.height;
    image->channels = std::min(spec.nchannels, 4);
    image->integer = spec.format.is_floating_point() ? 0 : 1;
    std::snprintf(image->colorSpace, sizeof image->colorSpace, "%s", spec.get_string_attribute("oiio:ColorSpace").c_str());
    image->values = nullptr;
    if (headerOnly) return 0;
    const std::size_t count = static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height) * static_cast<std::size_t>(image->channels);
    auto* values = static_cast<float*>(std::malloc(std::max<std::size_t>(count, 1) * sizeof(float)));
    if (!values) {
        say(error, errorSize, "out of memory");
        return 1;
    }
    if (!in->read_image(0, 0, 0, image->channels, TypeDesc::FLOAT, values)) {
        say(error, errorSize, in->geterror());
        std::free(values);
        return 1;
    }
    image->values = values;
    return 0;
}

}  // namespace

extern "C" {

__attribute__((visibility("default"))) int hybridlab_oiio_read(const unsigned char* bytes, std::size_t size, const char* extension,
                                                               int headerOnly, HybridlabOiioImage* image, char* error, std::size_t errorSize) {
    try {
        return read(bytes, size, extension, headerOnly, image, error, errorSize);
    } catch (const std::exception& e) {
        say(error, errorSize, e.what());
        return 1;
    }
}

__attribute__((visibility("default"))) void hybridlab_oiio_free(float* values) { std::free(values); }

}  // extern "C"

// Both match the types the program calls them through.
static_assert(std::is_same_v<decltype(&hybridlab_oiio_read), HybridlabOiioRead>);
static_assert(std::is_same_v<decltype(&hybridlab_oiio_free), HybridlabOiioFree>);
