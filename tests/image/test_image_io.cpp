// Image files (image_io.h) and the Image class: exact EXR round trips, sRGB PNG round trips,
// atomic writes that leave nothing behind, and clear errors.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "common/core/input_error.h"
#include "common/image/color.h"
#include "common/image/image.h"
#include "common/image/image_io.h"
#include "common/image/mip_chain.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

// A 7 x 5 gradient with values that need float precision (and some outside [0, 1]).
Image testImage() {
    Image img(7, 5);
    for (int y = 0; y < img.height(); ++y) {
        for (int x = 0; x < img.width(); ++x) {
            img.at(x, y) = {static_cast<float>(x) / 6.0f, static_cast<float>(y) / 4.0f, 0.123456789f * static_cast<float>(x + y),
                            1.0f - 0.1f * static_cast<float>(x)};
        }
    }
    img.at(0, 0) = {-0.25f, 3.5f, 1e-6f, 1.0f};
    return img;
}

std::vector<std::string> folderContents(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

TEST(Image, StorageAndBilinearSampling) {
    Image img(3, 2, glm::vec4(0.5f));
    EXPECT_EQ(img.width(), 3);
    EXPECT_EQ(img.height(), 2);
    EXPECT_EQ(img.pixelCount(), 6u);
    EXPECT_FALSE(img.empty());
    EXPECT_TRUE(Image().empty());
    img.at(2, 1) = glm::vec4(1, 2, 3, 4);
    EXPECT_EQ(img.data()[5], glm::vec4(1, 2, 3, 4));
    Image copy = img;
    EXPECT_TRUE(copy == img);
    copy.at(0, 0).r = 0.0f;
    EXPECT_FALSE(copy == img);

    // Bilinear sampling wraps around.
    Image ramp(2, 1);
    ramp.at(0, 0) = glm::vec4(0.0f);
    ramp.at(1, 0) = glm::vec4(1.0f);
    // Texel centres at u = 0.25 and 0.75.
    EXPECT_VEC_NEAR(ramp.sampleBilinearWrap(0.25f, 0.5f), glm::vec4(0.0f), 1e-6f);
    EXPECT_VEC_NEAR(ramp.sampleBilinearWrap(0.75f, 0.5f), glm::vec4(1.0f), 1e-6f);
    EXPECT_VEC_NEAR(ramp.sampleBilinearWrap(0.5f, 0.5f), glm::vec4(0.5f), 1e-6f);
    // Halfway between the last texel and the first (wrapped) one.
    EXPECT_VEC_NEAR(ramp.sampleBilinearWrap(1.0f, 0.5f), glm::vec4(0.5f), 1e-6f);
    EXPECT_VEC_NEAR(ramp.sampleBilinearWrap(1.25f, 0.5f), glm::vec4(0.0f), 1e-6f);
    EXPECT_VEC_NEAR(ramp.sampleBilinearWrap(-0.25f, 0.5f), glm::vec4(1.0f), 1e-6f);
}

// The mip chain mirrors the rasterizer's blits: halved and floored sizes down to 1 x 1, each level
// the 2 x 2 box average of the one above (for even sizes); trilinear lookups blend two levels.
TEST(MipChain, LevelsAndTrilinearLookups) {
    Image board(4, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) board.at(x, y) = glm::vec4(static_cast<float>((x + y) % 2));
    const MipChain chain(board);
    ASSERT_EQ(chain.levels(), 3);
    EXPECT_EQ(chain.level(1).width(), 2);
    EXPECT_EQ(chain.level(2).width(), 1);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x) EXPECT_VEC_NEAR(chain.level(1).at(x, y), glm::vec4(0.5f), 1e-6f);
    // Magnified or at level 0: the bilinear lookup of the base image (texel (0, 0) is 0).
    EXPECT_VEC_NEAR(chain.sampleTrilinearWrap(0.125f, 0.125f, -3.0f), glm::vec4(0.0f), 1e-6f);
    EXPECT_VEC_NEAR(chain.sampleTrilinearWrap(0.125f, 0.125f, 0.25f), glm::vec4(0.125f), 1e-6f);  // 0.75 * 0 + 0.25 * 0.5
    EXPECT_VEC_NEAR(chain.sampleTrilinearWrap(0.3f, 0.7f, 9.0f), glm::vec4(0.5f), 1e-6f);

    const Image oddBase(5, 3, glm::vec4(0.25f));
    const MipChain odd(oddBase);
    EXPECT_EQ(odd.levels(), 3);
    EXPECT_EQ(odd.level(1).width(), 2);
    EXPECT_EQ(odd.level(1).height(), 1);
    EXPECT_EQ(odd.level(2).width(), 1);
}

TEST(Image, AMovedFromImageIsEmptyAndZeroSized) {
    Image a(4, 3, glm::vec4(1.0f));
    Image b = std::move(a);
    EXPECT_EQ(b.width(), 4);
    EXPECT_EQ(b.pixelCount(), 12u);
    EXPECT_EQ(a.width(), 0);  // NOLINT(bugprone-use-after-move): the state after a move is the point
    EXPECT_EQ(a.height(), 0);
    EXPECT_TRUE(a.empty());
    Image c;
    c = std::move(b);
    EXPECT_EQ(c.height(), 3);
    EXPECT_EQ(b.width(), 0);  // NOLINT(bugprone-use-after-move)
}

TEST(ImageIo, ExrRoundTripIsExact) {
    TempDir dir;
    const Image img = testImage();
    writeExr(dir / "image.exr", img);
    Image back = readImage(dir / "image.exr");
    ASSERT_EQ(back.width(), img.width());
    ASSERT_EQ(back.height(), img.height());
    EXPECT_TRUE(back == img) << "32-bit float EXR keeps every value, sign and alpha";
    // sRGB decoding applies to integer formats only: a float EXR reads back unchanged.
    EXPECT_TRUE(readImage(dir / "image.exr", ColorEncoding::Srgb) == img);
}

TEST(ImageIo, DisplayPngRoundTrip) {
    TempDir dir;
    const Image img = testImage();
    writeDisplayPng(dir / "image.png", img);
    Image encoded = readImage(dir / "image.png");  // the stored sRGB values
    Image linear = readImage(dir / "image.png", ColorEncoding::Srgb);
    ASSERT_EQ(encoded.width(), img.width());
    ASSERT_EQ(encoded.height(), img.height());
    for (int y = 0; y < img.height(); ++y) {
        for (int x = 0; x < img.width(); ++x) {
            const glm::vec4 expected = linearToDisplay(img.at(x, y));
            // 8 bits: within half a step of the exact encoded value, and on the 1/255 grid.
            ASSERT_VEC_NEAR(encoded.at(x, y), expected, 0.5f / 255.0f + 1e-6f) << "pixel " << x << ", " << y;
            for (int k = 0; k < 4; ++k) ASSERT_NEAR(encoded.at(x, y)[k] * 255.0f, std::round(encoded.at(x, y)[k] * 255.0f), 1e-3f);
            // Decoded: back to linear, the same within one step after sRGB encoding.
            const glm::vec4 d = linear.at(x, y);
            ASSERT_VEC_NEAR(glm::vec4(linearToSrgb(glm::vec3(d)), d.a), expected, 1.0f / 255.0f) << "pixel " << x << ", " << y;
        }
    }
    // Out-of-range values are clamped: (-0.25, 3.5) -> (0, 1).
    EXPECT_EQ(encoded.at(0, 0).r, 0.0f);
    EXPECT_EQ(encoded.at(0, 0).g, 1.0f);

    // 16 bits: within half a 16-bit step.
    writeDisplayPng(dir / "image16.png", img, 16);
    Image encoded16 = readImage(dir / "image16.png");
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x)
            ASSERT_VEC_NEAR(encoded16.at(x, y), linearToDisplay(img.at(x, y)), 0.5f / 65535.0f + 1e-6f);
}

TEST(ImageIo, PngKeepsStraightAlphaAndPlainValues) {
    // PNG stores colour unassociated from alpha. Colours must be written and read as they are,
    // not divided by alpha on write nor multiplied by it on read (premultiplied alpha).
    // (0.2, 1.0) at alpha 0.5 tells them apart: divided, 1.0 would clip to 1 and read back as 0.5.
    TempDir dir;
    Image mask(3, 1);
    mask.at(0, 0) = {0.5f, 0.25f, 2.0f, 1.0f};   // clamped to [0, 1], no transfer function
    mask.at(1, 0) = {-1.0f, 1.0f, 0.2f, 0.5f};
    mask.at(2, 0) = {0.8f, 0.6f, 0.4f, 0.25f};
    writePng(dir / "mask.png", mask);
    Image back = readImage(dir / "mask.png");
    const float tol = 0.5f / 255.0f + 1e-6f;
    EXPECT_VEC_NEAR(back.at(0, 0), glm::vec4(0.5f, 0.25f, 1.0f, 1.0f), tol);
    EXPECT_VEC_NEAR(back.at(1, 0), glm::vec4(0.0f, 1.0f, 0.2f, 0.5f), tol);
    EXPECT_VEC_NEAR(back.at(2, 0), glm::vec4(0.8f, 0.6f, 0.4f, 0.25f), tol);
    // The display PNG of a translucent pixel: the sRGB colour as it is, alpha as it is.
    Image translucent(1, 1, glm::vec4(0.5f, 0.25f, 0.1f, 0.5f));
    writeDisplayPng(dir / "translucent.png", translucent);
    EXPECT_VEC_NEAR(readImage(dir / "translucent.png").at(0, 0), linearToDisplay(translucent.at(0, 0)), tol);
    Image decoded = readImage(dir / "translucent.png", ColorEncoding::Srgb);
    EXPECT_VEC_NEAR(decoded.at(0, 0), translucent.at(0, 0), 0.005f) << "decoded back to linear";
}

TEST(ImageIo, AtomicWrite) {
    TempDir dir;
    const Image img = testImage();
    writeImageAtomically(dir / "frame.exr", img);
    writeImageAtomically(dir / "frame.png", img);
    EXPECT_EQ(folderContents(dir.path()), (std::vector<std::string>{"frame.exr", "frame.png"})) << "no temporary files left";
    EXPECT_TRUE(readImage(dir / "frame.exr") == img);
    Image png = readImage(dir / "frame.png");
    EXPECT_VEC_NEAR(png.at(3, 2), linearToDisplay(img.at(3, 2)), 0.5f / 255.0f + 1e-6f) << "PNG is the sRGB display image";
    // Overwriting replaces the file.
    Image black(7, 5, glm::vec4(0, 0, 0, 1));
    writeImageAtomically(dir / "frame.exr", black);
    EXPECT_TRUE(readImage(dir / "frame.exr") == black);
    // Upper-case extensions work.
    writeImageAtomically(dir / "FRAME.EXR", img);
    EXPECT_TRUE(readImage(dir / "FRAME.EXR") == img);
    EXPECT_EQ(folderContents(dir.path()).size(), 3u);

    // Unknown extensions are rejected before anything is written.
    for (const char* name : {"frame.bmp", "frame.jpg", "frame"}) {
        try {
            writeImageAtomically(dir / name, testImage());
            ADD_FAILURE() << name << ": expected InputError";
        } catch (const InputError& e) {
            EXPECT_CONTAINS(e.what(), (dir / name).string());
            EXPECT_CONTAINS(e.what(), "unsupported image extension");
            EXPECT_CONTAINS(e.what(), "(expected .exr or .png)");
        }
    }
    EXPECT_EQ(folderContents(dir.path()).size(), 3u) << "nothing written";
}

TEST(ImageIo, ReadErrorsNameTheFile) {
    TempDir dir;
    const fs::path missing = dir / "nowhere.exr";
    try {
        readImage(missing);
        ADD_FAILURE() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_CONTAINS(e.what(), missing.string());
        EXPECT_CONTAINS(e.what(), "not found");
    }

    // Garbage is an InputError too.
    test::writeTextFile(dir / "fake.png", "this is not a PNG file");
    try {
        readImage(dir / "fake.png");
        ADD_FAILURE() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_CONTAINS(e.what(), (dir / "fake.png").string());
    }

    // A device that never ends is refused before it is read.
    try {
        readImage("/dev/zero");
        ADD_FAILURE() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_CONTAINS(e.what(), "/dev/zero: is not a regular file (a device or a pipe), expected an image file");
    }
}

TEST(ImageIo, DecodesEncodedImagesFromMemory) {
    TempDir dir;
    Image img(3, 2, glm::vec4(0.5f, 0.25f, 1.0f, 1.0f));
    img.at(1, 1) = {0.7f, 0.35f, 0.05f, 0.4f};  // translucent: read without premultiplying
    writeDisplayPng(dir / "small.png", img);
    std::ifstream in(dir / "small.png", std::ios::binary);
    std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    Image back = readImageFromMemory(bytes.data(), bytes.size(), "embedded", ColorEncoding::Srgb);
    ASSERT_EQ(back.width(), 3);
    ASSERT_EQ(back.height(), 2);
    for (const auto& [x, y] : {std::pair{0, 0}, std::pair{1, 1}}) {
        const glm::vec4 d = back.at(x, y);
        EXPECT_VEC_NEAR(glm::vec4(linearToSrgb(glm::vec3(d)), d.a), linearToDisplay(img.at(x, y)), 1.0f / 255.0f);
    }
}

}  // namespace
}  // namespace hybridlab
