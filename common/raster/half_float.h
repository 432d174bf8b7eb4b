#pragma once
// Floats to IEEE half floats, as the host's G-buffer is uploaded into the 16-bit targets
// (gbuffer_pass.cpp): the same bits as glm::packHalf1x16 (round half away from zero, subnormal
// halves, infinities; NaNs keep their top mantissa bits), four at a time with SSE2 where every lane
// is a normal half, an overflow or a zero, which G-buffer values are. 22 M values a 720p frame: glm's
// scalar conversion took 25 ms of it on 2 cores.
#include <cstddef>
#include <cstdint>

namespace hybridlab {

std::uint16_t floatToHalf(float f);  // glm::packHalf1x16, one value
void floatsToHalves(const float* in, std::uint16_t* out, std::size_t count);

}  // namespace hybridlab
