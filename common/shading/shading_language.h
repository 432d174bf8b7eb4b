// What lets one source compile as C++ and as GLSL (the way *_records.h share their records): the
// headers beside this one hold the physics both ray backends run, written once in the subset of
// GLSL that glm mirrors. The C++ reads them in namespace hybridlab::shading_language, where GLSL's
// types are glm's and GLSL's built-in functions are the C++ library's (std::log2, not glm's
// log(x) * log2(e), so that the reference computes what it always has); glslc reads them as they
// are (cmake/HybridlabShaders.cmake puts this folder on its include path).
//
// The conventions, so that both languages compute the same numbers:
//   * every floating literal carries an f (a bare 1.0 is a double in C++);
//   * a function is declared SHARED_FUNCTION (inline in C++), its output parameters OUT_PARAM(T)
//     and INOUT_PARAM(T) (references in C++, out and inout in GLSL);
//   * no default arguments, overloads on struct types, member functions or pointers;
//   * a backend's own data (scene records, textures, rays) reaches these functions as values:
//     what differs between the backends stays in their code;
//   * where shared code must call into a backend (whitted_tree.h: trace a ray, test a shadow ray,
//     resolve a hit, ...), it is a BACKEND_FUNCTION whose first parameter is BACKEND_PARAM and
//     which calls BACKEND_CALL(name)(...) and names the backend's types BACKEND_TYPE(T): in C++ a
//     template on the backend's class (backend.name(...), Backend::T), in GLSL the functions and
//     types the shader defines before including the header (name(...), T).
// tests/shading/check_one_source.py fails if a shader defines a function defined here.
#ifndef SHADING_LANGUAGE_H
#define SHADING_LANGUAGE_H

#ifdef __cplusplus
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vector_relational.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#define SHARED_FUNCTION inline
#define OUT_PARAM(T) T&
#define INOUT_PARAM(T) T&
#define SHARED_INFINITY (std::numeric_limits<float>::infinity())
#define SHARED_BEGIN namespace hybridlab::shading_language {
#define SHARED_END }
#define BACKEND_FUNCTION template <class Backend> inline
#define BACKEND_PARAM Backend& backend,
#define BACKEND_ARG backend,
#define BACKEND_CALL(name) backend.name
#define BACKEND_TYPE(T) typename Backend::T
// Lights shaded before their shadow rays are traced (whitted_tree.h hitLocalColor): 8 on the CPU,
// where their arithmetic then overlaps; 1 on the device (no batch), where every array lives in the
// ray-tracing stack that NVIDIA's driver bounds (DESIGN.md, RayStackBudget).
#define SHARED_LIGHT_BATCH 8

namespace hybridlab::shading_language {

using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using bvec3 = glm::bvec3;
using uint = std::uint32_t;

using glm::cross;
using glm::distance;
using glm::dot;
using glm::length;
using glm::normalize;

// GLSL's scalar built-ins on floats, as the C++ library computes them.
inline float abs(float x) { return std::abs(x); }
inline float sqrt(float x) { return std::sqrt(x); }
inline float exp(float x) { return std::exp(x); }
inline float log2(float x) { return std::log2(x); }
inline float pow(float x, float y) { return std::pow(x, y); }
inline float min(float x, float y) { return std::min(x, y); }
inline int min(int x, int y) { return std::min(x, y); }
inline float max(float x, float y) { return std::max(x, y); }
inline float clamp(float x, float lo, float hi) { return std::clamp(x, lo, hi); }
inline vec3 max(vec3 x, vec3 y) { return glm::max(x, y); }
inline int floatBitsToInt(float x) { return std::bit_cast<std::int32_t>(x); }
inline float intBitsToFloat(int x) { return std::bit_cast<float>(static_cast<std::int32_t>(x)); }

}  // namespace hybridlab::shading_language

#else

#define SHARED_FUNCTION
#define OUT_PARAM(T) out T
#define INOUT_PARAM(T) inout T
#define SHARED_INFINITY (1.0f / 0.0f)
#define SHARED_BEGIN
#define SHARED_END
#define BACKEND_FUNCTION
#define BACKEND_PARAM
#define BACKEND_ARG
#define BACKEND_CALL(name) name
#define BACKEND_TYPE(T) T
#define SHARED_LIGHT_BATCH 1

#endif

#endif
