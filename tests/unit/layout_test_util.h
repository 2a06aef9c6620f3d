// What the G-buffer layout tests (tests/unit/test_layout.cpp, test_layout_roundtrip.cpp) share:
// a channel declaration in one call, and the disney layout as data (materials/disney.lua declares
// it for the pipelines; these tests take it without Lua).
#pragma once

#include <cstdint>
#include <string>

#include "layout/layout.h"

namespace rg::test {

inline ChannelDesc ch(const std::string& name, Encoding e, uint32_t bits, uint32_t components = 0) {
    ChannelDesc c;
    c.name = name;
    c.encoding = e;
    c.bits = bits;
    c.components = components;
    return c;
}

// Seed 000 tbl:2 as DESIGN.md §3 draws it (GB3 = rgba16f, emissive in RGB, A unused):
//   GB0 rgb10a2    normal oct 20 | smoothness unorm 10 | materialId uint 2
//   GB1 rgba8_srgb baseColor srgb 24 | materialData uint 5, normalExtra uint 3 (both in A)
//   GB2 rgba8      reserved unorm 8 | metalMask unorm 8 | reflectance unorm 8 | ao unorm 8
//   GB3 rgba16f    emissive float 48
inline LayoutDesc defaultDisneyLayout() {
    LayoutDesc d;
    d.name = "disney";
    d.targets = {
        {"GB0",
         Format::RGB10A2Unorm,
         {ch("normal", Encoding::Oct, 20), ch("smoothness", Encoding::Unorm, 10),
          ch("materialId", Encoding::Uint, 2)},
         ""},
        {"GB1",
         Format::RGBA8Srgb,
         {ch("baseColor", Encoding::Srgb, 24), ch("materialData", Encoding::Uint, 5),
          ch("normalExtra", Encoding::Uint, 3)},
         ""},
        {"GB2",
         Format::RGBA8Unorm,
         {ch("reserved", Encoding::Unorm, 8), ch("metalMask", Encoding::Unorm, 8),
          ch("reflectance", Encoding::Unorm, 8), ch("ao", Encoding::Unorm, 8)},
         ""},
        {"GB3", Format::RGBA16F, {ch("emissive", Encoding::Float, 48, 3)}, ""},
    };
    return d;
}

}  // namespace rg::test
