// Scene data shared by the geometry passes (G-buffer, shadow maps, visible-pixel queries). The
// layouts mirror the C++ structs in common/raster/gpu_scene.cpp (std140).
#ifndef SCENE_DATA_GLSL
#define SCENE_DATA_GLSL

struct ObjectData {
    mat4 model;         // object to world at the frame's time
    mat4 normalMatrix;  // inverse transpose of the upper 3x3 (normalMatrix() in transform.h)
};

struct MaterialData {
    vec4 emission;      // rgb
    vec4 ambient;       // rgb
    vec4 diffuse;       // rgb
    vec4 specular;      // rgb, a = Blinn-Phong exponent
    vec4 optical;       // reflectivity, IOR, opacity, fresnel (1 or 0)
    vec4 tilingOffset;  // xy texture tiling, zw texture offset
    ivec4 textures;     // x diffuse texture, y normal texture (-1: none)
};

// Per draw: the camera's (or light's) view-projection, and what is drawn.
layout(push_constant) uniform DrawConstants {
    mat4 viewProj;
    uint object;
    uint flags;         // kHasTangentSpace: the mesh has uvs and tangents (normal mapping possible)
} draw;

const uint kHasTangentSpace = 1u;

// The draw's object and material: one record per draw in a dynamic uniform buffer, bound at the
// draw's offset. Uniform loads are what lavapipe does fast (storage-buffer loads cost it several
// times more per pixel).
layout(std140, set = 0, binding = 0) uniform DrawData {
    ObjectData object;
    MaterialData material;
} drawData;

#endif
