#pragma once
// An indexed triangle mesh in object space, with one material.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "common/scene/transform.h"

namespace hybridlab {

struct Mesh {
    std::string name;
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;   // one per position, unit length
    std::vector<glm::vec2> uvs;       // empty, or one per position
    std::vector<glm::vec4> tangents;  // empty, or one per position (xyz, w = bitangent sign)
    std::vector<glm::uvec3> triangles;
    std::uint32_t material = 0;       // index into Scene::materials

    std::size_t triangleCount() const { return triangles.size(); }
    std::size_t vertexCount() const { return positions.size(); }
    Aabb bounds() const;
};

// glTF rule for meshes without normals: every triangle gets its own three vertices with the face
// normal. Keeps uvs.
void makeFlatNormals(Mesh& mesh);

// Area-weighted average of the face normals at shared vertices.
void makeSmoothNormals(Mesh& mesh);

// Per-vertex tangents from uv gradients (Lengyel's method), for normal mapping. Needs uvs.
void computeTangents(Mesh& mesh);

// Removes triangles with repeated indices or zero area; returns how many were removed.
std::size_t dropDegenerateTriangles(Mesh& mesh);

// Applies a transform to positions, normals and tangents (bakes glTF node transforms).
void transformMesh(Mesh& mesh, const glm::mat4& m);

}  // namespace hybridlab
