// DESIGN.md "Invariants": same config, same machine, byte-identical images and identical counters.
// Every technique in the registry, at its defaults, renders the same frames twice from scratch (a
// new scene context and technique each time, two frames each so that state kept between frames is
// covered); images, debug images, counters and the EXR and PNG files written must be equal.
// Counters that are times (named *_ms or *_per_second) are measurements, not counts, and are
// left out. The techniques that can trace on the Vulkan device do it once more with
// rays = "vulkan" (on lavapipe here).
#include <gtest/gtest.h>

#include <cstring>
#include <regex>
#include <string>

#include <tbb/task_arena.h>
#if defined(__x86_64__)
#include <xmmintrin.h>
#endif

#include "common/core/input_error.h"
#include "common/image/image_io.h"
#include "common/raster/vulkan_error.h"
#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "tests/support/technique_test_support.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

bool isTime(const std::string& counter) {
    const auto endsWith = [&](const std::string& suffix) {
        return counter.size() >= suffix.size() && counter.compare(counter.size() - suffix.size(), suffix.size(), suffix) == 0;
    };
    return endsWith("_ms") || endsWith("_per_second") || endsWith("_ns_per_ray");
}

bool sameBytes(const Image& a, const Image& b) {
    return a.width() == b.width() && a.height() == b.height() &&
           std::memcmp(a.data(), b.data(), a.pixelCount() * sizeof(*a.data())) == 0;
}

// Expects the same counters with the same values, times apart; returns how many were compared.
std::size_t expectSameCounters(const FrameResult& a, const FrameResult& b) {
    std::size_t compared = 0;
    for (const auto& [name, value] : a.counters) {
        if (isTime(name)) continue;
        SCOPED_TRACE("counter " + name);
        const auto other = b.counters.find(name);
        EXPECT_TRUE(other != b.counters.end());
        if (other != b.counters.end()) {
            EXPECT_EQ(value, other->second);
        }
        ++compared;
    }
    EXPECT_EQ(a.counters.size(), b.counters.size());
    return compared;
}

TEST(TechniqueDeterminism, EveryTechniqueRendersTheSameFramesTwice) {
    const Scene scene = loadSceneFile(findSceneFile("whitted-classic"));
    constexpr int kWidth = 96, kHeight = 54, kFrames = 2;
    const test::TempDir files;
    struct Case {
        std::string name;
        test::TechniqueParams params;
        std::string label;
    };
    std::vector<Case> cases;
    for (const TechniqueInfo& info : registeredTechniques()) {
        cases.push_back({info.name, {}, info.name});
        for (const ParamSpec& p : info.parameters) {
            if (p.name == "rays") cases.push_back({info.name, {{"rays", std::string("vulkan")}}, info.name + " rays=vulkan"});
            if (p.name == "lighting")
                cases.push_back({info.name,
                                 {{"gbuffer", std::string("rays")}, {"lighting", std::string("cpu")}, {"raster_shadows", std::string("rays")}},
                                 info.name + " lighting=cpu"});
        }
    }
    for (const Case& c : cases) {
        SCOPED_TRACE(c.label);
        FrameResult first, second;
        try {
            first = test::renderFrame(scene, c.name, c.params, kWidth, kHeight, kFrames);
            second = test::renderFrame(scene, c.name, c.params, kWidth, kHeight, kFrames);
        } catch (const VulkanUnavailable& e) {
            std::printf("[ skipped  ] %s: no Vulkan device (%s)\n", c.label.c_str(), e.what());
            continue;
        } catch (const InputError& e) {
            if (c.params.empty()) throw;  // only the device variants may find no ray-tracing device
            std::printf("[ skipped  ] %s: %s\n", c.label.c_str(), e.what());
            continue;
        }
        EXPECT_TRUE(sameBytes(first.image, second.image));
        // And the files: no write time or other varying metadata in them.
        for (const char* ext : {".exr", ".png"}) {
            SCOPED_TRACE(ext);
            writeImageAtomically(files / (c.label + "-1" + ext), first.image);
            writeImageAtomically(files / (c.label + "-2" + ext), second.image);
            const std::string a = test::readTextFile(files / (c.label + "-1" + ext)), b = test::readTextFile(files / (c.label + "-2" + ext));
            EXPECT_FALSE(a.empty());
            EXPECT_TRUE(a == b) << "files differ";
            // Two writes within one second would agree even with a write time in them: look for one.
            EXPECT_FALSE(std::regex_search(a, std::regex("[0-9]{4}:[0-9]{2}:[0-9]{2} [0-9]{2}:[0-9]{2}:[0-9]{2}"))) << "a date in the file";
        }
        ASSERT_EQ(first.debugImages.size(), second.debugImages.size());
        for (const auto& [name, image] : first.debugImages) {
            SCOPED_TRACE("debug image " + name);
            ASSERT_TRUE(second.debugImages.count(name));
            EXPECT_TRUE(sameBytes(image, second.debugImages.at(name)));
        }
        const std::size_t compared = expectSameCounters(first, second);
        std::printf("[ determin ] %s: %dx%d, %d frames twice: images and %zu counters identical\n", c.label.c_str(), kWidth, kHeight,
                    kFrames, compared);
    }
}

}  // namespace
}  // namespace hybridlab

namespace hybridlab {
namespace {

// A run's counters and image are a function of the run alone: the same whitted frame rendered in a
// fresh context, and after other techniques rendered other frames in the same context (the ray
// scene built at another time and moved about, the rasterizer created), as an experiment's runs
// follow one another. On an animated scene, where the ray scene's top level is rebuilt per frame.
TEST(TechniqueDeterminism, CountersDoNotDependOnWhatTheContextRenderedBefore) {
    const Scene scene = loadSceneFile(findSceneFile("selection-popping"));
    const CameraPath& path = *scene.findCameraPath("fly-by");
    constexpr int kWidth = 64, kHeight = 36;
    auto frame = [&](int f) { return FrameRequest{path.evaluate(path.frameTime(f), scene.camera), path.frameTime(f), kWidth, kHeight}; };
    auto whittedIn = [&](SceneContext& context) {
        auto t = createTechnique("whitted", {});
        t->prepare(context);
        return t->render(context, frame(20));
    };
    SceneContext fresh(scene);
    const FrameResult alone = whittedIn(fresh);

    SceneContext used(scene);
    used.rayScene(path.frameTime(40));  // built at another time than the whitted frame's
    for (const char* predecessor : {"rt_only", "raster", "heuristic_rt"}) {
        try {
            auto t = createTechnique(predecessor, {});
            t->prepare(used);
            t->render(used, frame(5));
            t->render(used, frame(40));
        } catch (const VulkanUnavailable&) {
            std::printf("[ skipped  ] %s: no Vulkan device\n", predecessor);
        }
    }
    const FrameResult after = whittedIn(used);
    EXPECT_TRUE(sameBytes(alone.image, after.image));
    const std::size_t compared = expectSameCounters(alone, after);
    EXPECT_GT(alone.counters.at("rays_shadow"), 0.0);
    std::printf("[ determin ] whitted after rt_only, raster, heuristic_rt in one context: image and %zu counters as alone\n", compared);
}

// TBB's tasks inherit the floating-point mode of the thread that started TBB's arena: flush-to-zero
// and denormals-are-zero when Embree's first BVH build started it, IEEE when the rasterizer's first
// parallel loop did (an experiment whose reference came from the cache and whose first technique
// was `raster`: whitted-classic at 320x180 then traced 117733 shadow rays instead of 115743, with
// the same image). The same whitted frame in arenas started in either mode traces the same rays.
TEST(TechniqueDeterminism, CountersDoNotDependOnTheFloatingPointModeTbbStartedIn) {
#if defined(__x86_64__)
    const Scene scene = loadSceneFile(findSceneFile("whitted-classic"));
    auto whittedInArenaStartedWith = [&](unsigned mxcsrBits) {
        const unsigned saved = _mm_getcsr();
        _mm_setcsr(saved | mxcsrBits);
        tbb::task_arena arena;
        arena.initialize();  // takes the starting thread's mode, as the implicit arena does
        _mm_setcsr(saved);
        FrameResult result;
        arena.execute([&] { result = test::renderFrame(scene, "whitted", {}, 160, 90); });
        return result;
    };
    constexpr unsigned kFlushToZero = 1u << 15, kDenormalsAreZero = 1u << 6;
    const FrameResult ieee = whittedInArenaStartedWith(0), flushed = whittedInArenaStartedWith(kFlushToZero | kDenormalsAreZero);
    EXPECT_TRUE(sameBytes(ieee.image, flushed.image));
    const std::size_t compared = expectSameCounters(ieee, flushed);
    std::printf("[ determin ] whitted in arenas started in IEEE and FTZ/DAZ mode: image and %zu counters compared (%.0f shadow rays)\n",
                compared, ieee.counters.at("rays_shadow"));
#else
    GTEST_SKIP() << "the MXCSR modes are x86's";
#endif
}

}  // namespace
}  // namespace hybridlab
