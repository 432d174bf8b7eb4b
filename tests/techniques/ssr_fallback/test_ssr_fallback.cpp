// The `ssr_fallback` technique (de Macedo & Rodrigues) against the reference: with SSR switched off
// everything falls back and it matches `whitted`; on a mirror wall reflecting an object behind the
// camera, the ray-traced fallback restores what SSR cannot see, and without a fallback the mirror
// visibly differs; the counters and the debug image account for every reflective pixel.
#include <cstdio>

#include <gtest/gtest.h>

#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "metrics/metrics.h"
#include "techniques/technique.h"
#include "tests/support/raster_test_support.h"
#include "tests/support/ssr_scenes.h"
#include "tests/support/technique_test_support.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

using Params = test::TechniqueParams;
using test::renderFrame;

// The pixels where the G-buffer shows `object`.
PixelMask objectMask(const Scene& scene, std::int64_t object, int width, int height) {
    Rasterizer rasterizer(scene);
    RasterRequest request;
    request.camera = scene.camera;
    request.width = width;
    request.height = height;
    request.readback = kGBufferObjectId;
    request.lighting = false;
    const RasterFrame frame = rasterizer.render(request);
    Image mask(width, height);
    for (std::size_t i = 0; i < frame.gbuffer.pixelCount(); ++i)
        mask.data()[i] = frame.gbuffer.object(i) == object ? glm::vec4(1.0f) : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    return PixelMask::fromImage(mask);
}

class SsrOffAgainstWhitted : public ::testing::TestWithParam<const char*> {};

TEST_P(SsrOffAgainstWhitted, EverythingFallsBackAndMatchesTheReference) {
    const std::string name = GetParam();
    const Scene scene = loadSceneFile(findSceneFile(name));
    RASTERIZER_OR_SKIP(probe, scene);
    constexpr int kWidth = 640, kHeight = 360;
    const FrameResult whitted = renderFrame(scene, "whitted", {}, kWidth, kHeight);
    const FrameResult rt = renderFrame(scene, "ssr_fallback", {{"ssr", false}, {"shadows", std::string("rt")}}, kWidth, kHeight);
    const FrameResult map = renderFrame(scene, "ssr_fallback", {{"ssr", false}}, kWidth, kHeight);
    const double ssimRt = computeMetrics(rt.image, whitted.image).whole.ssim;
    const double ssimMap = computeMetrics(map.image, whitted.image).whole.ssim;
    std::printf("[ ssr      ] %s, SSR off: SSIM against whitted %.5f with ray-traced shadows, %.5f with shadow maps; %g fallback rays "
                "for %g reflective pixels\n",
                name.c_str(), ssimRt, ssimMap, rt.counters.at("fallback_rays"), rt.counters.at("reflective_pixels"));
    RecordProperty("ssim_shadows_rt", std::to_string(ssimRt));
    RecordProperty("ssim_shadows_map", std::to_string(ssimMap));
    EXPECT_GE(ssimRt, 0.99);
    EXPECT_EQ(rt.counters.at("ssr_hits"), 0.0);
    EXPECT_EQ(rt.counters.at("fallback_rays"), rt.counters.at("reflective_pixels"));
}

INSTANTIATE_TEST_SUITE_P(SsrFallback, SsrOffAgainstWhitted, ::testing::Values("whitted-classic", "cornell-mirror-glass", "sponza-spheres"),
                         test::SceneTestName());

TEST(SsrFallback, TheFallbackRestoresAReflectionOfAnObjectBehindTheCamera) {
    const Scene scene = test::mirrorWallScene();
    RASTERIZER_OR_SKIP(probe, scene);
    constexpr int kWidth = 320, kHeight = 180;
    const PixelMask mirror = objectMask(scene, 0, kWidth, kHeight);
    const FrameResult whitted = renderFrame(scene, "whitted", {}, kWidth, kHeight);
    const Params common = {{"shadows", std::string("rt")}};
    auto with = [&](const std::string& fallback) {
        Params p = common;
        p.emplace_back("fallback", fallback);
        return renderFrame(scene, "ssr_fallback", p, kWidth, kHeight);
    };
    const FrameResult rt = with("rt"), none = with("none"), sky = with("sky");
    const double ssimRt = computeMetrics(rt.image, whitted.image, {}, &mirror).masked->ssim;
    const double ssimNone = computeMetrics(none.image, whitted.image, {}, &mirror).masked->ssim;
    const double ssimSky = computeMetrics(sky.image, whitted.image, {}, &mirror).masked->ssim;
    std::printf("[ ssr      ] mirror wall, object behind the camera: SSIM on the %zu mirror pixels, fallback rt %.5f, sky %.5f, none %.5f; "
                "SSR hits %g, fallback rays %g of %g reflective pixels\n",
                mirror.count(), ssimRt, ssimSky, ssimNone, rt.counters.at("ssr_hits"), rt.counters.at("fallback_rays"),
                rt.counters.at("reflective_pixels"));
    RecordProperty("ssim_mirror_fallback_rt", std::to_string(ssimRt));
    RecordProperty("ssim_mirror_fallback_none", std::to_string(ssimNone));
    EXPECT_GE(ssimRt, 0.99);
    EXPECT_LT(ssimNone, 0.9);
    EXPECT_LT(ssimSky, 0.95);
    // The mask of failed texels (the fallback rays) covers the slab's reflection, and SSR still
    // resolves the visible floor's.
    EXPECT_GT(rt.counters.at("fallback_rays"), 2000.0);
    EXPECT_GT(rt.counters.at("ssr_hits"), 1000.0);
    EXPECT_GT(rt.counters.at("ssr_fail_off_screen"), 2000.0);
    EXPECT_EQ(rt.counters.at("reflective_pixels"), static_cast<double>(mirror.count()));
    // The debug image (the paper's Figure 2) marks every mirror pixel by its path, and nothing else.
    const Image& source = rt.debugImages.at("reflection_source");
    std::size_t marked = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const bool isMarked = glm::vec3(source.at(x, y)) != glm::vec3(0.0f);
            EXPECT_EQ(isMarked, mirror.contains(x, y)) << x << ", " << y;
            marked += isMarked;
        }
    EXPECT_EQ(marked, mirror.count());
}

TEST(SsrFallback, OnAMirrorFloorTheHybridIsCloseToTheReferenceAndSsrCarriesMostPixels) {
    const Scene scene = test::mirrorFloorScene(0.8f);
    RASTERIZER_OR_SKIP(probe, scene);
    constexpr int kWidth = 320, kHeight = 180;
    const FrameResult whitted = renderFrame(scene, "whitted", {}, kWidth, kHeight);
    const FrameResult hybrid = renderFrame(scene, "ssr_fallback", {{"shadows", std::string("rt")}}, kWidth, kHeight);
    const FrameResult single = renderFrame(scene, "ssr_fallback", {{"shadows", std::string("rt")}, {"recursion", std::string("single")}}, kWidth,
                                      kHeight);
    const FrameResult unblurred = renderFrame(scene, "ssr_fallback", {{"shadows", std::string("rt")}, {"blur_radius", 0LL}}, kWidth, kHeight);
    const double ssim = computeMetrics(hybrid.image, whitted.image).whole.ssim;
    const double ssimUnblurred = computeMetrics(unblurred.image, whitted.image).whole.ssim;
    std::printf("[ ssr      ] mirror floor: SSIM against whitted %.5f (seam blur off: %.5f; %g pixels blurred); SSR hit rate %.3f, "
                "%g fallback rays of %g reflective pixels\n",
                ssim, ssimUnblurred, hybrid.counters.at("seam_blurred_pixels"), hybrid.counters.at("ssr_hit_rate"),
                hybrid.counters.at("fallback_rays"), hybrid.counters.at("reflective_pixels"));
    EXPECT_GE(ssim, 0.98);
    EXPECT_GT(hybrid.counters.at("seam_blurred_pixels"), 0.0);
    EXPECT_EQ(unblurred.counters.at("seam_blurred_pixels"), 0.0);
    // The matte objects it reflects do not reflect: both recursion modes agree exactly.
    EXPECT_EQ(hybrid.counters.at("ssr_recursion_rays"), 0.0);
    for (std::size_t i = 0; i < hybrid.image.pixelCount(); ++i) ASSERT_EQ(hybrid.image.data()[i], single.image.data()[i]) << i;
    // Every reflective pixel took SSR's answer, the fallback's, or both (below full confidence).
    EXPECT_LE(hybrid.counters.at("ssr_hits"), hybrid.counters.at("reflective_pixels"));
    EXPECT_GE(hybrid.counters.at("ssr_hits") + hybrid.counters.at("fallback_rays"), hybrid.counters.at("reflective_pixels"));
}

// glass = "ssr": refractive texels take their Fresnel reflection from SSR as mirrors do and trace
// only their refraction. With SSR off the fallback traces that reflection: the image is exactly
// glass = "rt"'s. With SSR on, SSR resolves some glass texels (fewer reflection rays, more SSR hits)
// and the image stays close to the reference.
TEST(SsrFallback, GlassTakesItsReflectionFromSsr) {
    const Scene scene = loadSceneFile(findSceneFile("whitted-classic"));
    RASTERIZER_OR_SKIP(probe, scene);
    constexpr int kWidth = 320, kHeight = 180;
    const Params glassSsr = {{"glass", std::string("ssr")}};
    const FrameResult offRt = renderFrame(scene, "ssr_fallback", {{"ssr", false}}, kWidth, kHeight);
    const FrameResult offSsr = renderFrame(scene, "ssr_fallback", {{"ssr", false}, {"glass", std::string("ssr")}}, kWidth, kHeight);
    for (std::size_t i = 0; i < offRt.image.pixelCount(); ++i) ASSERT_EQ(offRt.image.data()[i], offSsr.image.data()[i]) << i;

    const FrameResult whitted = renderFrame(scene, "whitted", {}, kWidth, kHeight);
    const FrameResult rt = renderFrame(scene, "ssr_fallback", {}, kWidth, kHeight);
    const FrameResult ssr = renderFrame(scene, "ssr_fallback", glassSsr, kWidth, kHeight);
    const double ssimRt = computeMetrics(rt.image, whitted.image).whole.ssim;
    const double ssimSsr = computeMetrics(ssr.image, whitted.image).whole.ssim;
    std::printf("[ ssr      ] glass reflection by SSR: SSIM %.5f (ray traced: %.5f); reflection rays %g (%g), SSR hits %g (%g)\n", ssimSsr,
                ssimRt, ssr.counters.at("rays_reflection"), rt.counters.at("rays_reflection"), ssr.counters.at("ssr_hits"),
                rt.counters.at("ssr_hits"));
    EXPECT_GT(ssr.counters.at("ssr_hits"), rt.counters.at("ssr_hits"));
    EXPECT_LT(ssr.counters.at("rays_reflection"), rt.counters.at("rays_reflection"));
    EXPECT_GT(ssr.counters.at("reflective_pixels"), rt.counters.at("reflective_pixels"));  // the glass texels join the composer
    EXPECT_GE(ssimSsr, 0.97);
}

}  // namespace
}  // namespace hybridlab
