// Validation and placement of G-buffer layouts (see layout.h for the packing rules).
#include "layout.h"

#include <algorithm>
#include <array>
#include <map>

namespace rg {

namespace {

constexpr std::array<std::string_view, 6> kEncodingNames{"unorm", "snorm", "srgb",
                                                         "oct",   "uint",  "float"};
constexpr std::array<char, 4> kComponentNames{'R', 'G', 'B', 'A'};
// At most this many colour attachments (Vulkan's guaranteed maxColorAttachments is 4; lavapipe
// and desktop GPUs have 8, which also bounds the pack function's out parameters).
constexpr size_t kMaxTargets = 8;
// Fixed-point fields are quantised in 32-bit float arithmetic (GLSL and C++ alike), which is
// exact up to 24 bits.
constexpr uint32_t kMaxFixedBits = 24;

// Words GLSL 4.60 reserves (keywords and reserved words): a struct member may not be one.
constexpr std::string_view kGlslReserved[] = {"const",
                                              "uniform",
                                              "buffer",
                                              "shared",
                                              "attribute",
                                              "varying",
                                              "coherent",
                                              "volatile",
                                              "restrict",
                                              "readonly",
                                              "writeonly",
                                              "atomic_uint",
                                              "layout",
                                              "centroid",
                                              "flat",
                                              "smooth",
                                              "noperspective",
                                              "patch",
                                              "sample",
                                              "invariant",
                                              "precise",
                                              "break",
                                              "continue",
                                              "do",
                                              "for",
                                              "while",
                                              "switch",
                                              "case",
                                              "default",
                                              "if",
                                              "else",
                                              "subroutine",
                                              "in",
                                              "out",
                                              "inout",
                                              "int",
                                              "void",
                                              "bool",
                                              "true",
                                              "false",
                                              "float",
                                              "double",
                                              "discard",
                                              "return",
                                              "vec2",
                                              "vec3",
                                              "vec4",
                                              "ivec2",
                                              "ivec3",
                                              "ivec4",
                                              "bvec2",
                                              "bvec3",
                                              "bvec4",
                                              "uint",
                                              "uvec2",
                                              "uvec3",
                                              "uvec4",
                                              "dvec2",
                                              "dvec3",
                                              "dvec4",
                                              "mat2",
                                              "mat3",
                                              "mat4",
                                              "mat2x2",
                                              "mat2x3",
                                              "mat2x4",
                                              "mat3x2",
                                              "mat3x3",
                                              "mat3x4",
                                              "mat4x2",
                                              "mat4x3",
                                              "mat4x4",
                                              "dmat2",
                                              "dmat3",
                                              "dmat4",
                                              "dmat2x2",
                                              "dmat2x3",
                                              "dmat2x4",
                                              "dmat3x2",
                                              "dmat3x3",
                                              "dmat3x4",
                                              "dmat4x2",
                                              "dmat4x3",
                                              "dmat4x4",
                                              "lowp",
                                              "mediump",
                                              "highp",
                                              "precision",
                                              "sampler1D",
                                              "sampler2D",
                                              "sampler3D",
                                              "samplerCube",
                                              "sampler2DShadow",
                                              "sampler2DArray",
                                              "usampler2D",
                                              "isampler2D",
                                              "image1D",
                                              "image2D",
                                              "image3D",
                                              "uimage2D",
                                              "iimage2D",
                                              "imageCube",
                                              "imageBuffer",
                                              "image2DArray",
                                              "samplerBuffer",
                                              "sampler2DMS",
                                              "subpassInput",
                                              "texture2D",
                                              "texture3D",
                                              "textureCube",
                                              "sampler",
                                              "samplerShadow",
                                              "struct",
                                              "common",
                                              "partition",
                                              "active",
                                              "asm",
                                              "class",
                                              "union",
                                              "enum",
                                              "typedef",
                                              "template",
                                              "this",
                                              "resource",
                                              "goto",
                                              "inline",
                                              "noinline",
                                              "public",
                                              "static",
                                              "extern",
                                              "external",
                                              "interface",
                                              "long",
                                              "short",
                                              "half",
                                              "fixed",
                                              "unsigned",
                                              "superp",
                                              "input",
                                              "output",
                                              "hvec2",
                                              "hvec3",
                                              "hvec4",
                                              "fvec2",
                                              "fvec3",
                                              "fvec4",
                                              "filter",
                                              "sizeof",
                                              "cast",
                                              "namespace",
                                              "using",
                                              "sampler3DRect",
                                              "demote",
                                              "int8_t",
                                              "int16_t",
                                              "int32_t",
                                              "int64_t",
                                              "uint8_t",
                                              "uint16_t",
                                              "uint32_t",
                                              "uint64_t",
                                              "float16_t",
                                              "float32_t",
                                              "float64_t",
                                              "i64vec2",
                                              "u64vec2",
                                              "f16vec2",
                                              "f16vec3",
                                              "f16vec4",
                                              "f32vec2",
                                              "f64vec2",
                                              "isampler3D",
                                              "usampler3D",
                                              "samplerCubeShadow",
                                              "sampler1DArray",
                                              "sampler2DRect",
                                              "isampler2DArray",
                                              "usampler2DArray",
                                              "textureBuffer",
                                              "rayQueryEXT"};

bool isGlslReserved(std::string_view s) {
    return std::find(std::begin(kGlslReserved), std::end(kGlslReserved), s) !=
           std::end(kGlslReserved);
}

// A letter, then letters, digits and single '_' not at the end: valid in every generated name
// (GBuffer_<layout>, RG_GBUFFER_<layout>_GLSL) without GLSL's reserved "__".
bool isPlainIdentifier(std::string_view s) {
    if (s.empty()) return false;
    auto letter = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); };
    auto digit = [](char c) { return c >= '0' && c <= '9'; };
    if (!letter(s[0]) || s.back() == '_') return false;
    for (size_t i = 0; i < s.size(); ++i) {
        char c = s[i];
        if (!letter(c) && !digit(c) && c != '_') return false;
        if (c == '_' && i + 1 < s.size() && s[i + 1] == '_') return false;
    }
    return true;
}

const char* kIdentifierRule =
    "expected a GLSL identifier: a letter, then letters, digits and single '_' not at the end";

uint32_t defaultComponents(Encoding e) {
    switch (e) {
        case Encoding::Oct:
            return 2;
        case Encoding::Srgb:
            return 3;
        default:
            return 1;
    }
}

bool isFixedPoint(Encoding e) {
    return e == Encoding::Unorm || e == Encoding::Snorm || e == Encoding::Oct ||
           e == Encoding::Srgb;
}

std::string floatFormatList() {
    std::string s;
    for (size_t i = 0; i < static_cast<size_t>(Format::Count); ++i) {
        auto f = static_cast<Format>(i);
        auto tc = texelComponents(f);
        if (!tc || tc->kind != TexelComponents::Kind::Float) continue;
        if (!s.empty()) s += ", ";
        s += "'" + std::string(formatName(f)) + "'";
    }
    return s;
}

std::string colourFormatList() {
    std::string s;
    for (size_t i = 0; i < static_cast<size_t>(Format::Count); ++i) {
        auto f = static_cast<Format>(i);
        if (!texelComponents(f)) continue;
        if (!s.empty()) s += ", ";
        s += "'" + std::string(formatName(f)) + "'";
    }
    return s;
}

// Builds error messages: "origin: layout 'L' target 'T' (fmt) channel 'c': what".
class Blame {
public:
    explicit Blame(const LayoutDesc& d) : m_layout(d) {}

    std::unexpected<Error> layout(const std::string& what,
                                  ErrorCode code = ErrorCode::InvalidInput) const {
        return fail(code, prefix(m_layout.origin) + "layout '" + m_layout.name + "': " + what);
    }
    std::unexpected<Error> target(const TargetDesc& t, const std::string& what,
                                  bool withFormat = true,
                                  ErrorCode code = ErrorCode::InvalidInput) const {
        return fail(code, prefix(originOf(t)) + targetPart(t, withFormat) + ": " + what);
    }
    // "origin: layout 'L' target 'T'", for messages that put the format elsewhere.
    std::string head(const TargetDesc& t) const {
        return prefix(originOf(t)) + targetPart(t, false);
    }
    std::unexpected<Error> channel(const TargetDesc& t, const ChannelDesc& c,
                                   const std::string& what) const {
        return fail(ErrorCode::InvalidInput, prefix(c.origin.empty() ? originOf(t) : c.origin) +
                                                 targetPart(t, true) + " channel '" + c.name +
                                                 "': " + what);
    }

private:
    std::string originOf(const TargetDesc& t) const {
        return t.origin.empty() ? m_layout.origin : t.origin;
    }
    static std::string prefix(const std::string& origin) {
        return origin.empty() ? "" : origin + ": ";
    }
    std::string targetPart(const TargetDesc& t, bool withFormat) const {
        std::string s = "layout '" + m_layout.name + "' target '" + t.name + "'";
        if (withFormat) s += " (" + std::string(formatName(t.format)) + ")";
        return s;
    }
    const LayoutDesc& m_layout;
};

std::string bitsText(uint32_t n) { return std::to_string(n) + (n == 1 ? " bit" : " bits"); }

}  // namespace

std::string_view encodingName(Encoding e) { return kEncodingNames[static_cast<size_t>(e)]; }

std::optional<Encoding> parseEncoding(std::string_view name) {
    for (size_t i = 0; i < kEncodingNames.size(); ++i)
        if (kEncodingNames[i] == name) return static_cast<Encoding>(i);
    return std::nullopt;
}

std::string encodingNameList() {
    std::string s;
    for (auto n : kEncodingNames) {
        if (!s.empty()) s += ", ";
        s += "'" + std::string(n) + "'";
    }
    return s;
}

std::optional<TexelComponents> texelComponents(Format f) {
    using K = TexelComponents::Kind;
    switch (f) {
        case Format::R8Unorm:
            return TexelComponents{K::Unorm, 1, {8, 0, 0, 0}};
        case Format::RG8Unorm:
            return TexelComponents{K::Unorm, 2, {8, 8, 0, 0}};
        case Format::RGBA8Unorm:
            return TexelComponents{K::Unorm, 4, {8, 8, 8, 8}};
        case Format::RGBA8Srgb:
            return TexelComponents{K::Srgb, 4, {8, 8, 8, 8}};
        case Format::RGB10A2Unorm:
            return TexelComponents{K::Unorm, 4, {10, 10, 10, 2}};
        case Format::R11G11B10F:
            return TexelComponents{K::Float, 3, {11, 11, 10, 0}};
        case Format::R16F:
            return TexelComponents{K::Float, 1, {16, 0, 0, 0}};
        case Format::RG16F:
            return TexelComponents{K::Float, 2, {16, 16, 0, 0}};
        case Format::RGBA16F:
            return TexelComponents{K::Float, 4, {16, 16, 16, 16}};
        case Format::R32F:
            return TexelComponents{K::Float, 1, {32, 0, 0, 0}};
        case Format::RG32F:
            return TexelComponents{K::Float, 2, {32, 32, 0, 0}};
        case Format::RGBA32F:
            return TexelComponents{K::Float, 4, {32, 32, 32, 32}};
        case Format::R8Uint:
            return TexelComponents{K::Uint, 1, {8, 0, 0, 0}};
        case Format::R32Uint:
            return TexelComponents{K::Uint, 1, {32, 0, 0, 0}};
        case Format::RGBA32Uint:
            return TexelComponents{K::Uint, 4, {32, 32, 32, 32}};
        default:
            return std::nullopt;
    }
}

int LayoutInfo::find(std::string_view channelName) const {
    for (size_t i = 0; i < channels.size(); ++i)
        if (channelDesc(i).name == channelName) return static_cast<int>(i);
    return -1;
}

uint32_t valueComponents(const ChannelDesc& c) {
    if (c.encoding == Encoding::Oct || c.encoding == Encoding::Srgb) return 3;
    return c.components ? c.components : 1;
}

Result<LayoutInfo> analyzeLayout(const LayoutDesc& desc) {
    using K = TexelComponents::Kind;
    Blame blame(desc);
    if (!isPlainIdentifier(desc.name))
        return blame.layout(std::string("bad name; ") + kIdentifierRule);
    if (desc.targets.empty())
        return blame.layout("no targets; expected 1 to " + std::to_string(kMaxTargets));
    if (desc.targets.size() > kMaxTargets)
        return blame.layout(std::to_string(desc.targets.size()) + " targets; expected at most " +
                            std::to_string(kMaxTargets) + " (colour attachments)");

    LayoutInfo info;
    info.desc = desc;
    std::map<std::string, std::string> channelOwner;  // channel name -> its target's name
    for (uint32_t ti = 0; ti < desc.targets.size(); ++ti) {
        const TargetDesc& t = desc.targets[ti];
        if (t.name.empty()) return blame.layout("target " + std::to_string(ti) + " has no name");
        for (char c : t.name)
            if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
                return blame.layout("target " + std::to_string(ti) +
                                    " has a control character in its name");
        for (uint32_t tj = 0; tj < ti; ++tj)
            if (desc.targets[tj].name == t.name)
                return blame.target(
                    t, "duplicate target name (also target " + std::to_string(tj) + ")", false);
        if (t.format == Format::Undefined)
            return blame.target(t, "no format; expected one of: " + colourFormatList(), false);
        if (isDepthStencil(t.format))
            return blame.target(
                t,
                "depth/stencil formats cannot hold G-buffer channels; expected one of: " +
                    colourFormatList(),
                true, ErrorCode::Unsupported);
        auto texel = texelComponents(t.format);
        if (!texel)
            return blame.target(t, "unsupported format; expected one of: " + colourFormatList());
        if (t.channels.empty()) return blame.target(t, "no channels; expected at least one");
        const std::string fmt(formatName(t.format));

        // Per channel: name, components, bits, and whether the format can hold the encoding.
        uint32_t needBits = 0, needComponents = 0;
        for (const ChannelDesc& c : t.channels) {
            if (!isPlainIdentifier(c.name))
                return blame.channel(t, c, std::string("bad name; ") + kIdentifierRule);
            if (c.name.starts_with("gl_"))
                return blame.channel(t, c, "names starting with 'gl_' are reserved by GLSL");
            if (isGlslReserved(c.name))
                return blame.channel(t, c,
                                     "'" + c.name + "' is a GLSL keyword; expected another name");
            if (auto it = channelOwner.find(c.name); it != channelOwner.end())
                return blame.channel(
                    t, c, "duplicate channel name (already in target '" + it->second + "')");
            channelOwner.emplace(c.name, t.name);
            const std::string enc(encodingName(c.encoding));
            const uint32_t comps = c.components ? c.components : defaultComponents(c.encoding);
            if ((c.encoding == Encoding::Oct || c.encoding == Encoding::Srgb) &&
                comps != defaultComponents(c.encoding))
                return blame.channel(t, c,
                                     enc + " takes " +
                                         std::to_string(defaultComponents(c.encoding)) +
                                         " components, got " + std::to_string(comps));
            if (comps > 4)
                return blame.channel(t, c, std::to_string(comps) + " components; expected 1 to 4");
            if (c.bits == 0)
                return blame.channel(t, c, "0 bits; expected at least " + bitsText(comps));
            if (c.bits % comps != 0)
                return blame.channel(
                    t, c,
                    bitsText(c.bits) + " do not split into " + std::to_string(comps) +
                        " components; expected a multiple of " + std::to_string(comps));
            const uint32_t bpc = c.bits / comps;
            if (c.encoding == Encoding::Snorm && bpc < 2)
                return blame.channel(
                    t, c, "snorm needs at least 2 bits per component, got " + std::to_string(bpc));
            if (isFixedPoint(c.encoding) && bpc > kMaxFixedBits)
                return blame.channel(t, c,
                                     enc + " takes at most " + std::to_string(kMaxFixedBits) +
                                         " bits per component, got " + std::to_string(bpc));
            if (texel->kind == K::Float && c.encoding != Encoding::Float)
                return blame.channel(t, c, fmt + " takes only float channels, got " + enc);
            if (texel->kind != K::Float && c.encoding == Encoding::Float)
                return blame.channel(
                    t, c,
                    "a float channel needs a float format; expected one of: " + floatFormatList());
            needBits += c.bits;
            needComponents += comps;
        }
        if (texel->kind == K::Float && needComponents > texel->count)
            return fail(ErrorCode::InvalidInput,
                        blame.head(t) + " (" + fmt + ", " + std::to_string(texel->count) +
                            " components): channels need " + std::to_string(needComponents) +
                            " components");
        if (texel->kind != K::Float && needBits > texel->totalBits())
            return fail(ErrorCode::InvalidInput, blame.head(t) + " (" + fmt + ", " +
                                                     bitsText(texel->totalBits()) +
                                                     "): channels need " + bitsText(needBits));

        // Placement: a cursor walks the texel components from bit 0 of R.
        uint32_t comp = 0, offset = 0;
        for (uint32_t ci = 0; ci < t.channels.size(); ++ci) {
            const ChannelDesc& c = t.channels[ci];
            ChannelPlacement p;
            p.target = ti;
            p.channel = ci;
            p.components = c.components ? c.components : defaultComponents(c.encoding);
            p.bitsPerComponent = c.bits / p.components;
            if (texel->kind == K::Srgb && c.encoding == Encoding::Srgb &&
                (comp != 0 || offset != 0 || p.bitsPerComponent != 8))
                return blame.channel(
                    t, c,
                    "an srgb channel in " + fmt +
                        " fills R, G and B with 8 bits each (the hardware encodes them), got 3 x " +
                        bitsText(p.bitsPerComponent) + " from bit " + std::to_string(offset) +
                        " of " + std::string(1, kComponentNames[std::min<uint32_t>(comp, 3)]));
            for (uint32_t k = 0; k < p.components; ++k) {
                if (comp >= texel->count)  // unreachable after the totals above; kept as a guard
                    return blame.channel(t, c, "runs past the last texel component of " + fmt);
                const uint32_t width = texel->bits[comp];
                const std::string where = std::string(1, kComponentNames[comp]);
                if (texel->kind == K::Float) {
                    if (p.bitsPerComponent > width)
                        return blame.channel(t, c,
                                             bitsText(p.bitsPerComponent) +
                                                 " per component do not fit " + where + " (" +
                                                 bitsText(width) + "); expected at most " +
                                                 std::to_string(width));
                } else {
                    if (texel->kind == K::Srgb && comp < 3 && c.encoding != Encoding::Srgb)
                        return blame.channel(t, c,
                                             "R, G and B of " + fmt +
                                                 " take only an srgb channel (the hardware "
                                                 "sRGB-encodes them), got " +
                                                 std::string(encodingName(c.encoding)));
                    if (offset + p.bitsPerComponent > width)
                        return blame.channel(
                            t, c,
                            "component " + std::to_string(k) + " needs bits " +
                                std::to_string(offset) + ".." +
                                std::to_string(offset + p.bitsPerComponent - 1) + " of " + where +
                                ", which has " + bitsText(width) +
                                "; a channel component must lie inside one texel component"
                                " (declare a padding channel to skip bits)");
                }
                p.slots[k] = {comp, offset};
                offset = texel->kind == K::Float ? width : offset + p.bitsPerComponent;
                if (offset == width) {
                    ++comp;
                    offset = 0;
                }
            }
            p.component = p.slots[0].component;
            p.bitOffset = p.slots[0].bitOffset;
            info.channels.push_back(p);
        }
    }
    return info;
}

}  // namespace rg
