// SSIM, RMSE and PSNR against independent implementations: scikit-image's structural_similarity
// (gaussian_weights=True, sigma=1.5, use_sample_covariance=False, data_range=1.0) and numpy, run
// by tests/metrics/metrics_reference.py on six image pairs this test writes: noise, blur, JPEG-like
// blocking, brightness shift, contrast change, and a rendered pair. No reference number is
// stored here; scikit-image computes them every time.
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "metrics/metrics.h"
#include "techniques/technique.h"
#include "tests/support/metric_test_images.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

namespace fs = std::filesystem;

// numpy's .npy format, version 1.0: float32 little-endian, C order, height x width x channels.
void writeNpy(const fs::path& path, const cv::Mat& values) {
    CV_Assert(values.depth() == CV_32F && values.isContinuous());
    std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (" + std::to_string(values.rows) + ", " +
                         std::to_string(values.cols) + (values.channels() > 1 ? ", " + std::to_string(values.channels()) : "") + "), }";
    // Magic (6) + version (2) + length (2) + header, padded with spaces and ended by '\n' to a
    // multiple of 64 bytes.
    header.append(64 - (10 + header.size() + 1) % 64, ' ');
    header += '\n';
    std::ofstream out(path, std::ios::binary);
    const std::uint16_t length = static_cast<std::uint16_t>(header.size());
    out.write("\x93NUMPY\x01\x00", 8);
    out.put(static_cast<char>(length & 0xff)).put(static_cast<char>(length >> 8));
    out << header;
    out.write(reinterpret_cast<const char*>(values.data), static_cast<std::streamsize>(values.total() * values.elemSize()));
    if (!out) throw std::runtime_error("cannot write " + path.string());
}

struct CommandOutput {
    int exitStatus = -1;
    std::string out;
};

CommandOutput runAndCapture(const std::string& command) {
    FILE* pipe = ::popen(command.c_str(), "r");
    if (!pipe) throw std::runtime_error("cannot run " + command);
    CommandOutput result;
    std::array<char, 4096> buffer;
    while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) result.out.append(buffer.data(), n);
    const int status = ::pclose(pipe);
    result.exitStatus = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

// Runs the reference script with a python3 that has scikit-image: Debian's (the set-up script
// installs python3-skimage for it), else whichever python3 comes first on the PATH. Nothing when
// neither has it.
std::optional<std::string> referenceNumbers(const fs::path& script, const fs::path& dir) {
    for (const char* python : {"/usr/bin/python3", "python3"}) {
        const CommandOutput r = runAndCapture(std::string(python) + " '" + script.string() + "' '" + dir.string() + "' 2>/dev/null");
        if (r.exitStatus == 0) return r.out;
        if (r.exitStatus != 3 && r.exitStatus != 127) throw std::runtime_error(script.string() + " failed:\n" + r.out);
    }
    return std::nullopt;
}

struct ImagePair {
    std::string name;
    Image test, reference;
};

// Every value v of `image` replaced by f(v), clamped to [0, 1].
cv::Mat3f mapped(const cv::Mat3f& image, const std::function<float(float)>& f) {
    cv::Mat3f out(image.size());
    for (int y = 0; y < image.rows; ++y) {
        for (int x = 0; x < image.cols; ++x) {
            for (int c = 0; c < 3; ++c) out(y, x)[c] = std::clamp(f(image(y, x)[c]), 0.0f, 1.0f);
        }
    }
    return out;
}

// Each 8 x 8 block keeps a quarter of its detail around the block mean, quantised to 1/32.
cv::Mat3f jpegLikeBlocks(const cv::Mat3f& image) {
    cv::Mat3f out = image.clone();
    for (int by = 0; by < image.rows; by += 8) {
        for (int bx = 0; bx < image.cols; bx += 8) {
            const cv::Rect block(bx, by, std::min(8, image.cols - bx), std::min(8, image.rows - by));
            const cv::Scalar mean = cv::mean(image(block));
            for (int y = block.y; y < block.y + block.height; ++y) {
                for (int x = block.x; x < block.x + block.width; ++x) {
                    for (int c = 0; c < 3; ++c) {
                        const double v = mean[c] + 0.25 * (image(y, x)[c] - mean[c]);
                        out(y, x)[c] = static_cast<float>(std::round(v * 32.0) / 32.0);
                    }
                }
            }
        }
    }
    return out;
}

Image renderWhittedClassic(const std::vector<std::pair<std::string, ParamValue>>& params) {
    Scene scene = loadSceneFile(findSceneFile("whitted-classic"));
    SceneContext context(scene);
    auto technique = createTechnique("whitted", params);
    technique->prepare(context);
    return technique->render(context, {scene.camera, 0.0, 160, 90}).image;
}

std::vector<ImagePair> imagePairs() {
    const cv::Mat3f base = test::displayPattern(128, 96);
    const Image reference = test::fromDisplay(base);
    std::mt19937 random(5);
    std::normal_distribution<float> gaussian(0.0f, 0.05f);
    cv::Mat3f blurred;
    cv::GaussianBlur(base, blurred, cv::Size(0, 0), 2.0);
    return {
        {"noise", test::fromDisplay(mapped(base, [&](float v) { return v + gaussian(random); })), reference},
        {"blur", test::fromDisplay(blurred), reference},
        {"blocking", test::fromDisplay(jpegLikeBlocks(base)), reference},
        {"brightness", test::fromDisplay(mapped(base, [](float v) { return v + 0.08f; })), reference},
        {"contrast", test::fromDisplay(mapped(base, [](float v) { return 0.5f + 0.6f * (v - 0.5f); })), reference},
        {"rendered", renderWhittedClassic({{"max_depth", std::string("1")}}), renderWhittedClassic({})},
    };
}

TEST(MetricsAgainstScikitImage, SsimRmseAndPsnrAgreeOnSixPairs) {
    test::TempDir dir;
    struct Ours {
        double ssimLuma, ssimRgb, rmse, psnr;
    };
    std::map<std::string, Ours> ours;
    for (const ImagePair& pair : imagePairs()) {
        SCOPED_TRACE(pair.name);
        // Exactly the values every metric reads.
        const cv::Mat3f t = metricRgb(pair.test, ValueSpace::Display), r = metricRgb(pair.reference, ValueSpace::Display);
        const cv::Mat1f lumaMap = ssimMap(t, r, SsimChannels::Luma);
        writeNpy(dir / (pair.name + ".test.npy"), t);
        writeNpy(dir / (pair.name + ".reference.npy"), r);
        writeNpy(dir / (pair.name + ".ssim_map.npy"), lumaMap);
        const ErrorStats error = errorStats(t, r, nullptr);
        ours[pair.name] = {ssimMean(lumaMap, nullptr), ssimMean(ssimMap(t, r, SsimChannels::PerChannel), nullptr), error.rmse, error.psnr};

        // The report computes the same numbers from the images.
        MetricOptions perChannel;
        perChannel.ssimChannels = SsimChannels::PerChannel;
        const MetricReport luma = computeMetrics(pair.test, pair.reference), rgb = computeMetrics(pair.test, pair.reference, perChannel);
        EXPECT_EQ(luma.whole.ssim, ours[pair.name].ssimLuma);
        EXPECT_EQ(rgb.whole.ssim, ours[pair.name].ssimRgb);
        EXPECT_EQ(luma.whole.error.rmse, error.rmse);
    }

    const fs::path script = test::sourceDir() / "tests" / "metrics" / "metrics_reference.py";
    const std::optional<std::string> numbers = referenceNumbers(script, dir.path());
    if (!numbers) {
        GTEST_SKIP() << "no python3 with scikit-image and numpy (Debian: apt-get install python3-skimage python3-numpy; "
                        "setup.sh installs them)";
    }
    const std::string& output = *numbers;
    std::istringstream lines(output);
    std::size_t compared = 0;
    double worstSsim = 0.0, worstMap = 0.0, worstRmse = 0.0, worstPsnr = 0.0;
    for (std::string line; std::getline(lines, line);) {
        nlohmann::json reference;
        ASSERT_NO_THROW(reference = nlohmann::json::parse(line)) << "unexpected output from " << script << ":\n" << output;
        const std::string name = reference.at("name");
        SCOPED_TRACE(name);
        ASSERT_TRUE(ours.count(name));
        const Ours& o = ours[name];
        EXPECT_NEAR(o.ssimLuma, reference.at("ssim_luma").get<double>(), 1e-4);
        EXPECT_NEAR(o.ssimRgb, reference.at("ssim_rgb").get<double>(), 1e-4);
        // The whole map, border included: cv::BORDER_REFLECT is scipy's mode 'reflect'.
        EXPECT_LT(reference.at("ssim_map_max_abs_diff").get<double>(), 1e-4);
        EXPECT_NEAR(o.rmse, reference.at("rmse").get<double>(), 1e-9);
        EXPECT_NEAR(o.psnr, reference.at("psnr").get<double>(), 1e-7);
        worstSsim = std::max({worstSsim, std::abs(o.ssimLuma - reference.at("ssim_luma").get<double>()),
                              std::abs(o.ssimRgb - reference.at("ssim_rgb").get<double>())});
        worstMap = std::max(worstMap, reference.at("ssim_map_max_abs_diff").get<double>());
        worstRmse = std::max(worstRmse, std::abs(o.rmse - reference.at("rmse").get<double>()));
        worstPsnr = std::max(worstPsnr, std::abs(o.psnr - reference.at("psnr").get<double>()));
        ++compared;
    }
    EXPECT_EQ(compared, ours.size()) << output;
    std::printf("largest |ours - reference| over %zu pairs: SSIM %.3g, SSIM map %.3g, RMSE %.3g, PSNR %.3g dB\n", compared, worstSsim,
                worstMap, worstRmse, worstPsnr);
}

}  // namespace
}  // namespace hybridlab
