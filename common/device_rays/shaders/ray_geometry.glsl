// common/raytrace/ray_offset.h and ray_cone.h in GLSL, for the device ray tracer (held to the
// Embree tracer's images by DeviceRays.WhittedAgrees*, tests/device_rays/test_device_rays.cpp).
#ifndef RAY_GEOMETRY_GLSL
#define RAY_GEOMETRY_GLSL

// As offsetRayOrigin() (Wächter & Binder, Ray Tracing Gems ch. 6): p offset along the unit
// geometric normal n towards the side the new ray leaves from.
vec3 offsetRayOrigin(vec3 p, vec3 n) {
    const float kOrigin = 1.0 / 32.0, kFloatScale = 1.0 / 65536.0, kIntScale = 256.0;
    vec3 outP;
    for (int i = 0; i < 3; ++i) {
        int ofi = int(kIntScale * n[i]);
        float pi = intBitsToFloat(floatBitsToInt(p[i]) + (p[i] < 0.0 ? -ofi : ofi));
        outP[i] = abs(p[i]) < kOrigin ? p[i] + kFloatScale * n[i] : pi;
    }
    return outP;
}

// As uvFootprintLod() (Akenine-Möller et al., Ray Tracing Gems ch. 20): log2 of the cone's
// footprint in uv units at a hit; -inf without a footprint.
float uvFootprintLod(float uvDensityLod, float coneWidthAtHit, vec3 direction, vec3 geometricNormal) {
    if (coneWidthAtHit <= 0.0) return -1.0 / 0.0;
    float cosine = max(abs(dot(direction, geometricNormal)), 1e-4);
    return uvDensityLod + log2(coneWidthAtHit / cosine);
}

#endif
