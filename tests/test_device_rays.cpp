// The Vulkan ray-tracing backend (common/device_rays) against closed-form answers and against the
// Embree reference: analytic single rays through both backends, backend agreement on whole frames
// (SSIM and ray counts by kind), and rays = "vulkan" on a device without ray tracing.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "cli_runner.h"
#include "common/device_rays/device_whitted_tracer.h"
#include "common/raster/vulkan_error.h"
#include "common/raytrace/whitted_tracer.h"
#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "metrics/metrics.h"
#include "scene_fixtures.h"
#include "technique_test_support.h"
#include "test_support.h"

namespace hybridlab {
namespace {

using test::SceneBuilder;
using test::emissive;
using test::matte;
using test::placed;

// The ray-tracing device, or a skip when the machine has none (Mesa older than 25, no Vulkan).
#define REQUIRE_RAY_TRACING_DEVICE()                                                                  \
    try {                                                                                             \
        VulkanDevice::shared({.rayTracing = true});                                                   \
    } catch (const VulkanUnavailable& e) {                                                            \
        GTEST_SKIP() << "no ray-tracing Vulkan device: " << e.what();                                 \
    }

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

// Whitted (or rt_only) on both backends at a small size: SSIM and ray counts by kind.
void expectBackendsAgree(const std::string& sceneName, const std::string& technique, int width, int height) {
    SCOPED_TRACE(sceneName + " " + technique);
    const Scene scene = loadSceneFile(findSceneFile(sceneName));
    const FrameResult embree = test::renderFrame(scene, technique, {{"rays", std::string("embree")}}, width, height);
    const FrameResult device = test::renderFrame(scene, technique, {{"rays", std::string("vulkan")}}, width, height);
    const double ssim = computeMetrics(device.image, embree.image).whole.ssim;
    EXPECT_GE(ssim, 0.995);
    std::printf("[ backends ] %s %s %dx%d: SSIM %.5f", sceneName.c_str(), technique.c_str(), width, height, ssim);
    for (const char* kind : {"rays_primary", "rays_shadow", "rays_reflection", "rays_refraction"}) {
        const double e = embree.counters.at(kind), d = device.counters.at(kind);
        EXPECT_LE(std::abs(d - e), 0.005 * e) << kind << ": vulkan " << d << ", embree " << e;
        std::printf(", %s %.0f / %.0f", kind + 5, d, e);
    }
    std::printf("\n");
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
