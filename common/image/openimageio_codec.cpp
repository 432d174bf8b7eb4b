// The formats only OpenImageIO reads here (TIFF, PFM, DDS, WebP, ...), through the plugin
// hybridlab_openimageio.so (openimageio_plugin.cpp), loaded on the first such file: OpenImageIO
// links every codec there is, which cost each start of the program 0.4 s when it was linked in.
#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "common/image/image_codecs.h"
#include "common/image/openimageio_plugin_api.h"

namespace hybridlab {

namespace fs = std::filesystem;

namespace {

constexpr const char* kPluginFile = "hybridlab_openimageio.so";

struct Magic {
    std::size_t offset;
    std::string bytes;
};

struct OpenImageIoFormat {
    const char* extension;  // how OpenImageIO knows the format
    const char* name;       // in messages
    std::vector<Magic> magic;  // all must match
};

// The formats recognised by their first bytes, each as its specification or OpenImageIO's reader
// checks them. PNM's P1-P6 stay with stb_image; PFM (PF / Pf) is OpenImageIO's.
const std::vector<std::vector<OpenImageIoFormat>>& formatAlternatives() {
    using namespace std::string_literals;
    static const std::vector<std::vector<OpenImageIoFormat>> formats = {
        {{"tif", "TIFF", {{0, "II*\0"s}}}, {"tif", "TIFF", {{0, "MM\0*"s}}}, {"tif", "BigTIFF", {{0, "II+\0"s}}},
         {"tif", "BigTIFF", {{0, "MM\0+"s}}}},
        {{"pfm", "PFM", {{0, "PF\n"s}}}, {"pfm", "PFM", {{0, "Pf\n"s}}}, {"pfm", "PFM", {{0, "PF\r"s}}}, {"pfm", "PFM", {{0, "Pf\r"s}}},
         {"pfm", "PFM", {{0, "PF "s}}}, {"pfm", "PFM", {{0, "Pf "s}}}},
        {{"dds", "DDS", {{0, "DDS "s}}}},
        {{"webp", "WebP", {{0, "RIFF"s}, {8, "WEBP"s}}}},
        {{"jp2", "JPEG 2000", {{0, "\0\0\0\x0CjP  \r\n\x87\n"s}}}, {"j2k", "JPEG 2000", {{0, "\xFF\x4F\xFF\x51"s}}}},
        {{"dpx", "DPX", {{0, "SDPX"s}}}, {"dpx", "DPX", {{0, "XPDS"s}}}},
        {{"cin", "Cineon", {{0, "\x80\x2A\x5F\xD7"s}}}, {"cin", "Cineon", {{0, "\xD7\x5F\x2A\x80"s}}}},
        {{"sgi", "SGI", {{0, "\x01\xDA"s}}}},
        {{"fits", "FITS", {{0, "SIMPLE  ="s}}}},
        {{"heic", "HEIF", {{4, "ftypheic"s}}}, {"heic", "HEIF", {{4, "ftypheix"s}}}, {"heic", "HEIF", {{4, "ftypmif1"s}}},
         {"avif", "AVIF", {{4, "ftypavif"s}}}},
        {{"iff", "IFF", {{0, "FOR4"s}}}},
    };
    return formats;
}

bool matches(const OpenImageIoFormat& f, const unsigned char* bytes, std::size_t size) {
    for (const Magic& m : f.magic)
        if (size < m.offset + m.bytes.size() || std::memcmp(bytes + m.offset, m.bytes.data(), m.bytes.size()) != 0) return false;
    return true;
}

const OpenImageIoFormat* formatOf(const unsigned char* bytes, std::size_t size) {
    for (const auto& alternatives : formatAlternatives())
        for (const OpenImageIoFormat& f : alternatives)
            if (matches(f, bytes, size)) return &f;
    return nullptr;
}

// The plugin, loaded once: beside the program (the build folder, or a bundle that carries it),
// else where the build put it.
struct Plugin {
    HybridlabOiioRead read = nullptr;
    HybridlabOiioFree free = nullptr;
    std::string problem;  // why it is not loaded
};

std::vector<fs::path> pluginCandidates() {
    std::vector<fs::path> candidates;
    std::error_code ec;
    const fs::path program = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) candidates.push_back(program.parent_path() / kPluginFile);
#ifdef HYBRIDLAB_OPENIMAGEIO_PLUGIN
    candidates.push_back(HYBRIDLAB_OPENIMAGEIO_PLUGIN);
#endif
    return candidates;
}

Plugin loadPlugin() {
    Plugin plugin;
    std::string looked;
    for (const fs::path& candidate : pluginCandidates()) {
        looked += (looked.empty() ? "" : ", ") + candidate.string();
        std::error_code ec;
        if (!fs::exists(candidate, ec)) continue;
        void* handle = ::dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            const char* reason = ::dlerror();
            plugin.problem = candidate.string() + " did not load (" + (reason ? reason : "no reason given") +
                             "; setup.sh installs OpenImageIO, Debian's libopenimageio2.4)";
            return plugin;
        }
        plugin.read = reinterpret_cast<HybridlabOiioRead>(::dlsym(handle, kHybridlabOiioReadSymbol));
        plugin.free = reinterpret_cast<HybridlabOiioFree>(::dlsym(handle, kHybridlabOiioFreeSymbol));
        if (!plugin.read || !plugin.free) plugin.problem = candidate.string() + " is not hybridlab's OpenImageIO plugin";
        return plugin;  // kept loaded for the process's life
    }
    plugin.problem = "hybridlab's OpenImageIO plugin is not installed (looked for " + looked + ")";
    return plugin;
}

const Plugin& plugin() {
    static const Plugin loaded = loadPlugin();
    return loaded;
}

ColorTag colorTagOf(const std::string& space) {
    if (space.empty()) return {};
    if (space == "sRGB") return {ColorTag::Kind::Srgb, 1.0f, "OpenImageIO colour space sRGB"};
    if (space == "Linear" || space == "linear") return {ColorTag::Kind::Linear, 1.0f, "OpenImageIO colour space " + space};
    if (space.rfind("Gamma", 0) == 0) {
        char* end = nullptr;
        const float gamma = std::strtof(space.c_str() + 5, &end);
        if (end && *end == '\0' && gamma > 0.0f) return {ColorTag::Kind::Gamma, gamma, "OpenImageIO colour space " + space};
    }
    return {ColorTag::Kind::Unrecognised, 1.0f, "OpenImageIO colour space " + space};
}

// The plugin's call, its failure thrown with the format's name.
HybridlabOiioImage readWithPlugin(const unsigned char* bytes, std::size_t size, bool headerOnly) {
    const OpenImageIoFormat* format = formatOf(bytes, size);
    if (!format) throw ImageCodecError("not a format OpenImageIO reads here");
    const Plugin& p = plugin();
    if (!p.read) throw ImageCodecError(std::string("a ") + format->name + " image is read through OpenImageIO: " + p.problem);
    HybridlabOiioImage image{};
    char error[512] = "";
    if (p.read(bytes, size, format->extension, headerOnly ? 1 : 0, &image, error, sizeof error) != 0)
        throw ImageCodecError(std::string(format->name) + " through OpenImageIO: " + error);
    return image;
}

}  // namespace

bool isOpenImageIoFormat(const unsigned char* bytes, std::size_t size) { return formatOf(bytes, size) != nullptr; }

ImageHeader readOpenImageIoHeader(const unsigned char* bytes, std::size_t size) {
    const HybridlabOiioImage image = readWithPlugin(bytes, size, true);
    return {image.width, image.height, image.channels};
}

DecodedImage decodeOpenImageIo(const unsigned char* bytes, std::size_t size) {
    HybridlabOiioImage image = readWithPlugin(bytes, size, false);
    const std::unique_ptr<float, HybridlabOiioFree> owned(image.values, plugin().free);
    DecodedImage decoded;
    decoded.header = {image.width, image.height, image.channels};
    decoded.integer = image.integer != 0;
    decoded.tag = colorTagOf(image.colorSpace);
    const std::size_t count = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * static_cast<std::size_t>(image.channels);
    decoded.values.assign(image.values, image.values + count);
    return decoded;
}

}  // namespace hybridlab
