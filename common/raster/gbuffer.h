#pragma once
// The G-buffer as the CPU stages see it after read-back (Walewski 2019 §3.1 and Table 2, plus what
// the other techniques need). Row-major, row 0 at the top, like Image. Only the targets a technique
// asked for are filled (`targets`); the others stay empty.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "common/scene/material.h"

namespace hybridlab {

// The render targets, as bits of a GBufferTargets mask.
enum GBufferTarget : std::uint32_t {
    kGBufferPosition = 1u << 0,  // RGBA32F: world position; w 1
    kGBufferNormal = 1u << 1,    // RGBA16F: world shading normal after normal mapping (as SurfaceHit::shadingNormal,
                                 //          not turned to the viewer); w +1 where the viewer sees the front face, -1 the back
    kGBufferEmission = 1u << 2,  // RGBA16F: emission; w the geometric normal's first octahedral coordinate
    kGBufferAmbient = 1u << 3,   // RGBA16F: material ambient times the diffuse texture; w the second one
    kGBufferDiffuse = 1u << 4,   // RGBA16F: material diffuse times the diffuse texture
    kGBufferSpecular = 1u << 5,  // RGBA16F: specular colour; w the Blinn-Phong exponent
    kGBufferOptical = 1u << 6,   // RGBA16F: reflectivity, IOR, opacity, fresnel (1 or 0)
    kGBufferObjectId = 1u << 7,  // R32_UINT: object index + 1; 0 where the sky shows
    kGBufferDepth = 1u << 8,     // 32-bit float reverse-Z depth (near 1, far and sky 0)
};
using GBufferTargets = std::uint32_t;
inline constexpr GBufferTargets kGBufferMaterial =
    kGBufferEmission | kGBufferAmbient | kGBufferDiffuse | kGBufferSpecular | kGBufferOptical;
// The triangle's geometric normal is packed into the spare w channels of these two (all eight colour
// attachments are taken).
inline constexpr GBufferTargets kGBufferGeometricNormal = kGBufferEmission | kGBufferAmbient;
inline constexpr GBufferTargets kGBufferAll = kGBufferPosition | kGBufferNormal | kGBufferMaterial | kGBufferObjectId | kGBufferDepth;

inline constexpr std::uint32_t kSkyObjectId = 0;

struct GBuffer {
    int width = 0;
    int height = 0;
    GBufferTargets targets = 0;

    std::vector<glm::vec4> position;
    std::vector<glm::vec4> normal;
    std::vector<glm::vec4> emission;
    std::vector<glm::vec4> ambient;
    std::vector<glm::vec4> diffuse;
    std::vector<glm::vec4> specular;
    std::vector<glm::vec4> optical;
    std::vector<std::uint32_t> objectId;
    std::vector<float> depth;

    bool has(GBufferTargets t) const { return (targets & t) == t; }
    std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * width + x; }
    std::size_t pixelCount() const { return static_cast<std::size_t>(width) * height; }
    // The object seen at texel i (needs kGBufferObjectId): its index, or -1 for the sky.
    std::int64_t object(std::size_t i) const { return static_cast<std::int64_t>(objectId[i]) - 1; }

    // The normal turned to the side the viewer sees (as WhittedTracer::shade works), at texel i.
    glm::vec3 facingNormal(std::size_t i) const { return normal[i].w < 0.0f ? -glm::vec3(normal[i]) : glm::vec3(normal[i]); }
    bool frontFace(std::size_t i) const { return normal[i].w > 0.0f; }
    // The triangle's unit normal by its winding, as SurfaceHit::geometricNormal (needs
    // kGBufferGeometricNormal); precise to about 1e-3.
    glm::vec3 geometricNormal(std::size_t i) const;

    // The material at texel i, rebuilt from the material targets (needs kGBufferMaterial), with the
    // texture already applied (ambient and diffuse are the textured values, so pass a texture value
    // of 1 to the shading functions). Shadow and absorption properties are not in the G-buffer.
    Material materialAt(std::size_t i) const;
};

// Per-object visible-pixel counts (Walewski 2019 §3.2's A) from the object-id target: counts[o] is
// the number of texels showing object o. Exact; linear in the pixel count.
std::vector<std::uint64_t> visiblePixelsFromIds(const GBuffer& g, std::size_t objectCount);

}  // namespace hybridlab
