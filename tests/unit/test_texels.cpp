// gpu::decodeTexels, what readbacks decode GPU texels with: every one of the 65536 half floats of
// an R16F texel decodes to the float glm's unpackHalf1x16 gives (subnormals, ±0, ±inf; NaN as NaN).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/gtc/packing.hpp>

#include "gpu/resources.h"

TEST(Texels, EveryHalfFloatDecodesExactly) {
    std::vector<uint16_t> halves(65536);
    for (uint32_t h = 0; h < 65536; ++h) halves[h] = static_cast<uint16_t>(h);
    std::vector<float> decoded(halves.size());
    rg::gpu::decodeTexels(rg::Format::R16F, halves.data(), halves.size(), decoded.data());
    int wrong = 0;
    for (uint32_t h = 0; h < 65536; ++h) {
        const float want = glm::unpackHalf1x16(static_cast<uint16_t>(h));
        const bool same =
            std::isnan(want) ? std::isnan(decoded[h])
                             : std::bit_cast<uint32_t>(want) == std::bit_cast<uint32_t>(decoded[h]);
        if (!same && ++wrong <= 5)
            ADD_FAILURE() << "half 0x" << std::hex << h << ": " << decoded[h] << ", expected "
                          << want;
    }
    EXPECT_EQ(wrong, 0);
}
