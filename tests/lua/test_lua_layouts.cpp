// G-buffer layouts from scripts: every layout a shipped pipeline or a README example declares
// packs and unpacks within its encoding's bound, and the deferred shaders generated per lighting
// path over them. No GPU.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "image/image.h"
#include "layout/layout.h"

#include "lua/lua_host.h"
#include "lua_test_util.h"
#include "runtime/session.h"

namespace fs = std::filesystem;
using namespace rg;
using namespace rg::test;

namespace {

// Every layout any shipped pipeline or README example declares survives pack -> unpack within its
// encoding's bound (uint exact; unorm/snorm half a step; sRGB half a step in the encoded domain;
// octahedral normals within 2·asin(3√2 / 2N); floats at the format's precision).
void roundTrip(const LayoutDesc& layout, std::mt19937& rng) {
    auto info = analyzeLayout(layout);
    ASSERT_TRUE(info.has_value()) << info.error().message;
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), signedUnit(-1.0f, 1.0f);
    for (int trial = 0; trial < 2000; ++trial) {
        std::vector<ChannelValue> in(info->channels.size());
        for (size_t c = 0; c < in.size(); ++c) {
            const ChannelDesc& ch = info->channelDesc(c);
            for (int k = 0; k < 4; ++k) {
                in[c].v[static_cast<size_t>(k)] =
                    ch.encoding == Encoding::Snorm || ch.encoding == Encoding::Oct ? signedUnit(rng)
                                                                                   : unit(rng);
                in[c].u[static_cast<size_t>(k)] = static_cast<uint32_t>(rng());
            }
            if (ch.encoding == Encoding::Oct) {
                float len = std::sqrt(in[c].v[0] * in[c].v[0] + in[c].v[1] * in[c].v[1] +
                                      in[c].v[2] * in[c].v[2]);
                if (len < 1e-3f) in[c].v = {0, 0, 1, 0};
            }
        }
        auto out = unpackTexel(*info, packTexel(*info, in));
        ASSERT_EQ(out.size(), in.size());
        for (size_t c = 0; c < in.size(); ++c) {
            const ChannelDesc& ch = info->channelDesc(c);
            const ChannelPlacement& pl = info->channels[c];
            const double n = std::pow(2.0, pl.bitsPerComponent) - 1.0;
            SCOPED_TRACE(layout.name + "." + ch.name);
            for (uint32_t k = 0; k < pl.components; ++k) {
                switch (ch.encoding) {
                    case Encoding::Uint: {
                        uint32_t mask =
                            pl.bitsPerComponent >= 32 ? ~0u : (1u << pl.bitsPerComponent) - 1u;
                        EXPECT_EQ(out[c].u[k], std::min(in[c].u[k], mask));
                        break;
                    }
                    case Encoding::Unorm:
                        EXPECT_NEAR(out[c].v[k], in[c].v[k], 0.5 / n + 1e-6);
                        break;
                    case Encoding::Snorm:
                        EXPECT_NEAR(out[c].v[k], in[c].v[k], 1.0 / (n - 1.0) + 1e-6);
                        break;
                    case Encoding::Srgb:
                        EXPECT_NEAR(srgbEncode(out[c].v[k]), srgbEncode(in[c].v[k]),
                                    0.5 / n + 1e-5);
                        break;
                    case Encoding::Float:
                        EXPECT_NEAR(out[c].v[k], in[c].v[k], std::abs(in[c].v[k]) * 1e-3 + 1e-6);
                        break;
                    case Encoding::Oct:
                        break;
                }
            }
            if (ch.encoding == Encoding::Oct) {
                const auto& a = in[c].v;
                const auto& b = out[c].v;
                double la = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
                double cosAngle = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / la;
                double bound = 2.0 * std::asin(3.0 * std::sqrt(2.0) / (2.0 * n));
                EXPECT_LE(std::acos(std::min(1.0, cosAngle)), bound + 1e-5);
            }
        }
    }
}

TEST(LuaLayouts, EveryDeclaredLayoutRoundTrips) {
    std::vector<std::string> files;
    for (const auto& e : fs::directory_iterator(std::string(RG_SOURCE_ROOT) + "/scripts/pipelines"))
        if (e.path().extension() == ".lua") files.push_back(e.path().string());
    fs::create_directories(RG_TEST_TMP);
    auto examples = readmeExamples();
    for (size_t i = 0; i < examples.size(); ++i) {
        files.push_back(std::string(RG_TEST_TMP) + "/layout_example_" + std::to_string(i + 1) +
                        ".lua");
        std::ofstream(files.back()) << examples[i];
    }
    std::mt19937 rng(7);
    size_t layouts = 0;
    for (const auto& f : files) {
        LuaHost host(luaHostOptionsWithoutDevice());
        auto p = host.load(f);
        ASSERT_TRUE(p.has_value()) << f << ": " << p.error().message;
        for (const auto& l : p->layouts) {
            roundTrip(l, rng);
            ++layouts;
        }
    }
    EXPECT_GE(layouts, 3u);  // disney (deferred.lua, the README) and the README's compact layout
}

}  // namespace

namespace {

// A lighting path with a shading function and a material gets its deferred pass's shader
// generated (lighting.path_pass declares the pass): its layout unpacked from every target, by
// name, then the path's rgShade; a path without a material gets none.
TEST(LuaLayouts, EveryShadedPathGetsItsDeferredShader) {
    LuaHost host(luaHostOptionsWithoutDevice());
    auto p = host.load(std::string(RG_SOURCE_ROOT) + "/materials/examples/toon/pipeline.lua");
    ASSERT_TRUE(p.has_value()) << p.error().describe();
    const auto shaders = generateLightingShaders(*p);
    std::vector<std::string> names;
    for (const auto& [name, text] : shaders) names.push_back(name);
    EXPECT_EQ(names, (std::vector<std::string>{
                         "lighting_path_standard.frag", "lighting_path_clearcoat.frag",
                         "lighting_path_two_colour.frag", "lighting_path_sheen.frag",
                         "lighting_path_toon.frag"}));
    const std::string& toon = shaders.back().second;
    for (const char* part :
         {"#include \"gbuffer_toon.glsl\"", "toon/toon_shading.glsl\"", "uniform sampler2D GB3;",
          "uniform sampler2D depth;", "readonly buffer exposure { RgExposureState state; } ex;",
          "unpackGBuffer_toon(texelFetch(GB0, p, 0), texelFetch(GB1, p, 0), texelFetch(GB2, p, 0), "
          "texelFetch(GB3, p, 0))",
          "rgShade(g, position, rgViewDirection(position), p)"})
        EXPECT_NE(toon.find(part), std::string::npos) << part << "\n" << toon;
    // Without its material the toon path has nothing to decode: no shader.
    p->materials.pop_back();
    EXPECT_EQ(generateLightingShaders(*p).size(), 4u);
}

// lighting.path_pass names its path and class, or stops at the caller's line.
TEST(LuaLayouts, APathPassNamesItsPathAndClass) {
    const std::string file = std::string(RG_TEST_TMP) + "/path_pass_no_class.lua";
    std::ofstream(file) << "require \"pipelines.deferred\"\n"
                           "local lighting = require \"lighting\"\n"
                           "rg.pass \"lighting_x\" (lighting.path_pass { path = \"standard\" })\n";
    LuaHost host(luaHostOptionsWithoutDevice());
    auto p = host.load(file);
    ASSERT_FALSE(p.has_value());
    EXPECT_EQ(
        firstLine(p.error()),
        fs::relative(file, RG_SOURCE_ROOT).string() +
            ":3: lighting.path_pass: expected { path = \"PATH\", class = \"STENCIL_CLASS\" }");
}

}  // namespace
