// What a pass kind accepts, as plain data: the Lua loader checks pass declarations against it
// (unknown field, wrong type, suggestion), the docs list it, and no Vulkan is needed to read it.
#pragma once

#include <string>
#include <vector>

#include "graph.h"

namespace rg {

struct ParamSpec {
    std::string name;
    // "string", "number", "boolean", "table" (string keys), "list", "number|list" (a number or a
    // list of numbers), "string|list", "written" (the name of a resource the pass writes: the
    // Lua host resolves it like the pass's accesses and refuses any other).
    std::string type;
    std::string doc;
};

struct PassKindSchema {
    std::string name;
    PassType type = PassType::Raster;
    std::string summary;
    std::vector<ParamSpec> params;
    Usage defaultRead = Usage::Sampled;           // usage of a plain name in `reads`
    Usage defaultWrite = Usage::ColorAttachment;  // usage of a plain name in `writes`
    bool writesLoad = false;  // a plain name in `writes` keeps what is there (e.g. mips)
};

}  // namespace rg
