// Objects placed with negative scale factors, on every path that takes a triangle's outside from
// its winding: a scene mirrored through the plane x = 0 (tests/support/mirrored_scene.h: a glass
// ball at scale -1.6, a box and a post with their x factor negated) renders as the plain scene's
// image flipped left to right, on Embree (whitted), on the Vulkan ray backend (whitted with
// rays = "vulkan"), in the rasterizer (raster: its front faces decide entering glass) and in the
// layered EM's lens system. Before the mirror was moved into the meshes on load, the mirrored ball
// traced no refraction rays at all on Embree: inside and outside were swapped.
#include <ostream>

#include <gtest/gtest.h>

#include "common/raster/vulkan_error.h"
#include "common/scene/scene_file.h"
#include "metrics/metrics.h"
#include "tests/support/mirrored_scene.h"
#include "tests/support/raster_test_support.h"
#include "tests/support/technique_test_support.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

constexpr int kWidth = 64, kHeight = 48;

struct MirrorCase {
    const char* name;
    std::string technique;
    test::TechniqueParams params;
    bool rayTracingDevice = false;
};

void PrintTo(const MirrorCase& c, std::ostream* os) { *os << c.name; }

class MirroredObjects : public ::testing::TestWithParam<MirrorCase> {};

TEST_P(MirroredObjects, RenderAsThePlainScenesImageFlipped) {
    const MirrorCase& c = GetParam();
    if (c.rayTracingDevice) REQUIRE_RAY_TRACING_DEVICE();
    test::TempDir dir;
    const test::MirroredScenes files = test::writeMirroredScenes(dir.path());
    const Scene plain = loadSceneFile(files.plain), mirrored = loadSceneFile(files.mirrored);
    FrameResult a, b;
    try {
        a = test::renderFrame(plain, c.technique, c.params, kWidth, kHeight);
        b = test::renderFrame(mirrored, c.technique, c.params, kWidth, kHeight);
    } catch (const VulkanUnavailable& e) {
        GTEST_SKIP() << "no Vulkan device: " << e.what();
    }
    const Image flipped = test::flippedLeftToRight(a.image);
    const double ssim = computeMetrics(b.image, flipped).whole.ssim;
    EXPECT_GE(ssim, 0.999);
    // The scene is not its own mirror image: the comparison sees which way round it is.
    EXPECT_LT(computeMetrics(b.image, a.image).whole.ssim, 0.95);
    if (a.counters.count("rays_refraction")) {
        EXPECT_GT(a.counters.at("rays_refraction"), 500.0);
        EXPECT_NEAR(b.counters.at("rays_refraction"), a.counters.at("rays_refraction"), 0.01 * a.counters.at("rays_refraction"));
    }
    RecordProperty("ssim_mirrored_vs_flipped", std::to_string(ssim));
    std::printf("[ mirror ] %s: SSIM %.6f of the mirrored scene against the plain one flipped\n", c.name, ssim);
}

const test::TechniqueParams kLayeredEm = {{"tau", 1.0},         {"em_size", 32LL},    {"bake_width", 64LL}, {"bake_height", 48LL},
                                          {"supersampling", 2LL}, {"viewpoints", 1LL}, {"layers", 1LL},      {"em_cache", false}};

INSTANTIATE_TEST_SUITE_P(EveryPath, MirroredObjects,
                         ::testing::Values(MirrorCase{"embree", "whitted", {}}, MirrorCase{"vulkan_rays", "whitted", {{"rays", std::string("vulkan")}}, true},
                                           MirrorCase{"raster", "raster", {}}, MirrorCase{"layered_em", "layered_em", kLayeredEm}),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace hybridlab
