// The failure-case scenes (scenes/*.toml): each drives one method into a weak point its
// paper names. They are procedural (built-in primitives only, no assets), small, and each has the
// camera path that walks into its failure and out again; the middle frame of the path (the
// failure) renders with the reference.
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/scene/scene_file.h"
#include "common/scene/view.h"
#include "tests/support/technique_test_support.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

enum class Method { HeuristicRt, Ssr, LayeredEm };

struct FailureScene {
    std::string name, path;
    Method method;
};

// How GoogleTest prints the parameter (in test names and messages): the scene and its path.
void PrintTo(const FailureScene& s, std::ostream* os) { *os << s.name << " along " << s.path; }

const std::vector<FailureScene>& failureScenes() {
    static const std::vector<FailureScene> scenes = {
        {"large-mirror", "approach", Method::HeuristicRt},
        {"glass-thicket", "through", Method::HeuristicRt},
        {"selection-popping", "fly-by", Method::HeuristicRt},
        {"offscreen-reflection", "walk-past", Method::Ssr},
        {"occluded-reflection", "sidestep", Method::Ssr},
        {"thin-objects", "along-railing", Method::Ssr},
        {"facing-mirrors", "turn", Method::Ssr},
        {"grazing-floor", "descend", Method::Ssr},
        {"em-disocclusion", "approach", Method::LayeredEm},
        {"off-subspace", "rise", Method::LayeredEm},
        {"near-environment", "arc", Method::LayeredEm},
    };
    return scenes;
}

std::string testName(const testing::TestParamInfo<FailureScene>& info) {
    std::string name = info.param.name;
    for (char& c : name)
        if (c == '-') c = '_';
    return name;
}

class FailureScenes : public testing::TestWithParam<FailureScene> {};

TEST_P(FailureScenes, LoadsProceduralWithItsPath) {
    const FailureScene& f = GetParam();
    const Scene s = loadSceneFile(test::builtinSceneFile(f.name));
    // Procedural: every object is a built-in primitive, and the scene file is its only source.
    ASSERT_EQ(s.sourceFiles.size(), 1u);
    for (const auto& o : s.objects) {
        const bool primitive = o.source == "plane" || o.source == "cube" || o.source == "sphere" || o.source == "cylinder";
        EXPECT_TRUE(primitive) << o.name << " comes from " << o.source;
    }
    // Small enough for 640x360 experiments and tiny test renders.
    EXPECT_LT(s.stats().triangles, 20000u);
    EXPECT_GE(s.lights.size(), 2u);
    ASSERT_EQ(s.cameraPaths.size(), 1u);
    const CameraPath* path = s.findCameraPath(f.path);
    ASSERT_NE(path, nullptr) << f.path;
    EXPECT_GE(path->duration(), 3.0);  // in, the failure, out again: a few seconds at 30 fps
    EXPECT_GE(path->frameCount(), 91);
    // Every scene has something for its method to reflect or refract.
    std::size_t specular = 0, lenses = 0;
    for (std::size_t i = 0; i < s.objects.size(); ++i) {
        specular += s.objectIsReflective(i) || s.objectIsRefractive(i);
        lenses += s.objects[i].lens;
    }
    EXPECT_GE(specular, 1u);
    if (f.method == Method::LayeredEm) EXPECT_GE(lenses, 2u) << "layered-EM scenes mark their lens objects";
    else EXPECT_EQ(lenses, 0u);
}

TEST_P(FailureScenes, FailureFrameRendersWithTheReference) {
    const FailureScene& f = GetParam();
    const Scene s = loadSceneFile(test::builtinSceneFile(f.name));
    const CameraPath* path = s.findCameraPath(f.path);
    ASSERT_NE(path, nullptr);
    const View view = resolveView(s, f.path, path->frameCount() / 2, std::nullopt);
    SceneContext context(s);
    auto whitted = createTechnique("whitted", {});
    whitted->prepare(context);
    const Image image = whitted->render(context, {view.camera, view.time, 32, 18}).image;
    ASSERT_EQ(image.width(), 32);
    ASSERT_EQ(image.height(), 18);
    // Finite, not black, and not one flat colour (the camera sees the scene, not only the sky).
    float lo = 1e30f, hi = -1e30f;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            const glm::vec4 c = image.at(x, y);
            for (int k = 0; k < 3; ++k) ASSERT_TRUE(std::isfinite(c[k])) << x << "," << y;
            const float luminance = 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
            lo = std::min(lo, luminance);
            hi = std::max(hi, luminance);
        }
    EXPECT_GT(hi, 0.05f);
    EXPECT_GT(hi - lo, 0.05f);
}

INSTANTIATE_TEST_SUITE_P(FailureCases, FailureScenes, testing::ValuesIn(failureScenes()), testName);

}  // namespace
}  // namespace hybridlab
