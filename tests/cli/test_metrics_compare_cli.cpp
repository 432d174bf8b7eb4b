// `hybridlab compare` through the real program: the numbers it prints and writes are the
// library's, the maps have their legends, and bad input exits with status 2 writing nothing.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/image/image_codecs.h"
#include "common/image/image_io.h"
#include "metrics/heatmap.h"
#include "metrics/metrics.h"
#include "tests/support/cli_runner.h"
#include "tests/support/metric_test_images.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

namespace fs = std::filesystem;
using test::CliResult;
using test::CliRun;
using test::runHybridlab;
using test::runHybridlabAll;
using test::TempDir;

struct Files {
    TempDir dir;
    fs::path test = dir / "test.exr", reference = dir / "reference.exr", mask = dir / "mask.png";
    fs::path small = dir / "small.exr", wrongMask = dir / "wrong-mask.png", emptyMask = dir / "empty-mask.png";
    Image testImage, referenceImage, maskImage;

    Files() {
        const cv::Mat3f pattern = test::displayPattern(64, 48);
        referenceImage = test::fromDisplay(pattern);
        testImage = referenceImage;
        for (int y = 10; y < 30; ++y) {
            for (int x = 8; x < 40; ++x) testImage.at(x, y) *= 0.7f;
        }
        maskImage = Image(64, 48, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
        for (int y = 0; y < 24; ++y) {
            for (int x = 0; x < 32; ++x) maskImage.at(x, y) = glm::vec4(1.0f);
        }
        writeExr(test, testImage);
        writeExr(reference, referenceImage);
        writePng(mask, maskImage);
        writeExr(small, Image(32, 24, glm::vec4(0.5f)));
        writePng(wrongMask, Image(32, 24, glm::vec4(1.0f)));
        writePng(emptyMask, Image(64, 48, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f)));
    }
};

std::string readText(const fs::path& path) {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

struct BadInputCase {
    std::vector<std::string> args;
    std::string fragment;  // of the one-line message
};

std::vector<BadInputCase> badInputCases(const Files& f) {
    return {
        {{(f.dir / "missing.exr").string(), f.reference.string()}, "missing.exr: image file not found"},
        {{f.small.string(), f.reference.string()}, "small.exr is 32x24 but " + f.reference.string() + " is 64x48"},
        {{f.test.string(), f.reference.string(), "--mask", f.wrongMask.string()}, "wrong-mask.png is 32x24 but the images are 64x48"},
        {{f.test.string(), f.reference.string(), "--mask", f.emptyMask.string()}, "empty-mask.png: the mask selects no pixel"},
        {{f.test.string(), f.reference.string(), "--ppd", "0"}, "--ppd"},
    };
}

void expectReportFilesHoldTheLibrarysNumbers(const Files& f, const fs::path& out) {
    // The JSON holds the library's numbers for the files as read (EXR: linear, as written).
    const PixelMask mask = PixelMask::fromImage(readImage(f.mask));
    const MetricReport expected = computeMetrics(readImage(f.test), readImage(f.reference), {}, &mask);
    const nlohmann::json j = nlohmann::json::parse(readText(out / "metrics.json"));
    EXPECT_EQ(j.at("width"), 64);
    EXPECT_EQ(j.at("height"), 48);
    EXPECT_EQ(j.at("settings").at("error_space"), "display");
    EXPECT_EQ(j.at("whole").at("pixels"), 64 * 48);
    EXPECT_DOUBLE_EQ(j.at("whole").at("ssim").get<double>(), expected.whole.ssim);
    EXPECT_DOUBLE_EQ(j.at("whole").at("rmse").get<double>(), expected.whole.error.rmse);
    EXPECT_DOUBLE_EQ(j.at("whole").at("psnr_db").get<double>(), expected.whole.error.psnr);
    EXPECT_DOUBLE_EQ(j.at("whole").at("flip").at("mean").get<double>(), expected.whole.flip.mean);
    EXPECT_DOUBLE_EQ(j.at("whole").at("flip").at("weighted_median").get<double>(), expected.whole.flip.weightedMedian);
    EXPECT_EQ(j.at("masked").at("pixels"), 32 * 24);
    EXPECT_DOUBLE_EQ(j.at("masked").at("flip").at("mean").get<double>(), expected.masked->flip.mean);
    EXPECT_EQ(j.at("maps").at("flip").at("colormap"), "magma");
    EXPECT_DOUBLE_EQ(j.at("whole").at("flip_hdr").at("mean").get<double>(), expected.whole.flipHdr.mean);
    EXPECT_GT(expected.whole.flipHdr.mean, 0.0);

    for (const char* name : {"diff.png", "ssim.png", "flip.png", "flip_hdr.png"}) {
        SCOPED_TRACE(name);
        const Image map = readImage(out / name);
        EXPECT_EQ(map.width(), 64);
        EXPECT_EQ(map.height(), 48 + legendHeight(64));
    }
    std::vector<std::string> written;
    for (const auto& e : fs::directory_iterator(out)) written.push_back(e.path().filename().string());
    std::sort(written.begin(), written.end());
    EXPECT_EQ(written, (std::vector<std::string>{"diff.png", "flip.png", "flip_hdr.png", "metrics.json", "ssim.png"}));  // no temporary left
}

// One test, so that the program's start-up (~0.3 s) is paid by all the runs at once.
TEST(CompareCommand, WritesTheMetricsAndMapsAndRejectsBadInputWritingNothing) {
    Files f;
    const fs::path out = f.dir / "out", badOut = f.dir / "bad-out";
    std::vector<CliRun> runs = {
        {{"compare", f.test.string(), f.reference.string(), "--mask", f.mask.string(), "--out", out.string()}, {}},
        {{"compare", f.test.string(), f.reference.string(), "--linear", "--channels", "--ppd", "30"}, {}},
    };
    const std::vector<BadInputCase> bad = badInputCases(f);
    for (const BadInputCase& c : bad) {
        std::vector<std::string> args{"compare"};
        args.insert(args.end(), c.args.begin(), c.args.end());
        args.insert(args.end(), {"--out", badOut.string()});
        runs.push_back({args, {}});
    }
    const std::vector<CliResult> results = runHybridlabAll(runs);

    const CliResult& r = results[0];
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    for (const char* row : {"SSIM", "RMSE", "PSNR (dB)", "FLIP mean", "FLIP weighted median", "FLIP weighted 1st quartile",
                            "FLIP weighted 3rd quartile", "whole image", "mask"}) {
        EXPECT_CONTAINS(r.out, row);
    }
    expectReportFilesHoldTheLibrarysNumbers(f, out);

    const CliResult& options = results[1];
    ASSERT_EQ(options.exitStatus, 0) << options.err;
    EXPECT_CONTAINS(options.out, "SSIM on R, G, B (mean); RMSE and PSNR on linear values; FLIP at 30 pixels per degree");

    for (std::size_t i = 0; i < bad.size(); ++i) {
        SCOPED_TRACE(bad[i].fragment);
        const CliResult& b = results[2 + i];
        EXPECT_EQ(b.exitStatus, 2) << b.err;
        EXPECT_EQ(b.out, "");
        EXPECT_EQ(b.err.rfind("hybridlab: error: ", 0), 0u) << b.err;
        EXPECT_CONTAINS(b.err, bad[i].fragment);
    }
    EXPECT_FALSE(fs::exists(badOut));
}

// Writes `values` as a 16-bit PNG as they are, tagged Linear (a gAMA chunk of 1.0, as POV-Ray's
// File_Gamma=1.0 writes) or not at all (None).
void writeTaggedPng16(const fs::path& path, const Image& values, ColorTag::Kind tag) {
    const std::vector<unsigned char> bytes = encodePng(values, 16, tag);
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

TEST(CompareCommand, ALinearPngScoresAsTheSameImageInExrAndEachInputSaysWhatItWasTakenAs) {
    Files f;
    // Linear values that 16 bits hold exactly, so that the PNG and the EXR carry the same numbers.
    Image linear = f.testImage;
    for (std::size_t i = 0; i < linear.pixelCount(); ++i) {
        glm::vec4& p = linear.data()[i];
        for (int c = 0; c < 3; ++c) p[c] = std::round(std::clamp(p[c], 0.0f, 1.0f) * 65535.0f) / 65535.0f;
    }
    const fs::path exr = f.dir / "linear.exr", png = f.dir / "linear.png", untagged = f.dir / "untagged.png";
    writeExr(exr, linear);
    writeTaggedPng16(png, linear, ColorTag::Kind::Linear);
    writeTaggedPng16(untagged, linear, ColorTag::Kind::None);
    const std::vector<CliResult> r = runHybridlabAll({{{"compare", png.string(), f.reference.string()}, {}},
                                                     {{"compare", exr.string(), f.reference.string()}, {}},
                                                     {{"compare", untagged.string(), f.reference.string()}, {}}});
    for (const CliResult& c : r) ASSERT_EQ(c.exitStatus, 0) << c.err;
    // The same numbers, line for line, after the two lines that name the inputs.
    auto metrics = [](const std::string& out) { return out.substr(out.find('\n', out.find('\n') + 1)); };
    EXPECT_EQ(metrics(r[0].out), metrics(r[1].out));
    EXPECT_CONTAINS(r[0].out, "linear.png  [linear (colour-space metadata: gAMA 1)]");
    EXPECT_CONTAINS(r[1].out, "linear.exr  [linear (floating point)]");
    // Without metadata a PNG is sRGB, as before: the same values then score differently.
    EXPECT_CONTAINS(r[2].out, "untagged.png  [sRGB");
    EXPECT_NE(metrics(r[2].out), metrics(r[1].out));
}

// Several tests against one reference: one table, --json with every test's numbers, every
// difference map on one scale (the largest difference of all, or --range), and --fail-above's
// exit status.
TEST(CompareCommand, SeveralTestsAgainstOneReferenceOnOneScale) {
    Files f;
    Image darker = f.referenceImage;
    for (std::size_t i = 0; i < darker.pixelCount(); ++i) darker.data()[i] *= glm::vec4(0.4f, 0.4f, 0.4f, 1.0f);
    const fs::path dark = f.dir / "dark.exr", same = f.dir / "same.exr", out = f.dir / "maps", ranged = f.dir / "ranged";
    writeExr(dark, darker);
    writeExr(same, f.referenceImage);
    const std::vector<std::string> three = {"compare", f.test.string(), dark.string(), same.string(), f.reference.string()};
    auto with = [&](std::vector<std::string> extra) {
        std::vector<std::string> args = three;
        args.insert(args.end(), extra.begin(), extra.end());
        return CliRun{args, {}};
    };
    const std::vector<CliResult> r = runHybridlabAll({with({"--out", out.string()}),
                                                     with({"--json"}),
                                                     with({"--json", "--range", "0.5", "--out", ranged.string()}),
                                                     with({"--fail-above", "flip=1e-9"}),
                                                     with({"--fail-above", "ssim=0.999999", "--json"}),
                                                     with({"--fail-above", "sharpness=1"})});
    const CliResult& table = r[0];
    ASSERT_EQ(table.exitStatus, 0) << table.err;
    for (const char* column : {"test", "dark", "same"}) EXPECT_CONTAINS(table.out, column);
    EXPECT_CONTAINS(table.out, "reference  " + f.reference.string());

    // The JSON: each test's numbers are the library's, in the order given.
    ASSERT_EQ(r[1].exitStatus, 0) << r[1].err;
    const nlohmann::json j = nlohmann::json::parse(r[1].out);
    ASSERT_EQ(j.at("tests").size(), 3u);
    const Image reference = readImage(f.reference);
    double largest = 0.0;
    for (std::size_t i = 0; i < 3; ++i) {
        const fs::path path = i == 0 ? f.test : i == 1 ? dark : same;
        const MetricReport expected = computeMetrics(readImage(path), reference);
        const nlohmann::json& t = j.at("tests").at(i);
        EXPECT_EQ(t.at("test"), path.string());
        EXPECT_DOUBLE_EQ(t.at("whole").at("ssim").get<double>(), expected.whole.ssim);
        EXPECT_DOUBLE_EQ(t.at("whole").at("flip").at("mean").get<double>(), expected.whole.flip.mean);
        double high = 0.0;
        cv::minMaxLoc(expected.maps.absoluteDifference, nullptr, &high);
        largest = std::max(largest, high);
    }
    EXPECT_EQ(j.at("tests").at(2).at("whole").at("rmse").get<double>(), 0.0);
    EXPECT_EQ(j.at("failed"), nlohmann::json::array());
    // One scale for every map: the largest difference of the three (the darker image's).
    for (const nlohmann::json& t : j.at("tests")) EXPECT_DOUBLE_EQ(t.at("maps").at("diff").at("range").at(1).get<double>(), largest);
    EXPECT_GT(largest, j.at("tests").at(0).at("whole").at("rmse").get<double>());
    for (const char* name : {"test", "dark", "same"}) {
        SCOPED_TRACE(name);
        for (const char* file : {"diff.png", "ssim.png", "flip.png", "flip_hdr.png", "metrics.json"}) EXPECT_TRUE(fs::exists(out / name / file)) << file;
        EXPECT_DOUBLE_EQ(nlohmann::json::parse(readText(out / name / "metrics.json")).at("maps").at("diff").at("range").at(1).get<double>(),
                         largest);
    }
    // --range fixes the scale.
    ASSERT_EQ(r[2].exitStatus, 0) << r[2].err;
    EXPECT_DOUBLE_EQ(nlohmann::json::parse(r[2].out).at("tests").at(1).at("maps").at("diff").at("range").at(1).get<double>(), 0.5);
    EXPECT_DOUBLE_EQ(nlohmann::json::parse(readText(ranged / "same" / "metrics.json")).at("maps").at("diff").at("range").at(1).get<double>(), 0.5);

    // --fail-above: exit status 1 naming the tests worse than the bound (the two that differ from
    // the reference, not its copy), the table printed all the same.
    EXPECT_EQ(r[3].exitStatus, 1) << r[3].err;
    EXPECT_CONTAINS(r[3].out, "FLIP mean");
    EXPECT_CONTAINS(r[3].out, "fail: test: flip ");
    EXPECT_CONTAINS(r[3].out, "fail: dark: flip ");
    EXPECT_EQ(r[3].out.find("fail: same:"), std::string::npos) << r[3].out;
    // For SSIM worse is lower.
    EXPECT_EQ(r[4].exitStatus, 1) << r[4].err;
    const nlohmann::json failed = nlohmann::json::parse(r[4].out).at("failed");
    ASSERT_EQ(failed.size(), 2u) << failed;
    EXPECT_EQ(failed.at(0).get<std::string>().rfind("test: ssim ", 0), 0u) << failed;
    EXPECT_EQ(failed.at(1).get<std::string>().rfind("dark: ssim ", 0), 0u) << failed;
    EXPECT_CONTAINS(failed.at(1).get<std::string>(), "is worse than 0.999999 (below)");
    EXPECT_EQ(r[5].exitStatus, 2);
    EXPECT_CONTAINS(r[5].err, "--fail-above sharpness=1: expected METRIC=VALUE with METRIC one of ssim, rmse, psnr, flip, flip_hdr");
}

TEST(CompareCommand, TestsSharingAFileNameGetAFolderEachInsideOut) {
    Files f;
    const fs::path other = f.dir / "other", out = f.dir / "maps";
    fs::create_directories(other);
    const fs::path twin = other / f.test.filename();
    fs::copy_file(f.test, twin);
    // Absolute paths, one of them twice: every folder lies inside --out, named by place.
    const CliResult r = runHybridlab({"compare", f.test.string(), twin.string(), f.test.string(), f.reference.string(), "--out", out.string()});
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    const std::string stem = f.test.stem().string();
    for (const std::string& name : {stem + "-1", stem + "-2", stem + "-3"}) {
        SCOPED_TRACE(name);
        EXPECT_TRUE(fs::exists(out / name / "metrics.json"));
        EXPECT_CONTAINS(r.out, name);
    }
    std::size_t folders = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(out)) ++folders;
    EXPECT_EQ(folders, 3u);
    EXPECT_TRUE(fs::is_regular_file(f.test));  // not taken for a folder
}

}  // namespace
}  // namespace hybridlab
