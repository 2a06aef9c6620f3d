// G-buffer layouts without a GPU: placement and packed bits of the default (seed 000 tbl:2)
// layout, and the exact text of every layout error.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "layout/layout.h"
#include "layout_test_util.h"

using namespace rg;
using namespace rg::test;

namespace {

std::string errorOf(const LayoutDesc& d) {
    auto r = analyzeLayout(d);
    return r ? std::string("(no error)") : r.error().message;
}

// ---------------------------------------------------------------------------------------------

TEST(Layout, EncodingNamesParse) {
    EXPECT_EQ(parseEncoding("oct"), Encoding::Oct);
    EXPECT_EQ(parseEncoding("float"), Encoding::Float);
    EXPECT_FALSE(parseEncoding("octa").has_value());
    EXPECT_EQ(encodingName(Encoding::Srgb), "srgb");
    EXPECT_EQ(encodingNameList(), "'unorm', 'snorm', 'srgb', 'oct', 'uint', 'float'");
}

TEST(Layout, DefaultDisneyPlacements) {
    auto r = analyzeLayout(defaultDisneyLayout());
    ASSERT_TRUE(r.has_value()) << r.error().message;
    const LayoutInfo& info = *r;
    ASSERT_EQ(info.channels.size(), 11u);
    struct Want {
        const char* name;
        uint32_t target, component, bitOffset, components, bitsPerComponent;
    };
    const Want want[] = {
        {"normal", 0, 0, 0, 2, 10},      {"smoothness", 0, 2, 0, 1, 10},
        {"materialId", 0, 3, 0, 1, 2},   {"baseColor", 1, 0, 0, 3, 8},
        {"materialData", 1, 3, 0, 1, 5}, {"normalExtra", 1, 3, 5, 1, 3},
        {"reserved", 2, 0, 0, 1, 8},     {"metalMask", 2, 1, 0, 1, 8},
        {"reflectance", 2, 2, 0, 1, 8},  {"ao", 2, 3, 0, 1, 8},
        {"emissive", 3, 0, 0, 3, 16},
    };
    for (size_t i = 0; i < 11; ++i) {
        const ChannelPlacement& p = info.channels[i];
        SCOPED_TRACE(want[i].name);
        EXPECT_EQ(info.channelDesc(i).name, want[i].name);
        EXPECT_EQ(info.find(want[i].name), static_cast<int>(i));
        EXPECT_EQ(p.target, want[i].target);
        EXPECT_EQ(p.component, want[i].component);
        EXPECT_EQ(p.bitOffset, want[i].bitOffset);
        EXPECT_EQ(p.components, want[i].components);
        EXPECT_EQ(p.bitsPerComponent, want[i].bitsPerComponent);
        for (uint32_t k = 0; k < p.components; ++k)  // the default layout has no split fields
            EXPECT_EQ(p.slots[k].component,
                      want[i].component + (want[i].bitsPerComponent < 8 ? 0 : k));
    }
    // normal is the only channel spanning two texel components: R and G of GB0.
    EXPECT_EQ(info.channels[0].slots[1].component, 1u);
    EXPECT_EQ(info.find("nope"), -1);
}

TEST(Layout, PackedBitsOfTheDefaultLayout) {
    auto info = analyzeLayout(defaultDisneyLayout());
    ASSERT_TRUE(info.has_value());
    std::vector<ChannelValue> v(11);
    v[0].v = {0, 0, 1, 0};        // normal +z -> octahedral (0, 0) -> unorm 0.5 -> 512 of 1023
    v[1].v = {0.25f};             // smoothness -> round(255.75) = 256
    v[2].u = {7};                 // materialId clamps to 3
    v[3].v = {1.0f, 0.0f, 2.0f};  // baseColor, clamped to [0, 1]
    v[4].u = {17};                // materialData in A bits 0..4
    v[5].u = {5};                 // normalExtra in A bits 5..7: 17 | 5 << 5 = 177
    v[6].v = {0.0f};
    v[7].v = {1.0f};
    v[8].v = {0.5f};                       // round(127.5 + 0.5) = 128
    v[9].v = {-3.0f};                      // ao clamps to 0
    v[10].v = {1.0f / 3.0f, 1e6f, -2.0f};  // emissive: half rounding, clamp to 65504
    auto t = packTexel(*info, v);
    ASSERT_EQ(t.size(), 4u);
    EXPECT_EQ(t[0].f[0], 512.0f / 1023.0f);
    EXPECT_EQ(t[0].f[1], 512.0f / 1023.0f);
    EXPECT_EQ(t[0].f[2], 256.0f / 1023.0f);
    EXPECT_EQ(t[0].f[3], 1.0f);
    EXPECT_EQ(t[1].f[0], 1.0f);
    EXPECT_EQ(t[1].f[1], 0.0f);
    EXPECT_EQ(t[1].f[2], 1.0f);
    EXPECT_EQ(t[1].f[3], 177.0f / 255.0f);
    EXPECT_EQ(t[2].f[1], 1.0f);
    EXPECT_EQ(t[2].f[2], 128.0f / 255.0f);
    EXPECT_EQ(t[2].f[3], 0.0f);
    EXPECT_EQ(t[3].f[0], 0.333251953125f);  // 1/3 as a half: 0x3555
    EXPECT_EQ(t[3].f[1], 65504.0f);
    EXPECT_EQ(t[3].f[2], -2.0f);
    EXPECT_EQ(t[3].f[3], 0.0f);
    auto back = unpackTexel(*info, t);
    EXPECT_EQ(back[2].u[0], 3u);
    EXPECT_EQ(back[4].u[0], 17u);
    EXPECT_EQ(back[5].u[0], 5u);
    EXPECT_NEAR(back[0].v[2], 1.0f, 1e-6f);
    EXPECT_NEAR(back[0].v[0], 0.0f, 1e-3f);
}

TEST(Layout, SnormZeroAndEndsAreExactAndIntegerTargetsKeep32Bits) {
    LayoutDesc d;
    d.name = "ints";
    d.targets = {{"ids",
                  Format::RGBA32Uint,
                  {ch("id", Encoding::Uint, 32), ch("s", Encoding::Snorm, 16),
                   ch("u", Encoding::Unorm, 16), ch("n", Encoding::Oct, 32),
                   ch("rgb", Encoding::Srgb, 24, 3), ch("pad", Encoding::Uint, 8)},
                  ""}};
    auto info = analyzeLayout(d);
    ASSERT_TRUE(info.has_value()) << info.error().message;
    EXPECT_EQ(info->channels[2].component, 1u);
    EXPECT_EQ(info->channels[2].bitOffset, 16u);
    for (float s : {-1.0f, 0.0f, 1.0f}) {
        std::vector<ChannelValue> v(6);
        v[0].u = {0xfffffffeu};
        v[1].v = {s};
        v[3].v = {0, 0, 1, 0};
        auto t = packTexel(*info, v);
        EXPECT_EQ(t[0].u[0], 0xfffffffeu);
        auto back = unpackTexel(*info, t);
        EXPECT_EQ(back[0].u[0], 0xfffffffeu);
        EXPECT_EQ(back[1].v[0], s);
    }
}

// Every error, with its exact text.
struct ErrorCase {
    const char* what;
    LayoutDesc desc;
    std::string message;
};

LayoutDesc disneyWith(auto&& edit) {
    LayoutDesc d = defaultDisneyLayout();
    edit(d);
    return d;
}

std::vector<ErrorCase> errorCases() {
    const std::string colourFormats =
        "'r8', 'rg8', 'rgba8', 'rgba8_srgb', 'rgb10a2', 'r11g11b10f', 'r16f', 'rg16f', 'rgba16f', "
        "'r32f', 'rg32f', "
        "'rgba32f', 'r8ui', 'r32ui', 'rgba32ui'";
    const std::string ident =
        "expected a GLSL identifier: a letter, then letters, digits and single '_' not at the end";
    std::vector<ErrorCase> cases;
    cases.push_back({"overflow",
                     disneyWith([](LayoutDesc& d) { d.targets[0].channels[2].bits = 4; }),
                     "layout 'disney' target 'GB0' (rgb10a2, 32 bits): channels need 34 bits"});
    cases.push_back({"overflow with the layout's origin", disneyWith([](LayoutDesc& d) {
                         d.origin = "scripts/deferred.lua:3";
                         d.targets[0].channels[2].bits = 4;
                     }),
                     "scripts/deferred.lua:3: layout 'disney' target 'GB0' (rgb10a2, 32 bits): "
                     "channels need 34 bits"});
    cases.push_back({"the channel's origin wins", disneyWith([](LayoutDesc& d) {
                         d.origin = "deferred.lua:3";
                         d.targets[1].origin = "deferred.lua:5";
                         d.targets[1].channels[1].origin = "deferred.lua:6";
                         d.targets[1].channels[1].name = "normal";
                     }),
                     "deferred.lua:6: layout 'disney' target 'GB1' (rgba8_srgb) channel 'normal': "
                     "duplicate channel name "
                     "(already in target 'GB0')"});
    cases.push_back({"the target's origin over the layout's", disneyWith([](LayoutDesc& d) {
                         d.origin = "deferred.lua:3";
                         d.targets[3].origin = "deferred.lua:9";
                         d.targets[3].channels.push_back(ch("extra", Encoding::Float, 32, 2));
                     }),
                     "deferred.lua:9: layout 'disney' target 'GB3' (rgba16f, 4 components): "
                     "channels need 5 components"});
    cases.push_back(
        {"straddle", disneyWith([](LayoutDesc& d) {
             d.targets[2].channels = {ch("a", Encoding::Unorm, 6), ch("b", Encoding::Unorm, 6)};
         }),
         "layout 'disney' target 'GB2' (rgba8) channel 'b': component 0 needs bits 6..11 of R, "
         "which has 8 "
         "bits; a channel component must lie inside one texel component (declare a padding channel "
         "to skip bits)"});
    cases.push_back(
        {"straddle of a multi-component channel", disneyWith([](LayoutDesc& d) {
             d.targets[0].channels = {ch("a", Encoding::Uint, 3), ch("v", Encoding::Unorm, 8, 2)};
         }),
         "layout 'disney' target 'GB0' (rgb10a2) channel 'v': component 1 needs bits 7..10 of R, "
         "which has 10 "
         "bits; a channel component must lie inside one texel component (declare a padding channel "
         "to skip bits)"});
    cases.push_back({"float channel in a unorm format", disneyWith([](LayoutDesc& d) {
                         d.targets[2].channels[0] = ch("x", Encoding::Float, 8);
                     }),
                     "layout 'disney' target 'GB2' (rgba8) channel 'x': a float channel needs a "
                     "float format; expected one "
                     "of: 'r11g11b10f', 'r16f', 'rg16f', 'rgba16f', 'r32f', 'rg32f', 'rgba32f'"});
    cases.push_back({"unorm channel in a float format", disneyWith([](LayoutDesc& d) {
                         d.targets[3].channels.push_back(ch("x", Encoding::Unorm, 16));
                     }),
                     "layout 'disney' target 'GB3' (rgba16f) channel 'x': rgba16f takes only float "
                     "channels, got unorm"});
    cases.push_back({"unorm in R of an sRGB format", disneyWith([](LayoutDesc& d) {
                         d.targets[1].channels[0] = ch("x", Encoding::Unorm, 8);
                     }),
                     "layout 'disney' target 'GB1' (rgba8_srgb) channel 'x': R, G and B of "
                     "rgba8_srgb take only an srgb "
                     "channel (the hardware sRGB-encodes them), got unorm"});
    cases.push_back(
        {"srgb channel of 5-bit components in an sRGB format",
         disneyWith([](LayoutDesc& d) { d.targets[1].channels[0].bits = 15; }),
         "layout 'disney' target 'GB1' (rgba8_srgb) channel 'baseColor': an srgb channel in "
         "rgba8_srgb fills R, "
         "G and B with 8 bits each (the hardware encodes them), got 3 x 5 bits from bit 0 of R"});
    cases.push_back({"depth format",
                     disneyWith([](LayoutDesc& d) { d.targets[3].format = Format::D32F; }),
                     "layout 'disney' target 'GB3' (d32f): depth/stencil formats cannot hold "
                     "G-buffer channels; expected "
                     "one of: " +
                         colourFormats});
    cases.push_back({"no format",
                     disneyWith([](LayoutDesc& d) { d.targets[3].format = Format::Undefined; }),
                     "layout 'disney' target 'GB3': no format; expected one of: " + colourFormats});
    cases.push_back({"duplicate channel",
                     disneyWith([](LayoutDesc& d) { d.targets[2].channels[0].name = "ao"; }),
                     "layout 'disney' target 'GB2' (rgba8) channel 'ao': duplicate channel name "
                     "(already in target 'GB2')"});
    cases.push_back({"duplicate target",
                     disneyWith([](LayoutDesc& d) { d.targets[2].name = "GB0"; }),
                     "layout 'disney' target 'GB0': duplicate target name (also target 0)"});
    cases.push_back({"bits not a multiple of the components",
                     disneyWith([](LayoutDesc& d) { d.targets[0].channels[0].bits = 21; }),
                     "layout 'disney' target 'GB0' (rgb10a2) channel 'normal': 21 bits do not "
                     "split into 2 components; "
                     "expected a multiple of 2"});
    cases.push_back(
        {"oct with 3 components",
         disneyWith([](LayoutDesc& d) { d.targets[0].channels[0].components = 3; }),
         "layout 'disney' target 'GB0' (rgb10a2) channel 'normal': oct takes 2 components, got 3"});
    cases.push_back({"srgb with 4 components",
                     disneyWith([](LayoutDesc& d) { d.targets[1].channels[0].components = 4; }),
                     "layout 'disney' target 'GB1' (rgba8_srgb) channel 'baseColor': srgb takes 3 "
                     "components, got 4"});
    cases.push_back(
        {"5 components", disneyWith([](LayoutDesc& d) {
             d.targets[2].channels[0] = ch("v", Encoding::Unorm, 5, 5);
         }),
         "layout 'disney' target 'GB2' (rgba8) channel 'v': 5 components; expected 1 to 4"});
    cases.push_back({"0 bits", disneyWith([](LayoutDesc& d) { d.targets[2].channels[0].bits = 0; }),
                     "layout 'disney' target 'GB2' (rgba8) channel 'reserved': 0 bits; expected at "
                     "least 1 bit"});
    cases.push_back({"1-bit snorm", disneyWith([](LayoutDesc& d) {
                         d.targets[2].channels[0] = ch("s", Encoding::Snorm, 1);
                     }),
                     "layout 'disney' target 'GB2' (rgba8) channel 's': snorm needs at least 2 "
                     "bits per component, got 1"});
    cases.push_back(
        {"32-bit unorm", disneyWith([](LayoutDesc& d) {
             d.targets[3] = {"GB3", Format::R32Uint, {ch("depth", Encoding::Unorm, 32)}, ""};
         }),
         "layout 'disney' target 'GB3' (r32ui) channel 'depth': unorm takes at most 24 bits per "
         "component, got 32"});
    cases.push_back({"float wider than the component",
                     disneyWith([](LayoutDesc& d) { d.targets[3].format = Format::R11G11B10F; }),
                     "layout 'disney' target 'GB3' (r11g11b10f) channel 'emissive': 16 bits per "
                     "component do not fit R "
                     "(11 bits); expected at most 11"});
    cases.push_back({"bad layout name", disneyWith([](LayoutDesc& d) { d.name = "my-layout"; }),
                     "layout 'my-layout': bad name; " + ident});
    cases.push_back({"layout name ending in '_'",
                     disneyWith([](LayoutDesc& d) { d.name = "disney_"; }),
                     "layout 'disney_': bad name; " + ident});
    cases.push_back(
        {"dotted channel name",
         disneyWith([](LayoutDesc& d) { d.targets[1].channels[2].name = "normal.extra"; }),
         "layout 'disney' target 'GB1' (rgba8_srgb) channel 'normal.extra': bad name; " + ident});
    cases.push_back({"double underscore",
                     disneyWith([](LayoutDesc& d) { d.targets[2].channels[0].name = "my__ao"; }),
                     "layout 'disney' target 'GB2' (rgba8) channel 'my__ao': bad name; " + ident});
    cases.push_back({"keyword channel name",
                     disneyWith([](LayoutDesc& d) { d.targets[2].channels[0].name = "sample"; }),
                     "layout 'disney' target 'GB2' (rgba8) channel 'sample': 'sample' is a GLSL "
                     "keyword; expected another name"});
    cases.push_back({"gl_ channel name",
                     disneyWith([](LayoutDesc& d) { d.targets[2].channels[0].name = "gl_Ao"; }),
                     "layout 'disney' target 'GB2' (rgba8) channel 'gl_Ao': names starting with "
                     "'gl_' are reserved by GLSL"});
    cases.push_back({"no targets", disneyWith([](LayoutDesc& d) { d.targets.clear(); }),
                     "layout 'disney': no targets; expected 1 to 8"});
    cases.push_back({"9 targets", disneyWith([](LayoutDesc& d) {
                         d.targets.clear();
                         for (int i = 0; i < 9; ++i)
                             d.targets.push_back({"T" + std::to_string(i),
                                                  Format::R8Unorm,
                                                  {ch("c" + std::to_string(i), Encoding::Unorm, 8)},
                                                  ""});
                     }),
                     "layout 'disney': 9 targets; expected at most 8 (colour attachments)"});
    cases.push_back({"target without channels",
                     disneyWith([](LayoutDesc& d) { d.targets[2].channels.clear(); }),
                     "layout 'disney' target 'GB2' (rgba8): no channels; expected at least one"});
    cases.push_back({"target without a name",
                     disneyWith([](LayoutDesc& d) { d.targets[2].name.clear(); }),
                     "layout 'disney': target 2 has no name"});
    return cases;
}

TEST(Layout, ErrorsNameLayoutTargetChannelAndExpectation) {
    for (const auto& c : errorCases()) {
        SCOPED_TRACE(c.what);
        EXPECT_EQ(errorOf(c.desc), c.message);
    }
    auto depth =
        analyzeLayout(disneyWith([](LayoutDesc& d) { d.targets[3].format = Format::D32FS8; }));
    ASSERT_FALSE(depth.has_value());
    EXPECT_EQ(depth.error().code, ErrorCode::Unsupported);
}

}  // namespace
