#include "common/raster/half_float.h"

#include <bit>

#include <glm/gtc/packing.hpp>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace hybridlab {

float halfToFloat(std::uint16_t h) {
    const std::uint32_t sign = (h & 0x8000u) << 16, exponent = (h >> 10) & 0x1Fu, mantissa = h & 0x3FFu;
    std::uint32_t bits;
    if (exponent == 0x1Fu) {
        bits = sign | 0x7F800000u | (mantissa << 13);  // inf, NaN
    } else if (exponent != 0) {
        bits = sign | ((exponent + 112u) << 23) | (mantissa << 13);
    } else if (mantissa == 0) {
        bits = sign;
    } else {  // subnormal: value = mantissa * 2^-24
        const float v = static_cast<float>(mantissa) * 5.9604644775390625e-8f;
        return sign ? -v : v;
    }
    return std::bit_cast<float>(bits);
}

std::uint16_t floatToHalf(float f) { return glm::packHalf1x16(f); }

void floatsToHalves(const float* in, std::uint16_t* out, std::size_t count) {
    std::size_t i = 0;
#if defined(__SSE2__)
    // Lanes by the float's exponent e, rebiased to half's (e - 112): 1..30 normal, where
    // round-half-up is (m + 0x1000) >> 13 and its carry runs into the exponent as glm's
    // significand overflow does (into 0x7c00, infinity, from e = 30); above 30 an infinity; below
    // -10 a zero; -10..0 (subnormal halves) and 143 (a float's infinity or NaN) go to glm's code.
    const __m128i expMask = _mm_set1_epi32(0xff), mantMask = _mm_set1_epi32(0x7fffff), signMask = _mm_set1_epi32(0x8000);
    const __m128i bias = _mm_set1_epi32(112), half = _mm_set1_epi32(0x1000), inf = _mm_set1_epi32(0x7c00);
    const __m128i zero = _mm_setzero_si128(), one = _mm_set1_epi32(1), thirty = _mm_set1_epi32(30), minusEleven = _mm_set1_epi32(-11);
    const __m128i special = _mm_set1_epi32(143), offset = _mm_set1_epi32(0x8000);
    for (; i + 4 <= count; i += 4) {
        const __m128i bits = _mm_loadu_si128(reinterpret_cast<const __m128i*>(in + i));
        const __m128i sign = _mm_and_si128(_mm_srli_epi32(bits, 16), signMask);
        const __m128i e = _mm_sub_epi32(_mm_and_si128(_mm_srli_epi32(bits, 23), expMask), bias);
        const __m128i m = _mm_and_si128(bits, mantMask);
        const __m128i subnormal = _mm_and_si128(_mm_cmpgt_epi32(e, minusEleven), _mm_cmpgt_epi32(one, e));
        const __m128i nonFinite = _mm_cmpeq_epi32(e, special);
        if (_mm_movemask_epi8(_mm_or_si128(subnormal, nonFinite)) != 0) {
            for (int k = 0; k < 4; ++k) out[i + k] = floatToHalf(in[i + k]);
            continue;
        }
        const __m128i normal = _mm_add_epi32(_mm_slli_epi32(e, 10), _mm_srli_epi32(_mm_add_epi32(m, half), 13));
        const __m128i overflow = _mm_cmpgt_epi32(e, thirty), underflow = _mm_cmpgt_epi32(zero, e);
        __m128i h = _mm_or_si128(_mm_and_si128(overflow, inf), _mm_andnot_si128(_mm_or_si128(overflow, underflow), normal));
        h = _mm_or_si128(h, sign);
        // To 16 bits: signed saturation keeps -32768..32767, so shift the range there and back.
        const __m128i packed = _mm_xor_si128(_mm_packs_epi32(_mm_sub_epi32(h, offset), zero), _mm_set1_epi16(static_cast<short>(0x8000)));
        _mm_storel_epi64(reinterpret_cast<__m128i*>(out + i), packed);
    }
#endif
    for (; i < count; ++i) out[i] = floatToHalf(in[i]);
}

}  // namespace hybridlab
