// The Vulkan ray-tracing backend (common/device_rays) against closed-form answers and against the
// Embree reference: analytic single rays through both backends, backend agreement on whole frames
// (SSIM and ray counts by kind), and rays = "vulkan" on a device without ray tracing. Absorption
// and the depth limit follow the reference's rules (medium_stack.h, WhittedTracer::shadeParts).
#include <limits>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "common/core/input_error.h"
#include "common/device_rays/device_whitted_tracer.h"
#include "common/raster/vulkan_error.h"
#include "common/raytrace/whitted_tracer.h"
#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "metrics/metrics.h"
#include "tests/support/cli_runner.h"
#include "tests/support/lens_test_scenes.h"
#include "tests/support/scene_fixtures.h"
#include "tests/support/technique_test_support.h"
#include "tests/support/test_support.h"
#include "tests/support/raster_test_support.h"

namespace hybridlab {
namespace {

using test::SceneBuilder;
using test::absorbingGlass;
using test::emissive;
using test::matte;
using test::placed;

// One ray from `origin` along `dir`, traced by both backends: a 1 x 1 image whose pixel centre is
// the camera's forward direction, on the device; WhittedTracer::radiance on Embree.
struct BothBackends {
    glm::vec3 embree;
    glm::vec3 device;
};

BothBackends traceBoth(const Scene& scene, glm::vec3 origin, glm::vec3 dir, WhittedSettings settings = {}) {
    dir = glm::normalize(dir);
    RayScene rays(scene);
    RayStats stats;
    BothBackends r;
    r.embree = WhittedTracer(rays, settings).radiance({origin, dir}, 0, 1.0f, stats);
    DeformedMeshCache deformed(scene);
    DeviceRayScene deviceScene(VulkanDevice::shared({.rayTracing = true}), scene, deformed);
    Camera camera;
    camera.position = origin;
    camera.orientation = Camera::lookAtOrientation(origin, origin + dir, std::abs(dir.y) > 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0));
    r.device = glm::vec3(DeviceWhittedTracer(deviceScene).trace(camera, 1, 1, settings).image.at(0, 0));
    return r;
}

void expectBoth(const BothBackends& r, glm::vec3 expected, float tolerance, const std::string& what) {
    EXPECT_VEC_NEAR(r.embree, expected, tolerance) << what << " (embree)";
    EXPECT_VEC_NEAR(r.device, expected, tolerance) << what << " (vulkan)";
}

TEST(DeviceRays, MirrorReflectsTowardsTheMirroredTarget) {
    REQUIRE_RAY_TRACING_DEVICE();
    // A mirror floor at y = 0; a ray from (0, 1, 0) at 45 degrees hits it at (1, 0, 0) and must
    // reach a small emissive target at (2, 1, 0); a ray 3 degrees off misses it.
    SceneBuilder b;
    Material mirror = matte(glm::vec3(0));
    mirror.reflectivity = 1.0f;
    b.object("mirror", makePlane(), b.material(mirror), placed({0, 0, 0}, {20, 1, 20}));
    b.object("target", makeCube(), b.material(emissive({0.9f, 0.5f, 0.1f})), placed({2, 1, 0}, glm::vec3(0.02f)));
    b.scene().sky.color = glm::vec3(0.0f);
    expectBoth(traceBoth(b.scene(), {0, 1, 0}, {1, -1, 0}), {0.9f, 0.5f, 0.1f}, 1e-5f, "hits the target");
    expectBoth(traceBoth(b.scene(), {0, 1, 0}, {1, -1.05f, 0}), glm::vec3(0.0f), 1e-6f, "misses it");
}

TEST(DeviceRays, RefractionThroughAGlassSlabFollowsSnellsLaw) {
    REQUIRE_RAY_TRACING_DEVICE();
    // A glass slab 1 thick, IOR 1.5, no reflection: a ray at 40 degrees leaves parallel to itself,
    // shifted by Snell's law; a tiny emissive target on the predicted exit ray is hit, and missed
    // by the straight ray (IOR 1).
    const float i = glm::radians(40.0f), r = std::asin(std::sin(i) / 1.5f);
    SceneBuilder b;
    Material glass = matte(glm::vec3(1));
    glass.opacity = 0.0f;
    glass.ior = 1.5f;
    b.object("slab", makeCube(), b.material(glass), placed({0, -0.5f, 0}, {50, 1, 50}));
    const glm::vec3 dir(std::sin(i), -std::cos(i), 0), exit(std::tan(r), -1.0f, 0.0f);
    b.object("target", makeCube(), b.material(emissive({0.3f, 0.6f, 0.9f})), placed(exit + dir, glm::vec3(0.01f)));
    b.scene().sky.color = glm::vec3(0.0f);
    expectBoth(traceBoth(b.scene(), -dir, dir), {0.3f, 0.6f, 0.9f}, 1e-5f, "on the Snell path");
    b.scene().materials[0].ior = 1.0f;
    expectBoth(traceBoth(b.scene(), -dir, dir), glm::vec3(0.0f), 1e-6f, "the straight ray misses");
}

TEST(DeviceRays, TotalInternalReflectionSendsEverythingToTheReflectedRay) {
    REQUIRE_RAY_TRACING_DEVICE();
    // Inside a glass slab a ray meets the top face at 60 degrees (beyond the critical 41.8): all of
    // it reflects to an emissive target below; none reaches the red sky.
    const float a = glm::radians(60.0f);
    SceneBuilder b;
    Material glass = matte(glm::vec3(0));
    glass.opacity = 0.0f;
    glass.ior = 1.5f;
    glass.fresnel = true;
    b.object("slab", makeCube(), b.material(glass), placed({0, -5, 0}, {100, 10, 100}));
    const glm::vec3 top(std::tan(a), 0, 0), down(std::sin(a), -std::cos(a), 0);
    b.object("target", makeCube(), b.material(emissive({0.5f, 0.5f, 0.5f})), placed(top + 0.8f * down, glm::vec3(0.02f)));
    b.scene().sky.color = glm::vec3(1.0f, 0.0f, 0.0f);
    expectBoth(traceBoth(b.scene(), {0, -1, 0}, {std::sin(a), std::cos(a), 0}), {0.5f, 0.5f, 0.5f}, 1e-5f, "TIR");
}

TEST(DeviceRays, AShadowThroughAHalfTransparentPaneIsAttenuatedByItsTintTwice) {
    REQUIRE_RAY_TRACING_DEVICE();
    // A white floor under a point light (unshadowed radiance 1 straight below it); a pane of
    // opacity 0.5 and tint (0.8, 0.6, 0.4) between them. The shadow ray crosses its top and bottom
    // faces: (0.5 tint)^2. An opaque pane: black.
    auto shaded = [](float opacity) {
        SceneBuilder b;
        b.object("floor", makePlane(), b.material(matte({1, 1, 1})), placed({0, 0, 0}, {10, 1, 10}));
        Material pane = matte({0.8f, 0.6f, 0.4f});
        pane.opacity = opacity;
        b.object("pane", makeCube(), b.material(pane), placed({0, 1, 0}, {0.5f, 0.1f, 0.5f}));
        Light l;
        l.type = Light::Type::Point;
        l.position = {0, 4, 0};
        l.intensity = 16.0f;
        b.light(l);
        return traceBoth(b.scene(), {0, 0.5f, 0}, {0, -1, 0});
    };
    const glm::vec3 t = 0.5f * glm::vec3(0.8f, 0.6f, 0.4f);
    expectBoth(shaded(0.5f), t * t, 1e-5f, "half-transparent pane");
    expectBoth(shaded(1.0f), glm::vec3(0.0f), 0.0f, "opaque pane");
}

TEST(DeviceRays, AbsorptionThroughASlabOfKnownThickness) {
    REQUIRE_RAY_TRACING_DEVICE();
    // A clear slab (IOR 1, no reflection) 2 thick absorbing (0.1, 0.5, 1.0) per unit: a ray
    // straight through it reaches a white emitter below attenuated by exp(-a d) (Beer-Lambert).
    SceneBuilder b;
    Material glass = matte(glm::vec3(0));
    glass.opacity = 0.0f;
    glass.ior = 1.0f;
    glass.absorption = {0.1f, 0.5f, 1.0f};
    b.object("slab", makeCube(), b.material(glass), placed({0, -1, 0}, {50, 2, 50}));
    b.object("emitter", makePlane(), b.material(emissive({1, 1, 1})), placed({0, -5, 0}, {50, 1, 50}));
    b.scene().sky.color = glm::vec3(0.0f);
    const glm::vec3 expected = glm::exp(-2.0f * glm::vec3(0.1f, 0.5f, 1.0f));
    expectBoth(traceBoth(b.scene(), {0.3f, 1, 0.2f}, {0, -1, 0}), expected, 1e-5f, "exp(-a d)");
}

// An opaque emissive sphere of radius r inside an absorbing glass ball of radius R: the centre ray
// enters the glass at normal incidence (Fresnel transmittance 0.96) and runs R - r inside it to a
// surface that is not the ball's back face: 0.96 E exp(-a (R - r)) (absorption taken only on a
// segment ending on a back face would give 0.96 E).
TEST(DeviceRays, OpaqueSphereInsideAnAbsorbingBallAlongTheCentreRay) {
    REQUIRE_RAY_TRACING_DEVICE();
    const float R = 1.0f, r = 0.4f;
    const glm::vec3 a(0.5f, 1.0f, 2.0f), E(0.8f, 0.6f, 0.4f);
    SceneBuilder b;
    b.object("ball", makeSphere(256, 128), b.material(absorbingGlass(a)), placed({0, 0, 0}, glm::vec3(2.0f * R)));
    b.object("core", makeSphere(128, 64), b.material(emissive(E)), placed({0, 0, 0}, glm::vec3(2.0f * r)));
    b.scene().sky.color = glm::vec3(0.0f);
    b.scene().ambient = glm::vec3(0.0f);
    const BothBackends both = traceBoth(b.scene(), {0, 0, 5}, {0, 0, -1});
    const glm::vec3 expected = 0.96f * E * glm::exp(-a * (R - r));
    expectBoth(both, expected, 0.01f * expected.b, "0.96 E exp(-a (R - r))");
    EXPECT_VEC_NEAR(both.device, both.embree, 1e-5f);
}

// A shadow ray through an absorbing slab of thickness h (glass whose surfaces let light through
// untinted): the floor under the light, seen from the side, is lit exp(-a h) times as brightly
// as without absorption, towards a point light (tau = sum of +-a (D - t_i)) and a directional one
// (tau = sum of -+a t_i); from a point light it is diffuse I / d^2 exp(-a h) exactly.
TEST(DeviceRays, AShadowThroughAnAbsorbingSlabIsAttenuatedByExpMinusAH) {
    REQUIRE_RAY_TRACING_DEVICE();
    const float h = 0.5f;
    const glm::vec3 absorption(0.4f, 1.2f, 3.0f);
    auto shaded = [&](glm::vec3 a, Light::Type type) {
        SceneBuilder b;
        b.object("floor", makePlane(), b.material(matte(glm::vec3(0.5f))), placed({0, 0, 0}, {20, 1, 20}));
        b.object("slab", makeCube(), b.material(absorbingGlass(a)), placed({0, 1.25f, 0}, {1, h, 1}));
        Light l;
        l.type = type;
        l.position = {0, 3, 0};
        l.direction = {0, -1, 0};
        l.intensity = 9.0f;
        b.light(l);
        b.scene().ambient = glm::vec3(0.0f);
        b.scene().sky.color = glm::vec3(0.0f);
        const glm::vec3 from(3.0f, 0.5f, 0.0f);
        return traceBoth(b.scene(), from, -from);
    };
    const glm::vec3 T = glm::exp(-absorption * h);
    expectBoth(shaded(absorption, Light::Type::Point), 0.5f * T, 1e-4f * 0.5f, "point light");
    for (Light::Type type : {Light::Type::Point, Light::Type::Directional}) {
        const BothBackends absorbed = shaded(absorption, type), clear = shaded(glm::vec3(0.0f), type);
        ASSERT_GT(clear.device.r, 0.0f);
        EXPECT_VEC_NEAR(absorbed.device / clear.device, T, 1e-4f) << "vulkan, light type " << static_cast<int>(type);
        EXPECT_VEC_NEAR(absorbed.embree / clear.embree, T, 1e-4f) << "embree, light type " << static_cast<int>(type);
    }
}

// Nested and touching absorbing balls (IOR 1: straight paths): the stack follows the centre ray
// through all of them, outer alone over 2 x 0.5, outer + inner (overlapping media add) over 1,
// the touching ball over 1: exp(-tau) on both backends.
TEST(DeviceRays, NestedAndTouchingMediaAttenuateEachSegmentByItsMedia) {
    REQUIRE_RAY_TRACING_DEVICE();
    const glm::vec3 aOuter(0.3f, 0.6f, 0.9f), aInner(1.0f, 0.5f, 0.25f), aTouching(0.2f, 0.2f, 0.2f);
    Material outer = absorbingGlass(aOuter), inner = absorbingGlass(aInner), touching = absorbingGlass(aTouching);
    for (Material* m : {&outer, &inner, &touching}) m->ior = 1.0f, m->fresnel = false;
    SceneBuilder b;
    b.object("outer", makeSphere(256, 128), b.material(outer), placed({0, 0, 0}, glm::vec3(2.0f)));
    b.object("inner", makeSphere(256, 128), b.material(inner), placed({0, 0, 0}, glm::vec3(1.0f)));
    b.object("touching", makeSphere(256, 128), b.material(touching), placed({0, 0, -1.51f}, glm::vec3(1.0f)));
    b.object("wall", makePlane(), b.material(emissive(glm::vec3(1.0f))), placed({0, 0, -4}, {10, 1, 10}, {90, 0, 0}));
    b.scene().sky.color = glm::vec3(0.0f);
    b.scene().ambient = glm::vec3(0.0f);
    const BothBackends both = traceBoth(b.scene(), {0, 0, 5}, {0, 0, -1});
    const glm::vec3 expected = glm::exp(-(aOuter * 1.0f + (aOuter + aInner) * 1.0f + aTouching * 1.0f));
    expectBoth(both, expected, 2e-3f * expected.r, "exp(-tau)");
    EXPECT_VEC_NEAR(both.device, both.embree, 1e-5f);
}

// A camera inside a closed absorbing ball: its ray leaves a medium it never entered. It renders,
// finite, unabsorbed, and the device counts it in medium_errors as the reference does.
TEST(DeviceRays, LeavingAMediumNeverEnteredIsCountedNotFatal) {
    REQUIRE_RAY_TRACING_DEVICE();
    SceneBuilder b;
    b.object("ball", makeSphere(64, 32), b.material(absorbingGlass({1, 2, 3})), placed({0, 0, 0}, glm::vec3(2.0f)));
    b.scene().sky.color = glm::vec3(0.2f, 0.4f, 0.6f);
    const glm::vec3 dir = glm::normalize(glm::vec3(0.3f, 0.2f, -1.0f));
    RayScene rays(b.scene());
    RayStats stats;
    const glm::vec3 reference = WhittedTracer(rays, {}).radiance({glm::vec3(0.0f), dir}, 0, 1.0f, stats);
    DeformedMeshCache deformed(b.scene());
    DeviceRayScene deviceScene(VulkanDevice::shared({.rayTracing = true}), b.scene(), deformed);
    Camera camera;
    camera.position = glm::vec3(0.0f);
    camera.orientation = Camera::lookAtOrientation(glm::vec3(0.0f), dir, glm::vec3(0, 1, 0));
    const DeviceTraceResult traced = DeviceWhittedTracer(deviceScene).trace(camera, 1, 1, {});
    const glm::vec3 device(traced.image.at(0, 0));
    EXPECT_TRUE(std::isfinite(device.r) && std::isfinite(device.g) && std::isfinite(device.b));
    EXPECT_GT(device.b, 0.0f);
    EXPECT_VEC_NEAR(device, reference, 1e-5f);
    EXPECT_GE(stats.mediumErrors, 1u);
    EXPECT_EQ(traced.rays.mediumErrors, stats.mediumErrors);
}

// depth_limit on the device: an emissive half-mirror (reflectivity 0.5, local colour E) under a
// blue sky. At max_depth 0 "weighted" returns 0.5 E (the reflected ray counting 0), "local" E;
// at max_depth 1 both 0.5 sky + 0.5 E.
TEST(DeviceRays, DepthLimitReturnsTheWeightedOrTheLocalColour) {
    REQUIRE_RAY_TRACING_DEVICE();
    const glm::vec3 E(0.6f, 0.4f, 0.2f), sky(0.0f, 0.0f, 1.0f);
    SceneBuilder b;
    Material halfMirror = emissive(E);
    halfMirror.reflectivity = 0.5f;
    b.object("mirror", makePlane(), b.material(halfMirror), placed({0, 0, 0}, {10, 1, 10}));
    b.scene().sky.color = sky;
    b.scene().ambient = glm::vec3(0.0f);
    WhittedSettings s;
    ASSERT_EQ(s.depthLimit, DepthLimit::Weighted);
    s.maxDepth = 0;
    expectBoth(traceBoth(b.scene(), {0, 1, 0}, {0, -1, 0}, s), 0.5f * E, 1e-6f, "depth 0, weighted");
    s.depthLimit = DepthLimit::Local;
    expectBoth(traceBoth(b.scene(), {0, 1, 0}, {0, -1, 0}, s), E, 1e-6f, "depth 0, local");
    for (DepthLimit limit : {DepthLimit::Weighted, DepthLimit::Local}) {
        s.depthLimit = limit;
        s.maxDepth = 1;
        expectBoth(traceBoth(b.scene(), {0, 1, 0}, {0, -1, 0}, s), 0.5f * sky + 0.5f * E, 1e-6f, "depth 1");
    }
}

// A technique (whitted, rt_only, heuristic_rt, ssr_fallback) on both backends at a small size, with
// `params` besides `rays`: SSIM and ray counts by kind. Returns the Embree frame.
FrameResult expectBackendsAgree(const std::string& sceneName, const std::string& technique, int width, int height,
                                const test::TechniqueParams& params = {}) {
    SCOPED_TRACE(sceneName + " " + technique);
    const Scene scene = loadSceneFile(findSceneFile(sceneName));
    auto on = [&](const std::string& rays) {
        test::TechniqueParams p = params;
        p.push_back({"rays", rays});
        return test::renderFrame(scene, technique, p, width, height);
    };
    const FrameResult embree = on("embree"), device = on("vulkan");
    const double ssim = computeMetrics(device.image, embree.image).whole.ssim;
    EXPECT_GE(ssim, 0.995);
    std::printf("[ backends ] %s %s %dx%d: SSIM %.5f", sceneName.c_str(), technique.c_str(), width, height, ssim);
    for (const char* kind : {"rays_primary", "rays_shadow", "rays_reflection", "rays_refraction"}) {
        const double e = embree.counters.at(kind), d = device.counters.at(kind);
        EXPECT_LE(std::abs(d - e), 0.005 * e) << kind << ": vulkan " << d << ", embree " << e;
        std::printf(", %s %.0f / %.0f", kind + 5, d, e);
    }
    EXPECT_EQ(device.counters.at("medium_errors"), embree.counters.at("medium_errors"));
    // The hybrids' own work: the same texels traced, the same objects selected.
    for (const char* counter : {"pixels_ray_traced", "objects_selected", "cost_selected", "fallback_rays", "ssr_hits", "ssr_recursion_rays"}) {
        if (!embree.counters.count(counter)) continue;
        EXPECT_EQ(device.counters.at(counter), embree.counters.at(counter)) << counter;
        std::printf(", %s %.0f", counter, device.counters.at(counter));
    }
    std::printf("\n");
    return embree;
}

// heuristic_rt with an unlimited budget and with half of the visible objects' cost (the same
// selection on both backends: it is made from the same G-buffer).
void expectHeuristicAgrees(const std::string& sceneName, int width, int height) {
    const FrameResult unlimited = expectBackendsAgree(sceneName, "heuristic_rt", width, height);
    const double budget = 0.5 * unlimited.counters.at("cost_visible");
    const FrameResult finite = expectBackendsAgree(sceneName, "heuristic_rt", width, height, {{"budget", budget}});
    EXPECT_LT(finite.counters.at("cost_selected"), unlimited.counters.at("cost_selected")) << sceneName << ": the budget selects less";
}

TEST(DeviceRays, HeuristicRtAgreesWithEmbreeOnTheBuiltInScenes) {
    REQUIRE_RAY_TRACING_DEVICE();
    expectHeuristicAgrees("whitted-classic", 160, 90);
    expectHeuristicAgrees("cornell-mirror-glass", 160, 90);
}

TEST(DeviceRays, SsrFallbackAgreesWithEmbreeOnTheFourScenes) {
    REQUIRE_RAY_TRACING_DEVICE();
    for (const char* scene : {"whitted-classic", "cornell-mirror-glass", "sponza-spheres", "teapot-lens"})
        expectBackendsAgree(scene, "ssr_fallback", 160, 90);
}

TEST(DeviceRays, HeuristicRtAgreesWithEmbreeOnThePaperScenes) {
    REQUIRE_RAY_TRACING_DEVICE();
    expectHeuristicAgrees("sponza-spheres", 160, 90);
    expectHeuristicAgrees("teapot-lens", 160, 90);
}

TEST(DeviceRays, WhittedAgreesWithEmbreeOnTheBuiltInScenes) {
    REQUIRE_RAY_TRACING_DEVICE();
    expectBackendsAgree("whitted-classic", "whitted", 160, 90);
    expectBackendsAgree("cornell-mirror-glass", "whitted", 160, 90);
    expectBackendsAgree("whitted-classic", "rt_only", 160, 90);
}

TEST(DeviceRays, WhittedAgreesWithEmbreeOnThePaperScenes) {
    REQUIRE_RAY_TRACING_DEVICE();
    expectBackendsAgree("sponza-spheres", "whitted", 160, 90);
    expectBackendsAgree("teapot-lens", "whitted", 160, 90);
}

// Frame 1 at time 0, frame 2 at `time` in the same context: the device's instances move (rigid) or
// its bottom levels refit (deforming) rather than being built at `time`.
void expectBackendsAgreeAfterAnUpdate(const std::string& sceneName, double time) {
    SCOPED_TRACE(sceneName);
    const Scene scene = loadSceneFile(findSceneFile(sceneName));
    auto secondFrame = [&](const std::string& rays) {
        SceneContext context(scene);
        auto t = createTechnique("whitted", {{"rays", rays}});
        t->prepare(context);
        t->render(context, {scene.camera, 0.0, 96, 54});
        return t->render(context, {scene.camera, time, 96, 54});
    };
    const FrameResult embree = secondFrame("embree"), device = secondFrame("vulkan");
    const double ssim = computeMetrics(device.image, embree.image).whole.ssim;
    EXPECT_GE(ssim, 0.995);
    for (const char* counter : {"bvh_triangles", "bvh_moving_triangles", "bvh_refit_triangles"})
        EXPECT_EQ(device.counters.at(counter), embree.counters.at(counter)) << counter;
    for (const char* kind : {"rays_primary", "rays_shadow", "rays_reflection", "rays_refraction"}) {
        const double e = embree.counters.at(kind), d = device.counters.at(kind);
        EXPECT_LE(std::abs(d - e), 0.005 * e) << kind << ": vulkan " << d << ", embree " << e;
    }
    std::printf("[ backends ] %s at t = %.1f s after t = 0: SSIM %.5f, moving %.0f, refit %.0f triangles\n", sceneName.c_str(), time, ssim,
                device.counters.at("bvh_moving_triangles"), device.counters.at("bvh_refit_triangles"));
}

TEST(DeviceRays, RigidAndDeformingAnimationUpdateTheAccelerationStructures) {
    REQUIRE_RAY_TRACING_DEVICE();
    expectBackendsAgreeAfterAnUpdate("bunnies-falling-5", 1.5);
    expectBackendsAgreeAfterAnUpdate("teapots-deforming-5", 1.5);
}

TEST(DeviceRays, AComputerWithoutRayTracingIsToldWhichExtensionItLacks) {
    REQUIRE_RAY_TRACING_DEVICE();
    // The driver plays one without the ray-tracing pipeline: exit 2 before anything renders, one
    // message naming the device and the extension, no file written.
    test::TempDir dir;
    const test::CliResult r = test::runHybridlab(
        {"render", "--scene", "whitted-classic", "--technique", "whitted", "--param", "rays=vulkan", "--width", "64", "--height", "36",
         "--out", (dir / "frame.exr").string()},
        {{"HYBRIDLAB_VULKAN_HIDE_EXTENSIONS", "VK_KHR_ray_tracing_pipeline"}});
    EXPECT_EQ(r.exitStatus, 2) << r.err;
    EXPECT_CONTAINS(r.err, "rays = \"vulkan\"");
    EXPECT_CONTAINS(r.err, "lacks VK_KHR_ray_tracing_pipeline");
    EXPECT_CONTAINS(r.err, VulkanDevice::shared({.rayTracing = true})->name());
    EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

TEST(DeviceRays, ASceneOfMoreObjectsOrMaterialsThanAMediumEntryAddressesIsRefused) {
    REQUIRE_RAY_TRACING_DEVICE();
    // A pending ray's medium stack packs object and material in 16 bits each
    // (device_medium_stack.glsl): 65535 of either is refused by name, before anything is built.
    auto refusal = [](const Scene& scene) -> std::string {
        DeformedMeshCache deformed(scene);
        try {
            DeviceRayScene deviceScene(VulkanDevice::shared({.rayTracing = true}), scene, deformed);
        } catch (const InputError& e) {
            return e.what();
        }
        return "";
    };
    SceneBuilder objects;
    objects.object("first", makeCube(), objects.material(matte({0.5f, 0.5f, 0.5f})));
    objects.scene().objects.resize(0xFFFF, objects.scene().objects.front());
    EXPECT_CONTAINS(refusal(objects.scene()), "scene test has 65535 objects and 1 materials; rays = \"vulkan\" addresses at most 65534");
    SceneBuilder materials;
    materials.object("only", makeCube(), materials.material(matte({0.5f, 0.5f, 0.5f})));
    materials.scene().materials.resize(0xFFFF, materials.scene().materials.front());
    EXPECT_CONTAINS(refusal(materials.scene()), "has 1 objects and 65535 materials");
    // One fewer of each builds.
    objects.scene().objects.resize(0xFFFE);
    EXPECT_EQ(refusal(objects.scene()), "");
}

TEST(DeviceRays, ASceneTooLargeForTheDeviceIsToldItsSize) {
    REQUIRE_RAY_TRACING_DEVICE();
    // A device of 0.1 MiB: whitted-classic's 7938 triangles need about 1 MiB. Exit 2 before
    // rendering, the scene's size in the message, nothing written.
    test::TempDir dir;
    const test::CliResult r = test::runHybridlab(
        {"render", "--scene", "whitted-classic", "--technique", "rt_only", "--param", "rays=vulkan", "--width", "64", "--height", "36",
         "--out", (dir / "frame.exr").string()},
        {{"HYBRIDLAB_VULKAN_DEVICE_MEMORY_BYTES", "100000"}});
    EXPECT_EQ(r.exitStatus, 2) << r.err;
    EXPECT_CONTAINS(r.err, "scene whitted-classic (7938 triangles) needs");
    EXPECT_CONTAINS(r.err, "has 0.1 MiB");
    EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

}  // namespace
}  // namespace hybridlab
