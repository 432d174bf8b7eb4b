#pragma once
// The face and face coordinates of a cube-map direction (OpenGL's major-axis table, 3.19 in the
// 4.x specification; faces +X, -X, +Y, -Y, +Z, -Z). One rule for every cube map in the project: the
// sky's (shading.h) and the layered EMs' (techniques/layered_em/em_cube_map.h); the GLSL
// cubeMapCoordinate in common/raster/shaders/cube_map.glsl computes the same (held equal through
// the sky by RasterLighting and the layered EMs by LayeredEmPass, tests/).
#include <glm/common.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace hybridlab {

struct CubeMapCoordinate {
    int face = 0;
    glm::vec2 st{0.5f};  // in [0, 1] across the face
};

inline CubeMapCoordinate cubeMapCoordinate(glm::vec3 d) {
    const glm::vec3 a = glm::abs(d);
    float sc, tc, ma;
    CubeMapCoordinate c;
    if (a.x >= a.y && a.x >= a.z) {
        c.face = d.x >= 0.0f ? 0 : 1;
        ma = a.x;
        sc = d.x >= 0.0f ? -d.z : d.z;
        tc = -d.y;
    } else if (a.y >= a.z) {
        c.face = d.y >= 0.0f ? 2 : 3;
        ma = a.y;
        sc = d.x;
        tc = d.y >= 0.0f ? d.z : -d.z;
    } else {
        c.face = d.z >= 0.0f ? 4 : 5;
        ma = a.z;
        sc = d.z >= 0.0f ? d.x : -d.x;
        tc = -d.y;
    }
    if (ma > 0.0f) c.st = glm::vec2(0.5f * (sc / ma + 1.0f), 0.5f * (tc / ma + 1.0f));
    return c;
}

}  // namespace hybridlab
