#pragma once
// SPIR-V of the GLSL in shaders/ here and in the technique folders, compiled by glslc at build time
// and embedded in the binary (the program needs no shader files at run time). The embedded_shaders.cpp
// that hybridlab_embed_shaders() (cmake/HybridlabShaders.cmake) generates defines these.
#include <cstdint>
#include <span>
#include <string_view>

namespace hybridlab {

// The SPIR-V words of the shader file <name> (e.g. "gbuffer.frag"); throws std::logic_error for an
// unknown name.
std::span<const std::uint32_t> embeddedShader(std::string_view name);

}  // namespace hybridlab
