// The face and face coordinates of a cube-map direction: cubeMapCoordinate of
// common/image/cube_map_coordinate.h (OpenGL's major-axis table) in GLSL, for the sky (shading.glsl) and the
// layered EMs (techniques/layered_em/shaders/layered_em.frag).
#ifndef CUBE_MAP_GLSL
#define CUBE_MAP_GLSL

void cubeMapCoordinate(vec3 d, out int face, out vec2 st) {
    vec3 a = abs(d);
    float sc, tc, ma;
    if (a.x >= a.y && a.x >= a.z) {
        face = d.x >= 0.0 ? 0 : 1;
        ma = a.x;
        sc = d.x >= 0.0 ? -d.z : d.z;
        tc = -d.y;
    } else if (a.y >= a.z) {
        face = d.y >= 0.0 ? 2 : 3;
        ma = a.y;
        sc = d.x;
        tc = d.y >= 0.0 ? d.z : -d.z;
    } else {
        face = d.z >= 0.0 ? 4 : 5;
        ma = a.z;
        sc = d.z >= 0.0 ? d.x : -d.x;
        tc = -d.y;
    }
    st = ma > 0.0 ? vec2(0.5 * (sc / ma + 1.0), 0.5 * (tc / ma + 1.0)) : vec2(0.5);
}

#endif
