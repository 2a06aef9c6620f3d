// G-buffer layouts as data: a layout names its render targets (each with a colour Format) and
// the channels packed into each target, in declaration order. analyzeLayout() validates a layout
// and places every channel; generateGlsl() emits the pack/unpack GLSL for it; packTexel() and
// unpackTexel() are the same code in C++, so tests can check GPU output texel for texel.
// Vulkan-free. Seed 000 §3.2, tbl:2 (Frostbite's G-buffer of the Disney base material).
//
// Packing rules (each violation is an Error naming the layout, target and channel):
// - Channels fill the texel components of their target in order (R, G, B, A); within one texel
//   component several small channel components share the bits as fields, from bit 0 (LSB) up.
//   A channel component never straddles two texel components, and nothing is padded implicitly:
//   declare an unused channel (e.g. `reserved`) to skip bits.
// - Unorm formats (r8, rg8, rgba8, rgb10a2): unorm, snorm, oct, srgb and uint fields, stored as
//   fixed-point bit fields of the texel component's integer value; the pack code assembles each
//   component as an integer w and writes w / (2^W - 1) (W = the component's width).
// - rgba8_srgb: R, G and B are sRGB-encoded by the hardware, so they take exactly one srgb
//   channel of 3 x 8 bits (the shader writes linear colour); A is a plain unorm8 component.
// - Integer formats (r8ui, r32ui, rgba32ui): the same fixed-point fields as unorm formats, written
//   as integers (uvec4 outputs).
// - Float formats (r16f ... rgba32f, r11g11b10f): float channels only, one whole texel component
//   per channel component; a float channel's bits per component are the precision it needs and
//   must not exceed the component's width (stored at the format's own precision).
// - Depth/stencil formats cannot hold channels; at most 8 targets (colour attachments).
//
// Fixed-point quantisation is round to nearest, q = floor(clamp(x) * (2^B - 1) + 0.5):
//   unorm x in [0, 1]; snorm x in [-1, 1] stored offset-binary, q = floor(x * h + 0.5) + 2^(B-1)
//   with h = 2^(B-1) - 1, so 0 and +-1 are exact (as Vulkan's snorm); oct = a unit vector mapped to
//   the octahedron, unfolded to [-1, 1]^2 and stored as two unorm components; srgb = linear colour
//   sRGB-encoded (exact transfer function) then unorm; uint = min(value, 2^B - 1).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/format.h"
#include "core/result.h"

namespace rg {

enum class Encoding : uint8_t {
    Unorm,  // float in [0, 1]
    Snorm,  // float in [-1, 1]
    Srgb,   // linear colour in [0, 1]^3, stored sRGB-encoded (3 components)
    Oct,    // unit normal as 2 octahedral components; unpacks to a normalised vec3
    Uint,   // unsigned integer bit field
    Float,  // float, in a float-format target
};

// Script names: "unorm", "snorm", "srgb", "oct", "uint", "float".
std::string_view encodingName(Encoding e);
std::optional<Encoding> parseEncoding(std::string_view name);
std::string encodingNameList();  // "'unorm', 'snorm', ..." for error messages

struct ChannelDesc {
    std::string name;  // a GLSL identifier: the member of GBuffer_<layout>
    Encoding encoding = Encoding::Unorm;
    uint32_t bits = 0;        // total over its components
    std::string origin;       // "file:line" of the declaration, or ""
    uint32_t components = 0;  // 0 = the encoding's default: oct 2, srgb 3, others 1
};

struct TargetDesc {
    std::string name;  // e.g. "GB0"; the resource name in the graph
    Format format = Format::Undefined;
    std::vector<ChannelDesc> channels;
    std::string origin;
};

struct LayoutDesc {
    std::string name;  // a GLSL identifier: GBuffer_<name>, packGBuffer_<name>, ...
    std::vector<TargetDesc> targets;
    std::string origin;
};

// Where one channel lives. Its component k occupies bits
// [slots[k].bitOffset, slots[k].bitOffset + bitsPerComponent) of texel component slots[k].component
// of target `target` (for float channels: the whole texel component).
struct ChannelPlacement {
    struct Slot {
        uint32_t component = 0;  // 0 = R, 1 = G, 2 = B, 3 = A
        uint32_t bitOffset = 0;  // from bit 0 (LSB) of the texel component's integer value
    };
    uint32_t target = 0;            // index into LayoutDesc::targets
    uint32_t channel = 0;           // index into that target's channels
    uint32_t component = 0;         // texel component of the channel's first component
    uint32_t bitOffset = 0;         // bit offset of the channel's first component
    uint32_t components = 0;        // resolved component count (oct 2, srgb 3, ...)
    uint32_t bitsPerComponent = 0;  // bits / components
    std::array<Slot, 4> slots{};    // one per component, [0, components)
};

// The texel components of a colour format as the pack code sees them.
struct TexelComponents {
    enum class Kind : uint8_t { Unorm, Srgb, Uint, Float };
    Kind kind = Kind::Unorm;         // Srgb: R, G, B are sRGB-encoded by the hardware, A is unorm
    uint32_t count = 0;              // texel components (1..4)
    std::array<uint32_t, 4> bits{};  // width of each
    uint32_t totalBits() const { return bits[0] + bits[1] + bits[2] + bits[3]; }
};
// nullopt for depth/stencil and Undefined formats.
std::optional<TexelComponents> texelComponents(Format f);

struct LayoutInfo {
    LayoutDesc desc;
    std::vector<ChannelPlacement> channels;  // every channel, in declaration order over targets

    const ChannelDesc& channelDesc(size_t i) const {
        return desc.targets[channels[i].target].channels[channels[i].channel];
    }
    // Index into `channels`, or -1.
    int find(std::string_view channelName) const;
};

// Components of a channel's unpacked value (its GBuffer_<layout> member, ChannelValue): 3 for
// oct (the normal) and srgb (the colour), else its declared count (1 by default).
uint32_t valueComponents(const ChannelDesc& c);

// Validates and places every channel. Errors (InvalidInput, Unsupported for depth formats) name
// the layout, the target and the channel and say what was expected; the message starts with
// "origin: " of the most specific declaration that has one (channel, then target, then layout).
Result<LayoutInfo> analyzeLayout(const LayoutDesc& desc);

// The GLSL (#version-less, for #include) for one layout: `struct GBuffer_<name>` with one member
// per channel (float/vecN for unorm, snorm and float; vec3 for oct = the unit normal, vec3 for
// srgb = linear colour; uint/uvecN for uint), `void packGBuffer_<name>(GBuffer_<name> g, out vec4
// t0, ...)` (out uvec4 for integer formats) writing exactly what colour attachments of the
// targets' formats should receive, and `GBuffer_<name> unpackGBuffer_<name>(vec4 t0, ...)` taking
// the values sampled from the targets (sRGB textures sample as linear; uvec4 for integer ones).
// Wrapped in `#ifndef RG_GBUFFER_<name>_GLSL`; shared helpers (rg_gb*) have their own guard, so
// the code of several layouts can be included together.
std::string generateGlsl(const LayoutInfo& info);

// One channel's value: `v` for every encoding but uint (oct: the normal in v[0..2], any length;
// srgb: linear RGB), `u` for uint; components beyond the channel's are ignored.
struct ChannelValue {
    std::array<float, 4> v{};
    std::array<uint32_t, 4> u{};
};

// One target's texel as a shader samples it (and as Executor::readback decodes it): `f` for unorm,
// sRGB (linear, as sampled) and float formats; `u` for integer formats (and f = float(u)).
// Components beyond the format's are 0.
struct TexelValue {
    std::array<float, 4> f{};
    std::array<uint32_t, 4> u{};
};

// The C++ twin of packGBuffer_<name>: what each target holds after the format's own quantisation
// (unorm rounding, sRGB 8-bit encode + decode, half / 11-10-bit float rounding to nearest even;
// exact for 32-bit float and integer formats). `values` has one entry per LayoutInfo::channels.
std::vector<TexelValue> packTexel(const LayoutInfo& info, std::span<const ChannelValue> values);
// The C++ twin of unpackGBuffer_<name>; one texel per target.
std::vector<ChannelValue> unpackTexel(const LayoutInfo& info, std::span<const TexelValue> texels);
// A texel from Executor::readback floats (`count` = the format's components): integer formats
// are exact only up to 2^24, as the readback's float conversion.
TexelValue texelFromFloats(Format f, const float* values, uint32_t count);

}  // namespace rg
