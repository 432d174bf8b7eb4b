// The `raster` technique against the reference: on scenes without reflective or refractive
// objects and with shadows off in both, the two images are the same up to rasterization
// (SSIM >= 0.99); with shadow maps against ray-traced hard shadows they stay close; and
// `hybridlab render --technique raster` works like `whitted`.
//
// Textured, the two filter differently (mip-mapping from screen-space gradients against ray cones,
// which ignore the pixel's anisotropy and the off-axis widening of the pixel's cone), so the
// textured comparison has a looser bound than the untextured one.
#include <cstdio>

#include <gtest/gtest.h>

#include "common/image/image_io.h"
#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "metrics/metrics.h"
#include "techniques/technique.h"
#include "tests/support/cli_runner.h"
#include "tests/support/raster_test_support.h"
#include "tests/support/technique_test_support.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

constexpr int kWidth = 640, kHeight = 360;

// The scene with every mirror and glass material made matte, so that nothing reflects or refracts.
Scene matteScene(const std::string& name) {
    Scene scene = loadSceneFile(findSceneFile(name));
    for (Material& m : scene.materials) {
        m.reflectivity = 0.0f;
        m.fresnel = false;
        m.opacity = 1.0f;
    }
    return scene;
}

Image render(const Scene& scene, const std::string& technique, const test::TechniqueParams& params) {
    return test::renderImage(scene, technique, params, kWidth, kHeight);
}

double rasterAgainstWhitted(const Scene& scene, bool shadows) {
    const Image raster = render(scene, "raster", {{"shadows", std::string(shadows ? "map" : "off")}});
    const Image whitted = render(scene, "whitted", {{"shadows", shadows}});
    return computeMetrics(raster, whitted).whole.ssim;
}

class RasterAgainstWhitted : public ::testing::TestWithParam<const char*> {};

TEST_P(RasterAgainstWhitted, WithoutReflectionOrRefractionTheyAgree) {
    const std::string name = GetParam();
    const Scene texturedScene = matteScene(name);
    const Scene scene = test::withoutTextures(texturedScene);
    RASTERIZER_OR_SKIP(probe, scene);
    const double unshadowed = rasterAgainstWhitted(scene, false);
    const double shadowed = rasterAgainstWhitted(scene, true);
    const double textured = texturedScene.textures.empty() ? unshadowed : rasterAgainstWhitted(texturedScene, false);
    std::printf("[ raster   ] %s, matte: SSIM raster vs whitted %.5f with shadows off in both, %.5f with shadow maps vs shadow "
                "rays; %.5f with textures and shadows off\n",
                name.c_str(), unshadowed, shadowed, textured);
    RecordProperty("ssim_shadows_off", std::to_string(unshadowed));
    RecordProperty("ssim_shadows", std::to_string(shadowed));
    RecordProperty("ssim_textured_shadows_off", std::to_string(textured));
    EXPECT_GE(unshadowed, 0.99);
    EXPECT_GE(shadowed, 0.95);
    EXPECT_GE(textured, 0.98);
}

INSTANTIATE_TEST_SUITE_P(Raster, RasterAgainstWhitted, ::testing::Values("cornell-mirror-glass", "whitted-classic", "sponza-spheres"),
                         test::SceneTestName());

// The experiment runner renders a technique many times into fresh FrameResults; every frame must
// be whole and the same (a moved-out read-back image once left the second frame without pixels).
TEST(RasterTechnique, RepeatedFramesAreWholeAndIdentical) {
    const Scene scene = loadSceneFile(findSceneFile("cornell-mirror-glass"));
    RASTERIZER_OR_SKIP(probe, scene);
    SceneContext context(scene);
    auto t = createTechnique("raster", {});
    t->prepare(context);
    const FrameRequest request{scene.camera, 0.0, 96, 54};
    const Image first = t->render(context, request).image;
    for (int i = 0; i < 3; ++i) {
        const Image again = t->render(context, request).image;
        ASSERT_EQ(again.width(), 96);
        ASSERT_EQ(again.pixelCount(), 96u * 54u);
        EXPECT_EQ(again, first) << "frame " << i + 2;
    }
}

TEST(RasterTechnique, RendersFromTheCommandLineLikeWhitted) {
    {
        const Scene probeScene = loadSceneFile(findSceneFile("cornell-mirror-glass"));
        RASTERIZER_OR_SKIP(probe, probeScene);
    }
    test::TempDir dir;
    const auto out = dir / "raster.exr";
    test::CliResult r = test::runHybridlab({"render", "--scene", "cornell-mirror-glass", "--technique", "raster", "--width", "160",
                                            "--height", "90", "--out", out.string()});
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    EXPECT_CONTAINS(r.out, "stage gbuffer");
    EXPECT_CONTAINS(r.out, "stage lighting");
    const Image image = readImage(out, ColorEncoding::Linear);
    EXPECT_EQ(image.width(), 160);
    EXPECT_EQ(image.height(), 90);
    EXPECT_TRUE(std::filesystem::exists(dir / "raster.png"));
}

TEST(RasterTechnique, WithoutAVulkanDeviceTheCommandLineSaysSoAndExitsNonZero) {
    // The loader finds no driver when it is pointed at none.
    test::TempDir dir;
    test::CliResult r = test::runHybridlab({"render", "--scene", "cornell-mirror-glass", "--technique", "raster", "--width", "64",
                                            "--height", "36", "--out", (dir / "x.exr").string()},
                                           {{"VK_ICD_FILENAMES", (dir / "no-driver.json").string()}, {"VK_DRIVER_FILES", std::nullopt}});
    EXPECT_EQ(r.exitStatus, 1) << r.err;
    EXPECT_CONTAINS(r.err, "hybridlab: error: no Vulkan");
    EXPECT_CONTAINS(r.err, "mesa-vulkan-drivers");
    EXPECT_FALSE(std::filesystem::exists(dir / "x.exr"));
}

}  // namespace
}  // namespace hybridlab
