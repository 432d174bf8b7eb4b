#include "common/scene/mesh.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace hybridlab {

Aabb Mesh::bounds() const {
    Aabb b;
    for (const auto& p : positions) b.extend(p);
    return b;
}

namespace {
glm::vec3 faceCross(const Mesh& m, const glm::uvec3& t) {
    return glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]);
}
}  // namespace

void makeFlatNormals(Mesh& mesh) {
    Mesh flat;
    flat.name = mesh.name;
    flat.material = mesh.material;
    const bool hasUv = !mesh.uvs.empty();
    flat.positions.reserve(mesh.triangles.size() * 3);
    flat.normals.reserve(mesh.triangles.size() * 3);
    for (const auto& t : mesh.triangles) {
        glm::vec3 n = glm::normalize(faceCross(mesh, t));
        auto base = static_cast<std::uint32_t>(flat.positions.size());
        for (int k = 0; k < 3; ++k) {
            flat.positions.push_back(mesh.positions[t[k]]);
            flat.normals.push_back(n);
            if (hasUv) flat.uvs.push_back(mesh.uvs[t[k]]);
        }
        flat.triangles.emplace_back(base, base + 1, base + 2);
    }
    mesh = std::move(flat);
}

void makeSmoothNormals(Mesh& mesh) {
    // The cross product's length is twice the area: summing unnormalised face normals weights
    // them by area.
    std::vector<glm::vec3> acc(mesh.positions.size(), glm::vec3(0.0f));
    for (const auto& t : mesh.triangles) {
        glm::vec3 n = faceCross(mesh, t);
        for (int k = 0; k < 3; ++k) acc[t[k]] += n;
    }
    mesh.normals.resize(mesh.positions.size());
    for (std::size_t i = 0; i < acc.size(); ++i) {
        float len = glm::length(acc[i]);
        mesh.normals[i] = len > 0.0f ? acc[i] / len : glm::vec3(0.0f, 1.0f, 0.0f);
    }
}

void computeTangents(Mesh& mesh) {
    if (mesh.uvs.empty()) return;
    std::vector<glm::vec3> tan(mesh.positions.size(), glm::vec3(0.0f));
    std::vector<glm::vec3> bit(mesh.positions.size(), glm::vec3(0.0f));
    for (const auto& t : mesh.triangles) {
        glm::vec3 e1 = mesh.positions[t.y] - mesh.positions[t.x];
        glm::vec3 e2 = mesh.positions[t.z] - mesh.positions[t.x];
        glm::vec2 d1 = mesh.uvs[t.y] - mesh.uvs[t.x];
        glm::vec2 d2 = mesh.uvs[t.z] - mesh.uvs[t.x];
        float det = d1.x * d2.y - d2.x * d1.y;
        if (std::abs(det) < 1e-20f) continue;
        float r = 1.0f / det;
        glm::vec3 sdir = (e1 * d2.y - e2 * d1.y) * r;
        glm::vec3 tdir = (e2 * d1.x - e1 * d2.x) * r;
        for (int k = 0; k < 3; ++k) { tan[t[k]] += sdir; bit[t[k]] += tdir; }
    }
    mesh.tangents.resize(mesh.positions.size());
    for (std::size_t i = 0; i < tan.size(); ++i) {
        const glm::vec3& n = mesh.normals[i];
        glm::vec3 t = tan[i] - n * glm::dot(n, tan[i]);  // Gram-Schmidt
        float len = glm::length(t);
        if (len < 1e-12f) {
            // No uv gradient: any vector orthogonal to n.
            t = std::abs(n.x) < 0.9f ? glm::cross(n, glm::vec3(1, 0, 0)) : glm::cross(n, glm::vec3(0, 1, 0));
            len = glm::length(t);
        }
        t /= len;
        float w = glm::dot(glm::cross(n, t), bit[i]) < 0.0f ? -1.0f : 1.0f;
        mesh.tangents[i] = glm::vec4(t, w);
    }
}

std::size_t dropDegenerateTriangles(Mesh& mesh) {
    std::size_t before = mesh.triangles.size();
    std::erase_if(mesh.triangles, [&](const glm::uvec3& t) {
        if (t.x == t.y || t.y == t.z || t.x == t.z) return true;
        return glm::length(faceCross(mesh, t)) == 0.0f;
    });
    return before - mesh.triangles.size();
}

void transformMesh(Mesh& mesh, const glm::mat4& m) {
    glm::mat3 nm = normalMatrix(m);
    glm::mat3 lin(m);
    // A mirroring transform flips the winding and the handedness of (normal, tangent, bitangent):
    // the triangles are turned back to counter-clockwise about their normal, and the bitangent
    // sign flipped, so that cross(n, t) * w is still the mapped bitangent.
    const bool mirrors = glm::determinant(lin) < 0.0f;
    for (auto& p : mesh.positions) p = glm::vec3(m * glm::vec4(p, 1.0f));
    for (auto& n : mesh.normals) n = glm::normalize(nm * n);
    for (auto& t : mesh.tangents) t = glm::vec4(glm::normalize(lin * glm::vec3(t)), mirrors ? -t.w : t.w);
    if (mirrors) {
        for (auto& t : mesh.triangles) std::swap(t.y, t.z);
    }
}

}  // namespace hybridlab
