// End-to-end analytic checks of the Whitted reference: rays traced through RayScene and
// WhittedTracer in scenes built so that the answer is known in closed form.
#include <cmath>
#include <functional>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <glm/geometric.hpp>

#include "common/core/input_error.h"
#include "common/raytrace/ray_log.h"
#include "common/raytrace/ray_offset.h"
#include "common/raytrace/whitted_tracer.h"
#include "common/shading/whitted_tree.h"
#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "techniques/technique.h"
#include "tests/support/scene_fixtures.h"
#include "tests/support/technique_test_support.h"

namespace hybridlab {
namespace {

using test::SceneBuilder;
using test::emissive;
using test::matte;
using test::placed;

constexpr float kInf = std::numeric_limits<float>::infinity();

glm::vec3 trace(const Scene& scene, glm::vec3 origin, glm::vec3 dir, WhittedSettings settings = {}) {
    RayScene rays(scene);
    WhittedTracer tracer(rays, settings);
    RayStats stats;
    return tracer.radiance({origin, glm::normalize(dir)}, 0, 1.0f, stats);
}

void expectNear(glm::vec3 a, glm::vec3 b, float tol, const std::string& what = "") {
    EXPECT_NEAR(a.r, b.r, tol) << what;
    EXPECT_NEAR(a.g, b.g, tol) << what;
    EXPECT_NEAR(a.b, b.b, tol) << what;
}

TEST(Whitted, MissReturnsTheSky) {
    SceneBuilder b;
    b.object("far", makeCube(), b.material(matte(glm::vec3(1))), placed({0, -100, 0}, glm::vec3(1)));
    b.scene().sky.color = glm::vec3(0.2f, 0.3f, 0.4f);
    expectNear(trace(b.scene(), glm::vec3(0), glm::vec3(0, 1, 0)), glm::vec3(0.2f, 0.3f, 0.4f), 0.0f);
}

TEST(Whitted, MirrorReflectsTowardsTheMirroredTarget) {
    // A mirror floor at y = 0; a ray from (0, 1, 0) at 45 degrees hits it at (1, 0, 0) and must
    // reach a small emissive target at (2, 1, 0); a target off the mirrored ray is not seen.
    SceneBuilder b;
    Material mirror = matte(glm::vec3(0));
    mirror.reflectivity = 1.0f;
    b.object("mirror", makePlane(), b.material(mirror), placed({0, 0, 0}, {20, 1, 20}));
    b.object("target", makeCube(), b.material(emissive({0.9f, 0.5f, 0.1f})), placed({2, 1, 0}, glm::vec3(0.02f)));
    b.scene().sky.color = glm::vec3(0.0f);
    expectNear(trace(b.scene(), {0, 1, 0}, {1, -1, 0}), {0.9f, 0.5f, 0.1f}, 1e-6f, "hits the target");
    expectNear(trace(b.scene(), {0, 1, 0}, {1, -1.05f, 0}), glm::vec3(0.0f), 1e-6f, "misses it");
}

TEST(Whitted, RefractionThroughASlabFollowsSnellsLaw) {
    // A glass slab 1 thick (y in [-1, 0]), IOR 1.5, no reflection: a ray arriving at 40 degrees
    // leaves the slab parallel to itself, shifted sideways by t sin(i - r) / cos r. A tiny
    // emissive target on the predicted exit ray is hit.
    const float i = glm::radians(40.0f), r = std::asin(std::sin(i) / 1.5f);
    SceneBuilder b;
    Material glass = matte(glm::vec3(1));
    glass.opacity = 0.0f;
    glass.ior = 1.5f;
    b.object("slab", makeCube(), b.material(glass), placed({0, -0.5f, 0}, {50, 1, 50}));
    // Entry at the origin; exit at x = tan(r), y = -1; then 1 more unit along the incident direction.
    glm::vec3 dir(std::sin(i), -std::cos(i), 0);
    glm::vec3 exit(std::tan(r), -1.0f, 0.0f);
    b.object("target", makeCube(), b.material(emissive({0.3f, 0.6f, 0.9f})), placed(exit + dir, glm::vec3(0.01f)));
    b.scene().sky.color = glm::vec3(0.0f);
    glm::vec3 origin = -dir;  // starts 1 unit before the entry point
    expectNear(trace(b.scene(), origin, dir), {0.3f, 0.6f, 0.9f}, 1e-6f, "on the Snell path");
    // Without refraction (IOR 1) the straight ray passes far from the target.
    b.scene().materials[0].ior = 1.0f;
    expectNear(trace(b.scene(), origin, dir), glm::vec3(0.0f), 1e-6f, "straight ray misses");
    const float shift = std::sin(i - r) / std::cos(r);
    EXPECT_GT(shift, 0.1f);  // the test would not discriminate otherwise
}

TEST(Whitted, TotalInternalReflectionSendsEverythingToTheReflectedRay) {
    // Inside a glass slab a ray meets the top face at 60 degrees (> 41.8, the critical angle):
    // all of it reflects down to an emissive target below, nothing escapes to the sky.
    const float a = glm::radians(60.0f);
    SceneBuilder b;
    Material glass = matte(glm::vec3(0));
    glass.opacity = 0.0f;
    glass.ior = 1.5f;
    glass.fresnel = true;
    b.object("slab", makeCube(), b.material(glass), placed({0, -5, 0}, {100, 10, 100}));
    glm::vec3 dir(std::sin(a), std::cos(a), 0);  // upwards from (0, -1, 0), hits the top at x = tan(a)
    glm::vec3 top(std::tan(a), 0, 0);
    glm::vec3 down(std::sin(a), -std::cos(a), 0);
    b.object("target", makeCube(), b.material(emissive({0.5f, 0.5f, 0.5f})), placed(top + 0.8f * down, glm::vec3(0.02f)));
    b.scene().sky.color = glm::vec3(1.0f, 0.0f, 0.0f);
    expectNear(trace(b.scene(), {0, -1, 0}, dir), {0.5f, 0.5f, 0.5f}, 1e-5f);
}

TEST(Whitted, PointLightContributionFallsOffWithInverseSquareDistance) {
    for (float h : {1.0f, 2.0f, 4.0f}) {
        SceneBuilder b;
        b.object("floor", makePlane(), b.material(matte({0.5f, 0.5f, 0.5f})), placed({0, 0, 0}, {10, 1, 10}));
        Light l;
        l.type = Light::Type::Point;
        l.position = {0, h, 0};
        l.intensity = 3.0f;
        b.light(l);
        // Looking straight down at the point under the light: N.L = 1.
        glm::vec3 c = trace(b.scene(), {0, 0.5f, 0}, {0, -1, 0});
        EXPECT_NEAR(c.r, 0.5f * 3.0f / (h * h), 1e-6f) << h;
    }
}

TEST(Whitted, OpaqueOccluderCastsAHardShadowAndATransparentOneLetsItsShareThrough) {
    auto shaded = [](float occluderOpacity, float x) {
        SceneBuilder b;
        b.object("floor", makePlane(), b.material(matte({1, 1, 1})), placed({0, 0, 0}, {10, 1, 10}));
        Material blocker = matte({0.8f, 0.6f, 0.4f});
        blocker.opacity = occluderOpacity;
        b.object("blocker", makeCube(), b.material(blocker), placed({0, 1, 0}, {0.5f, 0.1f, 0.5f}));
        Light l;
        l.type = Light::Type::Point;
        l.position = {0, 4, 0};
        l.intensity = 16.0f;
        b.light(l);
        return trace(b.scene(), {x, 0.5f, 0}, {0, -1, 0});
    };
    const glm::vec3 lit = shaded(1.0f, 2.0f);  // outside the shadow
    EXPECT_GT(lit.r, 0.0f);
    expectNear(shaded(1.0f, 0.0f), glm::vec3(0.0f), 0.0f, "opaque: hard shadow");
    // Just inside and just outside the shadow edge (light at 4, blocker half-width 0.25 at y = 1.05
    // top face: the edge on the floor is at x = 0.25 * 4 / 2.95 = 0.339).
    expectNear(shaded(1.0f, 0.32f), glm::vec3(0.0f), 0.0f, "inside the edge");
    EXPECT_GT(shaded(1.0f, 0.36f).r, 0.0f);
    // Transparent: (1 - opacity) * tint, twice (the ray crosses the slab's top and bottom faces).
    const glm::vec3 t = 0.75f * glm::vec3(0.8f, 0.6f, 0.4f);
    const glm::vec3 unshadowed = glm::vec3(16.0f / 16.0f);  // diffuse 1, N.L 1, I / d^2 = 1
    expectNear(shaded(0.25f, 0.0f), unshadowed * t * t, 1e-6f, "transparent occluder");
}

// A grey half-mirror floor at y = 0 lit from straight above (its local colour C = 0.5), under a blue sky.
Scene halfMirrorUnderTheSun() {
    SceneBuilder b;
    Material m = matte({0.5f, 0.5f, 0.5f});
    m.reflectivity = 0.5f;
    b.object("floor", makePlane(), b.material(m), placed({0, 0, 0}, {10, 1, 10}));
    Light l;
    l.type = Light::Type::Directional;
    l.direction = {0, -1, 0};
    l.intensity = 1.0f;
    b.light(l);
    b.scene().sky.color = glm::vec3(0.0f, 0.0f, 1.0f);
    return b.scene();
}

TEST(Whitted, DepthLimitReturnsTheWeightedOrTheLocalColour) {
    // The half-mirror reflects the sky. With max_depth 0 the hit returns its local colour weighted
    // as the composition weights it, 0.5 C (the reflected ray counting 0), or with depth_limit
    // "local" C alone; with 1, 0.5 sky + 0.5 C either way.
    const Scene scene = halfMirrorUnderTheSun();
    const glm::vec3 C(0.5f);
    WhittedSettings s;
    EXPECT_EQ(s.depthLimit, DepthLimit::Weighted);
    s.maxDepth = 0;
    expectNear(trace(scene, {0, 1, 0}, {0, -1, 0}, s), 0.5f * C, 1e-6f, "depth 0, weighted");
    s.depthLimit = DepthLimit::Local;
    expectNear(trace(scene, {0, 1, 0}, {0, -1, 0}, s), C, 1e-6f, "depth 0, local");
    for (DepthLimit limit : {DepthLimit::Weighted, DepthLimit::Local}) {
        s.depthLimit = limit;
        s.maxDepth = 1;
        expectNear(trace(scene, {0, 1, 0}, {0, -1, 0}, s), 0.5f * glm::vec3(0, 0, 1) + 0.5f * C, 1e-6f, "depth 1");
    }
}

TEST(Whitted, DepthLimitParameterReachesEveryRayTracingTechnique) {
    for (const char* name : {"whitted", "rt_only", "heuristic_rt", "ssr_fallback"}) {
        EXPECT_NO_THROW(createTechnique(name, {{"depth_limit", std::string("local")}})) << name;
        EXPECT_THROW(createTechnique(name, {{"depth_limit", std::string("black")}}), InputError) << name;
    }
}

TEST(Whitted, ALocalColourTheCallerHasIsComposedAsIsWithoutShadowRays) {
    // The half-mirror again: a hybrid hands shadeParts the lit G-buffer texel as C; it is composed
    // (0.5 sky + 0.5 C) and not shaded again (no shadow ray).
    const Scene scene = halfMirrorUnderTheSun();
    RayScene rays(scene);
    const WhittedTracer tracer(rays, {});
    const Ray down{{0, 1, 0}, {0, -1, 0}};
    SurfaceHit hit;
    ASSERT_TRUE(rays.intersect(down, 0.0f, kInf, hit));
    const glm::vec3 given(0.1f, 0.2f, 0.3f);
    RayStats withGiven, shaded;
    const shading_language::HitParts parts = tracer.shadeParts(hit, down.direction, 0, 1.0f, withGiven, {}, {}, given);
    expectNear(parts.local, given, 0.0f, "C as given");
    expectNear(shading_language::composedParts(parts, false), 0.5f * glm::vec3(0, 0, 1) + 0.5f * given, 1e-6f, "composed with the given C");
    EXPECT_EQ(withGiven.shadow, 0u);
    EXPECT_EQ(withGiven.reflection, 1u);
    expectNear(tracer.shadeParts(hit, down.direction, 0, 1.0f, shaded).local, glm::vec3(0.5f), 1e-6f, "C shaded");
    EXPECT_EQ(shaded.shadow, 1u);
}

TEST(Whitted, RayCountsFollowTheRayTree) {
    // One camera ray hitting a Fresnel glass sphere in an empty sky: one reflection and one
    // refraction ray at the first hit, and per light one shadow ray where N.L > 0.
    SceneBuilder b;
    Material glass = matte({1, 1, 1});
    glass.opacity = 0.0f;
    glass.fresnel = true;
    b.object("ball", makeSphere(64, 32), b.material(glass), placed({0, 0, 0}, glm::vec3(2)));
    RayScene rays(b.scene());
    WhittedSettings s;
    s.maxDepth = 1;
    WhittedTracer tracer(rays, s);
    RayStats stats;
    tracer.radiance({{0, 0, 5}, {0, 0, -1}}, 0, 1.0f, stats);
    EXPECT_EQ(stats.reflection, 1u);
    EXPECT_EQ(stats.refraction, 1u);
    EXPECT_EQ(stats.shadow, 0u);  // no lights
}

// Where C weighs nothing in the composition ((1 - o_m)(1 - o_r) = 0: clear glass, a perfect mirror,
// total internal reflection) and stands in for no untraced ray of non-zero weight, shade() skips C
// and its shadow rays; the radiance is still the composition of the shaded C, bit for bit. At
// every camera ray's first hit, under both rules, with and without the importance cut-off, at
// importances that cut rays off and at the depth limit, on scenes with each kind of surface.
TEST(Whitted, ShadeSkipsTheLocalColourOnlyWhereItWeighsNothing) {
    struct Case {
        const char* scene;
        std::function<void(Material&)> edit;
    };
    const std::vector<Case> cases = {
        {"whitted-classic", {}},
        {"teapot-lens", {}},
        {"cornell-mirror-glass", {}},
        {"facing-mirrors", [](Material& m) { if (m.reflectivity > 0.0f) m.reflectivity = 1.0f; }},  // perfect mirrors
        // Half-transparent perfect mirrors, and glass without Fresnel (o_m = 0 under total internal
        // reflection): an untraced ray's stand-in C still weighs there.
        {"facing-mirrors", [](Material& m) { if (m.reflectivity > 0.0f) m.reflectivity = 1.0f, m.opacity = 0.5f; }},
        {"teapot-lens", [](Material& m) { if (m.fresnel) m.fresnel = false, m.reflectivity = 0.0f, m.ambient = glm::vec3(0.3f); }},
    };
    for (const Case& c : cases) {
        Scene scene = loadSceneFile(findSceneFile(c.scene));
        if (c.edit)
            for (Material& m : scene.materials) c.edit(m);
        RayScene rays(scene);
        int skipped = 0;
        for (const BlendRule rule : {BlendRule::Design, BlendRule::Walewski2019}) {
            for (const float cutoff : {0.0f, 0.1f}) {
                WhittedSettings settings;
                settings.blend = rule;
                settings.importanceCutoff = cutoff;
                settings.maxDepth = 3;
                const WhittedTracer tracer(rays, settings);
                const int w = 32, h = 18;
                const CameraRays camera(scene.camera, static_cast<float>(w) / h);
                const RayCone cone = pixelCone(scene.camera, h);
                int differing = 0;
                auto compare = [&](const SurfaceHit& hit, glm::vec3 incoming, RayCone footprint) {
                    for (const int depth : {0, 3}) {
                        for (const float importance : {1.0f, 0.3f, 0.05f}) {
                            RayStats always, ifWeighted;
                            const shading_language::HitParts parts = tracer.shadeParts(hit, incoming, depth, importance, always, {}, footprint);
                            const glm::vec3 shaded = tracer.shade(hit, incoming, depth, importance, ifWeighted, footprint);
                            differing += shading_language::composedParts(parts, rule == BlendRule::Walewski2019) != shaded;
                            EXPECT_LE(ifWeighted.shadow, always.shadow);
                            skipped += ifWeighted.shadow < always.shadow;
                        }
                    }
                };
                for (int y = 0; y < h; ++y) {
                    for (int x = 0; x < w; ++x) {
                        const Ray ray = camera.throughNdc(pixelCenterNdc(x, y, w, h));
                        SurfaceHit hit;
                        if (!rays.intersect(ray, 0.0f, kInf, hit)) continue;
                        compare(hit, ray.direction, cone.at(hit.t));
                        // The hit inside a refractive object too, where total internal reflection happens.
                        glm::vec3 inward;
                        if (hit.material->isRefractive() && glm::dot(ray.direction, hit.geometricNormal) < 0.0f &&
                            refractDirection(ray.direction, hit.shadingNormal, scene.ambientIor / hit.material->ior, inward)) {
                            SurfaceHit inner;
                            if (rays.intersect({offsetRayOrigin(hit.position, -hit.geometricNormal), inward}, 0.0f, kInf, inner))
                                compare(inner, inward, cone.at(hit.t + inner.t));
                        }
                    }
                }
                EXPECT_EQ(differing, 0) << c.scene << ", cut-off " << cutoff;
            }
        }
        EXPECT_GT(skipped, 0) << c.scene;
    }
}

FrameResult renderWithThreads(const Scene& scene, int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    SceneContext context(scene);
    auto technique = createTechnique("whitted", {});
    technique->prepare(context);
    return technique->render(context, {scene.camera, 0.0, 160, 90});
}

// Ray cones (Akenine-Möller et al. 2019): a checkerboard so far away that every pixel covers many
// squares is filtered to their mean, as the rasterizer's mip-mapping does, instead of aliasing to
// light or dark; seen close up (magnified), a square's centre keeps its own colour.
TEST(Whitted, TexturesAreFilteredOverTheRayConesFootprint) {
    SceneBuilder b;
    b.scene().textures.push_back(makeBuiltinTexture("builtin:checker"));
    Material board = matte(glm::vec3(0.0f));
    board.ambient = glm::vec3(1.0f);  // no lights, scene ambient 1: the pixel is the texture value
    board.diffuseTexture = 0;
    board.textureTiling = glm::vec2(64.0f);  // 512 x 512 squares over the plane
    b.object("board", makePlane(), b.material(board), placed({0, 0, 0}, {100, 1, 100}));
    b.scene().ambient = glm::vec3(1.0f);
    Camera& camera = b.scene().camera;
    camera.fovYDegrees = 90.0f;
    camera.position = {0, 50, 0};  // sees the 100-wide plane edge to edge: 16 squares a pixel at 32 x 32
    camera.orientation = Camera::lookAtOrientation(camera.position, {0, 0, 0}, {0, 0, -1});
    const Texture& checker = b.scene().textures[0];
    const float light = checker.image.at(0, 0).r, dark = checker.image.at(64, 0).r;
    const Image far = test::renderImage(b.scene(), "whitted", {}, 32, 32);
    float lo = 1e9f, hi = -1e9f;
    for (std::size_t i = 0; i < far.pixelCount(); ++i) lo = std::min(lo, far.data()[i].r), hi = std::max(hi, far.data()[i].r);
    EXPECT_NEAR(lo, 0.5f * (light + dark), 0.01f);
    EXPECT_NEAR(hi, 0.5f * (light + dark), 0.01f);

    // Close up: one square (100 / 512 wide) fills the view; the pixel at the centre of the view
    // looks at a square's centre (the world origin is a corner: offset by half a square).
    const float halfSquare = 100.0f / 512.0f * 0.5f;
    camera.position = {halfSquare, 0.01f, halfSquare};
    camera.orientation = Camera::lookAtOrientation(camera.position, camera.position - glm::vec3(0, 1, 0), {0, 0, -1});
    const Image close = test::renderImage(b.scene(), "whitted", {}, 33, 33);
    const float centre = close.at(16, 16).r;
    EXPECT_TRUE(std::abs(centre - light) < 1e-3f || std::abs(centre - dark) < 1e-3f) << centre;
}

TEST(Whitted, RendersAreByteIdenticalWhateverTheThreadCount) {
    for (const char* name : {"whitted-classic", "cornell-mirror-glass"}) {
        Scene scene = loadSceneFile(findSceneFile(name));
        FrameResult one = renderWithThreads(scene, 1);
        FrameResult two = renderWithThreads(scene, 2);
        FrameResult four = renderWithThreads(scene, 4);
        EXPECT_TRUE(one.image == two.image) << name;
        EXPECT_TRUE(one.image == four.image) << name;
        EXPECT_EQ(one.counters, two.counters) << name;
        EXPECT_EQ(one.counters, four.counters) << name;
    }
}

// The technique's pixel loop traces camera rays in coherent packets, and their first hits' shadow
// rays a packet per light; a pixel is still what WhittedTracer::radiance gives for its camera ray
// alone, bit for bit, edges of odd-sized images (partial packets) included. The packets' shadow
// rays are the walk's: it traces no first-hit shadow ray again, and few of theirs go unused.
TEST(Whitted, PacketsOfCameraAndShadowRaysShadeAsSingleRays) {
    for (const char* name : {"whitted-classic", "teapot-lens", "cornell-mirror-glass"}) {
        Scene scene = loadSceneFile(findSceneFile(name));
        const int w = 61, h = 35;
        SceneContext context(scene);
        auto whitted = createTechnique("whitted", {});
        whitted->prepare(context);
        RayLog log;
        context.rayScene(0.0).setRayLog(&log);
        const FrameResult frame = whitted->render(context, {scene.camera, 0.0, w, h});
        context.rayScene(0.0).setRayLog(nullptr);
        const Image& image = frame.image;
        RayScene rays(scene);
        const WhittedTracer tracer(rays, WhittedSettings{});
        const CameraRays camera(scene.camera, static_cast<float>(w) / h);
        const RayCone cone = pixelCone(scene.camera, h);
        int differing = 0;
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                RayStats stats;
                const glm::vec3 single = tracer.radiance(camera.throughNdc(pixelCenterNdc(x, y, w, h)), 0, 1.0f, stats, cone);
                differing += glm::vec3(image.at(x, y)) != single;
            }
        }
        EXPECT_EQ(differing, 0) << name;
        double inPackets = 0, alone = 0;
        for (const LoggedRay& r : log.collect()) {
            if (!r.shadow) continue;
            (r.packetSize > 1 ? inPackets : alone) += 1;
        }
        const double counted = frame.counters.at("rays_shadow");
        EXPECT_GT(inPackets, 0.25 * counted) << name;
        EXPECT_LE(inPackets + alone, 1.02 * counted) << name;  // traced once, few in vain
    }
}

TEST(RtOnly, IsWhittedWithWalewskisImportanceCutoff) {
    // Same code, other default: with the cut-off at 0 rt_only renders the reference exactly.
    Scene scene = loadSceneFile(findSceneFile("cornell-mirror-glass"));
    auto render = [&](const std::string& name, std::vector<std::pair<std::string, ParamValue>> params) {
        SceneContext context(scene);
        auto t = createTechnique(name, params);
        t->prepare(context);
        return t->render(context, {scene.camera, 0.0, 96, 54});
    };
    FrameResult reference = render("whitted", {});
    FrameResult rtOnly = render("rt_only", {});
    FrameResult uncut = render("rt_only", {{"importance_cutoff", 0.0}});
    EXPECT_TRUE(uncut.image == reference.image);
    EXPECT_EQ(uncut.counters, reference.counters);
    EXPECT_LT(rtOnly.counters.at("rays_reflection") + rtOnly.counters.at("rays_refraction"),
              reference.counters.at("rays_reflection") + reference.counters.at("rays_refraction"));
}

TEST(Whitted, ParametersAreCheckedAgainstTheirDeclarations) {
    EXPECT_NO_THROW(createTechnique("whitted", {{"max_depth", std::string("3")}}));
    EXPECT_THROW(createTechnique("whitted", {{"max_depth", std::string("-1")}}), InputError);
    EXPECT_THROW(createTechnique("whitted", {{"max_depth", std::string("2.5")}}), InputError);
    EXPECT_THROW(createTechnique("whitted", {{"depth", std::string("3")}}), InputError);
    EXPECT_THROW(createTechnique("whitted", {{"blend", std::string("average")}}), InputError);
    EXPECT_THROW(createTechnique("nope", {}), InputError);
    try {
        createTechnique("whitted", {{"max_depth", std::string("99")}});
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("an integer in [0, 64]"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace hybridlab
