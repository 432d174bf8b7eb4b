// The deferred lighting pass in GLSL against the C++ shading functions (DESIGN.md "The shading
// model"; both compile common/shading, the pass reading the G-buffer and the lights' records): on every texel of a read-back G-buffer,
// the C++ local term (shadows off: visibility 1), the C++ sky where nothing was hit, and with
// environment mapping the C++ composition with the sky in the reflected and refracted directions,
// agree with the GPU's output to within 1e-3 in linear light.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "common/raster/rasterizer.h"
#include "common/raytrace/shading.h"
#include "common/scene/primitives.h"
#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "tests/support/raster_test_support.h"
#include "tests/support/scene_fixtures.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

constexpr int kWidth = 320, kHeight = 180;

// The local colour C at G-buffer texel i by the C++ shading functions, every light unshadowed.
glm::vec3 localColor(const Scene& scene, const std::vector<SpotCone>& cones, const GBuffer& g, std::size_t i, glm::vec3 incoming) {
    const Material m = g.materialAt(i);  // the texture is in its colours: T = 1
    const SurfacePoint s{glm::vec3(g.position[i]), g.facingNormal(i), glm::vec2(0.0f), &m};
    glm::vec3 c = unlitTerm(scene, s, glm::vec3(1.0f));
    for (std::size_t l = 0; l < scene.lights.size(); ++l)
        c += blinnPhong(s, glm::vec3(1.0f), -incoming, sampleLight(scene.lights[l], cones[l], s.position));
    return c;
}

// WhittedTracer::shade's composition with the sky standing in for the traced rays.
glm::vec3 environmentMapped(const Scene& scene, const GBuffer& g, std::size_t i, glm::vec3 incoming, glm::vec3 C) {
    const Material m = g.materialAt(i);
    const bool entering = g.frontFace(i);
    const glm::vec3 n = g.facingNormal(i);
    const float orr = 1.0f - m.opacity;
    const float n1 = entering ? scene.ambientIor : m.ior, n2 = entering ? m.ior : scene.ambientIor;
    const float om = m.fresnel ? fresnelDielectric(std::max(-glm::dot(incoming, n), 0.0f), n1, n2) : m.reflectivity;
    if (om <= 0.0f && orr <= 0.0f) return C;
    glm::vec3 refracted;
    const bool tir = orr > 0.0f && !refractDirection(incoming, n, n1 / n2, refracted);
    const float weightM = tir ? om + (1.0f - om) * orr : om, weightR = tir ? 0.0f : (1.0f - om) * orr;
    glm::vec3 M = C, R = C;
    if (weightM > 0.0f) M = skyRadiance(scene, reflectDirection(incoming, n));
    if (tir) R = M;
    else if (weightR > 0.0f) R = skyRadiance(scene, refracted);
    return compose(om, orr, M, R, C);
}

struct Difference {
    double maxLocal = 0.0, maxSky = 0.0;
    std::size_t surfaceTexels = 0, skyTexels = 0;
};

Difference compareLighting(const Scene& scene, bool environmentMapping) {
    Rasterizer raster(scene);
    RasterRequest request;
    request.camera = scene.camera;
    request.width = kWidth;
    request.height = kHeight;
    request.readback = kGBufferAll;
    request.lightingOptions.environmentMapping = environmentMapping;
    const RasterFrame frame = raster.render(request);
    const GBuffer& g = frame.gbuffer;
    std::vector<SpotCone> cones;
    for (const Light& l : scene.lights) cones.push_back(spotCone(l));
    const float aspect = static_cast<float>(kWidth) / kHeight;
    Difference d;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            const std::size_t i = g.index(x, y);
            const glm::vec3 incoming = scene.camera.rayThroughNdc(pixelCenterNdc(x, y, kWidth, kHeight), aspect).direction;
            const glm::vec3 gpu(frame.lighting.at(x, y));
            if (g.objectId[i] == kSkyObjectId) {
                const glm::vec3 e = glm::abs(gpu - skyRadiance(scene, incoming));
                d.maxSky = std::max(d.maxSky, static_cast<double>(std::max({e.r, e.g, e.b})));
                ++d.skyTexels;
                continue;
            }
            glm::vec3 expected = localColor(scene, cones, g, i, incoming);
            if (environmentMapping) expected = environmentMapped(scene, g, i, incoming, expected);
            const glm::vec3 e = glm::abs(gpu - expected);
            d.maxLocal = std::max(d.maxLocal, static_cast<double>(std::max({e.r, e.g, e.b})));
            ++d.surfaceTexels;
        }
    }
    return d;
}

// Every light type, a spot cone edge in view, a cube-map sky, a mirror and Fresnel glass.
Scene everyLightAndACubeSky() {
    using namespace test;
    SceneBuilder b;
    Material shiny = matte({0.6f, 0.5f, 0.4f});
    shiny.specular = glm::vec3(0.5f);
    shiny.specularExponent = 40.0f;
    shiny.ambient = glm::vec3(0.3f);
    b.object("floor", makePlane(), b.material(shiny), placed({0, 0, 0}, {12, 1, 12}));
    Material mirror = matte(glm::vec3(0.05f));
    mirror.reflectivity = 0.8f;
    mirror.specular = glm::vec3(0.9f);
    mirror.specularExponent = 200.0f;
    b.object("mirror", makeSphere(48, 24), b.material(mirror), placed({-1.2f, 1, 0}, glm::vec3(1.6f)));
    Material glass = matte({0.7f, 0.75f, 0.8f});
    glass.opacity = 0.0f;
    glass.fresnel = true;
    glass.ior = 1.5f;
    b.object("glass", makeSphere(48, 24), b.material(glass), placed({1.2f, 1, 0.5f}, glm::vec3(1.4f)));
    Material lamp = emissive({2.0f, 1.5f, 0.5f});
    b.object("lamp", makeCube(), b.material(lamp), placed({0, 0.3f, 2}, glm::vec3(0.4f)));
    Light sun;
    sun.type = Light::Type::Directional;
    sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.2f));
    sun.intensity = 0.8f;
    b.light(sun);
    Light point;
    point.type = Light::Type::Point;
    point.position = {2, 3, 2};
    point.color = {1.0f, 0.8f, 0.6f};
    point.intensity = 12.0f;
    b.light(point);
    Light spot;
    spot.type = Light::Type::Spot;
    spot.position = {-2, 4, 1};
    spot.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.1f));
    spot.innerConeDegrees = 15.0f;
    spot.outerConeDegrees = 30.0f;
    spot.intensity = 30.0f;
    b.light(spot);
    Scene& s = b.scene();
    s.ambient = glm::vec3(0.1f);
    for (int f = 0; f < 6; ++f) {
        Texture t{"face" + std::to_string(f), true, Image(16, 16)};
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x) t.image.at(x, y) = glm::vec4(0.1f + 0.15f * f, x / 15.0f, y / 15.0f, 1.0f);
        s.sky.cubeFaces[f] = static_cast<std::int32_t>(s.textures.size());
        s.textures.push_back(std::move(t));
    }
    s.camera.position = {0, 2.5f, 7};
    s.camera.orientation = Camera::lookAtOrientation(s.camera.position, {0, 0.8f, 0});
    s.camera.fovYDegrees = 60.0f;
    return s;
}

void expectAgreement(const Scene& scene, const std::string& name, bool environmentMapping) {
    const Difference d = compareLighting(scene, environmentMapping);
    std::printf("[ raster   ] %s%s: GLSL vs C++ max |difference| %.3g on %zu surface texels, %.3g on %zu sky texels\n", name.c_str(),
                environmentMapping ? " (environment-mapped)" : "", d.maxLocal, d.surfaceTexels, d.maxSky, d.skyTexels);
    EXPECT_GT(d.surfaceTexels, 0u) << name;
    EXPECT_LT(d.maxLocal, 1e-3) << name;
    EXPECT_LT(d.maxSky, 1e-3) << name;
}

TEST(RasterLighting, GlslLocalTermEqualsTheCppShadingOnEveryTexel) {
    {
        const Scene probe = everyLightAndACubeSky();
        RASTERIZER_OR_SKIP(unused, probe);
    }
    expectAgreement(everyLightAndACubeSky(), "every light type + cube sky", false);
    const std::vector<std::string> scenes = {"whitted-classic", "cornell-mirror-glass", "sponza-spheres"};
    for (const auto& name : scenes) expectAgreement(loadSceneFile(findSceneFile(name)), name, false);
}

TEST(RasterLighting, EnvironmentMappedReflectionAndRefractionFollowTheComposition) {
    {
        const Scene probe = everyLightAndACubeSky();
        RASTERIZER_OR_SKIP(unused, probe);
    }
    expectAgreement(everyLightAndACubeSky(), "every light type + cube sky", true);
    expectAgreement(loadSceneFile(findSceneFile("whitted-classic")), "whitted-classic", true);
}

}  // namespace
}  // namespace hybridlab
