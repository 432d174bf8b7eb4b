// The G-buffer's texel encoding (common/raster/gbuffer.h): what the G-buffer pass (gbuffer.frag)
// and the primary rays on the ray-tracing device (device_gbuffer_cast.rgen) write into the eight
// colour targets, one function for both, so that every later pass reads either unchanged; and the
// decoding of the geometric normal that the device's ray stages read back (device_gbuffer_rays.glsl).
#ifndef GBUFFER_ENCODING_GLSL
#define GBUFFER_ENCODING_GLSL

// Octahedral encoding of a unit vector into [-1, 1]^2 (Cigolle et al., JCGT 2014); decoded by
// octahedralDecode below and in gbuffer.cpp. All eight targets are taken, so the geometric normal
// rides in two spare 16-bit channels (about 1e-3 precision: enough to offset ray origins and pick a side).
vec2 octahedralEncode(vec3 n) {
    n /= abs(n.x) + abs(n.y) + abs(n.z);
    vec2 e = n.xy;
    if (n.z < 0.0) e = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    return e;
}

vec3 octahedralDecode(float u, float v) {
    vec3 n = vec3(u, v, 1.0 - abs(u) - abs(v));
    if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    return normalize(n);
}

const uint kSkyObjectId = 0u;  // the object id where the sky shows (gbuffer.h)

// A covered texel of the eight colour targets, in GBufferTarget order (the sky's texels are all zero).
struct GBufferTexel {
    vec4 position;  // xyz world position, w 1
    vec4 normal;    // xyz shading normal (unit, world), w +1 front face seen, -1 back face
    vec4 emission;  // rgb; w the geometric normal's first octahedral coordinate
    vec4 ambient;   // material ambient * texture; w the second octahedral coordinate
    vec4 diffuse;   // material diffuse * texture
    vec4 specular;  // rgb, a = exponent
    vec4 optical;   // reflectivity, IOR, opacity, fresnel
    uint objectId;  // object index + 1; 0 is the sky
};

// The texel of a surface: its world `position`, unit `shadingNormal` (after normal mapping),
// `frontFace` whether the viewer sees the side its winding normal `geometricNormal` points to, the
// material's colours (`specular.a` the exponent, `optical` as MaterialData), the diffuse texture's
// value `texel` there, and its `object` index.
GBufferTexel encodeGBufferTexel(vec3 position, vec3 shadingNormal, bool frontFace, vec3 geometricNormal, vec3 emission, vec3 ambient,
                                vec3 diffuse, vec4 specular, vec4 optical, vec3 texel, uint object) {
    const vec2 ng = octahedralEncode(geometricNormal);
    GBufferTexel t;
    t.position = vec4(position, 1.0);
    t.normal = vec4(shadingNormal, frontFace ? 1.0 : -1.0);
    t.emission = vec4(emission, ng.x);
    t.ambient = vec4(ambient * texel, ng.y);
    t.diffuse = vec4(diffuse * texel, 0.0);
    t.specular = specular;
    t.optical = optical;
    t.objectId = object + 1u;
    return t;
}

#endif
