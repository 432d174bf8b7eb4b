#pragma once
// SPIR-V of the GLSL in shaders/, compiled by glslc at build time and embedded in the binary (the
// program needs no shader files at run time). The generated embedded_shaders.cpp defines these.
#include <cstdint>
#include <span>
#include <string_view>

namespace hybridlab {

// The SPIR-V words of shaders/<name> (e.g. "gbuffer.frag"); throws std::logic_error for an
// unknown name.
std::span<const std::uint32_t> embeddedShader(std::string_view name);

}  // namespace hybridlab
