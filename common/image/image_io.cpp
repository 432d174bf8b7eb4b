#include "common/image/image_io.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <memory>
#include <system_error>
#include <vector>

#include <glm/common.hpp>
#include <glm/exponential.hpp>

#include "common/core/atomic_file.h"
#include "common/core/input_error.h"
#include "common/core/number_check.h"
#include "common/image/color.h"

namespace hybridlab {
namespace fs = std::filesystem;
using OIIO::ImageInput;
using OIIO::ImageOutput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;

namespace {

// Pixels are unassociated (straight) alpha, as PNG stores them. Without this OpenImageIO
// premultiplies colour by alpha on read and divides by it on write.
ImageSpec unassociatedAlphaConfig() {
    ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    return config;
}

// The transfer function of integer channels: none (linear), sRGB, or a power `gamma`.
struct Transfer {
    enum class Kind { Linear, Srgb, Power } kind = Transfer::Kind::Linear;
    float gamma = 1.0f;
    std::string description;
};

Transfer transferOf(const ImageSpec& spec, bool integer, ColorEncoding decode) {
    if (!integer) return {Transfer::Kind::Linear, 1.0f, "linear (floating point)"};
    if (decode == ColorEncoding::Linear) return {Transfer::Kind::Linear, 1.0f, "as stored"};
    if (decode == ColorEncoding::Srgb) return {Transfer::Kind::Srgb, 1.0f, "sRGB"};
    const std::string tag(spec.get_string_attribute("oiio:ColorSpace"));
    std::string space = tag;
    std::transform(space.begin(), space.end(), space.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    const float gamma = spec.get_float_attribute("oiio:Gamma", 0.0f);
    if (space == "linear" || space == "scene_linear" || space == "lin_srgb" || gamma == 1.0f) {
        return {Transfer::Kind::Linear, 1.0f, "linear (colour-space metadata: linear)"};
    }
    if (space == "srgb" || space.empty()) {
        return {Transfer::Kind::Srgb, 1.0f, space.empty() ? "sRGB (no colour-space metadata)" : "sRGB (colour-space metadata: sRGB)"};
    }
    if (gamma > 0.0f) {
        char text[96];
        std::snprintf(text, sizeof text, "gamma %.4g (colour-space metadata: %s)", gamma, tag.c_str());
        return {Transfer::Kind::Power, gamma, text};
    }
    return {Transfer::Kind::Srgb, 1.0f, "sRGB (unrecognised colour-space metadata '" + tag + "')"};
}

Image decodeOpened(ImageInput& in, const std::string& name, ColorEncoding decode, std::string* assumed = nullptr) {
    const ImageSpec& spec = in.spec();
    const int w = spec.width, h = spec.height, nc = spec.nchannels;
    if (w <= 0 || h <= 0 || nc <= 0) throw InputError(name + ": image has no pixels");
    std::vector<float> raw(static_cast<std::size_t>(w) * h * nc);
    if (!in.read_image(0, 0, 0, nc, TypeDesc::FLOAT, raw.data())) {
        throw InputError(name + ": cannot decode image (" + in.geterror() + ")");
    }
    const bool integer = spec.format.basetype != TypeDesc::FLOAT && spec.format.basetype != TypeDesc::HALF &&
                         spec.format.basetype != TypeDesc::DOUBLE;
    const Transfer transfer = transferOf(spec, integer, decode);
    if (assumed) *assumed = transfer.description;
    Image img(w, h);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const float* p = &raw[(static_cast<std::size_t>(y) * w + x) * nc];
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

}  // namespace

namespace {

// The file opened as an image with its header read: a regular file, of a format OpenImageIO knows,
// with a size the header states within limits::kImageSide a side.
std::unique_ptr<ImageInput> openImage(const fs::path& path) {
    if (!fs::exists(path)) throw InputError(path.string() + ": image file not found");
    if (fs::is_directory(path)) throw InputError(path.string() + ": is a directory, expected an image file");
    // A device or a pipe (/dev/zero) never ends: OpenImageIO would read it forever.
    if (!fs::is_regular_file(path)) throw InputError(path.string() + ": is not a regular file (a device or a pipe), expected an image file");
    const ImageSpec config = unassociatedAlphaConfig();
    auto in = ImageInput::open(path.string(), &config);
    if (!in) throw InputError(path.string() + ": cannot read image (" + OIIO::geterror() + ")");
    const ImageSpec& spec = in->spec();
    if (spec.width > limits::kImageSide || spec.height > limits::kImageSide)
        throw InputError(path.string() + ": image of " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                         " pixels exceeds the limit of " + std::to_string(limits::kImageSide) + " a side");
    return in;
}

}  // namespace

Image readImage(const fs::path& path, ColorEncoding decode, std::string* assumed) {
    auto in = openImage(path);
    return decodeOpened(*in, path.string(), decode, assumed);
}

void checkImageFile(const fs::path& path) {
    auto in = openImage(path);
    const ImageSpec& spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) throw InputError(path.string() + ": image has no pixels");
}

Image readImageFromMemory(const unsigned char* bytes, std::size_t size, const std::string& name,
                          const std::string& mimeType, ColorEncoding decode) {
    std::string hint = name;
    if (mimeType == "image/png") hint = "embedded.png";
    else if (mimeType == "image/jpeg") hint = "embedded.jpg";
    OIIO::Filesystem::IOMemReader proxy(const_cast<unsigned char*>(bytes), size);
    ImageSpec config = unassociatedAlphaConfig();
    // With a config, OpenImageIO 2.4 takes the proxy from it rather than from the argument.
    void* proxyPtr = &proxy;
    config.attribute("oiio:ioproxy", TypeDesc::PTR, &proxyPtr);
    auto in = ImageInput::open(hint, &config, &proxy);
    if (!in) throw InputError(name + ": cannot read embedded image (" + OIIO::geterror() + ")");
    return decodeOpened(*in, name, decode);
}

namespace {

// Encodes into memory, so that the bytes reach the disk through writeFileAtomically, which checks
// every step: OpenImageIO's PNG writer does not report a failed write (a full disk left truncated
// PNGs behind).
void writePixels(const fs::path& path, const Image& img, TypeDesc type, const std::vector<float>& rgba) {
    auto out = ImageOutput::create(path.string());
    if (!out) throw std::runtime_error(path.string() + ": no image writer (" + OIIO::geterror() + ")");
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput memory(bytes);
    ImageSpec spec(img.width(), img.height(), 4, type);
    spec.attribute("oiio:UnassociatedAlpha", 1);  // see unassociatedAlphaConfig()
    // No write time in the file (EXR capDate, PNG tIME): same pixels, same bytes.
    spec.attribute("DateTime", "");
    // zlib's fastest level: a 1280x720 display PNG in 140 ms instead of level 6's 470 ms, 17%
    // larger. A run writes several (the image, its error maps, debug images), one after another
    // on a GPU machine whose frames take milliseconds.
    spec.attribute("png:compressionLevel", 1);
    void* proxy = &memory;
    spec.attribute("oiio:ioproxy", TypeDesc::PTR, &proxy);
    if (!out->open(path.string(), spec) || !out->write_image(TypeDesc::FLOAT, rgba.data()) || !out->close()) {
        throw std::runtime_error(path.string() + ": cannot encode image (" + out->geterror() + ")");
    }
    writeFileAtomically(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

std::vector<float> flatten(const Image& img, glm::vec4 (*map)(glm::vec4)) {
    std::vector<float> out(img.pixelCount() * 4);
    for (std::size_t i = 0; i < img.pixelCount(); ++i) {
        glm::vec4 c = map(img.data()[i]);
        for (int k = 0; k < 4; ++k) out[i * 4 + k] = c[k];
    }
    return out;
}

TypeDesc pngType(int bits) { return bits == 16 ? TypeDesc::UINT16 : TypeDesc::UINT8; }

}  // namespace

void writeExr(const fs::path& path, const Image& linear) {
    writePixels(path, linear, TypeDesc::FLOAT, flatten(linear, [](glm::vec4 c) { return c; }));
}

void writeDisplayPng(const fs::path& path, const Image& linear, int bits) {
    writePixels(path, linear, pngType(bits), flatten(linear, linearToDisplay));
}

void writePng(const fs::path& path, const Image& display, int bits) {
    writePixels(path, display, pngType(bits),
                flatten(display, [](glm::vec4 c) { return glm::clamp(c, glm::vec4(0.0f), glm::vec4(1.0f)); }));
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
