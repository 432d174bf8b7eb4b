// Analytic checks of the shading model's building blocks (common/raytrace/shading).
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "common/raytrace/shading.h"

namespace hybridlab {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

TEST(Shading, MirrorReflectsAtTheMirroredAngle) {
    for (float deg : {0.0f, 10.0f, 45.0f, 80.0f}) {
        float a = glm::radians(deg);
        glm::vec3 d(std::sin(a), -std::cos(a), 0.0f);  // arriving at `deg` from the normal
        glm::vec3 r = reflectDirection(d, glm::vec3(0, 1, 0));
        EXPECT_NEAR(r.x, std::sin(a), 1e-6f);
        EXPECT_NEAR(r.y, std::cos(a), 1e-6f);
        EXPECT_NEAR(glm::length(r), 1.0f, 1e-6f);
    }
}

TEST(Shading, RefractionFollowsSnellsLaw) {
    const float n1 = 1.0f, n2 = 1.5f;
    for (float deg : {0.0f, 15.0f, 30.0f, 60.0f, 89.0f}) {
        float a = glm::radians(deg);
        glm::vec3 d(std::sin(a), -std::cos(a), 0.0f);
        glm::vec3 t;
        ASSERT_TRUE(refractDirection(d, glm::vec3(0, 1, 0), n1 / n2, t));
        float sinT = t.x;  // angle from -N, in the plane of incidence
        EXPECT_NEAR(n1 * std::sin(a), n2 * sinT, 1e-5f) << deg;
        EXPECT_LT(t.y, 0.0f);
        EXPECT_NEAR(glm::length(t), 1.0f, 1e-6f);
    }
}

TEST(Shading, TotalInternalReflectionPastTheCriticalAngle) {
    const float n1 = 1.5f, n2 = 1.0f;  // glass to air
    const float critical = std::asin(n2 / n1);  // 41.81 degrees
    glm::vec3 t;
    for (float a : {critical - 0.01f, 0.5f * critical}) {
        glm::vec3 d(std::sin(a), -std::cos(a), 0.0f);
        EXPECT_TRUE(refractDirection(d, glm::vec3(0, 1, 0), n1 / n2, t)) << a;
        EXPECT_LT(fresnelDielectric(std::cos(a), n1, n2), 1.0f);
    }
    for (float a : {critical + 0.01f, 1.2f, 1.5f}) {
        glm::vec3 d(std::sin(a), -std::cos(a), 0.0f);
        EXPECT_FALSE(refractDirection(d, glm::vec3(0, 1, 0), n1 / n2, t)) << a;
        EXPECT_EQ(fresnelDielectric(std::cos(a), n1, n2), 1.0f);
    }
}

TEST(Shading, FresnelAtNormalIncidence) {
    for (float n : {1.33f, 1.5f, 2.4f}) {
        float expected = ((n - 1.0f) / (n + 1.0f)) * ((n - 1.0f) / (n + 1.0f));
        EXPECT_NEAR(fresnelDielectric(1.0f, 1.0f, n), expected, 1e-7f);
        EXPECT_NEAR(fresnelDielectric(1.0f, n, 1.0f), expected, 1e-7f);  // same from inside
    }
    EXPECT_NEAR(fresnelDielectric(1.0f, 1.0f, 1.5f), 0.04f, 1e-7f);
}

TEST(Shading, FresnelMatchesTheAngleFormOfTheFresnelEquations) {
    // Rs = sin^2(i - t) / sin^2(i + t), Rp = tan^2(i - t) / tan^2(i + t): an independent form.
    const float n1 = 1.0f, n2 = 1.5f;
    for (float deg : {10.0f, 30.0f, 45.0f, 56.31f, 70.0f, 85.0f}) {
        double i = glm::radians(static_cast<double>(deg));
        double t = std::asin(n1 / n2 * std::sin(i));
        double rs = std::pow(std::sin(i - t) / std::sin(i + t), 2.0);
        double rp = std::pow(std::tan(i - t) / std::tan(i + t), 2.0);
        EXPECT_NEAR(fresnelDielectric(static_cast<float>(std::cos(i)), n1, n2), 0.5 * (rs + rp), 2e-6) << deg;
    }
    EXPECT_NEAR(fresnelDielectric(0.0f, 1.0f, 1.5f), 1.0f, 1e-6f);  // grazing
}

TEST(Shading, PointLightFallsOffWithInverseSquareDistance) {
    Light l;
    l.type = Light::Type::Point;
    l.intensity = 8.0f;
    l.color = glm::vec3(1.0f, 0.5f, 0.25f);
    l.position = glm::vec3(0.0f, 2.0f, 0.0f);
    LightSample near = sampleLight(l, glm::vec3(0.0f));
    l.position.y = 4.0f;
    LightSample far = sampleLight(l, glm::vec3(0.0f));
    EXPECT_NEAR(near.radiance.r, 8.0f / 4.0f, 1e-6f);
    EXPECT_NEAR(far.radiance.r, 8.0f / 16.0f, 1e-6f);
    EXPECT_NEAR(near.radiance.g / far.radiance.g, 4.0f, 1e-5f);
    EXPECT_NEAR(near.distance, 2.0f, 1e-6f);
}

TEST(Shading, SpotLightConeIsSmoothstepBetweenOuterAndInner) {
    Light l;
    l.type = Light::Type::Spot;
    l.position = glm::vec3(0.0f, 1.0f, 0.0f);
    l.direction = glm::vec3(0.0f, -1.0f, 0.0f);
    l.innerConeDegrees = 20.0f;
    l.outerConeDegrees = 40.0f;
    auto at = [&](float deg) {
        float a = glm::radians(deg);
        glm::vec3 p = l.position + glm::vec3(std::sin(a), -std::cos(a), 0.0f);  // distance 1
        return sampleLight(l, p).radiance.r;
    };
    EXPECT_NEAR(at(0.0f), 1.0f, 1e-6f);
    EXPECT_NEAR(at(19.0f), 1.0f, 1e-6f);
    EXPECT_NEAR(at(41.0f), 0.0f, 1e-6f);
    float c = std::cos(glm::radians(30.0f)), co = std::cos(glm::radians(40.0f)), ci = std::cos(glm::radians(20.0f));
    float x = (c - co) / (ci - co);
    EXPECT_NEAR(at(30.0f), x * x * (3 - 2 * x), 1e-5f);
}

TEST(Shading, BlinnPhongTerms) {
    Material m;
    m.diffuse = glm::vec3(0.5f);
    m.specular = glm::vec3(0.25f);
    m.specularExponent = 10.0f;
    SurfacePoint s{glm::vec3(0.0f), glm::vec3(0, 1, 0), glm::vec2(0.0f), &m};
    LightSample ls{glm::vec3(2.0f), glm::normalize(glm::vec3(1, 1, 0)), 1.0f};
    glm::vec3 v = glm::normalize(glm::vec3(-1, 1, 0));  // mirror of L: H = N
    glm::vec3 c = blinnPhong(s, glm::vec3(1.0f), v, ls);
    EXPECT_NEAR(c.r, 2.0f * (0.5f * std::cos(kPi / 4) + 0.25f), 1e-5f);
    ls.toLight = glm::vec3(0, -1, 0);  // below the surface: nothing
    EXPECT_EQ(blinnPhong(s, glm::vec3(1.0f), v, ls), glm::vec3(0.0f));
}

TEST(Shading, CompositionRule) {
    glm::vec3 M(1, 0, 0), R(0, 1, 0), C(0, 0, 1);
    glm::vec3 c = compose(0.25f, 0.5f, M, R, C);
    EXPECT_NEAR(c.r, 0.25f, 1e-7f);
    EXPECT_NEAR(c.g, 0.75f * 0.5f, 1e-7f);
    EXPECT_NEAR(c.b, 0.75f * 0.5f, 1e-7f);
    // Walewski eqs. (5)-(6): the mean of both orders.
    glm::vec3 w = compose(0.25f, 0.5f, M, R, C, BlendRule::Walewski2019);
    glm::vec3 cr = 0.5f * R + 0.5f * (0.25f * M + 0.75f * C);
    EXPECT_NEAR(w.r, 0.5f * (c.r + cr.r), 1e-7f);
    EXPECT_NEAR(w.g, 0.5f * (c.g + cr.g), 1e-7f);
    EXPECT_NEAR(w.b, 0.5f * (c.b + cr.b), 1e-7f);
}

// Recovering C from a composed colour inverts compose() under both rules; where C has (almost) no
// weight the fallback stands.
TEST(Shading, UncomposeLocalInvertsTheComposition) {
    const glm::vec3 M(0.9f, 0.2f, 0.1f), R(0.1f, 0.7f, 0.3f), C(0.3f, 0.4f, 0.8f), fallback(7.0f);
    for (BlendRule rule : {BlendRule::Design, BlendRule::Walewski2019}) {
        for (float om : {0.0f, 0.3f, 0.9f}) {
            for (float orr : {0.0f, 0.5f, 0.95f}) {
                const glm::vec3 c = uncomposeLocal(om, orr, M, R, compose(om, orr, M, R, C, rule), fallback, rule);
                for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], C[k], 2e-4f) << "om " << om << " orr " << orr;
            }
        }
        EXPECT_EQ(uncomposeLocal(1.0f, 0.5f, M, R, compose(1.0f, 0.5f, M, R, C, rule), fallback, rule), fallback);
    }
}

TEST(Shading, OccluderTransmittance) {
    Material m;
    m.opacity = 0.25f;
    m.diffuse = glm::vec3(0.8f, 0.6f, 0.4f);
    glm::vec3 t = occluderTransmittance(m);
    EXPECT_NEAR(t.r, 0.75f * 0.8f, 1e-7f);
    EXPECT_NEAR(t.b, 0.75f * 0.4f, 1e-7f);
    m.opacity = 1.0f;
    EXPECT_EQ(occluderTransmittance(m), glm::vec3(0.0f));
    m.castsShadows = false;
    EXPECT_EQ(occluderTransmittance(m), glm::vec3(1.0f));
}

TEST(Shading, CubeMapSkyPicksTheFaceOfTheMajorAxis) {
    Scene scene;
    const glm::vec3 colours[6] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {0, 1, 1}, {1, 0, 1}};
    for (int f = 0; f < 6; ++f) {
        scene.textures.push_back(Texture{"face", true, Image(4, 4, glm::vec4(colours[f], 1.0f))});
        scene.sky.cubeFaces[f] = f;
    }
    const glm::vec3 dirs[6] = {{1, 0.1f, 0.2f}, {-1, 0.2f, 0.1f}, {0.1f, 1, 0.2f}, {0.2f, -1, 0.1f}, {0.1f, 0.2f, 1}, {0.2f, 0.1f, -1}};
    for (int f = 0; f < 6; ++f) EXPECT_EQ(skyRadiance(scene, glm::normalize(dirs[f])), colours[f]) << f;
}

}  // namespace
}  // namespace hybridlab
