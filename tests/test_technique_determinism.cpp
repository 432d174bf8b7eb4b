// DESIGN.md "Invariants": same config, same machine, byte-identical images and identical counters.
// Every technique in the registry, at its defaults, renders the same frames twice from scratch (a
// new scene context and technique each time, two frames each so that state kept between frames is
// covered); images, debug images and counters must be equal. Counters that are times (named
// *_ms or *_per_second) are measurements, not counts, and are left out. The techniques that can
// trace on the Vulkan device do it once more with rays = "vulkan" (on lavapipe here).
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "common/core/input_error.h"
#include "common/raster/vulkan_error.h"
#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "technique_test_support.h"

namespace hybridlab {
namespace {

bool isTime(const std::string& counter) {
    const auto endsWith = [&](const std::string& suffix) {
        return counter.size() >= suffix.size() && counter.compare(counter.size() - suffix.size(), suffix.size(), suffix) == 0;
    };
    return endsWith("_ms") || endsWith("_per_second");
}

bool sameBytes(const Image& a, const Image& b) {
    return a.width() == b.width() && a.height() == b.height() &&
           std::memcmp(a.data(), b.data(), a.pixelCount() * sizeof(*a.data())) == 0;
}

TEST(TechniqueDeterminism, EveryTechniqueRendersTheSameFramesTwice) {
    const Scene scene = loadSceneFile(findSceneFile("whitted-classic"));
    constexpr int kWidth = 96, kHeight = 54, kFrames = 2;
    struct Case {
        std::string name;
        test::TechniqueParams params;
        std::string label;
    };
    std::vector<Case> cases;
    for (const TechniqueInfo& info : registeredTechniques()) {
        cases.push_back({info.name, {}, info.name});
        for (const ParamSpec& p : info.parameters)
            if (p.name == "rays") cases.push_back({info.name, {{"rays", std::string("vulkan")}}, info.name + " rays=vulkan"});
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
        ASSERT_EQ(first.debugImages.size(), second.debugImages.size());
        for (const auto& [name, image] : first.debugImages) {
            SCOPED_TRACE("debug image " + name);
            ASSERT_TRUE(second.debugImages.count(name));
            EXPECT_TRUE(sameBytes(image, second.debugImages.at(name)));
        }
        std::size_t compared = 0;
        for (const auto& [name, value] : first.counters) {
            if (isTime(name)) continue;
            SCOPED_TRACE("counter " + name);
            ASSERT_TRUE(second.counters.count(name));
            EXPECT_EQ(value, second.counters.at(name));
            ++compared;
        }
        EXPECT_EQ(first.counters.size(), second.counters.size());
        std::printf("[ determin ] %s: %dx%d, %d frames twice: images and %zu counters identical\n", c.label.c_str(), kWidth, kHeight,
                    kFrames, compared);
    }
}

}  // namespace
}  // namespace hybridlab
