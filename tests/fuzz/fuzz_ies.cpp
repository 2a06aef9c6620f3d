// Fuzz target: the IES LM-63 parser (graph/lighting/ies.h) and, for what parses, the evaluation
// every renderer path uses: the baked texture, the flux integral and the symmetric expansion.
#include "fuzz_common.h"
#include "lighting/ies.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    auto profile = rg::parseIes(rg::fuzz::asText(data, size), "fuzz.ies");
    if (!profile) return 0;
    const rg::IesTexture tex = rg::bakeIes(*profile, 16, 8);
    for (float t : tex.texels)
        if (!(t >= 0.0f && t <= 1.0f)) std::abort();  // normalised by the maximum: always in [0, 1]
    (void)rg::integrateLumens(*profile, 8);
    (void)rg::expandSymmetry(*profile);
    return 0;
}
