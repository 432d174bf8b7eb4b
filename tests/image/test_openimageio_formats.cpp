// The formats read through OpenImageIO's plugin (common/image/openimageio_codec.cpp): TIFF (8 and
// 16 bits, float) and PFM (RGB and grey) from tests/fixtures/image_formats/openimageio, made by its
// make_files.py, decode to the values OpenImageIO 2.4 gave for them, bit for bit; PFM's values sit
// where the file says (its rows are stored bottom up); a TIFF texture renders as the same pixels in a
// PNG do; `compare` takes a PFM; and the program itself does not link OpenImageIO, which only a file
// of those formats loads.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/image/image_codecs.h"
#include "common/image/image_io.h"
#include "tests/support/cli_runner.h"
#include "tests/support/decoded_image_checks.h"
#include "tests/support/shell_command.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

using test::expectSamePixels;
using test::fileBytes;

namespace fs = std::filesystem;

fs::path fixtures() { return test::fixturesDir() / "image_formats" / "openimageio"; }

TEST(OpenImageIoFormats, EveryFileDecodesAsOpenImageIoDecodedIt) {
    test::expectEveryFileDecodesAsOpenImageIoDecodedIt(fixtures(), 5);
}

// make_files.py writes 100 y + 10 x + c + 0.5 (RGB) and 100 y + 10 x + 0.25 (grey) at row y (from
// the top), column x, channel c.
TEST(OpenImageIoFormats, PfmValuesSitWhereTheFileSays) {
    const Image rgb = readImage(fixtures() / "files" / "rgb.pfm");
    const Image grey = readImage(fixtures() / "files" / "grey.pfm");
    ASSERT_EQ(rgb.width(), 5);
    ASSERT_EQ(rgb.height(), 3);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 5; ++x) {
            const float base = static_cast<float>(100 * y + 10 * x);
            EXPECT_EQ(rgb.at(x, y), glm::vec4(base + 0.5f, base + 1.5f, base + 2.5f, 1.0f)) << x << "," << y;
            EXPECT_EQ(grey.at(x, y), glm::vec4(base + 0.25f, base + 0.25f, base + 0.25f, 1.0f)) << x << "," << y;
        }
}

// A plane textured with the TIFF, and with a PNG of the same 8-bit values: the same image.
TEST(OpenImageIoFormats, ATiffTextureRendersAsThePngOfItsPixels) {
    test::TempDir dir;
    const Image tiff = readImage(fixtures() / "files" / "rgb8.tif");
    writePng(dir / "rgb8.png", tiff);
    fs::copy_file(fixtures() / "files" / "rgb8.tif", dir / "rgb8.tif");
    auto scene = [&](const std::string& texture) {
        const fs::path file = dir / ("textured-" + texture + ".toml");
        test::writeTextFile(file, "[materials.picture]\ndiffuse = [1, 1, 1]\ndiffuse_texture = \"" + texture +
                                      "\"\n[[objects]]\nname = \"wall\"\nprimitive = \"plane\"\nmaterial = \"picture\"\nrotation = [90, 0, 0]\n"
                                      "scale = 2.0\n[[lights]]\ntype = \"directional\"\ndirection = [0, 0, -1]\n"
                                      "[camera]\nposition = [0, 0, 3]\nlook_at = [0, 0, 0]\n");
        return file.string();
    };
    const std::vector<test::CliResult> r = test::runHybridlabAll(
        {{{"render", "--scene", scene("rgb8.tif"), "--width", "40", "--height", "24", "--out", (dir / "tif.exr").string()}, {}},
         {{"render", "--scene", scene("rgb8.png"), "--width", "40", "--height", "24", "--out", (dir / "png.exr").string()}, {}}});
    for (const test::CliResult& c : r) ASSERT_EQ(c.exitStatus, 0) << c.err;
    const Image fromTiff = readImage(dir / "tif.exr");
    expectSamePixels(fromTiff, readImage(dir / "png.exr"));
    // Not one flat colour: the texture is there.
    EXPECT_NE(fromTiff.at(10, 12), fromTiff.at(30, 12));
}

// A PFM written here (bottom row first, as the format stores it) against an EXR of the same values,
// top row first: the same image.
TEST(OpenImageIoFormats, CompareTakesAPfm) {
    test::TempDir dir;
    constexpr int kWidth = 24, kHeight = 16;
    Image image(kWidth, kHeight);
    std::string pfm = "PF\n" + std::to_string(kWidth) + " " + std::to_string(kHeight) + "\n-1.0\n";
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) image.at(x, y) = glm::vec4(0.05f * x, 0.03f * y, 0.5f, 1.0f);
    for (int y = kHeight - 1; y >= 0; --y)
        for (int x = 0; x < kWidth; ++x)
            for (int c = 0; c < 3; ++c) pfm.append(reinterpret_cast<const char*>(&image.at(x, y)[c]), sizeof(float));
    test::writeTextFile(dir / "image.pfm", pfm);
    writeExr(dir / "image.exr", image);
    const test::CliResult r = test::runHybridlab({"compare", (dir / "image.pfm").string(), (dir / "image.exr").string(), "--json"});
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j.at("tests").at(0).at("taken_as"), "linear (floating point)");
    EXPECT_EQ(j.at("tests").at(0).at("whole").at("rmse").get<double>(), 0.0);
    EXPECT_EQ(j.at("tests").at(0).at("whole").at("ssim").get<double>(), 1.0);
}

// OpenImageIO links every codec there is: the program loads it only for a file that needs it.
TEST(OpenImageIoFormats, TheProgramDoesNotLinkOpenImageIo) {
    const test::CommandOutput ldd = test::commandOutput("ldd '" + std::string(HYBRIDLAB_BIN) + "' 2>&1");
    ASSERT_EQ(ldd.exitStatus, 0) << ldd.out;
    EXPECT_CONTAINS(ldd.out, "libpng");
    EXPECT_EQ(ldd.out.find("OpenImageIO"), std::string::npos) << ldd.out;
}

}  // namespace
}  // namespace hybridlab
