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

layout(set = 1, binding = 0) uniform sampler2D diffuseTexture;  // the draw's material's (a white 1 x 1 texture without one)
layout(set = 1, binding = 1) uniform sampler2D normalTexture;

layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 worldNormal;
layout(location = 2) in vec2 uv;
layout(location = 3) in vec4 worldTangent;

layout(location = 0) out vec4 outPosition;  // xyz world position, w 1
layout(location = 1) out vec4 outNormal;    // xyz shading normal (unit, world), w +1 front face seen, -1 back face
layout(location = 2) out vec4 outEmission;  // rgb; w the geometric normal's first octahedral coordinate
layout(location = 3) out vec4 outAmbient;   // material ambient * texture; w the second octahedral coordinate
layout(location = 4) out vec4 outDiffuse;   // material diffuse * texture
layout(location = 5) out vec4 outSpecular;  // rgb, a = exponent
layout(location = 6) out vec4 outOptical;   // reflectivity, IOR, opacity, fresnel
layout(location = 7) out uint outObjectId;  // object index + 1; 0 is the sky

// Octahedral encoding of a unit vector into [-1, 1]^2 (Cigolle et al., JCGT 2014); decoded by
// octahedralDecode in gbuffer.cpp. All eight attachments are taken, so the geometric normal rides in
// two spare 16-bit channels (about 1e-3 precision: enough to offset ray origins and pick a side).
vec2 octahedralEncode(vec3 n) {
    n /= abs(n.x) + abs(n.y) + abs(n.z);
    vec2 e = n.xy;
    if (n.z < 0.0) e = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    return e;
}

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

    outPosition = vec4(worldPosition, 1.0);
    outNormal = vec4(n, gl_FrontFacing ? 1.0 : -1.0);
    const vec2 ng = octahedralEncode(windingNormal(worldPosition));
    outEmission = vec4(m.emission.rgb, ng.x);
    outAmbient = vec4(m.ambient.rgb * texel, ng.y);
    outDiffuse = vec4(m.diffuse.rgb * texel, 0.0);
    outSpecular = m.specular;
    outOptical = m.optical;
    outObjectId = draw.object + 1u;
}
