#include "techniques/layered_em/em_cube_map.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace hybridlab {

CubeMapCoordinate cubeMapCoordinate(glm::vec3 d) {
    const glm::vec3 a = glm::abs(d);
    float sc, tc, ma;
    int face;
    if (a.x >= a.y && a.x >= a.z) {
        face = d.x >= 0.0f ? 0 : 1;
        ma = a.x;
        sc = d.x >= 0.0f ? -d.z : d.z;
        tc = -d.y;
    } else if (a.y >= a.z) {
        face = d.y >= 0.0f ? 2 : 3;
        ma = a.y;
        sc = d.x;
        tc = d.y >= 0.0f ? d.z : -d.z;
    } else {
        face = d.z >= 0.0f ? 4 : 5;
        ma = a.z;
        sc = d.z >= 0.0f ? d.x : -d.x;
        tc = -d.y;
    }
    CubeMapCoordinate c;
    c.face = face;
    c.st = ma > 0.0f ? glm::vec2(0.5f * (sc / ma + 1.0f), 0.5f * (tc / ma + 1.0f)) : glm::vec2(0.5f);
    return c;
}

CubeMapLookup cubeMapLookup(glm::vec3 direction, int size) {
    const CubeMapCoordinate c = cubeMapCoordinate(direction);
    const float fs = static_cast<float>(size);
    const float u = std::clamp(c.st.x * fs - 0.5f, 0.0f, fs - 1.0f), v = std::clamp(c.st.y * fs - 0.5f, 0.0f, fs - 1.0f);
    const int i0 = std::min(static_cast<int>(u), size - 1), j0 = std::min(static_cast<int>(v), size - 1);
    const int i1 = std::min(i0 + 1, size - 1), j1 = std::min(j0 + 1, size - 1);
    const float fu = u - static_cast<float>(i0), fv = v - static_cast<float>(j0);
    const std::uint32_t base = static_cast<std::uint32_t>(c.face * size * size);
    auto texel = [&](int i, int j) { return base + static_cast<std::uint32_t>(j * size + i); };
    CubeMapLookup l;
    l.taps[0] = {texel(i0, j0), (1.0f - fu) * (1.0f - fv)};
    l.taps[1] = {texel(i1, j0), fu * (1.0f - fv)};
    l.taps[2] = {texel(i0, j1), (1.0f - fu) * fv};
    l.taps[3] = {texel(i1, j1), fu * fv};
    return l;
}

glm::vec3 cubeMapTexelDirection(std::uint32_t texel, int size) {
    const int perFace = size * size;
    const int face = static_cast<int>(texel) / perFace, rest = static_cast<int>(texel) % perFace;
    const float s = (static_cast<float>(rest % size) + 0.5f) / static_cast<float>(size) * 2.0f - 1.0f;
    const float t = (static_cast<float>(rest / size) + 0.5f) / static_cast<float>(size) * 2.0f - 1.0f;
    glm::vec3 d;
    switch (face) {
    case 0: d = {1.0f, -t, -s}; break;
    case 1: d = {-1.0f, -t, s}; break;
    case 2: d = {s, 1.0f, t}; break;
    case 3: d = {s, -1.0f, -t}; break;
    case 4: d = {s, -t, 1.0f}; break;
    default: d = {-s, -t, -1.0f}; break;
    }
    return glm::normalize(d);
}

Image cubeMapCross(const LayerCubeMap& map) {
    const int n = map.size;
    Image out(4 * n, 3 * n);
    // Face origins in face units: +X, -X, +Y, -Y, +Z, -Z.
    const int cell[6][2] = {{2, 1}, {0, 1}, {1, 0}, {1, 2}, {1, 1}, {3, 1}};
    for (int f = 0; f < 6; ++f) {
        for (int j = 0; j < n; ++j) {
            for (int i = 0; i < n; ++i) out.at(cell[f][0] * n + i, cell[f][1] * n + j) = map.texels[static_cast<std::size_t>((f * n + j) * n + i)];
        }
    }
    return out;
}

}  // namespace hybridlab
