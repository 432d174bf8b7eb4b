// The two-term greedy ray-path model (Hakura & Snyder 2001 §3) against hand-computed Fresnel
// products, absorption and exit rays through a glass slab and a glass sphere; lens systems from
// lens groups; the query count against the full binary ray tree.
#include <cmath>

#include <gtest/gtest.h>

#include "techniques/shared/lens_paths.h"
#include "techniques/shared/lens_system.h"
#include "tests/support/lens_test_scenes.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

const glm::vec3 kAbsorption(0.5f, 1.0f, 2.0f);

TEST(LensPaths, GlassSlabAtThirtyDegrees) {
    test::SceneBuilder b;
    b.object("slab", makeCube(), b.material(test::glassWithAbsorption(kAbsorption)), test::placed({0, 0, 0}, {40, 40, 0.2f}));
    Scene& scene = b.scene();
    RayScene lens(scene);
    const double ti = M_PI / 6.0, tt = std::asin(std::sin(ti) / 1.5);
    const glm::vec3 d(static_cast<float>(std::sin(ti)), 0.0f, -static_cast<float>(std::cos(ti)));
    const Ray ray{glm::vec3(0, 0, 0.1f) - 3.0f * d, d};
    LensRayCounter counter;
    TwoTermPaths p;
    ASSERT_TRUE(traceTwoTermPaths(lens, ray, {}, counter, p));

    const double r1 = test::handFresnel(ti, 1.0, 1.5), r2 = test::handFresnel(tt, 1.5, 1.0);
    const LensPath& R = p.reflection();
    EXPECT_TRUE(R.exists);
    EXPECT_NEAR(R.fresnel, r1, 1e-5);
    EXPECT_VEC_NEAR(R.absorption, glm::vec3(1.0f), 1e-6f);
    EXPECT_VEC_NEAR(R.exitDirection, glm::vec3(d.x, 0.0f, -d.z), 1e-5f);
    EXPECT_EQ(R.interfaces, 1);
    EXPECT_EQ(R.choices, 1u);

    const LensPath& T = p.refraction();
    EXPECT_TRUE(T.exists);
    EXPECT_NEAR(T.fresnel, (1.0 - r1) * (1.0 - r2), 1e-5);
    const double thickness = 0.2 / std::cos(tt);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(T.absorption[c], std::exp(-kAbsorption[c] * thickness), 1e-4);
    EXPECT_VEC_NEAR(T.exitDirection, d, 1e-5f) << "parallel faces: the ray leaves as it came";
    EXPECT_VEC_NEAR(T.exitOrigin, glm::vec3(static_cast<float>(0.2 * std::tan(tt)), 0.0f, -0.1f), 1e-4f);
    EXPECT_EQ(T.interfaces, 2);
    EXPECT_EQ(T.choices, 0u) << "refraction wins at both interfaces";
    EXPECT_FALSE(T.truncated);
    EXPECT_EQ(counter.queries, 1u + 1u + 2u) << "first hit; reflection: one miss; refraction: back face, then a miss";
}

TEST(LensPaths, GlassSphereOffAxis) {
    // A ray parallel to -z at height h = 0.5 meets the unit sphere at 30 degrees incidence.
    Scene scene = test::glassSphereScene({0, 0, 0}, 1.0f, kAbsorption);
    RayScene lens(scene);
    const double ti = M_PI / 6.0, tt = std::asin(std::sin(ti) / 1.5);
    LensRayCounter counter;
    TwoTermPaths p;
    ASSERT_TRUE(traceTwoTermPaths(lens, Ray{{0, 0.5f, 5}, {0, 0, -1}}, {}, counter, p));
    const double r1 = test::handFresnel(ti, 1.0, 1.5), r2 = test::handFresnel(tt, 1.5, 1.0);

    EXPECT_NEAR(p.reflection().fresnel, r1, 2e-3);
    EXPECT_VEC_NEAR(p.reflection().exitDirection, glm::vec3(0.0f, static_cast<float>(std::sin(2 * ti)), static_cast<float>(std::cos(2 * ti))), 3e-3f);

    const LensPath& T = p.refraction();
    EXPECT_EQ(T.interfaces, 2);
    EXPECT_NEAR(T.fresnel, (1.0 - r1) * (1.0 - r2), 2e-3);
    const double chord = 2.0 * std::cos(tt), deviation = 2.0 * (ti - tt);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(T.absorption[c], std::exp(-kAbsorption[c] * chord), 3e-3);
    EXPECT_VEC_NEAR(T.exitDirection, glm::vec3(0.0f, -static_cast<float>(std::sin(deviation)), -static_cast<float>(std::cos(deviation))), 3e-3f);
    // The chord inside subtends pi - 2 tt at the centre: it leaves at polar angle (from +z in the
    // yz plane, towards +y) ti + pi - 2 tt; the entry is at ti.
    const double exitAngle = ti + M_PI - 2.0 * tt;
    EXPECT_VEC_NEAR(T.exitOrigin, glm::vec3(0.0f, static_cast<float>(std::sin(exitAngle)), static_cast<float>(std::cos(exitAngle))), 3e-3f);
}

TEST(LensPaths, FullRayTreeMakesMoreQueries) {
    Scene scene = test::glassSphereScene({0, 0, 0}, 1.0f, kAbsorption, 64, 32);
    RayScene lens(scene);
    LensRayCounter counter;
    std::uint64_t tree = 0;
    int hits = 0;
    for (int i = 0; i < 9; ++i) {
        for (int j = 0; j < 9; ++j) {
            Ray ray{{-0.9f + 0.2f * i, -0.9f + 0.2f * j, 5.0f}, {0, 0, -1}};
            TwoTermPaths p;
            if (traceTwoTermPaths(lens, ray, {}, counter, p)) ++hits;
            tree += fullRayTreeQueries(lens, ray, {});
        }
    }
    EXPECT_GT(hits, 40);
    // The greedy paths cost about 1 + 2 + 2 queries a hit ray; the full tree to 10 interfaces
    // grows with every internal reflection.
    EXPECT_GT(static_cast<double>(tree), 3.0 * static_cast<double>(counter.queries));
}

TEST(LensPaths, LensSystemsFromGroups) {
    test::SceneBuilder b;
    auto glass = b.material(test::glassWithAbsorption(glm::vec3(0.0f)));
    b.object("pot", makeSphere(16, 8), glass, test::placed({0, 0, 0}, glm::vec3(2.0f)));
    b.object("wall", makeCube(), glass, test::placed({0, 0, -5}, {10, 10, 1}));
    b.object("cup", makeCube(), glass, test::placed({0, 0, 0}, glm::vec3(0.5f)));
    b.object("lone", makeCube(), glass, test::placed({4, 0, 0}, glm::vec3(1.0f)));
    Scene& s = b.scene();
    s.objects[0].lens = s.objects[2].lens = s.objects[3].lens = true;
    s.objects[0].lensGroup = s.objects[2].lensGroup = "pot-and-cup";
    auto systems = findLensSystems(s);
    ASSERT_EQ(systems.size(), 2u);
    EXPECT_EQ(systems[0].name, "pot-and-cup");
    EXPECT_EQ(systems[0].objects, (std::vector<std::uint32_t>{0, 2}));
    EXPECT_EQ(systems[1].name, "lone");

    LensSystem pot(s, systems[0]);
    EXPECT_VEC_NEAR(pot.center(), glm::vec3(0.0f), 1e-5f);
    SurfaceHit hit;
    // Inside the pot the cup is part of the system; the wall and the lone cube are environment.
    ASSERT_TRUE(pot.lensRays().intersect(Ray{{0, 0, 0.9f}, {0, 0, -1}}, 0.0f, 100.0f, hit));
    EXPECT_EQ(pot.lensObject(hit.object), 2u);
    EXPECT_NEAR(hit.t, 0.65f, 1e-4f);
    ASSERT_TRUE(pot.environmentRays().intersect(Ray{{0, 0, 0}, {0, 0, -1}}, 0.0f, 100.0f, hit));
    EXPECT_EQ(pot.environmentObject(hit.object), 1u);
    EXPECT_NEAR(hit.t, 4.5f, 1e-4f);
}

}  // namespace
}  // namespace hybridlab
