// `heuristic_rt` (Walewski 2019): with an unlimited budget it is the reference up to rasterization
// (DESIGN.md "Invariants that tests hold": SSIM >= 0.99 against `whitted`); with nothing selected it is the P-buffer,
// i.e. the `raster` image; "no heuristic" selects what an unlimited budget does; the selected cost
// never exceeds the budget; per-effect selection at an unlimited budget is per-object selection;
// and the frame-time target's controller settles on a target.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "metrics/metrics.h"
#include "techniques/heuristic_rt/frame_time_budget.h"
#include "tests/support/cli_runner.h"
#include "tests/support/raster_test_support.h"
#include "tests/support/technique_test_support.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

constexpr int kWidth = 640, kHeight = 360;

float maxDifference(const Image& a, const Image& b) {
    float d = 0.0f;
    for (std::size_t i = 0; i < a.pixelCount(); ++i) {
        const glm::vec4 e = glm::abs(a.data()[i] - b.data()[i]);
        d = std::max({d, e.r, e.g, e.b});
    }
    return d;
}

class HeuristicAtUnlimitedBudget : public ::testing::TestWithParam<const char*> {};

TEST_P(HeuristicAtUnlimitedBudget, MatchesWhitted) {
    const std::string name = GetParam();
    const Scene textured = loadSceneFile(findSceneFile(name));
    const Scene scene = test::withoutTextures(textured);
    RASTERIZER_OR_SKIP(probe, scene);
    // The reference's tracer settings: the full ray tree (rt_only's cut-off is heuristic_rt's default).
    const test::TechniqueParams full = {{"importance_cutoff", 0.0}};
    auto compare = [&](const Scene& s) {
        const FrameResult hybrid = test::renderFrame(s, "heuristic_rt", full, kWidth, kHeight);
        const Image reference = test::renderImage(s, "whitted", {}, kWidth, kHeight);
        EXPECT_EQ(hybrid.counters.at("objects_selected"), hybrid.counters.at("objects_visible"));
        return computeMetrics(hybrid.image, reference).whole.ssim;
    };
    const double ssim = compare(scene);
    const double ssimTextured = textured.textures.empty() ? ssim : compare(textured);
    std::printf("[ heuristic] %s: SSIM heuristic_rt (unlimited budget) vs whitted %.5f untextured, %.5f textured\n", name.c_str(), ssim,
                ssimTextured);
    RecordProperty("ssim", std::to_string(ssim));
    RecordProperty("ssim_textured", std::to_string(ssimTextured));
    EXPECT_GE(ssim, 0.99);
    EXPECT_GE(ssimTextured, 0.99);
}

INSTANTIATE_TEST_SUITE_P(HeuristicRt, HeuristicAtUnlimitedBudget, ::testing::Values("whitted-classic", "cornell-mirror-glass", "sponza-spheres"),
                         [](const auto& info) {
                             std::string n = info.param;
                             std::replace(n.begin(), n.end(), '-', '_');
                             return n;
                         });

TEST(HeuristicRt, SelectionBoundsTheImageBetweenRasterAndFullRayTracing) {
    const Scene scene = loadSceneFile(findSceneFile("cornell-mirror-glass"));
    RASTERIZER_OR_SKIP(probe, scene);
    constexpr int w = 160, h = 90;
    {
        SCOPED_TRACE("nothing fits a tiny budget: the P-buffer, which is the raster image");
        const FrameResult none = test::renderFrame(scene, "heuristic_rt", {{"budget", 1e-9}}, w, h);
        EXPECT_EQ(none.counters.at("objects_selected"), 0.0);
        EXPECT_EQ(none.counters.at("pixels_ray_traced"), 0.0);
        EXPECT_EQ(none.counters.at("rays_total"), 0.0);
        EXPECT_LE(maxDifference(none.image, test::renderImage(scene, "raster", {}, w, h)), 1e-6f);
    }
    const FrameResult unlimited = test::renderFrame(scene, "heuristic_rt", {}, w, h);
    {
        SCOPED_TRACE("no heuristic selects every visible object, as an unlimited budget");
        const FrameResult noHeuristic = test::renderFrame(scene, "heuristic_rt", {{"heuristic", false}}, w, h);
        EXPECT_EQ(noHeuristic.image, unlimited.image);
        EXPECT_EQ(noHeuristic.counters.at("objects_selected"), noHeuristic.counters.at("objects_visible"));
    }
    {
        SCOPED_TRACE("per-effect selection at an unlimited budget selects every effect");
        const FrameResult perEffect = test::renderFrame(scene, "heuristic_rt", {{"per_effect", true}}, w, h);
        EXPECT_LE(maxDifference(perEffect.image, unlimited.image), 1e-6f);
    }
    for (bool perEffect : {false, true}) {
        SCOPED_TRACE(perEffect ? "half the visible cost, per effect" : "half the visible cost, per object");
        const double half = 0.5 * unlimited.counters.at("cost_visible");
        const FrameResult r = test::renderFrame(scene, "heuristic_rt", {{"budget", half}, {"per_effect", perEffect}}, w, h);
        EXPECT_LE(r.counters.at("cost_selected"), half);
        EXPECT_GT(r.counters.at("cost_selected"), 0.0);
        EXPECT_LT(r.counters.at("pixels_ray_traced"), unlimited.counters.at("pixels_ray_traced"));
        // The mask marks exactly the pixels that were ray traced.
        const Image& mask = r.debugImages.at("heuristic_mask");
        double marked = 0.0;
        for (std::size_t i = 0; i < mask.pixelCount(); ++i) marked += glm::vec3(mask.data()[i]) != glm::vec3(0.0f);
        EXPECT_EQ(marked, r.counters.at("pixels_ray_traced"));
    }
}

TEST(HeuristicRt, RendersFromTheCommandLineWithWalewskisStages) {
    {
        const Scene probeScene = loadSceneFile(findSceneFile("whitted-classic"));
        RASTERIZER_OR_SKIP(probe, probeScene);
    }
    test::TempDir dir;
    test::CliResult r = test::runHybridlab({"render", "--scene", "whitted-classic", "--technique", "heuristic_rt", "--param",
                                            "budget=100000", "--width", "160", "--height", "90", "--out", (dir / "h.exr").string()});
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    // Walewski's RAST (here the rasterizer's stages), HEUR, RAYT and BLEND.
    for (const char* stage : {"stage gbuffer", "stage lighting", "stage heuristic", "stage trace", "stage blend"}) EXPECT_CONTAINS(r.out, stage);
}

// The frame-time target's controller against a machine whose ray tracing costs a fixed rate per
// unit of cost with 5% noise: after ten frames the frames land within 15% of the target.
TEST(FrameTimeBudget, SettlesOnTheTarget) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> noise(0.95, 1.05);
    const double msPerCost = 0.003, otherMs = 4.0, target = 20.0, available = 50000.0;
    FrameTimeBudget budget(target);
    int within = 0, frames = 0;
    for (int frame = 0; frame < 60; ++frame) {
        const double cost = std::min(budget.budget(), available);
        const double rayTracing = cost * msPerCost * noise(rng), other = otherMs * noise(rng);
        if (frame >= 10) {
            ++frames;
            within += std::abs(rayTracing + other - target) <= 0.15 * target;
            EXPECT_NEAR(budget.predictedMilliseconds(cost), target, 0.05 * target);
        }
        budget.observe(cost, rayTracing, other);
    }
    EXPECT_EQ(within, frames);
}

}  // namespace
}  // namespace hybridlab
