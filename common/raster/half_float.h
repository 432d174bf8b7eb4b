#pragma once
// IEEE half floats, as the G-buffer's 16-bit targets are read back and uploaded (gbuffer_pass.cpp).
// Halves to floats exactly. Floats to halves with the same bits as glm::packHalf1x16 (round half
// away from zero, subnormal halves, infinities; NaNs keep their top mantissa bits), four at a time
// with SSE2 where every lane is a normal half, an overflow or a zero, which G-buffer values are:
// 22 M values a 720p frame, where glm's scalar conversion took 25 ms on 2 cores.
#include <cstddef>
#include <cstdint>

namespace hybridlab {

float halfToFloat(std::uint16_t h);   // exact: every half is a float
std::uint16_t floatToHalf(float f);  // glm::packHalf1x16, one value
void floatsToHalves(const float* in, std::uint16_t* out, std::size_t count);

}  // namespace hybridlab
