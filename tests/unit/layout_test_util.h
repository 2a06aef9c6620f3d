// What the G-buffer layout tests (tests/unit/test_layout.cpp, test_layout_roundtrip.cpp) share:
// a channel declaration in one call.
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

}  // namespace rg::test
