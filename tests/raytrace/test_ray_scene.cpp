// RayScene: static geometry in one BVH, animated objects as instances re-committed per frame,
// and hits that map back to objects, meshes and materials.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "common/raytrace/ray_scene.h"
#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "techniques/technique.h"
#include "tests/support/lens_test_scenes.h"
#include "tests/support/scene_fixtures.h"

namespace hybridlab {
namespace {

using test::SceneBuilder;
using test::matte;
using test::placed;

constexpr float kInf = std::numeric_limits<float>::infinity();

// A static floor, a static box and a sphere that moves from x = -2 at t = 0 to x = +2 at t = 1.
Scene movingSphereScene() {
    SceneBuilder b;
    b.object("floor", makePlane(), b.material(matte({1, 1, 1})), placed({0, 0, 0}, {20, 1, 20}));
    b.object("box", makeCube(), b.material(matte({1, 0, 0})), placed({0, 0.5f, -3}, glm::vec3(1)));
    std::uint32_t ballMaterial = b.material(matte({0, 0, 1}));
    b.object("ball", makeSphere(32, 16), ballMaterial, placed({-2, 1, 0}, glm::vec3(1)));
    RigidAnimation& a = b.scene().objects.back().animation;
    a.times = {0.0, 1.0};
    a.positions = {{-2, 1, 0}, {2, 1, 0}};
    a.rotations = {glm::quat(1, 0, 0, 0), glm::quat(1, 0, 0, 0)};
    a.scales = {glm::vec3(1), glm::vec3(1)};
    return b.scene();
}

TEST(RayScene, HitsMapBackToObjectsMeshesAndMaterials) {
    Scene scene = movingSphereScene();
    RayScene rays(scene);
    SurfaceHit hit;
    ASSERT_TRUE(rays.intersect({{0, 0.5f, 5}, {0, 0, -1}}, 0.0f, kInf, hit));
    EXPECT_EQ(scene.objects[hit.object].name, "box");
    EXPECT_EQ(hit.mesh, scene.objects[hit.object].meshes[0]);
    EXPECT_EQ(hit.material, &scene.materials[1]);
    EXPECT_NEAR(hit.t, 5.0f + 2.5f, 1e-4f);
    EXPECT_NEAR(hit.position.z, -2.5f, 1e-5f);
    EXPECT_NEAR(glm::dot(hit.geometricNormal, glm::vec3(0, 0, 1)), 1.0f, 1e-6f);
    ASSERT_TRUE(rays.intersect({{-2, 5, 0}, {0, -1, 0}}, 0.0f, kInf, hit));
    EXPECT_EQ(scene.objects[hit.object].name, "ball");  // an instance resolves to its object too
    EXPECT_NEAR(hit.position.y, 1.5f, 1e-3f);
    EXPECT_EQ(hit.material, &scene.materials[2]);
}

TEST(RayScene, AnimatedObjectsMoveWhenTheTimeChanges) {
    Scene scene = movingSphereScene();
    RayScene rays(scene, 0.0);
    SurfaceHit hit;
    const Ray atLeft{{-2, 5, 0}, {0, -1, 0}}, atRight{{2, 5, 0}, {0, -1, 0}};
    ASSERT_TRUE(rays.intersect(atLeft, 0.0f, kInf, hit));
    EXPECT_EQ(scene.objects[hit.object].name, "ball");
    ASSERT_TRUE(rays.intersect(atRight, 0.0f, kInf, hit));
    EXPECT_EQ(scene.objects[hit.object].name, "floor");

    rays.setTime(1.0);
    EXPECT_EQ(rays.time(), 1.0);
    EXPECT_GE(rays.lastUpdateMilliseconds(), 0.0);
    ASSERT_TRUE(rays.intersect(atLeft, 0.0f, kInf, hit));
    EXPECT_EQ(scene.objects[hit.object].name, "floor");
    ASSERT_TRUE(rays.intersect(atRight, 0.0f, kInf, hit));
    EXPECT_EQ(scene.objects[hit.object].name, "ball");
    EXPECT_NEAR(hit.position.y, 1.5f, 1e-3f);
    EXPECT_NEAR(glm::dot(hit.shadingNormal, glm::vec3(0, 1, 0)), 1.0f, 1e-3f);

    // Halfway, the instance agrees with a scene built with the ball placed there statically.
    rays.setTime(0.5);
    Scene frozen = movingSphereScene();
    frozen.objects.back().animation = RigidAnimation{};
    frozen.objects.back().transform = placed({0, 1, 0}, glm::vec3(1));
    RayScene still(frozen);
    for (float x : {-0.4f, -0.1f, 0.2f, 0.45f}) {
        SurfaceHit a, b;
        ASSERT_TRUE(rays.intersect({{x, 5, 0.1f}, {0, -1, 0}}, 0.0f, kInf, a));
        ASSERT_TRUE(still.intersect({{x, 5, 0.1f}, {0, -1, 0}}, 0.0f, kInf, b));
        EXPECT_EQ(a.object, b.object);
        EXPECT_NEAR(a.t, b.t, 1e-5f);
        EXPECT_NEAR(glm::length(a.shadingNormal - b.shadingNormal), 0.0f, 1e-5f);
    }
    EXPECT_GT(rays.buildMilliseconds(), 0.0);
}

TEST(RayScene, ShadowRaysStopAtOpaqueCastersAndIgnoreNonCasters) {
    SceneBuilder b;
    Material ghost = matte({1, 1, 1});
    ghost.castsShadows = false;
    b.object("ghost", makeCube(), b.material(ghost), placed({0, 2, 0}, glm::vec3(1)));
    b.object("wall", makeCube(), b.material(matte({1, 1, 1})), placed({0, 4, 0}, glm::vec3(1)));
    RayScene rays(b.scene());
    EXPECT_EQ(rays.transmittance({0, 0, 0}, {0, 1, 0}, 3.0f), glm::vec3(1.0f));  // only the ghost
    EXPECT_EQ(rays.transmittance({0, 0, 0}, {0, 1, 0}, 10.0f), glm::vec3(0.0f));  // the wall too
}

// Camera rays through every pixel of a w x h image of `scene` at time 0.5 (the moving sphere an
// instance half-way), traced one at a time and in packets of 1 to kCoherentRays: the same hits
// (object, primitive, distance and position bit for bit), in each lane of a packet.
TEST(RayScene, CoherentPacketsFindTheHitsOfSingleRays) {
    Scene scene = movingSphereScene();
    scene.camera.position = {4, 4, 6};
    scene.camera.orientation = Camera::lookAtOrientation(scene.camera.position, {0, 0.5f, -1.5f}, {0, 1, 0});
    RayScene rays(scene, 0.5);
    const int w = 96, h = 54;
    const CameraRays camera(scene.camera, static_cast<float>(w) / h);
    std::vector<Ray> all;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) all.push_back(camera.throughNdc(pixelCenterNdc(x, y, w, h)));
    int hits = 0, objects[3] = {0, 0, 0};
    for (int size = 1; size <= RayScene::kCoherentRays; ++size) {
        for (std::size_t first = 0; first < all.size(); first += static_cast<std::size_t>(size)) {
            const int count = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(size), all.size() - first));
            SurfaceHit packet[RayScene::kCoherentRays];
            bool found[RayScene::kCoherentRays];
            rays.intersectCoherent(&all[first], count, packet, found);
            for (int k = 0; k < count; ++k) {
                SurfaceHit single;
                const bool singleFound = rays.intersect(all[first + k], 0.0f, kInf, single);
                ASSERT_EQ(found[k], singleFound) << "ray " << first + k << " in packets of " << size;
                if (!found[k]) continue;
                EXPECT_EQ(packet[k].object, single.object);
                EXPECT_EQ(packet[k].primitive, single.primitive);
                EXPECT_EQ(packet[k].t, single.t);
                EXPECT_EQ(packet[k].position, single.position);
                EXPECT_EQ(packet[k].material, single.material);
                hits += size == RayScene::kCoherentRays;
                if (size == RayScene::kCoherentRays) ++objects[packet[k].object];
            }
        }
    }
    EXPECT_GT(hits, w * h / 2);  // the test sees something
    for (int o = 0; o < 3; ++o) EXPECT_GT(objects[o], 50) << scene.objects[o].name;  // the instance too
    SurfaceHit unused[RayScene::kCoherentRays + 1];
    bool found[RayScene::kCoherentRays + 1];
    EXPECT_THROW(rays.intersectCoherent(all.data(), 0, unused, found), std::logic_error);
    EXPECT_THROW(rays.intersectCoherent(all.data(), RayScene::kCoherentRays + 1, unused, found), std::logic_error);
}

// Shadow rays from a grid of points on a floor towards a point light and a light at infinity,
// past an opaque box, a caster that casts no shadow, tinted glass spheres (two crossings each,
// touching one another) and an absorbing slab: traced in packets of 1 to kCoherentRays, each
// lane's transmittance is the single ray's (to the last bits, where the packet meets a ray's
// transparent surfaces in another order), and the packet's rays are logged as one.
TEST(RayScene, CoherentShadowPacketsLetThroughWhatSingleRaysDo) {
    SceneBuilder b;
    b.object("floor", makePlane(), b.material(matte({1, 1, 1})), placed({0, 0, 0}, {20, 1, 20}));
    b.object("box", makeCube(), b.material(matte({1, 0, 0})), placed({-1.5f, 2.0f, 0}, glm::vec3(0.8f)));
    Material ghost = matte({1, 1, 1});
    ghost.castsShadows = false;
    b.object("ghost", makeCube(), b.material(ghost), placed({1.5f, 2.0f, 1.0f}, glm::vec3(1.0f)));
    Material tinted = matte({0.9f, 0.6f, 0.3f});
    tinted.opacity = 0.2f;
    const std::uint32_t glass = b.material(tinted);
    for (int i = 0; i < 3; ++i)
        b.object("glass" + std::to_string(i), makeSphere(24, 12), glass, placed({-0.5f + 0.6f * i, 2.5f, -0.5f}, glm::vec3(0.3f)));
    b.object("slab", makeCube(), b.material(test::absorbingGlass({0.4f, 1.2f, 3.0f})), placed({0.5f, 3.5f, 0.5f}, {2.0f, 0.3f, 2.0f}));
    RayScene rays(b.scene());
    std::vector<ShadowQuery> all;
    const glm::vec3 light(0.0f, 6.0f, 0.0f), sun = glm::normalize(glm::vec3(0.2f, 1.0f, 0.1f));
    for (int infinite = 0; infinite < 2; ++infinite) {
        for (int z = 0; z < 24; ++z) {
            for (int x = 0; x < 24; ++x) {
                const glm::vec3 p(-3.0f + 0.25f * x, 0.001f, -3.0f + 0.25f * z);
                if (infinite) all.push_back({p, sun, kInf});
                else all.push_back({p, glm::normalize(light - p), glm::length(light - p)});
            }
        }
    }
    int lit = 0, dark = 0, tintedOrAbsorbed = 0;
    for (int size = 1; size <= RayScene::kCoherentRays; ++size) {
        for (std::size_t first = 0; first < all.size(); first += static_cast<std::size_t>(size)) {
            const int count = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(size), all.size() - first));
            glm::vec3 packet[RayScene::kCoherentRays];
            rays.transmittanceCoherent(&all[first], count, packet);
            for (int k = 0; k < count; ++k) {
                const ShadowQuery& q = all[first + k];
                const glm::vec3 single = rays.transmittance(q.origin, q.direction, q.tmax, q.startAbsorption);
                for (int c = 0; c < 3; ++c)
                    EXPECT_NEAR(packet[k][c], single[c], 1e-6f * single[c]) << "ray " << first + k << " in packets of " << size;
                if (size != RayScene::kCoherentRays) continue;
                lit += single == glm::vec3(1.0f);
                dark += single == glm::vec3(0.0f);
                tintedOrAbsorbed += single != glm::vec3(1.0f) && single != glm::vec3(0.0f);
            }
        }
    }
    // The test sees every kind of ray.
    EXPECT_GT(lit, 50);
    EXPECT_GT(dark, 20);
    EXPECT_GT(tintedOrAbsorbed, 20);

    RayLog log;
    rays.setRayLog(&log);
    glm::vec3 three[3];
    rays.transmittanceCoherent(all.data(), 3, three);
    const std::vector<LoggedRay> logged = log.collect();
    ASSERT_EQ(logged.size(), 3u);
    for (int k = 0; k < 3; ++k) {
        EXPECT_TRUE(logged[k].shadow);
        EXPECT_EQ(logged[k].tmax, all[k].tmax);
        EXPECT_EQ(logged[k].packetSize, 3);
        EXPECT_EQ(logged[k].packetLane, k);
    }
    glm::vec3 unused[RayScene::kCoherentRays + 1];
    EXPECT_THROW(rays.transmittanceCoherent(all.data(), 0, unused), std::logic_error);
    EXPECT_THROW(rays.transmittanceCoherent(all.data(), RayScene::kCoherentRays + 1, unused), std::logic_error);
}

// Three parallel camera-like rays towards the moving sphere, a packet of them.
const Ray kThreeParallelRays[3] = {{{0, 0.5f, 5}, {0, 0, -1}}, {{0, 0.6f, 5}, {0, 0, -1}}, {{0, 0.7f, 5}, {0, 0, -1}}};

TEST(RayScene, CoherentPacketsAreLoggedRayByRay) {
    Scene scene = movingSphereScene();
    RayScene rays(scene);
    RayLog log;
    rays.setRayLog(&log);
    const Ray* three = kThreeParallelRays;
    SurfaceHit hits[3];
    bool found[3];
    rays.intersectCoherent(three, 3, hits, found);
    const std::vector<LoggedRay> logged = log.collect();
    ASSERT_EQ(logged.size(), 3u);
    for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(logged[k].origin, three[k].origin);
        EXPECT_FALSE(logged[k].shadow);
        EXPECT_EQ(logged[k].tmax, kInf);
        EXPECT_EQ(logged[k].packetSize, 3);  // so that a replay traces them as one packet too
        EXPECT_EQ(logged[k].packetLane, k);
    }
    SurfaceHit alone;
    rays.intersect(three[0], 0.0f, kInf, alone);
    EXPECT_EQ(log.collect().back().packetSize, 1);
}

// The call clock counts each Embree call once (a packet is one call) while it is set, and nothing
// after; its ticks grow with the calls.
TEST(RayScene, TheCallClockTimesEachEmbreeCallWhileSet) {
    Scene scene = movingSphereScene();
    RayScene rays(scene);
    EmbreeCallClock clock;
    rays.setCallClock(&clock);
    const Ray* three = kThreeParallelRays;
    SurfaceHit hits[3];
    bool found[3];
    rays.intersectCoherent(three, 3, hits, found);
    EXPECT_EQ(clock.calls(), 1u);
    SurfaceHit alone;
    rays.intersect(three[0], 0.0f, kInf, alone);
    rays.transmittance({0, 0.5f, 5}, {0, 0, -1}, 10.0f);
    rays.transmittance({0, 0.5f, 5}, {0, 1, 0}, 10.0f);
    EXPECT_EQ(clock.calls(), 4u);
    EXPECT_GT(clock.ticks(), 0u);
    rays.setCallClock(nullptr);
    rays.intersect(three[0], 0.0f, kInf, alone);
    EXPECT_EQ(clock.calls(), 4u);
}

FrameResult renderWhitted(const Scene& scene, std::vector<std::pair<std::string, ParamValue>> params, int w, int h) {
    SceneContext context(scene);
    auto t = createTechnique("whitted", params);
    t->prepare(context);
    return t->render(context, {scene.camera, 0.0, w, h});
}

TEST(WhittedParameters, SupersamplingAveragesSubPixelSamples) {
    // 2 x 2 samples at 64 x 36 sit exactly at the pixel centres of a 128 x 72 render, so the
    // supersampled image is that render's 2 x 2 box average (up to float rounding of the NDC).
    Scene scene = loadSceneFile(findSceneFile("whitted-classic"));
    FrameResult four = renderWhitted(scene, {{"supersample", std::string("2")}}, 64, 36);
    FrameResult fine = renderWhitted(scene, {}, 128, 72);
    EXPECT_EQ(four.counters.at("rays_primary"), fine.counters.at("rays_primary"));
    int close = 0;
    double total = 0.0;
    for (int y = 0; y < 36; ++y) {
        for (int x = 0; x < 64; ++x) {
            glm::vec4 avg = 0.25f * (fine.image.at(2 * x, 2 * y) + fine.image.at(2 * x + 1, 2 * y) +
                                     fine.image.at(2 * x, 2 * y + 1) + fine.image.at(2 * x + 1, 2 * y + 1));
            float d = glm::length(glm::vec3(avg - four.image.at(x, y)));
            total += d;
            close += d < 1e-5f;
        }
    }
    EXPECT_GE(close, 64 * 36 * 99 / 100);
    EXPECT_LT(total / (64 * 36), 1e-3);
}

TEST(WhittedParameters, ImportanceCutoffPrunesTheRayTree) {
    Scene scene = loadSceneFile(findSceneFile("cornell-mirror-glass"));
    FrameResult full = renderWhitted(scene, {}, 80, 45);
    FrameResult pruned = renderWhitted(scene, {{"importance_cutoff", std::string("0.2")}}, 80, 45);
    const double fullSecondary = full.counters.at("rays_reflection") + full.counters.at("rays_refraction");
    const double prunedSecondary = pruned.counters.at("rays_reflection") + pruned.counters.at("rays_refraction");
    EXPECT_LT(prunedSecondary, 0.9 * fullSecondary);
    EXPECT_GT(prunedSecondary, 0.0);
    FrameResult depth0 = renderWhitted(scene, {{"max_depth", std::string("0")}}, 80, 45);
    EXPECT_EQ(depth0.counters.at("rays_reflection") + depth0.counters.at("rays_refraction"), 0.0);
}

}  // namespace
}  // namespace hybridlab
