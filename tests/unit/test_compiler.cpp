// Graph compiler without a GPU, what it drops or refuses: culling, ordering and the exact error
// texts.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "compiler_test_util.h"
#include "core/compiler.h"

namespace {

using namespace rg;
using namespace rg::test;

std::string compileError(const GraphDesc& g, const CompileOptions& o = defaults()) {
    auto plan = compile(g, o);
    EXPECT_FALSE(plan.has_value()) << "expected an error";
    if (plan) return {};
    EXPECT_EQ(plan.error().code, ErrorCode::InvalidInput);
    return plan.error().message;
}

std::string culledReason(const Plan& p, const std::string& name) {
    for (const auto& c : p.culled)
        if (c.name == name) return c.reason;
    return "<not culled>";
}

// ---------------------------------------------------------------------------------------------
// Culling

TEST(CompilerCull, UnreadOutputIsCulledWithReason) {
    GraphDesc g;
    g.resources = {texture("ssao", Format::R8Unorm), exported(texture("hdr", Format::RGBA16F))};
    g.passes = {compute("ssao_pass", {storageWrite("ssao")}), raster("lighting", {color("hdr")})};
    Plan p = compileOk(g);
    EXPECT_EQ(passOrder(p), std::vector<std::string>{"lighting"});
    ASSERT_EQ(p.culled.size(), 1u);
    EXPECT_EQ(p.culled[0].name, "ssao_pass");
    EXPECT_EQ(p.culled[0].reason,
              "writes only 'ssao', which no kept pass reads and is not exported");
    // A culled pass's resources are not in the plan.
    EXPECT_EQ(p.findResource("ssao"), -1);
    EXPECT_EQ(p.findResource("hdr"), 0);
}

TEST(CompilerCull, CullingIsTransitiveAndListsEveryWrite) {
    GraphDesc g;
    g.resources = {texture("a"), texture("b"), texture("c"), exported(texture("out"))};
    g.passes = {raster("makeA", {color("a")}),
                raster("makeBC", {sampled("a"), color("b"), color("c")}),
                raster("final", {color("out")})};
    Plan p = compileOk(g);
    EXPECT_EQ(passOrder(p), std::vector<std::string>{"final"});
    EXPECT_EQ(culledReason(p, "makeA"),
              "writes only 'a', which no kept pass reads and is not exported");
    EXPECT_EQ(culledReason(p, "makeBC"),
              "writes only 'b' and 'c', which no kept pass reads and are not exported");
}

TEST(CompilerCull, SideEffectPassIsKeptAndKeepsItsInputs) {
    GraphDesc g;
    g.resources = {texture("ao", Format::R8Unorm), buffer("stats", 1024)};
    g.passes = {compute("ao", {storageWrite("ao")}), compute("histogram", {sampled("ao")}),
                compute("readback", {sampled("ao")})};
    g.passes[2].sideEffect = true;
    Plan p = compileOk(g);
    EXPECT_EQ(passOrder(p), (std::vector<std::string>{"ao", "readback"}));
    EXPECT_EQ(culledReason(p, "histogram"), "has no writes and no side effect");
}

TEST(CompilerCull, DisabledPassIsCulledAndReadingItsOnlyOutputIsAnError) {
    GraphDesc g;
    g.resources = {texture("bloom", Format::RGBA16F), exported(texture("hdr", Format::RGBA16F))};
    g.passes = {compute("bloom", {storageWrite("bloom")}), raster("tonemap", {color("hdr")})};
    g.passes[0].enabled = false;
    Plan p = compileOk(g);
    EXPECT_EQ(culledReason(p, "bloom"), "disabled");
    EXPECT_EQ(passOrder(p), std::vector<std::string>{"tonemap"});

    g.passes[1].accesses.insert(g.passes[1].accesses.begin(), sampled("bloom"));
    EXPECT_EQ(compileError(g),
              "pass 'tonemap' reads 'bloom', but its only writer 'bloom' is disabled");
}

// An output whose only writer is switched off is refused when it is switched off, naming the
// writer, rather than read back unwritten after the frame.
TEST(CompilerCull, AnOutputWhoseOnlyWriterIsDisabledIsAnError) {
    GraphDesc g;
    g.resources = {texture("pattern", Format::RGBA16F),
                   exported(texture("final", Format::RGBA16F))};
    g.passes = {compute("generate", {storageWrite("pattern")}),
                raster("show", {sampled("pattern"), color("final")})};
    compileOk(g);
    g.passes[1].enabled = false;
    EXPECT_EQ(compileError(g),
              "'final' is exported (an output or a capture) but not written: its only writer "
              "'show' is disabled");
    // Another writer that runs keeps it written.
    g.passes.push_back(raster("fallback", {color("final")}));
    compileOk(g);
}

TEST(CompilerCull, WritingAnImportedResourceIsARoot) {
    GraphDesc g;
    g.resources = {imported(texture("swapchain"))};
    g.passes = {raster("blit", {color("swapchain")})};
    Plan p = compileOk(g);
    EXPECT_EQ(passOrder(p), std::vector<std::string>{"blit"});
    EXPECT_FALSE(p.resources[0].transient);
    EXPECT_EQ(p.resources[0].heap, -1);
}

// A history (rg.resource's `history`) is read the frame after its keep pass writes it: the keep
// pass stays while a kept pass reads the history, and goes (with the reason) when none does —
// TAA switched off leaves no copy behind.
TEST(CompilerCull, AHistoryIsKeptWhileAKeptPassReadsIt) {
    ResourceDesc history = texture("taa_history", Format::RGBA16F);
    history.persistent = true;
    history.historyOf = "taa";
    GraphDesc g;
    g.resources = {texture("taa", Format::RGBA16F), history, exported(texture("display"))};
    g.passes = {raster("taa", {sampled("taa_history"), color("taa")}),
                raster("tonemap", {sampled("taa"), color("display")}),
                raster("taa_history_keep",
                       {use("taa", Usage::CopySrc), use("taa_history", Usage::CopyDst)})};
    Plan p = compileOk(g);
    EXPECT_EQ(passOrder(p), (std::vector<std::string>{"taa", "tonemap", "taa_history_keep"}));
    g.passes[0] = raster("taa", {color("taa")});  // nothing reads the history now
    p = compileOk(g);
    EXPECT_EQ(passOrder(p), (std::vector<std::string>{"taa", "tonemap"}));
    EXPECT_EQ(culledReason(p, "taa_history_keep"),
              "writes only 'taa_history', which no kept pass reads and is not exported");
}

// ---------------------------------------------------------------------------------------------
// Ordering

TEST(CompilerSchedule, DeclarationOrderIsStable) {
    GraphDesc g;
    g.resources = {exported(texture("a")), exported(texture("b")), exported(texture("c")),
                   texture("t")};
    g.passes = {raster("p0", {color("t")}), raster("p1", {color("a")}),
                raster("p2", {sampled("t"), color("b")}), raster("p3", {color("c")})};
    Plan p = compileOk(g);
    EXPECT_EQ(passOrder(p), (std::vector<std::string>{"p0", "p1", "p2", "p3"}));
    EXPECT_EQ(p.findPass("p2"), 2);
    EXPECT_EQ(p.findPass("nope"), -1);
}

TEST(CompilerSchedule, AfterMovesAPassBehindALaterOne) {
    GraphDesc g;
    g.resources = {exported(texture("a")), exported(texture("b")), exported(texture("c"))};
    g.passes = {raster("A", {color("a")}), raster("B", {color("b")}), raster("C", {color("c")})};
    g.passes[0].after = {"C"};
    Plan p = compileOk(g);
    EXPECT_EQ(passOrder(p), (std::vector<std::string>{"B", "C", "A"}));
}

TEST(CompilerSchedule, AfterKeepsTheNamedPass) {
    GraphDesc g;
    g.resources = {texture("scratch"), exported(texture("out"))};
    g.passes = {compute("warm", {storageWrite("scratch")}), raster("final", {color("out")})};
    g.passes[1].after = {"warm"};
    Plan p = compileOk(g);
    EXPECT_EQ(passOrder(p), (std::vector<std::string>{"warm", "final"}));
}

// ---------------------------------------------------------------------------------------------
// Error texts

TEST(CompilerErrors, Cycle) {
    GraphDesc g;
    g.resources = {exported(texture("w")), texture("r"), texture("s"), exported(texture("t"))};
    g.passes = {raster("W", {color("w")}), raster("X", {color("r")}),
                raster("Y", {sampled("r"), color("s")}), raster("Z", {sampled("s"), color("t")})};
    g.passes[1].after = {"Z"};
    EXPECT_EQ(compileError(g), "cycle between passes: 'X' -> 'Y' -> 'Z' -> 'X'");

    g.passes[1].after = {"X"};
    EXPECT_EQ(compileError(g), "cycle between passes: 'X' -> 'X'");
}

TEST(CompilerErrors, ReadBeforeWrite) {
    GraphDesc g;
    g.resources = {texture("ssao", Format::R8Unorm), exported(texture("hdr"))};
    g.passes = {raster("blur", {sampled("ssao"), color("hdr")})};
    EXPECT_EQ(compileError(g), "pass 'blur' reads 'ssao' before any pass writes it");

    g.passes.push_back(compute("ssao_pass", {storageWrite("ssao")}));
    EXPECT_EQ(compileError(g),
              "pass 'blur' reads 'ssao' before any pass writes it (first written by 'ssao_pass', "
              "declared later)");

    // Loading an attachment nobody wrote is a read too.
    GraphDesc l;
    l.resources = {exported(texture("hdr"))};
    l.passes = {raster("forward", {color("hdr", /* load= */ true)})};
    EXPECT_EQ(compileError(l), "pass 'forward' reads 'hdr' before any pass writes it");
}

TEST(CompilerErrors, ImportedResourcesCanBeReadFirst) {
    GraphDesc g;
    g.resources = {imported(texture("env", Format::RGBA16F)), exported(texture("hdr"))};
    g.passes = {raster("sky", {sampled("env"), color("hdr")})};
    compileOk(g);
}

TEST(CompilerErrors, TwoUnorderedWriters) {
    GraphDesc g;
    g.resources = {exported(texture("hdr", Format::RGBA16F))};
    g.passes = {raster("clear", {color("hdr")}), raster("draw", {color("hdr")})};
    EXPECT_EQ(compileError(g),
              "passes 'clear' and 'draw' both write 'hdr' with no order between them: make 'draw' "
              "load it or "
              "list 'clear' in its after");

    GraphDesc loaded = g;
    loaded.passes[1].accesses[0].load = true;
    EXPECT_EQ(passOrder(compileOk(loaded)), (std::vector<std::string>{"clear", "draw"}));

    GraphDesc ordered = g;
    ordered.passes[1].after = {"clear"};
    EXPECT_EQ(passOrder(compileOk(ordered)), (std::vector<std::string>{"clear", "draw"}));

    // Writing an imported resource twice is how a frame reuses what it was given.
    GraphDesc imp = g;
    imp.resources[0].imported = true;
    compileOk(imp);
}

TEST(CompilerErrors, UnknownResourceWithSuggestion) {
    GraphDesc g;
    g.resources = {texture("gbuffer0"), texture("gbuffer1"), exported(texture("hdr"))};
    g.passes = {raster("gbuffer", {color("gbuffer0"), color("gbuffer1")}),
                raster("lighting", {sampled("gbuffer0"), sampled("gbufer1"), color("hdr")})};
    g.passes[1].accesses[1].field = "passes.lighting.reads[1]";
    EXPECT_EQ(compileError(g),
              "pass 'lighting' field 'passes.lighting.reads[1]': unknown resource 'gbufer1' (did "
              "you mean "
              "'gbuffer1'?)");

    g.passes[1].accesses[1].field.clear();
    g.passes[1].accesses[1].resource = "shadowmap";
    EXPECT_EQ(compileError(g), "pass 'lighting' field 'accesses[1]': unknown resource 'shadowmap'");
}

TEST(CompilerErrors, UnknownAfterPass) {
    GraphDesc g;
    g.resources = {exported(texture("hdr"))};
    g.passes = {raster("lighting", {color("hdr")})};
    g.passes[0].after = {"gbufer"};
    g.passes.insert(g.passes.begin(), raster("gbuffer", {}));
    EXPECT_EQ(compileError(g),
              "pass 'lighting' field 'after[0]': unknown pass 'gbufer' (did you mean 'gbuffer'?)");
}

TEST(CompilerErrors, Feedback) {
    GraphDesc g;
    g.resources = {exported(texture("hdr", Format::RGBA16F))};
    g.passes = {raster("clear", {color("hdr")}),
                raster("bloom", {sampled("hdr"), color("hdr", true)})};
    EXPECT_EQ(compileError(g),
              "pass 'bloom' field 'accesses[1]': 'hdr' is used as ColorAttachment and also as "
              "Sampled (field "
              "'accesses[0]') in the same pass (feedback loop)");
}

TEST(CompilerErrors, SrgbStorage) {
    GraphDesc g;
    g.resources = {exported(texture("ldr", Format::RGBA8Srgb))};
    g.passes = {compute("tonemap", {storageWrite("ldr")})};
    EXPECT_EQ(compileError(g),
              "pass 'tonemap' field 'accesses[0]': 'ldr' has sRGB format 'rgba8_srgb', which "
              "cannot be used as "
              "StorageWrite (sRGB formats cannot be storage images; use a UNORM format and encode "
              "in the shader)");
}

TEST(CompilerErrors, DepthFormatAsColourAttachmentAndBack) {
    GraphDesc g;
    g.resources = {exported(texture("depth", Format::D32F))};
    g.passes = {raster("prepass", {color("depth")})};
    g.passes[0].accesses[0].field = "passes.prepass.color[0]";
    EXPECT_EQ(compileError(g),
              "pass 'prepass' field 'passes.prepass.color[0]': 'depth' has depth format 'd32f', "
              "which cannot be "
              "used as ColorAttachment (expected DepthStencilAttachment, DepthStencilRead, "
              "Sampled, CopySrc or "
              "CopyDst)");

    GraphDesc c;
    c.resources = {exported(texture("hdr", Format::RGBA16F))};
    c.passes = {raster("prepass", {depth("hdr")})};
    EXPECT_EQ(compileError(c),
              "pass 'prepass' field 'accesses[0]': 'hdr' has colour format 'rgba16f', which cannot "
              "be used as "
              "DepthStencilAttachment (needs a depth format: d16, d32f, d24_s8 or d32f_s8)");
}

TEST(CompilerErrors, KindAndBlendConflicts) {
    GraphDesc g;
    g.resources = {exported(buffer("lights", 4096))};
    g.passes = {raster("p", {sampled("lights")})};
    EXPECT_EQ(compileError(g),
              "pass 'p' field 'accesses[0]': 'lights' is a buffer, which cannot be used as Sampled "
              "(expected "
              "UniformRead, StorageRead, StorageWrite, StorageReadWrite, IndirectRead, CopySrc or "
              "CopyDst)");
    // Indirect commands: a buffer, read by a raster pass.
    GraphDesc ind;
    ind.resources = {buffer("commands", 4096), exported(texture("hdr"))};
    Access cmd{"commands", Usage::IndirectRead};
    ind.passes = {compute("write", {storageWrite("commands")}),
                  compute("draw", {cmd, storageWrite("hdr")})};
    EXPECT_EQ(compileError(ind),
              "pass 'draw' field 'accesses[0]': IndirectRead needs a raster pass (indirect draws), "
              "but 'draw' is a compute pass");
    GraphDesc tex;
    tex.resources = {texture("commands"), exported(texture("hdr"))};
    Access texCmd{"commands", Usage::IndirectRead};
    tex.passes = {raster("fill", {color("commands")}), raster("draw", {texCmd, color("hdr")})};
    EXPECT_EQ(compileError(tex),
              "pass 'draw' field 'accesses[0]': 'commands' is a texture, which cannot be used as "
              "IndirectRead (indirect commands live in buffers)");

    GraphDesc t;
    t.resources = {imported(texture("lut"))};
    t.passes = {raster("p", {use("lut", Usage::UniformRead)})};
    t.passes[0].sideEffect = true;
    EXPECT_EQ(compileError(t),
              "pass 'p' field 'accesses[0]': 'lut' is a texture, which cannot be used as "
              "UniformRead (uniform "
              "reads are for buffers)");

    GraphDesc b;
    b.resources = {exported(texture("ids", Format::R32Uint))};
    b.passes = {raster("ids", {color("ids")})};
    b.passes[0].params = Value(Value::Table{{"blend", Value(true)}});
    EXPECT_EQ(compileError(b),
              "pass 'ids' field 'accesses[0]': 'ids' has integer format 'r32ui', which cannot be a "
              "blended "
              "ColorAttachment (params.blend is set)");
    b.passes[0].params = Value(Value::Table{{"blend", Value(false)}});
    compileOk(b);

    GraphDesc a;
    a.resources = {exported(texture("hdr"))};
    a.passes = {compute("p", {color("hdr")})};
    EXPECT_EQ(compileError(a),
              "pass 'p' field 'accesses[0]': ColorAttachment needs a raster pass, but 'p' is a "
              "compute pass");
}

TEST(CompilerErrors, AttachmentSizeMismatch) {
    GraphDesc g;
    g.resources = {exported(texture("hdr", Format::RGBA16F)),
                   texture("half", Format::RGBA16F, 0.5f), texture("depth", Format::D32F)};
    g.passes = {raster("forward", {color("hdr"), depth("depth"), color("half")})};
    EXPECT_EQ(
        compileError(g),
        "pass 'forward': attachments differ in size: 'hdr' is 1280x720 but 'half' is 640x360");
}

TEST(CompilerErrors, ZeroSizes) {
    GraphDesc g;
    g.resources = {absolute("lut", Format::RGBA16F, 0, 32)};
    EXPECT_EQ(compileError(g),
              "resource 'lut': absolute size 0x32; width and height must be at least 1");

    GraphDesc b;
    b.resources = {buffer("lights", 0)};
    EXPECT_EQ(compileError(b), "resource 'lights': buffer size is 0 bytes; it must be at least 1");
}

TEST(CompilerErrors, NamesAndOrigins) {
    GraphDesc g;
    g.resources = {texture("a"), texture("a")};
    EXPECT_EQ(compileError(g), "resource 'a' is declared twice (resources[0] and resources[1])");

    GraphDesc p;
    p.passes = {raster("x", {}), raster("x", {})};
    EXPECT_EQ(compileError(p), "pass 'x' is declared twice (passes[0] and passes[1])");

    GraphDesc o;
    o.resources = {texture("hdr")};
    o.passes = {raster("x", {sampled("hdr")})};
    o.passes[0].origin = "deferred.lua:40";
    EXPECT_EQ(compileError(o), "deferred.lua:40: pass 'x' reads 'hdr' before any pass writes it");
}

TEST(CompilerErrors, TooManyMips) {
    GraphDesc g;
    g.resources = {absolute("env", Format::RGBA16F, 256, 256)};
    g.resources[0].texture.mips = 10;
    EXPECT_EQ(compileError(g),
              "resource 'env': 10 mips requested, but a 256x256 texture has at most 9");
}

}  // namespace
