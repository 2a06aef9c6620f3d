// The pack/unpack code of a layout, twice: as generated GLSL (generateGlsl) and as C++ (packTexel,
// unpackTexel). Each GLSL helper in kGlslHelpers has a C++ twin below with the same operations in
// the same order, in 32-bit float, so the two round to the same values (up to the GPU's fused
// multiply-adds and its pow/normalize approximations, which move a value by an ulp).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "core/check.h"
#include "layout.h"

namespace rg {

namespace {

using Kind = TexelComponents::Kind;

constexpr const char* kSwizzle[4] = {"x", "y", "z", "w"};

// ---------------------------------------------------------------------------------------------
// GLSL helpers (shared by every layout, guarded once).
constexpr const char* kGlslHelpers = R"(#ifndef RG_GBUFFER_HELPERS_GLSL
#define RG_GBUFFER_HELPERS_GLSL
// Round to nearest, q = floor(clamp(x, 0, 1) * m + 0.5) with m = 2^B - 1.
uint rg_gbUnorm(float x, float m) { return min(uint(floor(clamp(x, 0.0, 1.0) * m + 0.5)), uint(m)); }
float rg_gbUnormValue(uint q, float m) { return float(q) / m; }
// Offset binary with h = 2^(B-1) - 1: -1 -> 1, 0 -> h + 1, +1 -> 2h + 1 (0 and +-1 exact).
uint rg_gbSnorm(float x, float h) { return uint(floor(clamp(x, -1.0, 1.0) * h + 0.5) + (h + 1.0)); }
float rg_gbSnormValue(uint q, float h) { return max((float(q) - (h + 1.0)) / h, -1.0); }
// Octahedral map of a direction (any length; zero maps to +z) to [0, 1]^2: project onto the
// octahedron |x| + |y| + |z| = 1, fold the lower half over the diagonals, then p * 0.5 + 0.5.
vec2 rg_gbOctEncode(vec3 n) {
    float l1 = max(abs(n.x) + abs(n.y) + abs(n.z), 1e-30);
    n = n / l1;
    vec2 p = n.xy;
    if (n.z < 0.0) p = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    return p * 0.5 + 0.5;
}
vec3 rg_gbOctDecode(vec2 e) {
    vec2 p = e * 2.0 - 1.0;
    vec3 n = vec3(p, 1.0 - abs(p.x) - abs(p.y));
    float t = max(-n.z, 0.0);
    n.x += n.x >= 0.0 ? -t : t;
    n.y += n.y >= 0.0 ? -t : t;
    return normalize(n);
}
// The exact sRGB transfer functions (IEC 61966-2-1).
float rg_gbLinearToSrgb(float c) { return c <= 0.0031308 ? c * 12.92 : 1.055 * pow(c, 1.0 / 2.4) - 0.055; }
float rg_gbSrgbToLinear(float c) { return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4); }
#endif
)";

// ---------------------------------------------------------------------------------------------
// C++ twins of the helpers.
float clampf(float x, float lo, float hi) { return std::min(std::max(x, lo), hi); }

uint32_t quantUnorm(float x, float m) {
    return std::min(static_cast<uint32_t>(std::floor(clampf(x, 0.0f, 1.0f) * m + 0.5f)),
                    static_cast<uint32_t>(m));
}
float unormValue(uint32_t q, float m) { return static_cast<float>(q) / m; }
uint32_t quantSnorm(float x, float h) {
    return static_cast<uint32_t>(std::floor(clampf(x, -1.0f, 1.0f) * h + 0.5f) + (h + 1.0f));
}
float snormValue(uint32_t q, float h) {
    return std::max((static_cast<float>(q) - (h + 1.0f)) / h, -1.0f);
}

std::array<float, 2> octEncode(float x, float y, float z) {
    float l1 = std::max(std::fabs(x) + std::fabs(y) + std::fabs(z), 1e-30f);
    x = x / l1;
    y = y / l1;
    z = z / l1;
    float px = x, py = y;
    if (z < 0.0f) {
        px = (1.0f - std::fabs(y)) * (x >= 0.0f ? 1.0f : -1.0f);
        py = (1.0f - std::fabs(x)) * (y >= 0.0f ? 1.0f : -1.0f);
    }
    return {px * 0.5f + 0.5f, py * 0.5f + 0.5f};
}
std::array<float, 3> octDecode(float ex, float ey) {
    float px = ex * 2.0f - 1.0f, py = ey * 2.0f - 1.0f;
    float nx = px, ny = py, nz = 1.0f - std::fabs(px) - std::fabs(py);
    float t = std::max(-nz, 0.0f);
    nx += nx >= 0.0f ? -t : t;
    ny += ny >= 0.0f ? -t : t;
    float len = std::sqrt(nx * nx + ny * ny + nz * nz);
    return {nx / len, ny / len, nz / len};
}
float linearToSrgb(float c) {
    return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}
float srgbToLinear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// Rounds v to the nearest value (ties to even) of a float with a 5-bit exponent (bias 15) and
// `mantBits` mantissa bits: half (10) and the unsigned 11-/10-bit floats (6, 5). v is finite and
// already clamped to the format's range.
float roundSmallFloat(float v, int mantBits) {
    if (v == 0.0f) return v;
    int e = 0;
    std::frexp(v, &e);                     // |v| = m * 2^e, m in [0.5, 1)
    const int exp = std::max(e - 1, -14);  // subnormals share the quantum of 2^-14
    const float quantum = std::ldexp(1.0f, exp - mantBits);
    return std::nearbyint(v / quantum) * quantum;  // FE_TONEAREST: ties to even
}

// Largest finite values: half 65504; unsigned 11-bit 65024, 10-bit 64512.
struct FloatRange {
    float lo, hi;
    int mantBits;  // 0: 32-bit float, stored exactly
};
FloatRange floatRange(Format f, uint32_t component) {
    if (f == Format::R11G11B10F)
        return component < 2 ? FloatRange{0.0f, 65024.0f, 6} : FloatRange{0.0f, 64512.0f, 5};
    if (f == Format::R16F || f == Format::RG16F || f == Format::RGBA16F)
        return {-65504.0f, 65504.0f, 10};
    return {-3.402823466e38f, 3.402823466e38f, 0};
}

uint32_t maskOf(uint32_t bits) { return bits >= 32 ? 0xffffffffu : (1u << bits) - 1u; }
float maxOf(uint32_t bits) { return static_cast<float>(maskOf(bits)); }
float snormH(uint32_t bits) { return static_cast<float>((1u << (bits - 1)) - 1u); }

std::string glslFloat(float v) {
    std::ostringstream s;
    s.precision(9);
    s << v;
    std::string r = s.str();
    if (r.find_first_of(".e") == std::string::npos) r += ".0";
    return r;
}
std::string glslUint(uint32_t v) { return std::to_string(v) + "u"; }

std::string typeOf(const ChannelDesc& c, uint32_t comps) {
    if (c.encoding == Encoding::Oct || c.encoding == Encoding::Srgb) return "vec3";
    if (c.encoding == Encoding::Uint) return comps == 1 ? "uint" : "uvec" + std::to_string(comps);
    return comps == 1 ? "float" : "vec" + std::to_string(comps);
}

// g.<name> or g.<name>.<x|y|z|w> for component k.
std::string member(const ChannelDesc& c, uint32_t comps, uint32_t k) {
    return "g." + c.name + (comps == 1 ? "" : std::string(".") + kSwizzle[k]);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
std::string generateGlsl(const LayoutInfo& info) {
    const LayoutDesc& d = info.desc;
    const std::string sname = "GBuffer_" + d.name;
    std::ostringstream o;
    o << "// Generated by rgraph from G-buffer layout '" << d.name << "'"
      << (d.origin.empty() ? "" : " (" + d.origin + ")") << ". Do not edit: change the layout.\n";
    o << kGlslHelpers;
    o << "#ifndef RG_GBUFFER_" << d.name << "_GLSL\n#define RG_GBUFFER_" << d.name << "_GLSL\n";
    // The map of the layout: which bits of which texel component hold what.
    for (size_t ti = 0; ti < d.targets.size(); ++ti) {
        const TargetDesc& t = d.targets[ti];
        o << "// t" << ti << " = " << t.name << " (" << formatName(t.format) << "):";
        for (size_t i = 0; i < info.channels.size(); ++i) {
            const ChannelPlacement& p = info.channels[i];
            if (p.target != ti) continue;
            const ChannelDesc& c = info.channelDesc(i);
            for (uint32_t k = 0; k < p.components; ++k)
                o << " "
                  << "RGBA"[p.slots[k].component] << "[" << p.slots[k].bitOffset << ".."
                  << p.slots[k].bitOffset + p.bitsPerComponent - 1 << "]=" << c.name
                  << (p.components > 1 ? std::string(".") + kSwizzle[k] : "");
        }
        o << "\n";
    }
    o << "struct " << sname << " {\n";
    for (size_t i = 0; i < info.channels.size(); ++i) {
        const ChannelPlacement& p = info.channels[i];
        const ChannelDesc& c = info.channelDesc(i);
        o << "    " << typeOf(c, p.components) << " " << c.name << ";  // "
          << encodingName(c.encoding) << ", " << p.components << " x " << p.bitsPerComponent
          << " bits in " << d.targets[p.target].name << "\n";
    }
    o << "};\n";

    auto outType = [&](size_t ti) {
        return texelComponents(d.targets[ti].format)->kind == Kind::Uint ? "uvec4" : "vec4";
    };

    // pack
    o << "void packGBuffer_" << d.name << "(" << sname << " g";
    for (size_t ti = 0; ti < d.targets.size(); ++ti) o << ", out " << outType(ti) << " t" << ti;
    o << ") {\n";
    for (size_t ti = 0; ti < d.targets.size(); ++ti) {
        const TargetDesc& t = d.targets[ti];
        const TexelComponents tc = *texelComponents(t.format);
        std::array<std::string, 4> word;    // fixed-point: OR of the fields
        std::array<std::string, 4> direct;  // float formats, and R,G,B of sRGB formats
        for (size_t i = 0; i < info.channels.size(); ++i) {
            const ChannelPlacement& p = info.channels[i];
            if (p.target != ti) continue;
            const ChannelDesc& c = info.channelDesc(i);
            const uint32_t B = p.bitsPerComponent;
            if (c.encoding == Encoding::Oct)
                o << "    vec2 e" << i << " = rg_gbOctEncode(g." << c.name << ");\n";
            for (uint32_t k = 0; k < p.components; ++k) {
                const uint32_t comp = p.slots[k].component;
                const std::string m = member(c, p.components, k);
                if (c.encoding == Encoding::Float) {
                    FloatRange r = floatRange(t.format, comp);
                    direct[comp] = r.mantBits ? "clamp(" + m + ", " + glslFloat(r.lo) + ", " +
                                                    glslFloat(r.hi) + ")"
                                              : m;
                    continue;
                }
                if (c.encoding == Encoding::Srgb && tc.kind == Kind::Srgb) {
                    direct[comp] = "clamp(" + m + ", 0.0, 1.0)";  // linear: the hardware encodes
                    continue;
                }
                std::string q;
                switch (c.encoding) {
                    case Encoding::Unorm:
                        q = "rg_gbUnorm(" + m + ", " + glslFloat(maxOf(B)) + ")";
                        break;
                    case Encoding::Snorm:
                        q = "rg_gbSnorm(" + m + ", " + glslFloat(snormH(B)) + ")";
                        break;
                    case Encoding::Oct:
                        q = "rg_gbUnorm(e" + std::to_string(i) + "." + kSwizzle[k] + ", " +
                            glslFloat(maxOf(B)) + ")";
                        break;
                    case Encoding::Srgb:
                        q = "rg_gbUnorm(rg_gbLinearToSrgb(clamp(" + m + ", 0.0, 1.0)), " +
                            glslFloat(maxOf(B)) + ")";
                        break;
                    case Encoding::Uint:
                        q = B >= 32 ? m : "min(" + m + ", " + glslUint(maskOf(B)) + ")";
                        break;
                    case Encoding::Float:
                        break;
                }
                if (p.slots[k].bitOffset)
                    q = "(" + q + " << " + glslUint(p.slots[k].bitOffset) + ")";
                word[comp] += (word[comp].empty() ? "" : " | ") + q;
            }
        }
        std::array<std::string, 4> out;
        for (uint32_t comp = 0; comp < 4; ++comp) {
            const bool fixed = comp < tc.count && !word[comp].empty();
            if (fixed) o << "    uint w" << ti << "_" << comp << " = " << word[comp] << ";\n";
            if (tc.kind == Kind::Uint)
                out[comp] = fixed ? "w" + std::to_string(ti) + "_" + std::to_string(comp) : "0u";
            else if (fixed)
                out[comp] = "float(w" + std::to_string(ti) + "_" + std::to_string(comp) + ") / " +
                            glslFloat(maxOf(tc.bits[comp]));
            else
                out[comp] = direct[comp].empty() ? "0.0" : direct[comp];
        }
        o << "    t" << ti << " = " << outType(ti) << "(" << out[0] << ", " << out[1] << ", "
          << out[2] << ", " << out[3] << ");  // " << t.name << "\n";
    }
    o << "}\n";

    // unpack
    o << sname << " unpackGBuffer_" << d.name << "(";
    for (size_t ti = 0; ti < d.targets.size(); ++ti)
        o << (ti ? ", " : "") << outType(ti) << " t" << ti;
    o << ") {\n    " << sname << " g;\n";
    for (size_t ti = 0; ti < d.targets.size(); ++ti) {
        const TargetDesc& t = d.targets[ti];
        const TexelComponents tc = *texelComponents(t.format);
        // The integer value of each texel component that holds fixed-point fields.
        std::array<bool, 4> needWord{};
        for (size_t i = 0; i < info.channels.size(); ++i) {
            const ChannelPlacement& p = info.channels[i];
            if (p.target != ti) continue;
            const Encoding e = info.channelDesc(i).encoding;
            if (e == Encoding::Float || (e == Encoding::Srgb && tc.kind == Kind::Srgb)) continue;
            for (uint32_t k = 0; k < p.components; ++k) needWord[p.slots[k].component] = true;
        }
        for (uint32_t comp = 0; comp < tc.count; ++comp) {
            if (!needWord[comp]) continue;
            o << "    uint w" << ti << "_" << comp << " = ";
            if (tc.kind == Kind::Uint)
                o << "t" << ti << "." << kSwizzle[comp] << ";\n";
            else
                o << "uint(t" << ti << "." << kSwizzle[comp] << " * "
                  << glslFloat(maxOf(tc.bits[comp])) << " + 0.5);\n";
        }
        for (size_t i = 0; i < info.channels.size(); ++i) {
            const ChannelPlacement& p = info.channels[i];
            if (p.target != ti) continue;
            const ChannelDesc& c = info.channelDesc(i);
            const uint32_t B = p.bitsPerComponent;
            std::array<std::string, 4> field, value;
            for (uint32_t k = 0; k < p.components; ++k) {
                const auto& s = p.slots[k];
                std::string f = "w" + std::to_string(ti) + "_" + std::to_string(s.component);
                if (s.bitOffset) f = "(" + f + " >> " + glslUint(s.bitOffset) + ")";
                if (s.bitOffset + B < tc.bits[s.component])
                    f = "(" + f + " & " + glslUint(maskOf(B)) + ")";
                field[k] = f;
                const std::string tk = "t" + std::to_string(ti) + "." + kSwizzle[s.component];
                switch (c.encoding) {
                    case Encoding::Unorm:
                        value[k] = "rg_gbUnormValue(" + f + ", " + glslFloat(maxOf(B)) + ")";
                        break;
                    case Encoding::Snorm:
                        value[k] = "rg_gbSnormValue(" + f + ", " + glslFloat(snormH(B)) + ")";
                        break;
                    case Encoding::Oct:
                        value[k] = "rg_gbUnormValue(" + f + ", " + glslFloat(maxOf(B)) + ")";
                        break;
                    case Encoding::Srgb:
                        value[k] = tc.kind == Kind::Srgb
                                       ? tk
                                       : "rg_gbSrgbToLinear(rg_gbUnormValue(" + f + ", " +
                                             glslFloat(maxOf(B)) + "))";
                        break;
                    case Encoding::Uint:
                        value[k] = f;
                        break;
                    case Encoding::Float:
                        value[k] = tk;
                        break;
                }
            }
            std::string joined;
            for (uint32_t k = 0; k < p.components; ++k) joined += (k ? ", " : "") + value[k];
            o << "    g." << c.name << " = ";
            if (c.encoding == Encoding::Oct)
                o << "rg_gbOctDecode(vec2(" << joined << "));\n";
            else if (p.components == 1)
                o << joined << ";\n";
            else
                o << typeOf(c, p.components) << "(" << joined << ");\n";
        }
    }
    o << "    return g;\n}\n#endif\n";
    return o.str();
}

// ---------------------------------------------------------------------------------------------
std::vector<TexelValue> packTexel(const LayoutInfo& info, std::span<const ChannelValue> values) {
    RG_CHECK(values.size() == info.channels.size())
        << "packTexel: " << values.size() << " values for layout '" << info.desc.name << "' with "
        << info.channels.size() << " channels";
    const auto& targets = info.desc.targets;
    std::vector<std::array<uint32_t, 4>> words(targets.size(), {0, 0, 0, 0});
    std::vector<std::array<float, 4>> direct(targets.size(), {0, 0, 0, 0});
    for (size_t i = 0; i < info.channels.size(); ++i) {
        const ChannelPlacement& p = info.channels[i];
        const ChannelDesc& c = info.channelDesc(i);
        const Format fmt = targets[p.target].format;
        const TexelComponents tc = *texelComponents(fmt);
        const ChannelValue& v = values[i];
        const uint32_t B = p.bitsPerComponent;
        std::array<float, 2> e{};
        if (c.encoding == Encoding::Oct) e = octEncode(v.v[0], v.v[1], v.v[2]);
        for (uint32_t k = 0; k < p.components; ++k) {
            const uint32_t comp = p.slots[k].component;
            if (c.encoding == Encoding::Float) {
                FloatRange r = floatRange(fmt, comp);
                direct[p.target][comp] = r.mantBits ? clampf(v.v[k], r.lo, r.hi) : v.v[k];
                continue;
            }
            if (c.encoding == Encoding::Srgb && tc.kind == Kind::Srgb) {
                direct[p.target][comp] = clampf(v.v[k], 0.0f, 1.0f);
                continue;
            }
            uint32_t q = 0;
            switch (c.encoding) {
                case Encoding::Unorm:
                    q = quantUnorm(v.v[k], maxOf(B));
                    break;
                case Encoding::Snorm:
                    q = quantSnorm(v.v[k], snormH(B));
                    break;
                case Encoding::Oct:
                    q = quantUnorm(e[k], maxOf(B));
                    break;
                case Encoding::Srgb:
                    q = quantUnorm(linearToSrgb(clampf(v.v[k], 0.0f, 1.0f)), maxOf(B));
                    break;
                case Encoding::Uint:
                    q = std::min(v.u[k], maskOf(B));
                    break;
                case Encoding::Float:
                    break;
            }
            words[p.target][comp] |= q << p.slots[k].bitOffset;
        }
    }
    // What the attachment stores of the shader's output, as a sampler (or readback) returns it.
    std::vector<TexelValue> out(targets.size());
    for (size_t ti = 0; ti < targets.size(); ++ti) {
        const TexelComponents tc = *texelComponents(targets[ti].format);
        for (uint32_t comp = 0; comp < tc.count; ++comp) {
            TexelValue& t = out[ti];
            switch (tc.kind) {
                case Kind::Uint:
                    t.u[comp] = words[ti][comp];
                    t.f[comp] = static_cast<float>(t.u[comp]);
                    break;
                case Kind::Unorm:
                case Kind::Srgb:
                    if (tc.kind == Kind::Srgb && comp < 3) {
                        // The hardware's sRGB encode to 8 bits; sampling decodes to linear.
                        uint32_t code = quantUnorm(linearToSrgb(direct[ti][comp]), 255.0f);
                        t.f[comp] = srgbToLinear(static_cast<float>(code) / 255.0f);
                    } else {
                        // The shader writes w / m; the unorm conversion rounds back to w.
                        t.f[comp] = static_cast<float>(words[ti][comp]) / maxOf(tc.bits[comp]);
                    }
                    break;
                case Kind::Float: {
                    FloatRange r = floatRange(targets[ti].format, comp);
                    t.f[comp] = r.mantBits ? roundSmallFloat(direct[ti][comp], r.mantBits)
                                           : direct[ti][comp];
                    break;
                }
            }
        }
    }
    return out;
}

std::vector<ChannelValue> unpackTexel(const LayoutInfo& info, std::span<const TexelValue> texels) {
    const auto& targets = info.desc.targets;
    RG_CHECK(texels.size() == targets.size())
        << "unpackTexel: " << texels.size() << " texels for layout '" << info.desc.name << "' with "
        << targets.size() << " targets";
    std::vector<ChannelValue> out(info.channels.size());
    for (size_t i = 0; i < info.channels.size(); ++i) {
        const ChannelPlacement& p = info.channels[i];
        const ChannelDesc& c = info.channelDesc(i);
        const TexelComponents tc = *texelComponents(targets[p.target].format);
        const TexelValue& t = texels[p.target];
        const uint32_t B = p.bitsPerComponent;
        ChannelValue& v = out[i];
        std::array<float, 2> e{};
        for (uint32_t k = 0; k < p.components; ++k) {
            const auto& s = p.slots[k];
            if (c.encoding == Encoding::Float ||
                (c.encoding == Encoding::Srgb && tc.kind == Kind::Srgb)) {
                v.v[k] = t.f[s.component];
                continue;
            }
            const uint32_t word =
                tc.kind == Kind::Uint
                    ? t.u[s.component]
                    : static_cast<uint32_t>(t.f[s.component] * maxOf(tc.bits[s.component]) + 0.5f);
            uint32_t f = word >> s.bitOffset;
            if (s.bitOffset + B < tc.bits[s.component]) f &= maskOf(B);
            switch (c.encoding) {
                case Encoding::Unorm:
                    v.v[k] = unormValue(f, maxOf(B));
                    break;
                case Encoding::Snorm:
                    v.v[k] = snormValue(f, snormH(B));
                    break;
                case Encoding::Oct:
                    e[k] = unormValue(f, maxOf(B));
                    break;
                case Encoding::Srgb:
                    v.v[k] = srgbToLinear(unormValue(f, maxOf(B)));
                    break;
                case Encoding::Uint:
                    v.u[k] = f;
                    break;
                case Encoding::Float:
                    break;
            }
        }
        if (c.encoding == Encoding::Oct) {
            auto n = octDecode(e[0], e[1]);
            v.v = {n[0], n[1], n[2], 0.0f};
        }
    }
    return out;
}

TexelValue texelFromFloats(Format f, const float* values, uint32_t count) {
    TexelValue t;
    const auto tc = texelComponents(f);
    RG_CHECK(tc.has_value()) << "texelFromFloats: " << formatName(f) << " is not a colour format";
    for (uint32_t c = 0; c < count && c < 4; ++c) {
        t.f[c] = values[c];
        if (tc->kind == Kind::Uint) t.u[c] = static_cast<uint32_t>(values[c]);
    }
    return t;
}

}  // namespace rg
