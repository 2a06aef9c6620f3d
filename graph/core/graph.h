// Declarations of a render graph: plain data with defaults, the shape a Lua table has.
// Nothing here touches Vulkan; compile() (compiler.h) turns a GraphDesc into a Plan.
//
// Ordering model. Passes are declared in order. Each write of a resource makes a new version of
// it; a read sees the latest version written by a pass declared before the reader. So:
//  - a read with no earlier writer (and no import) is "read before write";
//  - a later writer of a resource must either read what is there (attachment load / blend,
//    storage read-write, depth test against it) or name the earlier writer in `after`; a full
//    overwrite with neither is "two unordered writers";
//  - `after` adds explicit edges; an `after` that points forward can make a cycle, reported with
//    the passes on it.
// Schedule = stable topological order of those edges (declaration order breaks ties).
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "format.h"
#include "value.h"

namespace rg {

enum class ResourceKind : uint8_t { Texture, Buffer };
enum class SizeMode : uint8_t { Absolute, OutputRelative };

struct TextureDesc {
    Format format = Format::RGBA8Unorm;
    SizeMode sizeMode = SizeMode::OutputRelative;
    float scaleX = 1.0f;  // OutputRelative: fraction of the output size
    float scaleY = 1.0f;
    uint32_t width = 0;  // Absolute: texels
    uint32_t height = 0;
    uint32_t layers = 1;  // array layers (6 for a cube)
    uint32_t mips = 1;    // 0 = full chain
    bool cube = false;
    // Layers the scene decides (Lua `scene_layers`: the name of a layer extent the scene has,
    // gpu::SceneBinding::layerExtent — the GPU scene's "shadow_views": as many as its shadowed
    // local lights can have views), at most `layers`; an extent of 0: one 1×1 layer. Applied where
    // a scene is known (the executor's build); without one, `layers` as declared.
    std::string sceneLayers;
};

struct BufferDesc {
    uint64_t size = 0;  // bytes
    // Screen-tiled buffers (light lists): `tileBytes` more per tile of tileSize x tileSize pixels
    // of the output, ceil(w / tileSize) x ceil(h / tileSize) tiles; 0 = a fixed size.
    uint32_t tileSize = 0;
    uint64_t tileBytes = 0;
    // Scene-sized buffers: `countBytes` more per item of the scene's extent `sceneCount` (e.g.
    // "shadow_casters"), settled when the graph is built with a scene; without one, none.
    std::string sceneCount;
    uint64_t countBytes = 0;
};

struct ResourceDesc {
    std::string name;
    ResourceKind kind = ResourceKind::Texture;
    TextureDesc texture;
    BufferDesc buffer;
    bool imported = false;  // contents come from outside the graph; never aliased, never owned
    bool exported = false;  // kept alive to the end of the frame (output, capture, readback)
    // Contents carry over to the next frame (history: exposure state, previous HDR). Like an
    // import it may be read before it is written in a frame (that reads the previous frame's
    // contents, zero at first); never aliased; it starts and ends every frame ready for sampling.
    bool persistent = false;
    // A history (Lua rg.resource's `history`): the persistent copy of this resource's last frame.
    // The passes that keep it stay while a kept pass reads it (compile's cull), and the executor
    // empties it when the passes writing `historyOf` change (gpu::Executor::build).
    std::string historyOf;
    // Lua `only_when`: the resource exists only while the scene has every feature of
    // `sceneFeatures` (gpu::SceneBinding::feature; without a scene it has none) and every boolean
    // parameter of `params` is on; otherwise it and every access to it leave the graph before the build, and a
    // pass that loses such an access loses `defines` (Session::buildableGraph). A pass's
    // only_when (no defines) disables the pass.
    struct Condition {
        std::vector<std::string> sceneFeatures;
        std::vector<std::string> params;
        std::vector<std::string> defines;
    };
    std::optional<Condition> onlyWhen;
    std::string origin;  // where it was declared ("deferred.lua:12"), for error messages
};

// How a pass touches a resource. Reads and writes are derived from the usage and `load`.
enum class Usage : uint8_t {
    Sampled,                 // read: texture sampled in a shader
    UniformRead,             // read: uniform buffer
    StorageRead,             // read: storage image / buffer
    StorageWrite,            // write: storage image / buffer (full overwrite)
    StorageReadWrite,        // read + write: storage image / buffer
    ColorAttachment,         // write (+ read when load = true: load op LOAD or blending)
    DepthStencilAttachment,  // write (+ read when load = true: test against existing values)
    DepthStencilRead,        // read: read-only depth/stencil attachment (depth or stencil test)
    CopySrc,                 // read: transfer source
    CopyDst,       // write (+ read when load = true: a partial write such as mip generation)
    IndirectRead,  // read: a buffer of indirect draw or dispatch commands
};

const char* usageName(Usage u);
bool usageReads(Usage u, bool load);
bool usageWrites(Usage u);

// Where a pass runs; decides the pipeline stages of its accesses.
enum class PassType : uint8_t { Raster, Compute, Transfer };
const char* passTypeName(PassType t);

struct Access {
    std::string resource;  // resource name
    Usage usage = Usage::Sampled;
    bool load =
        false;  // attachments and copy destinations: keep previous contents (load op LOAD / blend)
    // Lua `load = "pass"`: load while that pass runs (it drew the first part), clear otherwise;
    // Session::buildableGraph sets `load` from it.
    std::string loadAfter;
    std::string field;  // field path in the script ("passes.lighting.reads[3]"), for errors
    // Sampled: the stencil aspect of a depth/stencil texture (`as = "stencil"`), bound to the
    // shader's `usampler2D <resource>_stencil` (the value in .r).
    bool stencil = false;
};

// A pipeline material as a `scene` pass draws it (the Lua host resolves it from rg.material, its
// layout, lighting path and stencil class: graphWithParams): what the pass needs to generate and
// bind its shaders, typed.
// The textures of its own a pipeline material may declare (rg.material's `textures`): scene draws
// bind them after the five standard maps (shaders/lib/material.glsl materialTexture0..2).
inline constexpr size_t kMaterialTextureSlots = 3;

struct PassMaterial {
    std::string name;
    uint32_t id = 0;  // materialId written to the G-buffer
    std::string layout;
    std::vector<std::string> targets;  // the layout's targets, in order
    std::vector<bool> targetInteger;   // integer-format targets take uvec4
    std::vector<std::string> fills;    // the targets it writes; empty: all
    std::string surface;               // GLSL file with its surface function
    uint32_t stencilValue = 0, stencilMask = 0;
    std::vector<std::string> custom;    // game-team parameter names, in material.custom order
    std::vector<std::string> textures;  // its own textures' names, in slot order
    std::string shading;                // its lighting path's shading function (forward), or ""
    std::string fixup;                  // the fix-up pass that completes its layout, or ""
    bool forward = false;               // drawn by the forward pass only, never into the G-buffer
    std::string origin;                 // where the material was declared
    std::map<std::string, std::string> channels;  // standard parameter -> its layout's channel
    bool operator==(const PassMaterial&) const = default;
};

struct PassDesc {
    std::string name;
    std::string kind;  // pass kind implemented in passes/ ("fullscreen", "compute", "clear", ...)
    PassType type = PassType::Raster;
    std::vector<Access> accesses;
    std::vector<std::string> after;  // explicit ordering: run after these passes
    bool sideEffect = false;         // never culled (e.g. readback, statistics)
    bool enabled = true;             // disabled passes are dropped before culling, with a reason
    Value params;                    // kind-specific settings (shader, defines, clear value, ...)
    std::string origin;              // "deferred.lua:40", for error messages
    std::vector<PassMaterial> materials;  // a `scene` pass's materials (graphWithParams)
    // Lua `only_when`: the pass runs only while the condition holds (Session::buildableGraph).
    std::optional<ResourceDesc::Condition> onlyWhen;
};

struct GraphDesc {
    std::vector<ResourceDesc> resources;
    std::vector<PassDesc> passes;

    const ResourceDesc* findResource(const std::string& name) const;
    const PassDesc* findPass(const std::string& name) const;
};

}  // namespace rg
