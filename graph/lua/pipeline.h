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
    // Lua `scene = SETTING`: the value also sets the scene's setting of that name each frame
    // (passes::GpuScene::setSetting, e.g. the area-light model, a field of its light block), so
    // the C++ core names no parameter of the default pipeline.
    std::string sceneSetting;
    std::string origin;
};

// A named class of pixels in the stencil buffer (8 bits). The framework allocates the values:
// a class of its own takes a value 1..15 in the low four bits (the lighting-path bits); a
// variant of a class (`variant_of`, e.g. foliage: lit as standard, found by its fix-up) keeps its
// base's low bits and takes 1..15 in the high four. A pass on a class tests (stencil & mask) ==
// value: a class's mask is the low bits (so its variants are lit with it), a variant's all eight.
struct StencilClassDesc {
    std::string name;
    uint32_t value = 0;
    uint32_t mask = 0;
    std::string base;  // the class this one is a variant of, or ""
    std::string doc;
    std::string origin;
};
inline constexpr uint32_t kStencilPathBits = 4;     // low bits: up to 15 classes
inline constexpr uint32_t kStencilVariantBits = 4;  // high bits: up to 15 variants per class

struct LightingPathDesc {
    std::string name;
    std::string stencil;  // the stencil class its lighting pass runs on
    std::string
        shading;  // GLSL file defining rgShade(GBuffer_<layout>, ...) (forward shading), or ""
    std::string doc;
    std::string origin;
};

// The standard parameters decals blend and debug views show, by the name a layout's channel for
// them has (MaterialDesc::channels maps them when a layout names them otherwise).
inline const char* const kStandardChannels[] = {
    "normal", "baseColor", "smoothness", "metalMask", "reflectance", "f0", "ao", "emissive"};
inline const char* const kDecalParameters[] = {"normal", "baseColor", "smoothness", "metalMask",
                                               "reflectance"};

struct MaterialDesc {
    std::string name;
    uint32_t id = 0;  // RG_MATERIAL_ID: written to a layout's materialId, if any
    // Its pixels' stencil value (class in the low kStencilPathBits, variant in the high): how
    // every G-buffer reader knows which layout decodes a pixel (Builder::materialIdentities).
    uint32_t identity = 0;
    std::string layout;              // G-buffer layout
    std::string surface;             // GLSL file with the surface function
    std::string path;                // lighting path
    std::string stencil;             // stencil class
    std::vector<std::string> fills;  // targets it writes; empty = all targets of the layout
    std::string fixup;               // pass that fills the rest, when fills is partial
    Value params;                    // material parameters and their defaults
    // Its own textures' names, sorted (the order of their slots: Material::textures), at most
    // kMaterialTextureSlots.
    std::vector<std::string> textures;
    // Standard name (kStandardChannels) -> the layout's channel holding it, resolved: every
    // standard name the layout has under its own name or under the declared `channels` name.
    std::map<std::string, std::string> channels;
    std::vector<std::string> decals;  // the standard parameters decals blend on its pixels
    bool forward = false;  // drawn by the forward pass only (its scene materials must be blended)
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
    // What the load did that a script's author may not have meant (a second rg.output replacing
    // the first): printed by --verbose, kept in the session's log.
    std::vector<std::string> notes;

    const ParamDesc* findParam(const std::string& name) const;
    ParamDesc* findParam(const std::string& name);
};

// The GLSL (for #include "gbuffer_pipeline.glsl") that decodes any pixel of the pipeline's
// G-buffer by its materialId with that material's own layout: `#define RG_MATERIAL_<name> <id>u`
// per material; `struct RgGBufferView` (the standard parameters, RG_VIEW_* bits of the ones the
// layout holds in `has` and of the ones decals blend in `decals`); `RgGBufferView
// rgDecodeGBuffer(t0, ...)` and `void rgEncodeDecals(RgGBufferView v, t0..., out o0...)`, which
// re-packs the pixel's own layout with v's decal parameters written over their channels. The
// targets are the first material's layout's, in its order; every material's layout must use
// only those (an error names the layout and target otherwise).
Result<std::string> generatePipelineGlsl(const PipelineDesc& pipeline);

// The deferred lighting shader of every lighting path that has a shading function and a material
// (file name "lighting_path_<path>.frag", GLSL text), for the generated folder: the pixel's
// G-buffer of the path's layout unpacked, shaded by the path's rgShade at its world position, and
// written pre-exposed — the pass scripts/lighting.lua's lighting.path_pass declares. It binds by
// name: the layout's targets, `depth` (sampled), `exposure` (RgExposureState) and the `Params`
// block's initial_ev100; a pass that calls them otherwise maps them with `bind`.
std::vector<std::pair<std::string, std::string>> generateLightingShaders(
    const PipelineDesc& pipeline);

// The material system in words (`rgraph graph --format materials`): the materialIds with the
// materials that share each and their layout and decal parameters, the stencil classes with
// their values, masks and lighting paths, and what is left free.
std::string describeMaterialSystem(const PipelineDesc& pipeline);

// Checks `v` against the parameter's type and range; an error says what was expected.
Result<Value> checkParamValue(const ParamDesc& p, const Value& v);

}  // namespace rg
