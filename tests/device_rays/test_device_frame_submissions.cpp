// What a device frame costs outside the technique's work (techniques/device_frame_work.h), in a
// steady state (the frame after the first at its size): rt_only is one submission; ssr_fallback,
// whose CPU needs nothing between its stages, is one (the G-buffer cast, the rasterizer's passes
// with SSR, the trace, the composite and the copies in one command buffer); heuristic_rt is two,
// its CPU selection waiting for the visible-pixel counts between the rasterization and the trace
// (Walewski 2019 §3.2). No frame allocates anything on the device, the host reads back the image
// with little beside it, and the images equal the full launch's byte for byte. Diagnostics (SSR's
// statistics, debug images) come back after the timed work in one submission of their own.
#include <cstdio>
#include <cstring>
#include <string>

#include <gtest/gtest.h>

#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "tests/support/raster_test_support.h"
#include "tests/support/technique_test_support.h"

namespace hybridlab {
namespace {

constexpr int kWidth = 48, kHeight = 27;
constexpr double kImageBytes = kWidth * kHeight * 16.0;  // vec4 a pixel

bool sameBytes(const Image& a, const Image& b) {
    return a.width() == b.width() && a.height() == b.height() &&
           std::memcmp(a.data(), b.data(), a.pixelCount() * sizeof(*a.data())) == 0;
}

// The second frame of `technique` with rays = "vulkan" and `params`: its device work, and its image
// equal to the full launch's (a launch over every texel, in the same frame).
FrameResult expectSteadyFrame(const Scene& scene, const std::string& technique, test::TechniqueParams params, double submissions,
                              double diagnosticSubmissions) {
    params.push_back({"rays", std::string("vulkan")});
    const FrameResult frame = test::renderFrame(scene, technique, params, kWidth, kHeight, /*frames=*/2);
    const auto& c = frame.counters;
    EXPECT_EQ(c.at("device_submissions"), submissions);
    EXPECT_EQ(c.at("device_diagnostic_submissions"), diagnosticSubmissions);
    // The timed frame reads back the image, its counters and timestamps: nothing per texel besides.
    EXPECT_LT(c.at("device_readback_bytes"), kImageBytes + 1024);
    EXPECT_EQ(c.at("device_allocations"), 0.0);
    EXPECT_GE(c.at("device_readback_bytes"), kImageBytes);
    if (technique != "rt_only") {
        params.push_back({"launch", std::string("full")});
        EXPECT_TRUE(sameBytes(frame.image, test::renderFrame(scene, technique, params, kWidth, kHeight, 2).image));
    }
    std::printf("[ device   ] %s: %.0f submissions, %.0f bytes read back, %.0f allocations a frame; diagnostics %.0f, %.0f bytes\n",
                technique.c_str(), c.at("device_submissions"), c.at("device_readback_bytes"), c.at("device_allocations"),
                c.at("device_diagnostic_submissions"), c.at("device_diagnostic_readback_bytes"));
    return frame;
}

TEST(DeviceFrameSubmissions, RtOnlyIsOneSubmissionReadingBackTheImage) {
    REQUIRE_RAY_TRACING_DEVICE();
    const Scene scene = loadSceneFile(findSceneFile("cornell-mirror-glass"));
    const FrameResult frame = expectSteadyFrame(scene, "rt_only", {}, 1, 0);
    // The image, the ray counters and the trace's two timestamps.
    EXPECT_LT(frame.counters.at("device_readback_bytes"), kImageBytes + 256);
}

TEST(DeviceFrameSubmissions, SsrFallbackIsOneSubmissionWithEitherGBuffer) {
    REQUIRE_RAY_TRACING_DEVICE();
    const Scene scene = loadSceneFile(findSceneFile("cornell-mirror-glass"));
    // SSR's statistics: its outputs (2 x vec4) and the texels' records (4 x vec4) a pixel.
    for (const FrameResult& f : {expectSteadyFrame(scene, "ssr_fallback", {}, 1, 1),
                                 expectSteadyFrame(scene, "ssr_fallback", {{"gbuffer", std::string("rays")}}, 1, 1)})
        EXPECT_EQ(f.counters.at("device_diagnostic_readback_bytes"), 6 * kImageBytes);
}

TEST(DeviceFrameSubmissions, HeuristicRtWaitsOnlyForItsSelection) {
    REQUIRE_RAY_TRACING_DEVICE();
    const Scene scene = loadSceneFile(findSceneFile("cornell-mirror-glass"));
    // With debug images the texels' records (4 x vec4 a pixel) after the timed work.
    const FrameResult debug = expectSteadyFrame(scene, "heuristic_rt", {{"budget", 2000.0}}, 2, 1);
    EXPECT_EQ(debug.counters.at("device_diagnostic_readback_bytes"), 4 * kImageBytes);
    expectSteadyFrame(scene, "heuristic_rt", {{"budget", 2000.0}, {"gbuffer", std::string("rays")}}, 2, 1);
    // Without debug images nothing besides.
    const FrameResult bare = expectSteadyFrame(scene, "heuristic_rt", {{"budget", 2000.0}, {"debug_images", false}}, 2, 0);
    EXPECT_EQ(bare.counters.at("device_diagnostic_readback_bytes"), 0.0);
}

}  // namespace
}  // namespace hybridlab
