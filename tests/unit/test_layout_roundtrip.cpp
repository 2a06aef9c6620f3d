// G-buffer layouts without a GPU: pack -> unpack round trips against stated bounds (default layout
// and ~200 random valid layouts), and the generated GLSL compiling with glslang.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "layout/layout.h"
#include "layout_test_util.h"
#include "shader/shader_compiler.h"

using namespace rg;
using namespace rg::test;

namespace {

// ---------------------------------------------------------------------------------------------
// Bounds of one pack -> unpack round trip, per encoding (B = bits per component, N = 2^B - 1).
//
// unorm: q = floor(x N + 0.5) is round to nearest, so |x' - clamp(x)| <= 0.5 / N.
// snorm: offset binary with h = 2^(B-1) - 1 levels per side: |x' - clamp(x)| <= 0.5 / h.
// srgb:  the sRGB-encoded value is quantised to B bits, so in the encoded domain the error is
//        <= 0.5 / N; in linear terms it is at most that times the largest slope of the decode
//        curve, d/dS ((S + 0.055) / 1.055)^2.4 at S = 1, = 2.4 / 1.055 = 2.2749 (0.00446 for
//        8 bits: a plain 1/255 bound in linear would not hold near white).
// oct:   the encoded point p in [-1, 1]^2 moves by at most delta = 1 / N per coordinate (0.5 / N
//        in [0, 1], times 2). The unfolded decode n(p) = (p, 1 - |px| - |py|) (and its fold) is
//        piecewise linear with |dnx|, |dny| <= delta and |dnz| <= 2 delta, so |n - n'| <= sqrt(6)
//        delta. Both n and n' lie on the octahedron |x| + |y| + |z| = 1, so their lengths are
//        >= 1 / sqrt(3), and |n/|n| - n'/|n'|| <= |n - n'| / sqrt(|n| |n'|) <= sqrt(3) |n - n'|.
//        The chord between the unit vectors is therefore <= sqrt(18) / N = 3 sqrt(2) / N and the
//        angle <= 2 asin(3 sqrt(2) / (2 N)). For 10 + 10 bits (N = 1023): 4.147e-3 rad = 0.2376
//        degrees. (50 000 random normals reach 95 % of it: the bound is nearly tight.)
// uint:  exact after clamping to N.
// float: round to nearest in the format: relative 2^-(M+1) (M mantissa bits: half 10, the
//        unsigned 11-/10-bit floats 6 and 5), absolute 2^-(15+M) below the normal range; 32-bit
//        exact.
constexpr double kSrgbMaxSlope = 2.4 / 1.055;

double octBound(uint32_t bits) {
    const double n = std::ldexp(1.0, static_cast<int>(bits)) - 1.0;
    return 2.0 * std::asin(std::min(1.0, 3.0 * std::numbers::sqrt2 / (2.0 * n)));
}
double unormBound(uint32_t bits) { return 0.5 / (std::ldexp(1.0, static_cast<int>(bits)) - 1.0); }
double snormBound(uint32_t bits) {
    return 0.5 / (std::ldexp(1.0, static_cast<int>(bits) - 1) - 1.0);
}

double srgbEncode(double c) {
    return c <= 0.0031308 ? c * 12.92 : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

int mantissaBits(Format f, uint32_t component) {
    switch (f) {
        case Format::R16F:
        case Format::RG16F:
        case Format::RGBA16F:
            return 10;
        case Format::R11G11B10F:
            return component < 2 ? 6 : 5;
        default:
            return 0;  // 32-bit float: exact
    }
}
std::pair<float, float> floatRange(Format f, uint32_t component) {
    if (f == Format::R11G11B10F) return {0.0f, component < 2 ? 65024.0f : 64512.0f};
    if (mantissaBits(f, component) == 10) return {-65504.0f, 65504.0f};
    return {-3.0e38f, 3.0e38f};
}

double angleBetween(const std::array<float, 4>& a, const std::array<float, 4>& b) {
    double la = std::sqrt(double(a[0]) * a[0] + double(a[1]) * a[1] + double(a[2]) * a[2]);
    double lb = std::sqrt(double(b[0]) * b[0] + double(b[1]) * b[1] + double(b[2]) * b[2]);
    double d = (double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2]) / (la * lb);
    // atan2 form: accurate for small angles, where acos is not.
    double cx = double(a[1]) * b[2] - double(a[2]) * b[1],
           cy = double(a[2]) * b[0] - double(a[0]) * b[2],
           cz = double(a[0]) * b[1] - double(a[1]) * b[0];
    return std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz) / (la * lb), d);
}

// Largest error seen per encoding, relative to its bound (1.0 = at the bound).
struct Worst {
    double oct = 0, unorm = 0, snorm = 0, srgb = 0, floating = 0;
};

// Checks one unpacked channel against the value that was packed; adds a failure naming the
// channel when a bound is broken. Returns false on failure.
bool checkChannel(const LayoutInfo& info, size_t i, const ChannelValue& in, const ChannelValue& out,
                  Worst& worst, double floatUlps = 0.5) {
    const ChannelPlacement& p = info.channels[i];
    const ChannelDesc& c = info.channelDesc(i);
    const Format fmt = info.desc.targets[p.target].format;
    const uint32_t B = p.bitsPerComponent;
    const double eps = 1e-6;  // float arithmetic of pack/unpack
    // The error / bound ratios are recorded where the bound is well above float rounding.
    const bool record = B <= 16;
    auto failAt = [&](uint32_t k, double got, double want, double bound) {
        ADD_FAILURE() << "layout '" << info.desc.name << "' channel '" << c.name << "' ("
                      << encodingName(c.encoding) << " " << c.bits << " bits in " << formatName(fmt)
                      << ") component " << k << ": got " << got << ", want " << want << " within "
                      << bound;
        return false;
    };
    switch (c.encoding) {
        case Encoding::Uint:
            for (uint32_t k = 0; k < p.components; ++k) {
                const uint32_t want = B >= 32 ? in.u[k] : std::min(in.u[k], (1u << B) - 1u);
                if (out.u[k] != want) return failAt(k, out.u[k], want, 0);
            }
            return true;
        case Encoding::Unorm:
        case Encoding::Snorm:
            for (uint32_t k = 0; k < p.components; ++k) {
                const bool un = c.encoding == Encoding::Unorm;
                const double want = std::clamp(double(in.v[k]), un ? 0.0 : -1.0, 1.0);
                const double bound = un ? unormBound(B) : snormBound(B);
                const double err = std::fabs(out.v[k] - want);
                if (record)
                    (un ? worst.unorm : worst.snorm) =
                        std::max(un ? worst.unorm : worst.snorm, err / bound);
                if (err > bound + eps) return failAt(k, out.v[k], want, bound);
            }
            return true;
        case Encoding::Srgb: {
            for (uint32_t k = 0; k < 3; ++k) {
                const double want = std::clamp(double(in.v[k]), 0.0, 1.0);
                const double bound = unormBound(B);
                const double err = std::fabs(srgbEncode(std::clamp(double(out.v[k]), 0.0, 1.0)) -
                                             srgbEncode(want));
                if (record) worst.srgb = std::max(worst.srgb, err / bound);
                if (err > bound + 1e-5)
                    return failAt(k, srgbEncode(out.v[k]), srgbEncode(want), bound);
                if (std::fabs(out.v[k] - want) > bound * kSrgbMaxSlope + 1e-5)
                    return failAt(k, out.v[k], want, bound * kSrgbMaxSlope);
            }
            return true;
        }
        case Encoding::Oct: {
            const double a = angleBetween(in.v, out.v), bound = octBound(B);
            if (record) worst.oct = std::max(worst.oct, a / bound);
            const double len = std::sqrt(double(out.v[0]) * out.v[0] + double(out.v[1]) * out.v[1] +
                                         double(out.v[2]) * out.v[2]);
            if (std::fabs(len - 1.0) > 1e-5) return failAt(3, len, 1.0, 1e-5);
            if (a > bound + 2e-6) return failAt(0, a, 0, bound);
            return true;
        }
        case Encoding::Float:
            for (uint32_t k = 0; k < p.components; ++k) {
                const uint32_t comp = p.slots[k].component;
                const auto [lo, hi] = floatRange(fmt, comp);
                const double want = std::clamp(in.v[k], lo, hi);
                const int m = mantissaBits(fmt, comp);
                const double bound = m == 0 ? 0.0
                                            : floatUlps * std::max(std::ldexp(std::fabs(want), -m),
                                                                   std::ldexp(1.0, -14 - m));
                const double err = std::fabs(out.v[k] - want);
                if (bound > 0) worst.floating = std::max(worst.floating, err / bound);
                if (err > bound) return failAt(k, out.v[k], want, bound);
            }
            return true;
    }
    return false;
}

// A random value for every channel: some outside the encodable range, to exercise clamping.
std::vector<ChannelValue> randomValues(const LayoutInfo& info, std::mt19937& rng) {
    std::uniform_real_distribution<float> u01(0.0f, 1.0f);
    std::normal_distribution<float> gauss(0.0f, 1.0f);
    std::vector<ChannelValue> values(info.channels.size());
    for (size_t i = 0; i < info.channels.size(); ++i) {
        const ChannelPlacement& p = info.channels[i];
        const ChannelDesc& c = info.channelDesc(i);
        ChannelValue& v = values[i];
        const uint32_t B = p.bitsPerComponent;
        for (uint32_t k = 0; k < 4; ++k) {
            switch (c.encoding) {
                case Encoding::Unorm:
                case Encoding::Srgb:
                    v.v[k] = u01(rng) * 1.2f - 0.1f;
                    break;
                case Encoding::Snorm:
                    v.v[k] = u01(rng) * 2.4f - 1.2f;
                    break;
                case Encoding::Oct:
                    v.v[k] = gauss(rng) * (k == 0 ? 3.0f : 1.0f);
                    break;  // any length
                case Encoding::Uint: {
                    const uint32_t r = static_cast<uint32_t>(rng());
                    v.u[k] = (rng() % 4 == 0 || B >= 32) ? r : r & ((1u << B) - 1u);
                    break;
                }
                case Encoding::Float: {
                    const float mant = u01(rng) * 2.0f - 1.0f;
                    v.v[k] = rng() % 16 == 0 ? 0.0f
                                             : std::ldexp(mant, static_cast<int>(rng() % 40) - 20);
                    break;
                }
            }
        }
        // Exact axes and the octahedron's fold lines, where encodings tend to break.
        if (c.encoding == Encoding::Oct && rng() % 8 == 0) {
            const float axes[6][3] = {{1, 0, 0},  {0, -1, 0},  {0, 0, 1},
                                      {0, 0, -1}, {-1, 0, -1}, {0.5f, -0.5f, -0.0f}};
            const auto& a = axes[rng() % 6];
            v.v = {a[0], a[1], a[2], 0.0f};
        }
    }
    return values;
}

// Packs, simulates the formats, unpacks, checks every channel.
int roundTrip(const LayoutInfo& info, std::mt19937& rng, int samples, Worst& worst) {
    int failures = 0;
    for (int s = 0; s < samples && failures < 5; ++s) {
        auto values = randomValues(info, rng);
        auto texels = packTexel(info, values);
        auto back = unpackTexel(info, texels);
        for (size_t i = 0; i < values.size(); ++i)
            if (!checkChannel(info, i, values[i], back[i], worst)) ++failures;
    }
    return failures;
}

TEST(Layout, DefaultLayoutRoundTripsWithinBounds) {
    auto info = analyzeLayout(defaultDisneyLayout());
    ASSERT_TRUE(info.has_value());
    std::mt19937 rng(12345);
    Worst worst;
    EXPECT_EQ(roundTrip(*info, rng, 50000, worst), 0);
    // The bounds are not vacuous: the errors come close to them (and stay under).
    EXPECT_NEAR(octBound(10), 4.14726e-3, 1e-8);
    EXPECT_GT(worst.oct, 0.5);
    EXPECT_GT(worst.unorm, 0.99);
    EXPECT_GT(worst.srgb, 0.9);
    EXPECT_GT(worst.floating, 0.9);
    std::cout << "worst error / bound: oct " << worst.oct << ", unorm " << worst.unorm << ", srgb "
              << worst.srgb << ", float16 " << worst.floating
              << " (oct bound for 10+10 bits: " << octBound(10)
              << " rad = " << octBound(10) * 180.0 / std::numbers::pi << " deg)\n";
}

TEST(Layout, EveryFixedPointCodeSurvivesUnpackThenPack) {
    // Unpacking a texel and packing it again gives the same texel: the quantisers invert exactly
    // (unorm and snorm 12 bits, uint, srgb with the exact transfer functions at 8 and 10 bits).
    LayoutDesc d;
    d.name = "codes";
    d.targets = {
        {"a",
         Format::RGBA32Uint,
         {ch("u", Encoding::Unorm, 12), ch("s", Encoding::Snorm, 12), ch("pad", Encoding::Uint, 8),
          ch("c8", Encoding::Srgb, 24), ch("i", Encoding::Uint, 8), ch("c10", Encoding::Srgb, 30)},
         ""}};
    auto info = analyzeLayout(d);
    ASSERT_TRUE(info.has_value()) << info.error().message;
    EXPECT_EQ(info->channels[5].slots[2].component, 2u);
    EXPECT_EQ(info->channels[5].slots[2].bitOffset, 20u);
    int mismatches = 0;
    for (uint32_t q = 0; q < 4096; ++q) {
        TexelValue t;
        const uint32_t s = std::max(q, 1u);  // snorm code 0 is below -1 and reads back as code 1
        const uint32_t b = q & 255u, p = q & 1023u;
        t.u = {q | (s << 12) | (b << 24), b | (b << 8) | (b << 16) | (b << 24),
               p | (p << 10) | (p << 20), 0};
        auto v = unpackTexel(*info, std::span<const TexelValue>(&t, 1));
        auto again = packTexel(*info, v);
        for (int c = 0; c < 4; ++c) mismatches += again[0].u[c] != t.u[c];
    }
    EXPECT_EQ(mismatches, 0);
}

// ---------------------------------------------------------------------------------------------
// Random valid layouts. The generator walks the texel components with the same cursor rule as
// the analyser (fields from bit 0 up, never straddling), records where it put each channel, and
// the test checks analyzeLayout agrees, then round-trips random values through each layout.
struct Generated {
    LayoutDesc desc;
    std::vector<ChannelPlacement> expected;
};

Generated randomLayout(std::mt19937& rng, int index) {
    const Format formats[] = {Format::R8Unorm,   Format::RG8Unorm,     Format::RGBA8Unorm,
                              Format::RGBA8Srgb, Format::RGB10A2Unorm, Format::R11G11B10F,
                              Format::R16F,      Format::RG16F,        Format::RGBA16F,
                              Format::R32F,      Format::RG32F,        Format::RGBA32F,
                              Format::R8Uint,    Format::R32Uint,      Format::RGBA32Uint};
    auto pick = [&](uint32_t n) { return static_cast<uint32_t>(rng() % n); };
    Generated g;
    g.desc.name = "random" + std::to_string(index);
    const uint32_t targets = 1 + pick(8);
    int channelCount = 0;
    for (uint32_t ti = 0; ti < targets; ++ti) {
        TargetDesc t;
        t.name = "T" + std::to_string(ti);
        t.format = formats[pick(std::size(formats))];
        const TexelComponents tc = *texelComponents(t.format);
        uint32_t comp = 0, off = 0;
        auto add = [&](ChannelDesc c, std::vector<ChannelPlacement::Slot> slots) {
            ChannelPlacement p;
            p.target = ti;
            p.channel = static_cast<uint32_t>(t.channels.size());
            p.components = static_cast<uint32_t>(slots.size());
            p.bitsPerComponent = c.bits / p.components;
            for (size_t k = 0; k < slots.size(); ++k) p.slots[k] = slots[k];
            p.component = slots[0].component;
            p.bitOffset = slots[0].bitOffset;
            g.expected.push_back(p);
            t.channels.push_back(std::move(c));
        };
        auto name = [&] { return "c" + std::to_string(channelCount++); };
        if (tc.kind == TexelComponents::Kind::Float) {
            while (comp < tc.count && (t.channels.empty() || pick(6) != 0)) {
                const uint32_t n = 1 + pick(tc.count - comp);
                uint32_t narrowest = 32;
                std::vector<ChannelPlacement::Slot> slots;
                for (uint32_t k = 0; k < n; ++k) {
                    narrowest = std::min(narrowest, tc.bits[comp + k]);
                    slots.push_back({comp + k, 0});
                }
                const uint32_t bpc = pick(3) == 0 ? 1 + pick(narrowest) : narrowest;
                add(ch(name(), Encoding::Float, bpc * n, n == 1 && pick(2) ? 0 : n), slots);
                comp += n;
            }
        } else {
            if (tc.kind == TexelComponents::Kind::Srgb) {
                add(ch(name(), Encoding::Srgb, 24), {{0, 0}, {1, 0}, {2, 0}});
                comp = 3;
            }
            // Fixed-point fields until the texel is full (or, sometimes, earlier).
            while (comp < tc.count && (t.channels.empty() || pick(12) != 0)) {
                ChannelDesc c;
                std::vector<ChannelPlacement::Slot> slots;
                bool placed = false;
                for (int attempt = 0; attempt < 30 && !placed; ++attempt) {
                    const Encoding encodings[] = {Encoding::Unorm, Encoding::Snorm, Encoding::Oct,
                                                  Encoding::Uint, Encoding::Srgb};
                    // (A of an sRGB format is no place for a second, code-encoded srgb channel.)
                    const Encoding e =
                        encodings[pick(tc.kind == TexelComponents::Kind::Srgb ? 4 : 5)];
                    const uint32_t n = e == Encoding::Oct    ? 2
                                       : e == Encoding::Srgb ? 3
                                                             : (pick(3) == 0 ? 1 + pick(4) : 1);
                    const uint32_t room = tc.bits[comp] - off;
                    const uint32_t maxBits = e == Encoding::Uint ? 32 : 24;
                    const uint32_t minBits = e == Encoding::Snorm ? 2 : 1;
                    // Mostly whole or half components, sometimes any width that fits.
                    uint32_t bpc = pick(2) ? room : 1 + pick(std::min(room, maxBits));
                    bpc = std::min(std::max(bpc, minBits), maxBits);
                    // Simulate the cursor for n components.
                    uint32_t cc = comp, oo = off;
                    slots.clear();
                    bool ok = true;
                    for (uint32_t k = 0; k < n && ok; ++k) {
                        if (cc >= tc.count || oo + bpc > tc.bits[cc]) {
                            ok = false;
                            break;
                        }
                        slots.push_back({cc, oo});
                        oo += bpc;
                        if (oo == tc.bits[cc]) {
                            ++cc;
                            oo = 0;
                        }
                    }
                    if (!ok) continue;
                    c = ch(name(), e, bpc * n,
                           (e != Encoding::Oct && e != Encoding::Srgb) && n > 1 ? n : 0);
                    comp = cc;
                    off = oo;
                    placed = true;
                }
                if (!placed) {  // a uint field filling the rest of this texel component always fits
                    c = ch(name(), Encoding::Uint, tc.bits[comp] - off);
                    slots = {{comp, off}};
                    ++comp;
                    off = 0;
                }
                add(std::move(c), slots);
            }
        }
        g.desc.targets.push_back(std::move(t));
    }
    return g;
}

TEST(Layout, RandomValidLayoutsPlaceAndRoundTrip) {
    std::mt19937 layoutRng(2024), rng(7);
    Worst worst;
    int layouts = 0, channels = 0, fieldsSharingAComponent = 0;
    for (int i = 0; i < 200; ++i) {
        Generated g = randomLayout(layoutRng, i);
        auto info = analyzeLayout(g.desc);
        ASSERT_TRUE(info.has_value()) << info.error().message;
        ASSERT_EQ(info->channels.size(), g.expected.size());
        for (size_t c = 0; c < g.expected.size(); ++c) {
            const auto& a = info->channels[c];
            const auto& e = g.expected[c];
            SCOPED_TRACE(g.desc.name + " channel " + info->channelDesc(c).name);
            ASSERT_EQ(a.target, e.target);
            ASSERT_EQ(a.channel, e.channel);
            ASSERT_EQ(a.components, e.components);
            ASSERT_EQ(a.bitsPerComponent, e.bitsPerComponent);
            for (uint32_t k = 0; k < a.components; ++k) {
                ASSERT_EQ(a.slots[k].component, e.slots[k].component);
                ASSERT_EQ(a.slots[k].bitOffset, e.slots[k].bitOffset);
            }
            fieldsSharingAComponent += a.bitOffset > 0;
        }
        ASSERT_EQ(roundTrip(*info, rng, 300, worst), 0) << g.desc.name;
        ++layouts;
        channels += static_cast<int>(info->channels.size());
    }
    EXPECT_EQ(layouts, 200);
    EXPECT_GT(fieldsSharingAComponent, 100);  // the generator does exercise bit fields
    std::cout << layouts << " layouts, " << channels << " channels, " << fieldsSharingAComponent
              << " fields at a bit offset > 0; worst error / bound: oct " << worst.oct << ", unorm "
              << worst.unorm << ", snorm " << worst.snorm << ", srgb " << worst.srgb << ", float "
              << worst.floating << "\n";
}

// ---------------------------------------------------------------------------------------------
// The generated GLSL compiles (glslang, GLSL 460, SPIR-V validated).

std::string computeMain(const LayoutInfo& info) {
    // Reads one texel per target from storage buffers of raw words, unpacks, packs, writes back:
    // every generated function and every member is used.
    const auto& d = info.desc;
    std::string s =
        "layout(local_size_x = 64) in;\nlayout(std430, set = 0, binding = 0) buffer Texels { uvec4 "
        "texels[]; };\n";
    s += "void main() {\n    uint i = gl_GlobalInvocationID.x * " +
         std::to_string(d.targets.size()) + "u;\n";
    std::string args, outArgs;
    for (size_t t = 0; t < d.targets.size(); ++t) {
        const bool integer =
            texelComponents(d.targets[t].format)->kind == TexelComponents::Kind::Uint;
        s += std::string("    ") + (integer ? "uvec4" : "vec4") + " t" + std::to_string(t) + " = " +
             (integer ? "" : "uintBitsToFloat") + "(texels[i + " + std::to_string(t) + "u]);\n";
        args += (t ? ", t" : "t") + std::to_string(t);
    }
    s += "    GBuffer_" + d.name + " g = unpackGBuffer_" + d.name + "(" + args + ");\n";
    s += "    packGBuffer_" + d.name + "(g, " + args + ");\n";
    for (size_t t = 0; t < d.targets.size(); ++t) {
        const bool integer =
            texelComponents(d.targets[t].format)->kind == TexelComponents::Kind::Uint;
        s += "    texels[i + " + std::to_string(t) + "u] = " + (integer ? "" : "floatBitsToUint") +
             "(t" + std::to_string(t) + ");\n";
    }
    return s + "}\n";
}

Result<ShaderModule> compileLayout(ShaderCompiler& compiler,
                                   const std::vector<const LayoutInfo*>& layouts,
                                   const std::string& main) {
    ShaderRequest req;
    req.source = "#version 460\n";
    for (const LayoutInfo* l : layouts) req.source += generateGlsl(*l);
    req.source += main;
    req.virtualName = "layout_" + layouts[0]->desc.name + ".comp";
    return compiler.compile(req);
}

TEST(LayoutGlsl, DefaultLayoutCodeHasTheContractedShape) {
    auto info = analyzeLayout(defaultDisneyLayout());
    ASSERT_TRUE(info.has_value());
    const std::string glsl = generateGlsl(*info);
    for (const char* piece : {
             "#ifndef RG_GBUFFER_disney_GLSL\n#define RG_GBUFFER_disney_GLSL\n",
             "struct GBuffer_disney {\n    vec3 normal;",
             "    float smoothness;",
             "    uint materialId;",
             "    vec3 baseColor;",
             "    uint materialData;",
             "    uint normalExtra;",
             "    vec3 emissive;",
             "void packGBuffer_disney(GBuffer_disney g, out vec4 t0, out vec4 t1, out vec4 t2, out "
             "vec4 t3) {",
             "GBuffer_disney unpackGBuffer_disney(vec4 t0, vec4 t1, vec4 t2, vec4 t3) {",
             "// t1 = GB1 (rgba8_srgb): R[0..7]=baseColor.x G[0..7]=baseColor.y "
             "B[0..7]=baseColor.z A[0..4]=materialData "
             "A[5..7]=normalExtra",
             "uint w1_3 = min(g.materialData, 31u) | (min(g.normalExtra, 7u) << 5u);",
             "t1 = vec4(clamp(g.baseColor.x, 0.0, 1.0), clamp(g.baseColor.y, 0.0, 1.0), "
             "clamp(g.baseColor.z, 0.0, 1.0), "
             "float(w1_3) / 255.0);",
         })
        EXPECT_NE(glsl.find(piece), std::string::npos)
            << "missing: " << piece << "\n--- generated:\n"
            << glsl;
}

TEST(LayoutGlsl, DefaultLayoutCompilesWithGlslang) {
    auto info = analyzeLayout(defaultDisneyLayout());
    ASSERT_TRUE(info.has_value());
    ShaderCompiler compiler({});
    auto m = compileLayout(compiler, {&*info}, computeMain(*info));
    ASSERT_TRUE(m.has_value()) << m.error().describe() << "\n" << generateGlsl(*info);
    EXPECT_TRUE(validateSpirv(m->spirv).has_value());
    EXPECT_EQ(m->stage, ShaderStage::Compute);
    // Two layouts in one shader, one of them twice: the include guards keep the helpers single.
    LayoutDesc other = defaultDisneyLayout();
    other.name = "twoColour";
    auto info2 = analyzeLayout(other);
    ASSERT_TRUE(info2.has_value());
    auto both = compileLayout(compiler, {&*info, &*info2, &*info}, computeMain(*info2));
    ASSERT_TRUE(both.has_value()) << both.error().describe();
}

TEST(LayoutGlsl, RandomLayoutsCompileWithGlslang) {
    std::mt19937 layoutRng(2024);  // the same layouts as RandomValidLayoutsPlaceAndRoundTrip
    ShaderCompiler compiler({});
    int compiled = 0;
    for (int i = 0; i < 200; ++i) {
        Generated g = randomLayout(layoutRng, i);
        auto info = analyzeLayout(g.desc);
        ASSERT_TRUE(info.has_value()) << info.error().message;
        auto m = compileLayout(compiler, {&*info}, computeMain(*info));
        ASSERT_TRUE(m.has_value()) << m.error().describe() << "\n" << generateGlsl(*info);
        ++compiled;
    }
    EXPECT_EQ(compiled, 200);
}

}  // namespace
