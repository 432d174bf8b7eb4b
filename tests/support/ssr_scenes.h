#pragma once
// Scenes for the SSR tests: a planar mirror floor reflecting objects that
// the camera sees, and a mirror wall reflecting an object behind the camera. Matte objects without
// specular highlights, so that the colour SSR reads from the lit image is the colour the reflected
// ray sees; one directional light, ambient light so that nothing is black, a blue sky.
#include "tests/support/scene_fixtures.h"

namespace hybridlab::test {

inline Material matteWithAmbient(glm::vec3 colour) {
    Material m = matte(colour);
    m.ambient = colour;
    return m;
}

inline Material mirrorMaterial(float reflectivity) {
    Material m = matteWithAmbient(glm::vec3(0.3f));
    m.name = "mirror";
    m.reflectivity = reflectivity;
    return m;
}

inline void lightAndSky(SceneBuilder& b) {
    Light sun;
    sun.type = Light::Type::Directional;
    sun.direction = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.3f));
    sun.intensity = 1.5f;
    sun.castsShadows = false;
    b.light(sun);
    b.scene().ambient = glm::vec3(0.2f);
    b.scene().sky.color = glm::vec3(0.3f, 0.5f, 0.9f);
}

// A 40 x 40 mirror floor at y = 0; a red cube, a green sphere and a yellow cylinder in front of the
// camera, all on screen.
inline Scene mirrorFloorScene(float floorReflectivity = 1.0f) {
    SceneBuilder b;
    b.object("floor", makePlane(), b.material(mirrorMaterial(floorReflectivity)), placed({0, 0, 0}, {40, 1, 40}));
    b.object("red-cube", makeCube(), b.material(matteWithAmbient({0.8f, 0.1f, 0.1f})), placed({-1.2f, 0.6f, -1.0f}, {1.2f, 1.2f, 1.2f}, {0, 30, 0}));
    b.object("green-sphere", makeSphere(48, 24), b.material(matteWithAmbient({0.1f, 0.7f, 0.2f})), placed({1.3f, 0.8f, -0.5f}, {1.6f, 1.6f, 1.6f}));
    b.object("yellow-cylinder", makeCylinder(48), b.material(matteWithAmbient({0.8f, 0.7f, 0.1f})), placed({0.2f, 1.0f, -3.5f}, {1.0f, 2.0f, 1.0f}));
    lightAndSky(b);
    Scene& s = b.scene();
    s.camera.position = {0.0f, 1.6f, 4.5f};
    s.camera.orientation = Camera::lookAtOrientation(s.camera.position, {0.0f, 0.4f, -1.0f});
    s.camera.fovYDegrees = 50.0f;
    return s;
}

// A 12 x 6 mirror wall at z = -4 facing the camera, over a grey floor; a magenta slab behind the
// camera that only the mirror shows (SSR cannot: its rays leave the view through the near plane).
inline Scene mirrorWallScene(float wallReflectivity = 1.0f) {
    SceneBuilder b;
    b.object("wall", makePlane(), b.material(mirrorMaterial(wallReflectivity)), placed({0, 3, -4}, {12, 1, 6}, {90, 0, 0}));
    b.object("floor", makePlane(), b.material(matteWithAmbient(glm::vec3(0.5f))), placed({0, 0, 0}, {40, 1, 40}));
    b.object("magenta-slab", makeCube(), b.material(matteWithAmbient({0.8f, 0.1f, 0.7f})), placed({0.0f, 3.0f, 9.0f}, {8.0f, 6.0f, 0.5f}));
    lightAndSky(b);
    Scene& s = b.scene();
    s.camera.position = {0.0f, 1.6f, 4.5f};
    s.camera.orientation = Camera::lookAtOrientation(s.camera.position, {0.0f, 1.6f, -4.0f});
    s.camera.fovYDegrees = 50.0f;
    return s;
}

}  // namespace hybridlab::test
