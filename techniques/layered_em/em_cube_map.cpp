#include "techniques/layered_em/em_cube_map.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace hybridlab {

int cubeMapLevels(int size) {
    int levels = 1;
    while ((size >> levels) >= 1) ++levels;
    return levels;
}

std::size_t cubeMapLevelOffset(int size, int level) {
    std::size_t offset = 0;
    for (int k = 0; k < level; ++k) {
        const std::size_t side = static_cast<std::size_t>(cubeMapLevelSize(size, k));
        offset += 6u * side * side;
    }
    return offset;
}

CubeMapTexel cubeMapTexelAt(std::uint32_t texel, int size) {
    CubeMapTexel t;
    while (t.level + 1 < cubeMapLevels(size) && texel >= cubeMapLevelOffset(size, t.level + 1)) ++t.level;
    const int side = cubeMapLevelSize(size, t.level);
    const int rest = static_cast<int>(texel - cubeMapLevelOffset(size, t.level));
    t.face = rest / (side * side);
    t.row = rest % (side * side) / side;
    t.column = rest % side;
    return t;
}

std::uint32_t cubeMapTexelIndex(const CubeMapTexel& t, int size) {
    const int side = cubeMapLevelSize(size, t.level);
    return static_cast<std::uint32_t>(cubeMapLevelOffset(size, t.level)) + static_cast<std::uint32_t>((t.face * side + t.row) * side + t.column);
}

std::vector<std::uint32_t> cubeMapParents(int size) {
    std::vector<std::uint32_t> parents(cubeMapTexelCount(size), kNoParent);
    for (int level = 0; level + 1 < cubeMapLevels(size); ++level) {
        const int fine = cubeMapLevelSize(size, level), coarse = cubeMapLevelSize(size, level + 1);
        for (int f = 0; f < 6; ++f)
            for (int j = 0; j < fine; ++j)
                for (int i = 0; i < fine; ++i)
                    parents[cubeMapTexelIndex({level, f, i, j}, size)] = cubeMapTexelIndex({level + 1, f, i * coarse / fine, j * coarse / fine}, size);
    }
    return parents;
}

float cubeMapLod(float radiansPerPixel, int size) {
    const float halfFootprint = 0.5f * radiansPerPixel * static_cast<float>(size) * 0.5f;  // level-0 texels
    return halfFootprint > 1.0f ? std::log2(halfFootprint) : 0.0f;
}

namespace {

// Bilinear taps of one level (layered_em.frag's levelTaps computes the same), each weight times `scale`.
void levelTaps(const CubeMapCoordinate& c, int size, int level, float scale, CubeMapTap* taps) {
    const int side = cubeMapLevelSize(size, level);
    const float fs = static_cast<float>(side);
    const float u = std::clamp(c.st.x * fs - 0.5f, 0.0f, fs - 1.0f), v = std::clamp(c.st.y * fs - 0.5f, 0.0f, fs - 1.0f);
    const int i0 = std::min(static_cast<int>(u), side - 1), j0 = std::min(static_cast<int>(v), side - 1);
    const int i1 = std::min(i0 + 1, side - 1), j1 = std::min(j0 + 1, side - 1);
    const float fu = u - static_cast<float>(i0), fv = v - static_cast<float>(j0);
    const std::uint32_t base = static_cast<std::uint32_t>(cubeMapLevelOffset(size, level)) + static_cast<std::uint32_t>(c.face * side * side);
    auto texel = [&](int i, int j) { return base + static_cast<std::uint32_t>(j * side + i); };
    taps[0] = {texel(i0, j0), scale * (1.0f - fu) * (1.0f - fv)};
    taps[1] = {texel(i1, j0), scale * fu * (1.0f - fv)};
    taps[2] = {texel(i0, j1), scale * (1.0f - fu) * fv};
    taps[3] = {texel(i1, j1), scale * fu * fv};
}

}  // namespace

CubeMapLookup cubeMapLookup(glm::vec3 direction, int size, float lod) {
    const CubeMapCoordinate c = cubeMapCoordinate(direction);
    const int last = cubeMapLevels(size) - 1;
    lod = std::clamp(lod, 0.0f, static_cast<float>(last));
    const int level = std::min(static_cast<int>(lod), last);
    const float f = lod - static_cast<float>(level);
    CubeMapLookup l;
    levelTaps(c, size, level, 1.0f - f, l.taps.data());
    levelTaps(c, size, std::min(level + 1, last), f, l.taps.data() + 4);
    return l;
}

glm::vec3 cubeMapTexelDirection(std::uint32_t texel, int size) {
    const CubeMapTexel c = cubeMapTexelAt(texel, size);
    const float side = static_cast<float>(cubeMapLevelSize(size, c.level));
    const float s = (static_cast<float>(c.column) + 0.5f) / side * 2.0f - 1.0f;
    const float t = (static_cast<float>(c.row) + 0.5f) / side * 2.0f - 1.0f;
    glm::vec3 d;
    switch (c.face) {
    case 0: d = {1.0f, -t, -s}; break;
    case 1: d = {-1.0f, -t, s}; break;
    case 2: d = {s, 1.0f, t}; break;
    case 3: d = {s, -1.0f, -t}; break;
    case 4: d = {s, -t, 1.0f}; break;
    default: d = {-s, -t, -1.0f}; break;
    }
    return glm::normalize(d);
}

Image cubeMapCross(const LayerCubeMap& map, int level) {
    const int n = cubeMapLevelSize(map.size, level);
    const std::size_t first = cubeMapLevelOffset(map.size, level);
    Image out(4 * n, 3 * n);
    // Face origins in face units: +X, -X, +Y, -Y, +Z, -Z.
    const int cell[6][2] = {{2, 1}, {0, 1}, {1, 0}, {1, 2}, {1, 1}, {3, 1}};
    for (int f = 0; f < 6; ++f) {
        for (int j = 0; j < n; ++j) {
            for (int i = 0; i < n; ++i) out.at(cell[f][0] * n + i, cell[f][1] * n + j) = map.texels[first + static_cast<std::size_t>((f * n + j) * n + i)];
        }
    }
    return out;
}

}  // namespace hybridlab
