#version 460
// G-buffer pass, fragment stage: Walewski 2019 Table 2's targets (position, normal, emission,
// ambient, diffuse, specular, optical properties) plus the object id. Textured colours are the
// material colour times the texture (sRGB decoded to linear by the sampler), as the ray tracer's
// diffuseTextureValue; normal mapping follows RayScene::resolveHit.
#extension GL_GOOGLE_include_directive : require
#include "scene_data.glsl"
#include "gbuffer_encoding.glsl"

// Pipeline variants (lavapipe runs both sides of a branch, so a texture lookup that a material
// does not need is compiled out rather than skipped).
layout(constant_id = 0) const bool kDiffuseTexture = true;  // the material has a diffuse texture
layout(constant_id = 1) const bool kNormalMap = true;       // it has a normal map and the mesh uvs and tangents

layout(set = 1, binding = 0) uniform sampler2D diffuseTexture;  // the draw's material's (a white 1 x 1 texture without one)
layout(set = 1, binding = 1) uniform sampler2D normalTexture;

layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 worldNormal;
layout(location = 2) in vec2 uv;
layout(location = 3) in vec4 worldTangent;

// The eight targets, encoded as GBufferTexel (gbuffer_encoding.glsl) says.
layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outEmission;
layout(location = 3) out vec4 outAmbient;
layout(location = 4) out vec4 outDiffuse;
layout(location = 5) out vec4 outSpecular;
layout(location = 6) out vec4 outOptical;
layout(location = 7) out uint outObjectId;

// The triangle's normal by its winding (as SurfaceHit::geometricNormal). The screen-space
// derivatives of the world position span the triangle's plane (helper lanes extrapolate the same
// primitive's plane, so this holds on edges too). With x to the right and y down the screen (Vulkan)
// in a right-handed world, cross(d/dx, d/dy) points away from the viewer on every visible surface;
// its negation faces the viewer, and the winding normal is that turned away on a back face.
vec3 windingNormal(vec3 p) {
    vec3 towardViewer = -normalize(cross(dFdx(p), dFdy(p)));
    return gl_FrontFacing ? towardViewer : -towardViewer;
}

void main() {
    MaterialData m = drawData.material;
    vec2 tc = uv * m.tilingOffset.xy + m.tilingOffset.zw;
    // Texture gradients from the interpolated uv, scaled by the tiling: on lavapipe (Mesa 22.3) a
    // quad's helper lanes read 0 from buffers, so implicit derivatives of `tc` (which uses the
    // material) are spoilt where a quad straddles two triangles, and the lookup falls to the
    // coarsest mip level (grey dots along triangle edges).
    vec2 dtcdx = dFdx(uv) * m.tilingOffset.xy, dtcdy = dFdy(uv) * m.tilingOffset.xy;
    vec3 n = normalize(worldNormal);
    if (kNormalMap) {
        vec3 t = normalize(worldTangent.xyz);
        t = normalize(t - n * dot(n, t));
        vec3 b = cross(n, t) * (worldTangent.w < 0.0 ? -1.0 : 1.0);
        vec3 tn = textureGrad(normalTexture, tc, dtcdx, dtcdy).xyz * 2.0 - 1.0;
        n = normalize(t * tn.x + b * tn.y + n * tn.z);
    }
    vec3 texel = kDiffuseTexture ? textureGrad(diffuseTexture, tc, dtcdx, dtcdy).rgb : vec3(1.0);

    const GBufferTexel g = encodeGBufferTexel(worldPosition, n, gl_FrontFacing, windingNormal(worldPosition), m.emission.rgb, m.ambient.rgb,
                                              m.diffuse.rgb, m.specular, m.optical, texel, draw.object);
    outPosition = g.position;
    outNormal = g.normal;
    outEmission = g.emission;
    outAmbient = g.ambient;
    outDiffuse = g.diffuse;
    outSpecular = g.specular;
    outOptical = g.optical;
    outObjectId = g.objectId;
}
