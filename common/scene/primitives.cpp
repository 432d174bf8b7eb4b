#include "common/scene/primitives.h"

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace hybridlab {
namespace {

constexpr float kTwoPi = 2.0f * std::numbers::pi_v<float>;

// Adds the quad centre + (+-u +-v) / 2 with normal cross(u, v).
void addQuad(Mesh& m, glm::vec3 centre, glm::vec3 u, glm::vec3 v) {
    glm::vec3 n = glm::normalize(glm::cross(u, v));
    auto base = static_cast<std::uint32_t>(m.positions.size());
    const glm::vec2 corners[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (const auto& c : corners) {
        m.positions.push_back(centre + 0.5f * (c.x * u + c.y * v));
        m.normals.push_back(n);
        m.uvs.push_back(0.5f * (c + 1.0f));
    }
    m.triangles.emplace_back(base, base + 1, base + 2);
    m.triangles.emplace_back(base, base + 2, base + 3);
}

}  // namespace

Mesh makePlane() {
    Mesh m;
    m.name = "plane";
    addQuad(m, glm::vec3(0.0f), glm::vec3(1, 0, 0), glm::vec3(0, 0, -1));
    // uvs follow world x and z so that a texture is not mirrored on the floor.
    for (std::size_t i = 0; i < m.positions.size(); ++i) m.uvs[i] = {m.positions[i].x + 0.5f, m.positions[i].z + 0.5f};
    return m;
}

Mesh makeCube() {
    Mesh m;
    m.name = "cube";
    const glm::vec3 X(1, 0, 0), Y(0, 1, 0), Z(0, 0, 1);
    addQuad(m, 0.5f * X, -Z, Y);   // +X
    addQuad(m, -0.5f * X, Z, Y);   // -X
    addQuad(m, 0.5f * Y, X, -Z);   // +Y
    addQuad(m, -0.5f * Y, X, Z);   // -Y
    addQuad(m, 0.5f * Z, X, Y);    // +Z
    addQuad(m, -0.5f * Z, -X, Y);  // -Z
    return m;
}

Mesh makeSphere(int slices, int stacks) {
    Mesh m;
    m.name = "sphere";
    // Vertex (i, j): stack i from the north pole (theta = pi i / stacks), slice j (phi = 2 pi j /
    // slices); the seam and poles are duplicated so that uvs stay continuous.
    for (int i = 0; i <= stacks; ++i) {
        float theta = std::numbers::pi_v<float> * static_cast<float>(i) / stacks;
        for (int j = 0; j <= slices; ++j) {
            float phi = kTwoPi * static_cast<float>(j % slices) / slices;
            glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
            if (i == 0 || i == stacks) n = glm::vec3(0.0f, i == 0 ? 1.0f : -1.0f, 0.0f);
            m.positions.push_back(0.5f * n);
            m.normals.push_back(n);
            m.uvs.emplace_back(static_cast<float>(j) / slices, static_cast<float>(i) / stacks);
        }
    }
    auto v = [&](int i, int j) { return static_cast<std::uint32_t>(i * (slices + 1) + j); };
    // Going down (theta) and round (phi), cross(d phi, d theta) points out.
    for (int i = 0; i < stacks; ++i) {
        for (int j = 0; j < slices; ++j) {
            std::uint32_t a = v(i, j), b = v(i, j + 1), c = v(i + 1, j), d = v(i + 1, j + 1);
            if (i == 0) {
                m.triangles.emplace_back(a, d, c);
            } else if (i == stacks - 1) {
                m.triangles.emplace_back(a, b, c);
            } else {
                m.triangles.emplace_back(a, b, c);
                m.triangles.emplace_back(b, d, c);
            }
        }
    }
    return m;
}

Mesh makeCylinder(int slices) {
    Mesh m;
    m.name = "cylinder";
    // Side: two rings with radial normals.
    for (int i = 0; i <= 1; ++i) {
        for (int j = 0; j <= slices; ++j) {
            float phi = kTwoPi * static_cast<float>(j % slices) / slices;
            glm::vec3 n(std::cos(phi), 0.0f, std::sin(phi));
            m.positions.push_back(glm::vec3(0.5f * n.x, i == 0 ? 0.5f : -0.5f, 0.5f * n.z));
            m.normals.push_back(n);
            m.uvs.emplace_back(static_cast<float>(j) / slices, static_cast<float>(i));
        }
    }
    auto side = [&](int i, int j) { return static_cast<std::uint32_t>(i * (slices + 1) + j); };
    for (int j = 0; j < slices; ++j) {
        m.triangles.emplace_back(side(0, j), side(0, j + 1), side(1, j));
        m.triangles.emplace_back(side(0, j + 1), side(1, j + 1), side(1, j));
    }
    // Caps: a fan around the centre with the cap's flat normal.
    for (int cap = 0; cap < 2; ++cap) {
        float y = cap == 0 ? 0.5f : -0.5f;
        glm::vec3 n(0.0f, cap == 0 ? 1.0f : -1.0f, 0.0f);
        auto centre = static_cast<std::uint32_t>(m.positions.size());
        m.positions.emplace_back(0.0f, y, 0.0f);
        m.normals.push_back(n);
        m.uvs.emplace_back(0.5f, 0.5f);
        for (int j = 0; j < slices; ++j) {
            float phi = kTwoPi * static_cast<float>(j) / slices;
            m.positions.emplace_back(0.5f * std::cos(phi), y, 0.5f * std::sin(phi));
            m.normals.push_back(n);
            m.uvs.emplace_back(0.5f + 0.5f * std::cos(phi), 0.5f + 0.5f * std::sin(phi));
        }
        for (int j = 0; j < slices; ++j) {
            std::uint32_t r0 = centre + 1 + j, r1 = centre + 1 + (j + 1) % slices;
            if (cap == 0) m.triangles.emplace_back(centre, r1, r0);
            else m.triangles.emplace_back(centre, r0, r1);
        }
    }
    return m;
}

}  // namespace hybridlab
