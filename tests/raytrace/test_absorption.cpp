// Beer-Lambert absorption along every path inside a medium (common/raytrace/medium_stack.h):
// analytic eye-path and shadow-ray attenuation, nested media, and paths whose media cannot be
// tracked (counted, finite).
#include <cmath>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "common/raytrace/medium_stack.h"
#include "common/raytrace/whitted_tracer.h"
#include "tests/support/lens_test_scenes.h"
#include "tests/support/scene_fixtures.h"

namespace hybridlab {
namespace {

using test::SceneBuilder;
using test::absorbingGlass;
using test::emissive;
using test::matte;
using test::placed;

constexpr float kInf = std::numeric_limits<float>::infinity();


TEST(MediumStack, EntersLeavesInAnyOrderAndRefusesWhatItCannotTrack) {
    MediumStack s = kAmbientMedium;
    EXPECT_FALSE(mediumAbsorbs(s.absorption));
    EXPECT_TRUE(mediumEnter(s, {3, {0.1f, 0.2f, 0.3f}}));
    EXPECT_TRUE(mediumEnter(s, {5, {1.0f, 0.0f, 0.0f}}));
    EXPECT_EQ(s.absorption, glm::vec3(1.1f, 0.2f, 0.3f));  // overlapping media add
    EXPECT_TRUE(mediumLeave(s, 3));                          // not the top: overlapping objects
    EXPECT_EQ(s.absorption, glm::vec3(1.0f, 0.0f, 0.0f));
    EXPECT_FALSE(mediumLeave(s, 3));  // never entered (again)
    EXPECT_EQ(s.size, 1);
    for (int i = 1; i < kMediumCapacity; ++i) EXPECT_TRUE(mediumEnter(s, {static_cast<std::uint32_t>(10 + i), glm::vec3(0.0f)}));
    EXPECT_FALSE(mediumEnter(s, {99, glm::vec3(1.0f)}));  // full
    EXPECT_EQ(s.size, kMediumCapacity);
    const MediumStack copy = s;  // a copy holds the entries in use
    EXPECT_TRUE(mediumLeave(s, 5));
    EXPECT_EQ(s.absorption, glm::vec3(0.0f));
    EXPECT_EQ(copy.size, kMediumCapacity);
    EXPECT_EQ(copy.absorption, glm::vec3(1.0f, 0.0f, 0.0f));
    EXPECT_EQ(segmentTransmittance(glm::vec3(0.0f), kInf), glm::vec3(1.0f));  // not NaN
}

// An opaque emissive sphere of radius r inside an absorbing glass ball of radius R, both centred
// at the origin, no lights, black sky: the ray along a diameter enters the glass at normal
// incidence (Fresnel transmittance 1 - 0.04), runs R - r inside it, and sees the emission E:
// 0.96 E exp(-a (R - r)). Absorption taken only on leaving through a back face would give 0.96 E,
// which this case tells apart.
TEST(Absorption, OpaqueSphereInsideAnAbsorbingBallAlongTheCentreRay) {
    const float R = 1.0f, r = 0.4f;
    const glm::vec3 a(0.5f, 1.0f, 2.0f), E(0.8f, 0.6f, 0.4f);
    SceneBuilder b;
    b.object("ball", makeSphere(256, 128), b.material(absorbingGlass(a)), placed({0, 0, 0}, glm::vec3(2.0f * R)));
    b.object("core", makeSphere(128, 64), b.material(emissive(E)), placed({0, 0, 0}, glm::vec3(2.0f * r)));
    b.scene().sky.color = glm::vec3(0.0f);
    b.scene().ambient = glm::vec3(0.0f);
    RayScene rays(b.scene());
    WhittedTracer tracer(rays, {});
    RayStats stats;
    const glm::vec3 L = tracer.radiance({{0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, -1.0f}}, 0, 1.0f, stats);
    const double f0 = 0.04;  // ((1.5 - 1) / (1.5 + 1))^2
    for (int c = 0; c < 3; ++c) {
        const double expected = (1.0 - f0) * E[c] * std::exp(-a[c] * (R - r));
        EXPECT_NEAR(L[c], expected, 0.01 * expected) << "channel " << c;
    }
    EXPECT_EQ(stats.mediumErrors, 0u);
}

// A shadow ray through a glass slab of thickness h with absorption a: exp(-a h), whether the light
// is a point (finite distance) or at infinity, and from a point inside the slab exp(-a depth).
TEST(Absorption, ShadowRayThroughAnAbsorbingSlab) {
    const float h = 0.5f;
    const glm::vec3 a(0.4f, 1.2f, 3.0f);
    SceneBuilder b;
    b.object("slab", makeCube(), b.material(absorbingGlass(a)), placed({0, 1.25f, 0}, {4, h, 4}));  // y in [1, 1.5]
    RayScene rays(b.scene());
    const glm::vec3 up(0, 1, 0);
    for (float tmax : {3.0f, kInf}) {
        const glm::vec3 T = rays.transmittance({0, 0, 0}, up, tmax);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(T[c], std::exp(-a[c] * h), 1e-5f) << "tmax " << tmax << " channel " << c;
    }
    // From inside the slab, 0.2 below its top: the origin's medium is the slab's.
    for (float tmax : {3.0f, kInf}) {
        const glm::vec3 T = rays.transmittance({0, 1.3f, 0}, up, tmax, a);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(T[c], std::exp(-a[c] * 0.2f), 1e-5f) << "inside, tmax " << tmax;
    }
    // A light inside the slab, 0.1 above its bottom.
    const glm::vec3 T = rays.transmittance({0, 0, 0}, up, 1.1f);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(T[c], std::exp(-a[c] * 0.1f), 1e-5f) << "light inside";
}

// The same slab between a point light and a matte floor, seen by the reference from the side:
// the floor under the light gets diffuse * I / d^2 * exp(-a h).
TEST(Absorption, ShadowThroughAnAbsorbingSlabDarkensTheLitFloor) {
    const float h = 0.5f;
    const glm::vec3 a(0.4f, 1.2f, 3.0f);
    SceneBuilder b;
    b.object("floor", makePlane(), b.material(matte(glm::vec3(0.5f))), placed({0, 0, 0}, {20, 1, 20}));
    b.object("slab", makeCube(), b.material(absorbingGlass(a)), placed({0, 1.25f, 0}, {1, h, 1}));
    Light l;
    l.type = Light::Type::Point;
    l.position = {0, 3, 0};
    l.intensity = 9.0f;
    b.light(l);
    b.scene().ambient = glm::vec3(0.0f);
    b.scene().sky.color = glm::vec3(0.0f);
    RayScene rays(b.scene());
    WhittedTracer tracer(rays, {});
    RayStats stats;
    // From the side, under the slab, to the point below the light.
    const glm::vec3 from(3.0f, 0.5f, 0.0f);
    const glm::vec3 L = tracer.radiance({from, glm::normalize(-from)}, 0, 1.0f, stats);
    for (int c = 0; c < 3; ++c) {
        const double expected = 0.5 * 9.0 / 9.0 * std::exp(-a[c] * h);
        EXPECT_NEAR(L[c], expected, 1e-4 * 0.5) << "channel " << c;
    }
}

// Two touching absorbing balls and one nested in another: the stack follows the path through
// all of them, so the centre ray's transmittance is the product over every segment.
TEST(Absorption, NestedAndTouchingMediaAttenuateEachSegmentByItsMedia) {
    const glm::vec3 aOuter(0.3f, 0.6f, 0.9f), aInner(1.0f, 0.5f, 0.25f), aTouching(0.2f, 0.2f, 0.2f);
    SceneBuilder b;
    // Outer ball radius 1 at the origin, an inner ball radius 0.5 nested in it; a third ball of
    // radius 0.5 just outside the outer one (a gap of 0.01 at z = -1); an emissive wall behind.
    Material outer = absorbingGlass(aOuter), inner = absorbingGlass(aInner), touching = absorbingGlass(aTouching);
    for (Material* m : {&outer, &inner, &touching}) m->ior = 1.0f;  // no refraction, no reflection: straight paths
    for (Material* m : {&outer, &inner, &touching}) m->fresnel = false;
    b.object("outer", makeSphere(256, 128), b.material(outer), placed({0, 0, 0}, glm::vec3(2.0f)));
    b.object("inner", makeSphere(256, 128), b.material(inner), placed({0, 0, 0}, glm::vec3(1.0f)));
    b.object("touching", makeSphere(256, 128), b.material(touching), placed({0, 0, -1.51f}, glm::vec3(1.0f)));
    b.object("wall", makePlane(), b.material(emissive(glm::vec3(1.0f))), placed({0, 0, -4}, {10, 1, 10}, {90, 0, 0}));
    b.scene().sky.color = glm::vec3(0.0f);
    b.scene().ambient = glm::vec3(0.0f);
    RayScene rays(b.scene());
    WhittedTracer tracer(rays, {});
    RayStats stats;
    const glm::vec3 L = tracer.radiance({{0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, -1.0f}}, 0, 1.0f, stats);
    // Outer only over 2 x 0.5; outer + inner over 1 (overlapping media add); touching over 1.
    for (int c = 0; c < 3; ++c) {
        const double tau = aOuter[c] * 1.0 + (aOuter[c] + aInner[c]) * 1.0 + aTouching[c] * 1.0;
        EXPECT_NEAR(L[c], std::exp(-tau), 2e-3 * std::exp(-tau)) << "channel " << c;
    }
    EXPECT_EQ(stats.mediumErrors, 0u);
}

// A ray that starts inside a closed absorbing object (say, a camera inside it) leaves a medium it
// never entered: it still renders, finite, without absorption, and is counted.
TEST(Absorption, LeavingAMediumNeverEnteredIsCountedNotFatal) {
    SceneBuilder b;
    b.object("ball", makeSphere(64, 32), b.material(absorbingGlass({1, 2, 3})), placed({0, 0, 0}, glm::vec3(2.0f)));
    b.scene().sky.color = glm::vec3(0.2f, 0.4f, 0.6f);
    RayScene rays(b.scene());
    WhittedTracer tracer(rays, {});
    RayStats stats;
    const glm::vec3 L = tracer.radiance({{0.0f, 0.0f, 0.0f}, glm::normalize(glm::vec3(0.3f, 0.2f, -1.0f))}, 0, 1.0f, stats);
    EXPECT_TRUE(std::isfinite(L.r) && std::isfinite(L.g) && std::isfinite(L.b));
    EXPECT_GT(L.b, 0.0f);
    EXPECT_GE(stats.mediumErrors, 1u);
}

}  // namespace
}  // namespace hybridlab
