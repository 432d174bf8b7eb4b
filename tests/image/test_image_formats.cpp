// Every format and variant the image readers take (tests/fixtures/image_formats/files, made by its
// make_files.py: PNG 8 and 16 bits, grey, grey and alpha, a palette with transparency, Adam7
// interlacing; baseline, progressive and grey JPEG; half EXR with a data window off the origin,
// luminance EXR; BMP, TGA, Radiance HDR) decodes to the values OpenImageIO 2.4, an independent
// decoder, gave for it, bit for bit; and PNG's colour metadata picks the transfer function.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/core/input_error.h"
#include "common/image/color.h"
#include "common/image/image_io.h"
#include "tests/support/decoded_image_checks.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

using test::expectSamePixels;
using test::fileBytes;

namespace fs = std::filesystem;

fs::path fixtures() { return test::fixturesDir() / "image_formats"; }

TEST(ImageFormats, EveryFileDecodesAsOpenImageIoDecodedIt) {
    test::expectEveryFileDecodesAsOpenImageIoDecodedIt(fixtures(), 20);
}

// Truncated and corrupted copies of every fixture (a mini-fuzz, deterministic; the sanitizer
// build runs it too): each decodes (a JPEG decoder fills what is missing) or is refused with an
// InputError naming it, never another exception or a crash.
TEST(ImageFormats, DamagedFilesAreReadOrRefusedWithAnInputError) {
    std::uint32_t state = 12345;
    auto random = [&] { return state = state * 1664525u + 1013904223u; };
    int refused = 0, read = 0;
    for (const fs::directory_entry& e : fs::directory_iterator(fixtures() / "files")) {
        const std::string name = e.path().filename().string();
        const std::vector<unsigned char> bytes = fileBytes(e.path());
        std::vector<std::vector<unsigned char>> damaged;
        for (std::size_t keep : {std::size_t{0}, std::size_t{3}, std::size_t{9}, bytes.size() / 4, bytes.size() / 2, bytes.size() - 1})
            damaged.emplace_back(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(std::min(keep, bytes.size())));
        for (int k = 0; k < 40; ++k) {
            std::vector<unsigned char> copy = bytes;
            for (int flips = 1 + static_cast<int>(random() % 4); flips > 0; --flips) copy[random() % copy.size()] ^= static_cast<unsigned char>(1u << (random() % 8));
            damaged.push_back(std::move(copy));
        }
        for (std::size_t i = 0; i < damaged.size(); ++i) {
            SCOPED_TRACE(name + " damaged copy " + std::to_string(i));
            try {
                const Image img = readImageFromMemory(damaged[i].data(), damaged[i].size(), name);
                EXPECT_GT(img.pixelCount(), 0u);
                ++read;
            } catch (const InputError& error) {
                EXPECT_CONTAINS(error.what(), name + ": ");
                ++refused;
            }
        }
    }
    EXPECT_GT(refused, 100);
    EXPECT_GT(read, 100);
}

TEST(ImageFormats, PngColourMetadataPicksTheTransferFunction) {
    enum class Expect { Stored, Srgb, Gamma22 };
    struct Case {
        const char* file;
        const char* assumed;
        Expect values;
    };
    const Case cases[] = {
        {"rgb16.png", "sRGB (no colour-space metadata)", Expect::Srgb},
        {"tag-gama-linear.png", "linear (colour-space metadata: gAMA 1)", Expect::Stored},
        {"tag-gama-22.png", "gamma 2.2 (colour-space metadata: gAMA 0.45455)", Expect::Gamma22},
        // An sRGB chunk wins over gAMA; cICP wins over both (PNG, third edition).
        {"tag-srgb.png", "sRGB (colour-space metadata: sRGB chunk)", Expect::Srgb},
        {"tag-cicp-linear.png", "linear (colour-space metadata: cICP transfer 8)", Expect::Stored},
        {"tag-cicp-pq.png", "sRGB (unrecognised colour-space metadata: cICP transfer 16)", Expect::Srgb},
        {"rgb.jpg", "sRGB (no colour-space metadata)", Expect::Srgb},
        {"luminance.exr", "linear (floating point)", Expect::Stored},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.file);
        const fs::path path = fixtures() / "files" / c.file;
        std::string assumed;
        const Image tagged = readImage(path, ColorEncoding::Tagged, &assumed);
        EXPECT_EQ(assumed, c.assumed);
        const Image stored = readImage(path);
        for (std::size_t i = 0; i < stored.pixelCount(); ++i) {
            for (int k = 0; k < 3; ++k) {
                const float v = stored.data()[i][k];
                const float expected = c.values == Expect::Stored ? v
                                       : c.values == Expect::Srgb ? srgbToLinear(v)
                                                                  : std::pow(v, static_cast<float>(1.0 / 0.45455));
                ASSERT_NEAR(tagged.data()[i][k], expected, 1e-6f * std::max(1.0f, expected)) << "value " << i << "," << k;
            }
        }
    }
}

}  // namespace
}  // namespace hybridlab
