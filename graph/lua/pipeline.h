// A pipeline as a script declares it: the render graph plus the material system's data
// (G-buffer layouts, materials, stencil classes, lighting paths) and typed parameters.
// Plain data: no Lua, no Vulkan. The Lua host (lua_host.h) fills it and validates it.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "core/graph.h"
#include "core/value.h"
#include "layout/layout.h"

namespace rg {

enum class ParamType : uint8_t { Number, Integer, Boolean, Vec3, Choice };
const char* paramTypeName(ParamType t);

// A typed parameter: visible to shaders as a `Params` uniform member of the same name and to
// scripts as ctx.params.NAME.
struct ParamDesc {
    std::string name;
    ParamType type = ParamType::Number;
    Value value;  // default, then the current value
    double min = -1e300, max = 1e300;
    std::vector<std::string> choices;  // Choice
    std::string doc;
    std::string origin;
};

// A named class of pixels in the stencil buffer. The framework allocates each class a value in
// the low bits; classes are told apart by (value & mask).
struct StencilClassDesc {
    std::string name;
    uint32_t value = 0;
    uint32_t mask = 0;
    std::string origin;
};

struct LightingPathDesc {
    std::string name;
    std::string stencil;  // the stencil class its lighting pass runs on
    std::string doc;
    std::string origin;
};

struct MaterialDesc {
    std::string name;
    uint32_t id = 0;                 // materialId written to the G-buffer
    std::string layout;              // G-buffer layout
    std::string surface;             // GLSL file with the surface function
    std::string path;                // lighting path
    std::string stencil;             // stencil class
    std::vector<std::string> fills;  // targets it writes; empty = all targets of the layout
    std::string fixup;               // pass that fills the rest, when fills is partial
    Value params;                    // material parameters and their defaults
    std::string origin;
};

struct PipelineDesc {
    std::string file;  // the script it came from
    GraphDesc graph;
    std::string output = "output";  // the image `render` writes (PNG; EXR too unless `hdr` is set)
    // With a physical camera: the HDR target (luminance × pre-exposure) written to the EXR in
    // cd/m², and the persistent exposure state (shaders/lib/exposure.glsl) that says the
    // pre-exposure. Empty when the pipeline has no post chain.
    std::string hdr;
    std::string exposure;
    std::vector<LayoutDesc> layouts;
    std::vector<MaterialDesc> materials;
    std::vector<StencilClassDesc> stencilClasses;
    std::vector<LightingPathDesc> lightingPaths;
    std::vector<ParamDesc> params;
    std::vector<std::string> modules;  // module names in load order
    std::vector<std::string> files;    // every script loaded (for hot reload)

    const ParamDesc* findParam(const std::string& name) const;
    ParamDesc* findParam(const std::string& name);
};

// Checks `v` against the parameter's type and range; an error says what was expected.
Result<Value> checkParamValue(const ParamDesc& p, const Value& v);

}  // namespace rg
