// G-buffer layouts on the GPU (lavapipe in CI, validation layer on): a fullscreen pass packs
// deterministic per-pixel values with the generated GLSL into colour attachments of the targets'
// formats (sRGB formats cannot be storage images on lavapipe, so no compute pass), the targets
// are read back, unpacked on the CPU with rg::unpackTexel and compared with the same values
// computed in C++. Metric and tolerance per encoding (B bits per component, N = 2^B - 1):
//   uint exact; unorm 0.5/N; snorm 0.5/(2^(B-1)-1); oct the angular bound 2 asin(3 sqrt(2) / (2N))
//   derived in tests/unit/test_layout.cpp; srgb 0.5/N in the sRGB-encoded domain (+ 1 code of 8
//   bits for sRGB formats: Vulkan does not require an exact hardware encode); float one ulp of the
//   format (Vulkan leaves the rounding mode of float conversions open). All plus 2e-6 for float
//   arithmetic. The GPU texels are also compared with rg::packTexel, code for code.
// A failure writes the read-back targets to RG_TEST_TMP/layout/<layout>_gpu.exr.
#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <numbers>
#include <sstream>

#include "runtime/runtime.h"
#include "image/image.h"
#include "layout/layout.h"
#include "../unit/layout_test_util.h"

namespace fs = std::filesystem;
using namespace rg;

namespace {

class LayoutGpuTest : public GpuFixture {
protected:
};

// ---------------------------------------------------------------------------------------------
// C++ copies of shaders/test/layout/hash.glsl.
uint32_t testHash(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}
uint32_t testBits(uint32_t x, uint32_t y, uint32_t channel, uint32_t k) {
    return testHash(testHash(x + 4096u * y) ^ ((channel * 4u + k) * 0x9e3779b9u));
}
float testSteps(uint32_t h, int lo, int hi) {
    return static_cast<float>(static_cast<int>(h % static_cast<uint32_t>(hi - lo + 1)) + lo) *
           (1.0f / 8192.0f);
}
float testUnorm(uint32_t x, uint32_t y, uint32_t ch, uint32_t k) {
    return testSteps(testBits(x, y, ch, k), -819, 9011);
}
float testSnorm(uint32_t x, uint32_t y, uint32_t ch, uint32_t k) {
    return testSteps(testBits(x, y, ch, k), -9011, 9011);
}
uint32_t testUint(uint32_t x, uint32_t y, uint32_t ch, uint32_t k, uint32_t bits) {
    uint32_t h = testBits(x, y, ch, k);
    return bits >= 32 ? h : h % ((1u << bits) + 1u);
}
float testFloat(uint32_t x, uint32_t y, uint32_t ch, uint32_t k) {
    uint32_t h = testBits(x, y, ch, k);
    return std::ldexp(static_cast<float>(static_cast<int>(h & 0xffffu) - 32768),
                      static_cast<int>((h >> 16) % 15u) - 12);
}

// The value of every channel at pixel (x, y), as the test shaders compute it.
std::vector<ChannelValue> valuesAt(const LayoutInfo& info, uint32_t x, uint32_t y) {
    std::vector<ChannelValue> v(info.channels.size());
    for (uint32_t i = 0; i < info.channels.size(); ++i) {
        const ChannelPlacement& p = info.channels[i];
        switch (info.channelDesc(i).encoding) {
            case Encoding::Unorm:
                for (uint32_t k = 0; k < p.components; ++k) v[i].v[k] = testUnorm(x, y, i, k);
                break;
            case Encoding::Srgb:
                for (uint32_t k = 0; k < 3; ++k) v[i].v[k] = testUnorm(x, y, i, k);
                break;
            case Encoding::Snorm:
                for (uint32_t k = 0; k < p.components; ++k) v[i].v[k] = testSnorm(x, y, i, k);
                break;
            case Encoding::Oct:
                for (uint32_t k = 0; k < 3; ++k)
                    v[i].v[k] = testSteps(testBits(x, y, i, k), -8192, 8192);
                if (v[i].v[0] == 0 && v[i].v[1] == 0 && v[i].v[2] == 0) v[i].v[2] = 1.0f;
                break;
            case Encoding::Uint:
                for (uint32_t k = 0; k < p.components; ++k)
                    v[i].u[k] = testUint(x, y, i, k, p.bitsPerComponent);
                break;
            case Encoding::Float:
                for (uint32_t k = 0; k < p.components; ++k) v[i].v[k] = testFloat(x, y, i, k);
                break;
        }
    }
    return v;
}

// A fragment shader like shaders/test/layout/pack_disney.frag for any layout.
std::string packShaderFor(const LayoutInfo& info) {
    const LayoutDesc& d = info.desc;
    std::ostringstream s;
    s << "#version 460\n#include \"gbuffer_" << d.name
      << ".glsl\"\n#include \"test/layout/hash.glsl\"\n";
    for (size_t t = 0; t < d.targets.size(); ++t)
        s << "layout(location = " << t << ") out "
          << (texelComponents(d.targets[t].format)->kind == TexelComponents::Kind::Uint ? "uvec4"
                                                                                        : "vec4")
          << " t" << t << ";\n";
    s << "void main() {\n    uvec2 p = uvec2(gl_FragCoord.xy);\n    GBuffer_" << d.name << " g;\n";
    const char* sw = "xyzw";
    for (size_t i = 0; i < info.channels.size(); ++i) {
        const ChannelPlacement& p = info.channels[i];
        const ChannelDesc& c = info.channelDesc(i);
        const std::string ch = std::to_string(i) + "u";
        for (uint32_t k = 0; k < p.components; ++k) {
            const std::string m =
                "g." + c.name + (p.components > 1 ? std::string(".") + sw[k] : "");
            const std::string kk = std::to_string(k) + "u";
            switch (c.encoding) {
                case Encoding::Unorm:
                    s << "    " << m << " = rg_testUnorm(p, " << ch << ", " << kk << ");\n";
                    break;
                case Encoding::Snorm:
                    s << "    " << m << " = rg_testSnorm(p, " << ch << ", " << kk << ");\n";
                    break;
                case Encoding::Uint:
                    s << "    " << m << " = rg_testUint(p, " << ch << ", " << kk << ", "
                      << p.bitsPerComponent << "u);\n";
                    break;
                case Encoding::Float:
                    s << "    " << m << " = rg_testFloat(p, " << ch << ", " << kk << ");\n";
                    break;
                default:
                    break;
            }
        }
        if (c.encoding == Encoding::Oct)
            s << "    g." << c.name << " = rg_testDirection(p, " << ch << ");\n";
        if (c.encoding == Encoding::Srgb)
            s << "    g." << c.name << " = rg_testColour(p, " << ch << ");\n";
    }
    s << "    packGBuffer_" << d.name << "(g";
    for (size_t t = 0; t < d.targets.size(); ++t) s << ", t" << t;
    s << ");\n}\n";
    return s.str();
}

double srgbEncode(double c) {
    return c <= 0.0031308 ? c * 12.92 : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}
double octBound(uint32_t bits) {
    const double n = std::ldexp(1.0, static_cast<int>(bits)) - 1.0;
    return 2.0 * std::asin(std::min(1.0, 3.0 * std::numbers::sqrt2 / (2.0 * n)));
}
int mantissaBits(Format f, uint32_t component) {
    if (f == Format::R16F || f == Format::RG16F || f == Format::RGBA16F) return 10;
    if (f == Format::R11G11B10F) return component < 2 ? 6 : 5;
    return 0;
}
std::pair<float, float> floatRange(Format f, uint32_t component) {
    if (f == Format::R11G11B10F) return {0.0f, component < 2 ? 65024.0f : 64512.0f};
    if (mantissaBits(f, component) == 10) return {-65504.0f, 65504.0f};
    return {-3.0e38f, 3.0e38f};
}

// Error of one unpacked channel against the packed value, as a fraction of its tolerance
// (> 1 fails); uint: 0 or 2.
double errorRatio(const LayoutInfo& info, size_t i, const ChannelValue& in,
                  const ChannelValue& out) {
    const ChannelPlacement& p = info.channels[i];
    const ChannelDesc& c = info.channelDesc(i);
    const Format fmt = info.desc.targets[p.target].format;
    const uint32_t B = p.bitsPerComponent;
    const double N = std::ldexp(1.0, static_cast<int>(B)) - 1.0, slack = 2e-6;
    double worst = 0;
    switch (c.encoding) {
        case Encoding::Uint:
            for (uint32_t k = 0; k < p.components; ++k)
                if (out.u[k] != (B >= 32 ? in.u[k] : std::min(in.u[k], (1u << B) - 1u))) worst = 2;
            break;
        case Encoding::Unorm:
            for (uint32_t k = 0; k < p.components; ++k)
                worst = std::max(worst, std::fabs(out.v[k] - std::clamp(in.v[k], 0.0f, 1.0f)) /
                                            (0.5 / N + slack));
            break;
        case Encoding::Snorm: {
            const double h = std::ldexp(1.0, static_cast<int>(B) - 1) - 1.0;
            for (uint32_t k = 0; k < p.components; ++k)
                worst = std::max(worst, std::fabs(out.v[k] - std::clamp(in.v[k], -1.0f, 1.0f)) /
                                            (0.5 / h + slack));
            break;
        }
        case Encoding::Srgb: {
            const bool hardware = fmt == Format::RGBA8Srgb;
            const double tol = 0.5 / N + (hardware ? 1.0 / 255.0 : 0.0) + 1e-5;
            for (uint32_t k = 0; k < 3; ++k)
                worst =
                    std::max(worst, std::fabs(srgbEncode(std::clamp(double(out.v[k]), 0.0, 1.0)) -
                                              srgbEncode(std::clamp(double(in.v[k]), 0.0, 1.0))) /
                                        tol);
            break;
        }
        case Encoding::Oct: {
            const auto& a = in.v;
            const auto& b = out.v;
            double lb = std::sqrt(double(b[0]) * b[0] + double(b[1]) * b[1] + double(b[2]) * b[2]);
            double cx = double(a[1]) * b[2] - double(a[2]) * b[1],
                   cy = double(a[2]) * b[0] - double(a[0]) * b[2],
                   cz = double(a[0]) * b[1] - double(a[1]) * b[0];
            double dot = double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2];
            double angle = std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), dot);
            worst = std::max(angle / (octBound(B) + slack), std::fabs(lb - 1.0) / 1e-5);
            break;
        }
        case Encoding::Float:
            for (uint32_t k = 0; k < p.components; ++k) {
                const uint32_t comp = p.slots[k].component;
                const auto [lo, hi] = floatRange(fmt, comp);
                const double want = std::clamp(in.v[k], lo, hi);
                const int m = mantissaBits(fmt, comp);
                const double ulp =
                    m == 0 ? 0.0
                           : std::max(std::ldexp(std::fabs(want), -m), std::ldexp(1.0, -14 - m));
                const double err = std::fabs(out.v[k] - want);
                worst = std::max(worst, ulp == 0 ? (err == 0 ? 0.0 : 2.0) : err / ulp);
            }
            break;
    }
    return worst;
}

struct GpuRun {
    std::vector<Image> targets;  // read back, one per target
    std::string error;
};

// Writes the generated header and the pack shader into RG_TEST_TMP/layout/, renders one frame
// of width x height with one fullscreen pass and reads every target back.
GpuRun renderLayout(Runtime& rt, const LayoutInfo& info, const std::string& shaderText,
                    uint32_t width, uint32_t height) {
    GpuRun run;
    const fs::path dir = fs::path(RG_TEST_TMP) / "layout";
    fs::create_directories(dir);
    {
        std::ofstream(dir / ("gbuffer_" + info.desc.name + ".glsl")) << generateGlsl(info);
        std::ofstream(dir / ("pack_" + info.desc.name + ".frag")) << shaderText;
    }
    GraphDesc g;
    PassDesc pass;
    pass.name = "pack_" + info.desc.name;
    pass.kind = "fullscreen";
    pass.params = Value(
        Value::Table{{"shader", Value((dir / ("pack_" + info.desc.name + ".frag")).string())}});
    for (const TargetDesc& t : info.desc.targets) {
        ResourceDesc r;
        r.name = t.name;
        r.texture.format = t.format;
        r.exported = true;
        g.resources.push_back(r);
        pass.accesses.push_back({t.name, Usage::ColorAttachment});
    }
    g.passes = {pass};
    auto& ex = rt.executor();
    CompileOptions o;
    o.outputWidth = width;
    o.outputHeight = height;
    if (auto b = ex.build(g, o); !b) {
        run.error = b.error().describe();
        return run;
    }
    if (auto f = ex.frame(); !f) {
        run.error = f.error().describe();
        return run;
    }
    for (const TargetDesc& t : info.desc.targets) {
        auto img = ex.readback(t.name);
        if (!img) {
            run.error = img.error().describe();
            return run;
        }
        run.targets.push_back(std::move(*img));
    }
    return run;
}

struct Comparison {
    int pixels = 0, failures = 0;
    // GPU texels against packTexel's. Fixed-point components (unorm, uint, A of sRGB formats) are
    // computed by the generated GLSL alone and must be identical; the hardware's conversions
    // (sRGB encode, float narrowing) may round the other way and must be within one quantum.
    int fixedComponents = 0, fixedEqual = 0;
    int convertedComponents = 0, convertedEqual = 0, convertedTowardZero = 0;
    double worstConvertedDelta = 0;        // in quanta (8-bit sRGB codes, float ulps)
    std::map<std::string, int> differing;  // "target.R" -> texels differing from packTexel
    std::vector<double> worstRatio;        // per channel
};

// Unpacks every read-back texel and compares with the CPU's values and the CPU's packing.
Comparison compare(const LayoutInfo& info, const GpuRun& run) {
    Comparison c;
    c.worstRatio.assign(info.channels.size(), 0.0);
    const uint32_t w = run.targets[0].width, h = run.targets[0].height;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            ++c.pixels;
            const auto values = valuesAt(info, x, y);
            std::vector<TexelValue> texels;
            for (size_t t = 0; t < run.targets.size(); ++t) {
                const Image& img = run.targets[t];
                float px[4] = {0, 0, 0, 0};
                for (uint32_t ch = 0; ch < img.channels; ++ch) px[ch] = img.at(x, y, ch);
                texels.push_back(texelFromFloats(info.desc.targets[t].format, px, img.channels));
            }
            const auto back = unpackTexel(info, texels);
            bool bad = false;
            for (size_t i = 0; i < values.size(); ++i) {
                const double r = errorRatio(info, i, values[i], back[i]);
                c.worstRatio[i] = std::max(c.worstRatio[i], r);
                if (r > 1.0) {
                    if (!bad && c.failures < 5)
                        ADD_FAILURE() << "layout '" << info.desc.name << "' pixel (" << x << ", "
                                      << y << ") channel '" << info.channelDesc(i).name
                                      << "': error " << r << " x its tolerance";
                    bad = true;
                }
            }
            c.failures += bad;
            const auto cpu = packTexel(info, values);
            for (size_t t = 0; t < texels.size(); ++t) {
                const Format f = info.desc.targets[t].format;
                const TexelComponents tc = *texelComponents(f);
                for (uint32_t k = 0; k < tc.count; ++k) {
                    const float gpuF = texels[t].f[k], cpuF = cpu[t].f[k];
                    bool equal = false;
                    if (tc.kind == TexelComponents::Kind::Uint ||
                        tc.kind == TexelComponents::Kind::Unorm ||
                        (tc.kind == TexelComponents::Kind::Srgb && k == 3)) {
                        ++c.fixedComponents;
                        equal = tc.kind == TexelComponents::Kind::Uint
                                    ? texels[t].u[k] == cpu[t].u[k]
                                    : gpuF == cpuF;
                        c.fixedEqual += equal;
                    } else {
                        ++c.convertedComponents;
                        equal = gpuF == cpuF;
                        double delta = 0;
                        if (tc.kind == TexelComponents::Kind::Srgb) {
                            delta = std::fabs(srgbEncode(gpuF) - srgbEncode(cpuF)) * 255.0;
                        } else {
                            const int m = mantissaBits(f, k);
                            const double ulp = m ? std::max(std::ldexp(std::fabs(double(cpuF)), -m),
                                                            std::ldexp(1.0, -14 - m))
                                                 : 0.0;
                            delta = equal     ? 0.0
                                    : ulp > 0 ? std::fabs(double(gpuF) - cpuF) / ulp
                                              : 1e9;
                        }
                        c.convertedEqual += equal;
                        c.convertedTowardZero += !equal && std::fabs(gpuF) < std::fabs(cpuF);
                        c.worstConvertedDelta = std::max(c.worstConvertedDelta, delta);
                    }
                    if (!equal) ++c.differing[info.desc.targets[t].name + "." + "RGBA"[k]];
                }
            }
        }
    return c;
}

void keepImages(const LayoutInfo& info, const GpuRun& run) {
    std::vector<ImageLayer> layers;
    const char* names[4] = {"R", "G", "B", "A"};
    for (size_t t = 0; t < run.targets.size(); ++t) {
        ImageLayer l;
        l.name = info.desc.targets[t].name;
        for (uint32_t c = 0; c < run.targets[t].channels; ++c) l.channelNames.push_back(names[c]);
        l.image = run.targets[t];
        layers.push_back(std::move(l));
    }
    const std::string path = std::string(RG_TEST_TMP) + "/layout/" + info.desc.name + "_gpu.exr";
    ExrWriteOptions o;
    o.pixelType = ExrPixelType::Float;
    if (writeExr(path, layers, o)) std::cout << "read-back targets written to " << path << "\n";
}

std::string readFile(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

void report(const LayoutInfo& info, const Comparison& c) {
    std::cout << "layout '" << info.desc.name << "': " << c.pixels
              << " pixels; equal to packTexel's: fixed-point " << c.fixedEqual << " of "
              << c.fixedComponents << " texel components, hardware-converted (sRGB, float) "
              << c.convertedEqual << " of " << c.convertedComponents << " ("
              << c.convertedTowardZero << " of the others rounded toward zero), largest difference "
              << c.worstConvertedDelta << " quantum\n"
              << "  worst error / tolerance per channel:";
    for (size_t i = 0; i < info.channels.size(); ++i)
        std::cout << " " << info.channelDesc(i).name << " " << c.worstRatio[i];
    std::cout << "\n  texel components that differ from packTexel's:";
    for (const auto& [where, n] : c.differing) std::cout << " " << where << " " << n;
    std::cout << "\n";
}

using rg::test::ch;  // tests/unit/layout_test_util.h
using rg::test::defaultDisneyLayout;

// ---------------------------------------------------------------------------------------------

TEST_F(LayoutGpuTest, DefaultLayoutPackedOnTheGpuUnpacksOnTheCpu) {
    auto info = analyzeLayout(defaultDisneyLayout());
    ASSERT_TRUE(info.has_value()) << info.error().message;
    const std::string shader =
        readFile(std::string(RG_SOURCE_ROOT) + "/shaders/test/layout/pack_disney.frag");
    ASSERT_FALSE(shader.empty());
    GpuRun run = renderLayout(rt(), *info, shader, 128, 96);
    ASSERT_TRUE(run.error.empty()) << run.error;
    ASSERT_EQ(run.targets.size(), 4u);
    Comparison c = compare(*info, run);
    report(*info, c);
    EXPECT_EQ(c.pixels, 128 * 96);
    EXPECT_EQ(c.failures, 0);
    // GLSL and C++ agree: bit for bit where the shader alone decides, within a quantum where the
    // hardware converts.
    EXPECT_EQ(c.fixedEqual, c.fixedComponents);
    EXPECT_LE(c.worstConvertedDelta, 1.0 + 1e-3);
    if (c.failures) keepImages(*info, run);
}

TEST_F(LayoutGpuTest, EightTargetsOfEveryKindAgreeWithTheCpu) {
    // Every encoding, bit fields sharing components, and the remaining colour formats (except
    // r32ui/rgba32ui: Executor::readback returns floats, exact only up to 2^24).
    LayoutDesc d;
    d.name = "mixed";
    d.targets = {
        {"M0",
         Format::RGBA8Unorm,
         {ch("n8", Encoding::Oct, 16), ch("s8", Encoding::Snorm, 8), ch("flags", Encoding::Uint, 4),
          ch("rough4", Encoding::Unorm, 4)},
         ""},
        {"M1",
         Format::RGB10A2Unorm,
         {ch("albedo", Encoding::Srgb, 30), ch("kind", Encoding::Uint, 2)},
         ""},
        {"M2", Format::R11G11B10F, {ch("light", Encoding::Float, 30, 3)}, ""},
        {"M3", Format::R8Uint, {ch("id3", Encoding::Uint, 3), ch("u5", Encoding::Unorm, 5)}, ""},
        {"M4", Format::RG16F, {ch("motion", Encoding::Float, 32, 2)}, ""},
        {"M5", Format::R32F, {ch("depthLinear", Encoding::Float, 32)}, ""},
        {"M6", Format::RG8Unorm, {ch("tangent", Encoding::Oct, 16)}, ""},
        {"M7",
         Format::R8Unorm,
         {ch("sn4", Encoding::Snorm, 4), ch("pair", Encoding::Unorm, 4, 2)},
         ""},
    };
    auto info = analyzeLayout(d);
    ASSERT_TRUE(info.has_value()) << info.error().message;
    GpuRun run = renderLayout(rt(), *info, packShaderFor(*info), 64, 48);
    ASSERT_TRUE(run.error.empty()) << run.error;
    ASSERT_EQ(run.targets.size(), 8u);
    Comparison c = compare(*info, run);
    report(*info, c);
    EXPECT_EQ(c.failures, 0);
    // GLSL and C++ agree: bit for bit where the shader alone decides, within a quantum where the
    // hardware converts.
    EXPECT_EQ(c.fixedEqual, c.fixedComponents);
    EXPECT_LE(c.worstConvertedDelta, 1.0 + 1e-3);
    if (c.failures) keepImages(*info, run);
}

}  // namespace
