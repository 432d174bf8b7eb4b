// floatsToHalves: the same bits as glm::packHalf1x16 (which the G-buffer upload used) for every
// sign and exponent, every rounding case of the low mantissa bits, and mixed lanes.
#include <bit>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/packing.hpp>

#include "common/raster/half_float.h"

namespace hybridlab {
namespace {

TEST(HalfFloat, EveryExponentAndRoundingCaseMatchesGlm) {
    // All 2^14 low mantissa bits (the 13 that rounding drops and the half's last bit) under a few
    // high ones, for both signs and all 256 exponents: normal, subnormal, overflowing, zero,
    // infinite and NaN halves.
    std::vector<float> in;
    for (std::uint32_t sign = 0; sign < 2; ++sign)
        for (std::uint32_t exponent = 0; exponent < 256; ++exponent)
            for (std::uint32_t high : {0u, 0x4000u, 0x1fc000u, 0x7fc000u})
                for (std::uint32_t low = 0; low < 0x4000u; ++low)
                    in.push_back(std::bit_cast<float>(sign << 31 | exponent << 23 | high | low));
    // Then the same values with lanes of different exponents side by side (a stride coprime to the
    // count), and a count that leaves a tail.
    const std::size_t n = in.size();
    for (std::size_t i = 0; i < n; ++i) in.push_back(in[(i * 40503u) % n]);
    in.pop_back();
    std::vector<std::uint16_t> out(in.size());
    floatsToHalves(in.data(), out.data(), in.size());
    std::size_t wrong = 0;
    for (std::size_t i = 0; i < in.size(); ++i) {
        const std::uint16_t expected = glm::packHalf1x16(in[i]);
        if (out[i] != expected && ++wrong <= 5)
            ADD_FAILURE() << std::hex << "float bits 0x" << std::bit_cast<std::uint32_t>(in[i]) << ": 0x" << out[i] << ", glm 0x" << expected;
    }
    EXPECT_EQ(wrong, 0u);
    EXPECT_EQ(floatToHalf(1.0f), 0x3c00);
    EXPECT_EQ(floatToHalf(65520.0f), 0x7c00);  // rounds up past the largest half, 65504
}

}  // namespace
}  // namespace hybridlab
