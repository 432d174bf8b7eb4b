// The reference agrees with POV-Ray on scenes exported by `hybridlab export-pov` (DESIGN.md
// "Invariants that tests hold"): POV-Ray is an independent Whitted ray tracer, so the two display
// images must agree to SSIM >= 0.98 (luminance) and RMSE <= 0.02. Skipped when povray is not
// installed (setup.sh installs it).
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/image/color.h"
#include "common/image/image.h"
#include "common/image/image_io.h"
#include "tests/support/cli_runner.h"
#include "tests/support/test_support.h"

namespace hybridlab::test {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 320, kHeight = 180;

std::optional<fs::path> findOnPath(const std::string& program) {
    const char* path = std::getenv("PATH");
    if (!path) return std::nullopt;
    std::stringstream dirs(path);
    std::string dir;
    while (std::getline(dirs, dir, ':')) {
        if (dir.empty()) continue;
        fs::path candidate = fs::path(dir) / program;
        std::error_code ec;
        if (fs::is_regular_file(candidate, ec) && ::access(candidate.c_str(), X_OK) == 0) return candidate;
    }
    return std::nullopt;
}

std::string shellQuote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

std::string readText(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// Display sRGB values in [0, 1], as the metrics see them (DESIGN.md "The shading model", output).
std::vector<glm::vec3> displayValues(const Image& linear) {
    std::vector<glm::vec3> out(linear.pixelCount());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = glm::vec3(linearToDisplay(linear.data()[i]));
    return out;
}

double rmse(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
    double sum = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i)
        for (int c = 0; c < 3; ++c) sum += (static_cast<double>(a[i][c]) - b[i][c]) * (static_cast<double>(a[i][c]) - b[i][c]);
    return std::sqrt(sum / (3.0 * static_cast<double>(a.size())));
}

// Mean SSIM of the luminance (Rec. 709 weights on the display values) after Wang et al. 2004: an
// 11 x 11 Gaussian window with sigma 1.5, K1 = 0.01, K2 = 0.03, data range 1, weighted
// (population) statistics, over every window that lies inside the image.
double ssimLuminance(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b, int width, int height) {
    auto luma = [](glm::vec3 c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; };
    constexpr int kRadius = 5;
    std::array<double, 2 * kRadius + 1> g{};
    double gsum = 0.0;
    for (int i = -kRadius; i <= kRadius; ++i) gsum += g[i + kRadius] = std::exp(-(i * i) / (2.0 * 1.5 * 1.5));
    for (double& w : g) w /= gsum;
    const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
    double total = 0.0;
    int count = 0;
    for (int y = kRadius; y < height - kRadius; ++y) {
        for (int x = kRadius; x < width - kRadius; ++x) {
            double mx = 0, my = 0, mxx = 0, myy = 0, mxy = 0;
            for (int dy = -kRadius; dy <= kRadius; ++dy) {
                for (int dx = -kRadius; dx <= kRadius; ++dx) {
                    const double w = g[dy + kRadius] * g[dx + kRadius];
                    const std::size_t i = static_cast<std::size_t>(y + dy) * width + (x + dx);
                    const double va = luma(a[i]), vb = luma(b[i]);
                    mx += w * va, my += w * vb, mxx += w * va * va, myy += w * vb * vb, mxy += w * va * vb;
                }
            }
            const double sxx = mxx - mx * mx, syy = myy - my * my, sxy = mxy - mx * my;
            total += ((2 * mx * my + c1) * (2 * sxy + c2)) / ((mx * mx + my * my + c1) * (sxx + syy + c2));
            ++count;
        }
    }
    return total / count;
}

TEST(SsimLuminance, IsOneForIdenticalImagesAndDropsWithNoise) {
    std::vector<glm::vec3> a(64 * 48), b(64 * 48);
    for (std::size_t i = 0; i < a.size(); ++i) {
        a[i] = glm::vec3(static_cast<float>(i % 64) / 64.0f);
        b[i] = a[i] + glm::vec3((i * 7919) % 13 == 0 ? 0.3f : 0.0f);
    }
    EXPECT_NEAR(ssimLuminance(a, a, 64, 48), 1.0, 1e-12);
    EXPECT_LT(ssimLuminance(a, b, 64, 48), 0.95);
    EXPECT_NEAR(rmse(a, a), 0.0, 1e-12);
}

// Exports `scene` (a name in scenes/ or a .toml path), renders it with POV-Ray and with the
// reference (`extraParams` added) at kWidth x kHeight, and checks that they agree.
void expectPovrayAgreement(const std::string& scene, const std::vector<std::string>& extraParams = {}) {
    const auto povray = findOnPath("povray");
    if (!povray) GTEST_SKIP() << "povray is not installed (setup.sh installs it)";
    TempDir dir;
    const std::string w = std::to_string(kWidth), h = std::to_string(kHeight);

    CliResult exported = runHybridlab({"export-pov", "--scene", scene, "--width", w, "--height", h, "--out", (dir / "scene.pov").string()});
    ASSERT_EQ(exported.exitStatus, 0) << exported.err;

    // POV-Ray: linear 16-bit PNG (File_Gamma=1.0), one ray per pixel centre; run in the folder of
    // the scene so that it finds the textures beside it.
    std::string command = "cd " + shellQuote(dir.path().string()) + " && " + shellQuote(povray->string()) +
                          " +W" + w + " +H" + h + " -D -A File_Gamma=1.0 +FN16 +Iscene.pov +Opovray.png > povray.log 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << readText(dir / "povray.log");
    // The exported camera is an exact orthonormal basis: no "not perpendicular" warning.
    EXPECT_EQ(readText(dir / "povray.log").find("perpendicular"), std::string::npos) << readText(dir / "povray.log");

    // POV-Ray's image maps are point lookups (interpolated, not filtered over the pixel's
    // footprint): compare with the reference's point lookups.
    // POV-Ray returns black past max_trace_level: the reference's depth_limit "weighted".
    std::vector<std::string> render = {"render", "--scene", scene, "--technique", "whitted", "--param", "texture_filter=none",
                                       "--param", "depth_limit=weighted", "--width", w, "--height", h, "--out",
                                       (dir / "whitted.exr").string()};
    for (const auto& p : extraParams) render.insert(render.end(), {"--param", p});
    CliResult rendered = runHybridlab(render);
    ASSERT_EQ(rendered.exitStatus, 0) << rendered.err;

    const Image pov = readImage(dir / "povray.png", ColorEncoding::Linear);
    const Image ours = readImage(dir / "whitted.exr", ColorEncoding::Linear);
    ASSERT_EQ(pov.width(), kWidth);
    ASSERT_EQ(pov.height(), kHeight);
    ASSERT_EQ(ours.width(), kWidth);
    ASSERT_EQ(ours.height(), kHeight);
    const auto a = displayValues(pov), b = displayValues(ours);
    const double ssim = ssimLuminance(a, b, kWidth, kHeight);
    const double error = rmse(a, b);
    ::testing::Test::RecordProperty("ssim", std::to_string(ssim));
    ::testing::Test::RecordProperty("rmse", std::to_string(error));
    std::printf("[ pov      ] %s: SSIM %.5f, RMSE %.5f\n", scene.c_str(), ssim, error);
    EXPECT_GE(ssim, 0.98) << scene;
    EXPECT_LE(error, 0.02) << scene;
}

class PovAgreement : public ::testing::TestWithParam<std::string> {};

TEST_P(PovAgreement, WhittedReferenceMatchesPovray) { expectPovrayAgreement(GetParam()); }

// Nested and touching absorbing media: a coloured opaque sphere inside an absorbing glass ball,
// a second absorbing ball all but touching it (0.015 apart), lit through both (their shadows are absorbed too), over a
// checkerboard. Written here, outside scenes/, as a scene nobody tuned the tracer on.
TEST(PovAgreementMedia, NestedAbsorbingMediaMatchPovray) {
    TempDir dir;
    const fs::path scene = dir / "nested-media.toml";
    std::ofstream(scene) << R"(
[scene]
ambient = [0.1, 0.1, 0.1]
[sky]
color = [0.4, 0.55, 0.8]
[materials.checker]
ambient = [1.0, 1.0, 1.0]
diffuse = [0.9, 0.9, 0.9]
diffuse_texture = "builtin:checker"
texture_tiling = [4.0, 4.0]
[materials.core]
ambient = [1.0, 1.0, 1.0]
diffuse = [0.9, 0.85, 0.8]
specular = [0.3, 0.3, 0.3]
specular_exponent = 32
[materials.amber]
ambient = [0.0, 0.0, 0.0]
diffuse = [1.0, 1.0, 1.0]
specular = [0.8, 0.8, 0.8]
specular_exponent = 200
ior = 1.5
opacity = 0.0
fresnel = true
absorption = [0.15, 0.6, 1.4]
[materials.teal]
ambient = [0.0, 0.0, 0.0]
diffuse = [1.0, 1.0, 1.0]
specular = [0.8, 0.8, 0.8]
specular_exponent = 200
ior = 1.3
opacity = 0.0
fresnel = true
absorption = [1.2, 0.3, 0.4]
[[objects]]
name = "floor"
primitive = "plane"
material = "checker"
scale = [16.0, 1.0, 16.0]
[[objects]]
name = "ball"
primitive = "sphere"
slices = 96
stacks = 48
material = "amber"
position = [-0.6, 1.2, 0.0]
scale = 2.4
[[objects]]
name = "core"
primitive = "sphere"
slices = 64
stacks = 32
material = "core"
position = [-0.6, 1.2, 0.0]
scale = 1.0
[[objects]]
name = "touching"
primitive = "sphere"
slices = 96
stacks = 48
material = "teal"
position = [1.02, 0.72, 0.79]
scale = 1.3
[[lights]]
name = "key"
type = "point"
position = [3.0, 7.0, 5.0]
intensity = 70.0
[[lights]]
name = "fill"
type = "point"
position = [-5.0, 5.0, 3.0]
intensity = 25.0
[camera]
position = [0.0, 2.4, 7.5]
look_at = [0.0, 1.0, 0.0]
fov_y = 40
)";
    expectPovrayAgreement(scene.string());
}

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, PovAgreement, ::testing::Values("whitted-classic", "cornell-mirror-glass"),
                         [](const auto& info) {
                             std::string name = info.param;
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

}  // namespace
}  // namespace hybridlab::test
