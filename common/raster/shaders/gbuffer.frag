#version 460
// G-buffer pass, fragment stage: Walewski 2019 Table 2's targets (position, normal, emission,
// ambient, diffuse, specular, optical properties) plus the object id. Textured colours are the
// material colour times the texture (sRGB decoded to linear by the sampler), as the ray tracer's
// diffuseTextureValue; normal mapping follows RayScene::resolveHit.
#extension GL_GOOGLE_include_directive : require
#include "scene_data.glsl"

// Pipeline variants (lavapipe runs both sides of a branch, so a texture lookup that a material
// does not need is compiled out rather than skipped).
layout(constant_id = 0) const bool kDiffuseTexture = true;  // the material has a diffuse texture
layout(constant_id = 1) const bool kNormalMap = true;       // it has a normal map and the mesh uvs and tangents

layout(set = 1, binding = 0) uniform sampler2D diffuseTexture;  // the draw's material's (a white placeholder without one)
layout(set = 1, binding = 1) uniform sampler2D normalTexture;

layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 worldNormal;
layout(location = 2) in vec2 uv;
layout(location = 3) in vec4 worldTangent;

layout(location = 0) out vec4 outPosition;  // xyz world position, w 1
layout(location = 1) out vec4 outNormal;    // xyz shading normal (unit, world), w +1 front face seen, -1 back face
layout(location = 2) out vec4 outEmission;
layout(location = 3) out vec4 outAmbient;   // material ambient * texture
layout(location = 4) out vec4 outDiffuse;   // material diffuse * texture
layout(location = 5) out vec4 outSpecular;  // rgb, a = exponent
layout(location = 6) out vec4 outOptical;   // reflectivity, IOR, opacity, fresnel
layout(location = 7) out uint outObjectId;  // object index + 1; 0 is the sky

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

    outPosition = vec4(worldPosition, 1.0);
    outNormal = vec4(n, gl_FrontFacing ? 1.0 : -1.0);
    outEmission = vec4(m.emission.rgb, 0.0);
    outAmbient = vec4(m.ambient.rgb * texel, 0.0);
    outDiffuse = vec4(m.diffuse.rgb * texel, 0.0);
    outSpecular = m.specular;
    outOptical = m.optical;
    outObjectId = draw.object + 1u;
}
