// The GLSL rgraph generates for a pipeline material of the `scene` pass kind (scene_pass_glsl.cpp):
// its G-buffer, forward and probe capture fragment shaders, from the material's layout and
// surface function.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace rg::passes::detail {

// One pipeline material as the session resolved it (params.rg_materials entries).
struct MaterialInfo {
    std::string name;
    uint32_t id = 0;
    std::string layout;
    std::vector<std::string> targets;  // the layout's targets, in order
    std::vector<bool> targetInteger;   // integer-format targets take uvec4
    std::vector<std::string> fills;    // empty: all
    std::string surface;
    uint32_t stencilValue = 0, stencilMask = 0;
    std::vector<std::string> custom;  // game-team parameter names, in material.custom order
    std::string shading;              // its lighting path's shading function (forward), or ""
    std::string fixup;                // the fix-up pass that completes its layout, or ""
    std::string origin;               // where the material was declared
    std::map<std::string, std::string> channels;  // standard parameter -> its layout's channel
};

// A G-buffer attachment of this name (scripts/render_loop.lua) receives, from every material, the
// baked lightmap's pre-filtered specular radiance along the surface's reflection (lib/lightmap.glsl
// rgLightmapSpecular; black without a lightmap), which the reflection composition uses where SSR
// and the local probes leave off, instead of the distant probe.
inline constexpr const char* kLightmapSpecularTarget = "lightmap_specular";

// The shaders of one material; each generator says what its shader does.
std::string fragmentSource(const MaterialInfo& m, const std::vector<std::string>& attachments);
std::string forwardSource(const MaterialInfo& m);
std::string captureSource(const MaterialInfo& m);

}  // namespace rg::passes::detail
