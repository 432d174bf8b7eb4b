// The SSR compute pass (techniques/ssr_fallback/ssr_pass.h) against rays traced from the same
// G-buffer texels: on a mirror floor it resolves the reflections of surfaces that are on screen and
// reads their colour; on a mirror wall, reflections of an object behind the camera fail and are
// marked; non-reflective texels are left alone; its parameters do what they say.
#include <cstdio>
#include <limits>
#include <ostream>
#include <string>

#include <gtest/gtest.h>

#include "common/image/color.h"
#include "common/raytrace/ray_offset.h"
#include "common/raytrace/whitted_tracer.h"
#include "techniques/ssr_fallback/ssr_pass.h"
#include "tests/support/raster_test_support.h"
#include "tests/support/ssr_scenes.h"

namespace hybridlab {
namespace {
std::string traversalName(SsrSettings::Traversal t);
}  // namespace

// How GoogleTest prints the parameter (in test names and messages); found by argument-dependent
// lookup in the parameter type's namespace. Without it the parameter prints as its bytes.
void PrintTo(SsrSettings::Traversal t, std::ostream* os) { *os << traversalName(t); }

namespace {

constexpr int kWidth = 320, kHeight = 180;

struct SsrFrame {
    RasterFrame raster;
    SsrResult ssr;
};

SsrFrame renderSsr(Rasterizer& rasterizer, const Scene& scene, const SsrSettings& settings) {
    SsrPass pass;
    pass.setSettings(settings);
    RasterRequest request;
    request.camera = scene.camera;
    request.width = kWidth;
    request.height = kHeight;
    request.readback = kGBufferPosition | kGBufferNormal | kGBufferObjectId;
    request.passes = {&pass};
    SsrFrame frame;
    rasterizer.render(request, frame.raster);
    frame.ssr = pass.result();
    return frame;
}

// What the reference's mirror ray from texel i sees: the object it hits (-1 for the sky), whether
// that point is what the G-buffer shows at the pixel it projects to (so SSR could find it), and
// the radiance along the ray.
struct ReferenceReflection {
    std::int64_t object = -1;
    bool onScreen = false;
    glm::vec3 radiance{0.0f};
};

ReferenceReflection referenceReflection(const Scene& scene, const RayScene& rays, const GBuffer& g, std::size_t i) {
    const Camera& camera = scene.camera;
    const glm::vec3 p(g.position[i]);
    const glm::vec3 n = g.facingNormal(i);
    const glm::vec3 incoming = glm::normalize(p - camera.position);
    const Ray ray{offsetRayOrigin(p, n), reflectDirection(incoming, n)};
    ReferenceReflection ref;
    RayStats stats;
    ref.radiance = WhittedTracer(rays, {}).radiance(ray, 1, 1.0f, stats);
    SurfaceHit hit;
    if (!rays.intersect(ray, 0.0f, std::numeric_limits<float>::infinity(), hit)) return ref;
    ref.object = hit.object;
    const float aspect = static_cast<float>(g.width) / static_cast<float>(g.height);
    const glm::vec4 clip = camera.projectionMatrix(aspect) * camera.view() * glm::vec4(hit.position, 1.0f);
    if (clip.w <= 0.0f) return ref;
    const glm::vec2 pixel = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(g.width, g.height);
    if (pixel.x < 0.0f || pixel.y < 0.0f || pixel.x >= g.width || pixel.y >= g.height) return ref;
    const std::size_t j = g.index(static_cast<int>(pixel.x), static_cast<int>(pixel.y));
    ref.onScreen = g.object(j) == static_cast<std::int64_t>(hit.object) &&
                   glm::distance(glm::vec3(g.position[j]), hit.position) < 0.02f * glm::distance(camera.position, hit.position);
    return ref;
}

float displayDifference(glm::vec3 a, glm::vec3 b) {
    const glm::vec4 da = linearToDisplay(glm::vec4(a, 1.0f)), db = linearToDisplay(glm::vec4(b, 1.0f));
    return std::max({std::abs(da.r - db.r), std::abs(da.g - db.g), std::abs(da.b - db.b)});
}

// Both traversals must pass the same tests.
class SsrTraversal : public ::testing::TestWithParam<SsrSettings::Traversal> {
protected:
    SsrSettings settings() const {
        SsrSettings s;
        s.traversal = GetParam();
        return s;
    }
    const char* name() const { return GetParam() == SsrSettings::Traversal::HiZ ? "hiz" : "linear"; }
};

TEST_P(SsrTraversal, MirrorFloorResolvesTheReflectionsOfOnScreenSurfaces) {
    const Scene scene = test::mirrorFloorScene();
    RASTERIZER_OR_SKIP(rasterizer, scene);
    const SsrFrame f = renderSsr(*rasterizer, scene, settings());
    const RayScene rays(scene);
    const GBuffer& g = f.raster.gbuffer;
    std::size_t mirror = 0, onScreen = 0, resolved = 0, close = 0, falseHits = 0;
    for (std::size_t i = 0; i < g.pixelCount(); ++i) {
        if (g.object(i) != 0) continue;  // the floor
        ++mirror;
        const SsrPixel& s = f.ssr.pixels[i];
        ASSERT_TRUE(s.traced());
        const ReferenceReflection ref = referenceReflection(scene, rays, g, i);
        if (!ref.onScreen) {
            if (s.resolved()) ++falseHits;
            continue;
        }
        ++onScreen;
        if (!s.resolved()) continue;
        ++resolved;
        if (displayDifference(s.color, ref.radiance) <= 0.05f) ++close;
    }
    std::printf("[ ssr      ] %s, mirror floor: %zu mirror pixels, %zu reflect on-screen surfaces, SSR resolved %zu (%.1f%%), %zu of them "
                "within 0.05 (%.1f%%); %zu SSR hits where the reference reflection is off screen\n",
                name(), mirror, onScreen, resolved, 100.0 * resolved / onScreen, close, 100.0 * close / resolved, falseHits);
    ASSERT_GT(onScreen, 2000u);  // the objects' reflections cover a good part of the floor
    EXPECT_GE(static_cast<double>(resolved), 0.90 * onScreen);
    EXPECT_GE(static_cast<double>(close), 0.95 * resolved);
}

TEST_P(SsrTraversal, ReflectionsOfAnObjectBehindTheCameraFailAndAreMasked) {
    const Scene scene = test::mirrorWallScene();
    RASTERIZER_OR_SKIP(rasterizer, scene);
    const SsrFrame f = renderSsr(*rasterizer, scene, settings());
    const RayScene rays(scene);
    const GBuffer& g = f.raster.gbuffer;
    std::size_t behind = 0, failed = 0, offScreen = 0, floorResolved = 0, floorOnScreen = 0;
    for (std::size_t i = 0; i < g.pixelCount(); ++i) {
        if (g.object(i) != 0) continue;  // the mirror wall
        const SsrPixel& s = f.ssr.pixels[i];
        const ReferenceReflection ref = referenceReflection(scene, rays, g, i);
        if (ref.object == 2) {  // the slab behind the camera
            ++behind;
            if (!s.resolved()) ++failed;
            if (s.flags & kSsrOffScreen) ++offScreen;
        } else if (ref.object == 1 && ref.onScreen) {  // the floor in front of the wall, on screen
            ++floorOnScreen;
            if (s.resolved()) ++floorResolved;
        }
    }
    std::printf("[ ssr      ] %s, mirror wall: %zu pixels reflect the slab behind the camera, SSR failed on %zu, off-screen flag on %zu; "
                "%zu reflect the visible floor, SSR resolved %zu\n",
                name(), behind, failed, offScreen, floorOnScreen, floorResolved);
    ASSERT_GT(behind, 2000u);
    EXPECT_EQ(failed, behind);
    EXPECT_EQ(offScreen, behind);
    EXPECT_GE(static_cast<double>(floorResolved), 0.9 * floorOnScreen);
}

TEST_P(SsrTraversal, OnlyOpaqueReflectiveTexelsAreTraced) {
    const Scene scene = test::mirrorFloorScene();
    RASTERIZER_OR_SKIP(rasterizer, scene);
    const SsrFrame f = renderSsr(*rasterizer, scene, settings());
    const GBuffer& g = f.raster.gbuffer;
    for (std::size_t i = 0; i < g.pixelCount(); ++i) {
        const SsrPixel& s = f.ssr.pixels[i];
        EXPECT_EQ(s.traced(), g.object(i) == 0) << "texel " << i;
        if (!s.traced()) {
            EXPECT_EQ(s.flags, 0u);
            EXPECT_EQ(s.hit, glm::ivec2(-1));
        }
        if (s.resolved()) {
            EXPECT_GT(s.confidence, 0.0f);
            EXPECT_LE(s.confidence, 1.0f);
            EXPECT_GE(s.hit.x, 0);
            EXPECT_LT(s.hit.y, kHeight);
        } else {
            EXPECT_EQ(s.confidence, 0.0f);
        }
    }
}

// The linear march (stride is its parameter; the default traversal is the pyramid).
SsrSettings linearMarch() {
    SsrSettings s;
    s.traversal = SsrSettings::Traversal::Linear;
    return s;
}

TEST(SsrPass, ParametersLimitAndCoarsenTheMarch) {
    const Scene scene = test::mirrorFloorScene();
    RASTERIZER_OR_SKIP(rasterizer, scene);
    const SsrFrame fine = renderSsr(*rasterizer, scene, linearMarch());
    SsrSettings few = linearMarch();
    few.maxSteps = 3;
    const SsrFrame shortMarch = renderSsr(*rasterizer, scene, few);
    SsrSettings coarse = linearMarch();
    coarse.stride = 4;
    const SsrFrame strided = renderSsr(*rasterizer, scene, coarse);
    SsrSettings noFade = linearMarch();
    noFade.edgeFade = 0.0f;
    SsrSettings wideFade = linearMarch();
    wideFade.edgeFade = 0.5f;  // only the very centre of the screen keeps full confidence
    const SsrFrame faded = renderSsr(*rasterizer, scene, wideFade);
    const SsrFrame unfaded = renderSsr(*rasterizer, scene, noFade);
    std::size_t fineHits = 0, shortHits = 0, outOfSteps = 0, agree = 0, bothHit = 0, fewerSteps = 0, fadedHits = 0;
    for (std::size_t i = 0; i < fine.ssr.pixels.size(); ++i) {
        const SsrPixel &a = fine.ssr.pixels[i], &b = shortMarch.ssr.pixels[i], &c = strided.ssr.pixels[i], &d = unfaded.ssr.pixels[i];
        if (!a.traced()) continue;
        EXPECT_LE(b.steps, 3);
        if (b.flags & kSsrOutOfSteps) ++outOfSteps;
        fineHits += a.resolved();
        shortHits += b.resolved();
        if (a.resolved() && c.resolved()) {
            ++bothHit;
            if (std::abs(a.hit.x - c.hit.x) <= 1 && std::abs(a.hit.y - c.hit.y) <= 1) ++agree;
            if (c.steps < a.steps) ++fewerSteps;
        }
        const SsrPixel& e = faded.ssr.pixels[i];
        if (e.resolved()) {
            EXPECT_LE(e.confidence, a.confidence);
            if (e.confidence < 1.0f) ++fadedHits;
        }
        if (d.resolved()) {
            EXPECT_EQ(d.confidence, 1.0f);
        }
    }
    std::printf("[ ssr      ] hits with 512 steps %zu, with 3 steps %zu (%zu out of steps); stride 4 agrees within a pixel on %zu of %zu, "
                "fewer steps on %zu; %zu hits faded with a wide edge fade\n",
                fineHits, shortHits, outOfSteps, agree, bothHit, fewerSteps, fadedHits);
    EXPECT_LT(shortHits * 10, fineHits);
    EXPECT_GT(outOfSteps, fineHits / 2);
    EXPECT_GE(static_cast<double>(agree), 0.95 * bothHit);
    EXPECT_GE(static_cast<double>(fewerSteps), 0.8 * bothHit);
    EXPECT_GT(fadedHits, fineHits / 2);
}

std::string traversalName(SsrSettings::Traversal t) { return t == SsrSettings::Traversal::HiZ ? "hiz" : "linear"; }

INSTANTIATE_TEST_SUITE_P(SsrPass, SsrTraversal, ::testing::Values(SsrSettings::Traversal::Linear, SsrSettings::Traversal::HiZ),
                         [](const auto& info) { return traversalName(info.param); });

TEST(SsrPass, HiZFindsTheLinearMarchHitsInFewerSteps) {
    const Scene scene = test::mirrorFloorScene();
    RASTERIZER_OR_SKIP(rasterizer, scene);
    const SsrFrame linear = renderSsr(*rasterizer, scene, linearMarch());
    SsrSettings hizSettings;
    hizSettings.traversal = SsrSettings::Traversal::HiZ;
    const SsrFrame hiz = renderSsr(*rasterizer, scene, hizSettings);
    std::size_t traced = 0, sameOutcome = 0, bothHit = 0, samePixel = 0;
    double linearSteps = 0.0, hizSteps = 0.0;
    for (std::size_t i = 0; i < linear.ssr.pixels.size(); ++i) {
        const SsrPixel &a = linear.ssr.pixels[i], &b = hiz.ssr.pixels[i];
        if (!a.traced()) continue;
        ++traced;
        sameOutcome += a.resolved() == b.resolved();
        linearSteps += a.steps;
        hizSteps += b.steps;
        if (a.resolved() && b.resolved()) {
            ++bothHit;
            if (std::abs(a.hit.x - b.hit.x) <= 1 && std::abs(a.hit.y - b.hit.y) <= 1) ++samePixel;
        }
    }
    std::printf("[ ssr      ] hiz against linear: same outcome on %zu of %zu rays, same hit pixel (within 1) on %zu of %zu; mean steps %.1f "
                "linear, %.1f hiz\n",
                sameOutcome, traced, samePixel, bothHit, linearSteps / traced, hizSteps / traced);
    EXPECT_GE(static_cast<double>(sameOutcome), 0.98 * traced);
    EXPECT_GE(static_cast<double>(samePixel), 0.98 * bothHit);
    EXPECT_LT(hizSteps, 0.5 * linearSteps);
}

// The march runs on the texels the pyramid pass lists, and the outputs of the others are cleared:
// a pass reused for a frame that shows less of the mirror keeps nothing of the frame before.
TEST(SsrPass, AFrameWithFewerMirrorTexelsKeepsNothingOfTheFrameBefore) {
    Scene scene = test::mirrorFloorScene();
    RASTERIZER_OR_SKIP(rasterizer, scene);
    SsrPass pass;
    RasterRequest request;
    request.width = kWidth;
    request.height = kHeight;
    request.readback = kGBufferObjectId;
    request.passes = {&pass};
    auto tracedTexels = [&](const Camera& camera, RasterFrame& frame) {
        request.camera = camera;
        rasterizer->render(request, frame);
        std::size_t traced = 0;
        for (std::size_t i = 0; i < frame.gbuffer.pixelCount(); ++i) {
            const SsrPixel& s = pass.result().pixels[i];
            traced += s.traced();
            EXPECT_EQ(s.traced(), frame.gbuffer.object(i) == 0) << "texel " << i;  // the floor, object 0
            if (!s.traced()) {
                EXPECT_EQ(s.flags, 0u) << "texel " << i;
                EXPECT_EQ(s.hit, glm::ivec2(-1)) << "texel " << i;
                EXPECT_EQ(s.confidence, 0.0f) << "texel " << i;
            }
        }
        return traced;
    };
    RasterFrame frame;
    const std::size_t before = tracedTexels(scene.camera, frame);
    Camera up = scene.camera;  // the same place, looking up: the floor only at the bottom of the image
    up.orientation = Camera::lookAtOrientation(up.position, up.position + glm::vec3(0.0f, 0.3f, -1.0f));
    const std::size_t after = tracedTexels(up, frame);
    EXPECT_GT(before, 0u);
    EXPECT_GT(after, 0u);
    EXPECT_LT(after, before / 2);
}

}  // namespace
}  // namespace hybridlab
