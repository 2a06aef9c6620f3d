// Graph compiler without a GPU, the plan it builds: lifetimes, aliasing, barrier snapshots and
// the DOT/JSON dumps.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "compiler_test_util.h"
#include "core/compiler.h"

namespace {

using namespace rg;
using namespace rg::test;

// One line per barrier: "pass res: srcStages/srcAccess -> dstStages/dstAccess Old->New [aliased from x]".
std::string barrierSnapshot(const Plan& plan) {
    std::string s;
    for (const auto& p : plan.passes) {
        for (const auto& b : p.barriers) {
            s += p.name + " " + plan.resources[b.resource].name + ": " +
                 stageMaskName(b.srcStages) + "/" + accessMaskName(b.srcAccess) + " -> " +
                 stageMaskName(b.dstStages) + "/" + accessMaskName(b.dstAccess) + " " +
                 layoutName(b.oldLayout) + "->" + layoutName(b.newLayout);
            if (b.aliasedFrom >= 0)
                s += " aliased from " + plan.resources[static_cast<size_t>(b.aliasedFrom)].name;
            s += "\n";
        }
    }
    return s;
}

// ---------------------------------------------------------------------------------------------
// Lifetimes

TEST(CompilerLifetimes, FirstLastSizesAndFlags) {
    GraphDesc g;
    g.resources = {
        texture("gb", Format::RGBA8Unorm),          texture("half", Format::RGBA16F, 0.5f),
        absolute("env", Format::RGBA16F, 256, 256), imported(buffer("lights", 4096)),
        exported(texture("hdr", Format::RGBA16F)),  texture("unused")};
    g.resources[2].texture.cube = true;
    g.resources[2].texture.mips = 0;
    g.passes = {raster("gbuffer", {color("gb")}),                              // 0
                compute("envmap", {storageWrite("env")}),                      // 1
                compute("downsample", {sampled("gb"), storageWrite("half")}),  // 2
                raster("lighting", {sampled("half"), sampled("env"),
                                    use("lights", Usage::UniformRead), color("hdr")}),  // 3
                raster("extra", {color("gb", true)})};                                  // culled
    Plan p = compileOk(g);
    EXPECT_EQ(passOrder(p),
              (std::vector<std::string>{"gbuffer", "envmap", "downsample", "lighting"}));
    ASSERT_EQ(p.resources.size(), 5u);  // "unused" is not in the plan

    const PlanResource& gb = p.resources[static_cast<size_t>(p.findResource("gb"))];
    EXPECT_EQ(gb.firstPass, 0);
    EXPECT_EQ(gb.lastPass, 2);
    EXPECT_TRUE(gb.transient);
    EXPECT_EQ(gb.width, 1280u);
    EXPECT_EQ(gb.height, 720u);
    EXPECT_EQ(gb.usageMask, (1u << static_cast<uint32_t>(Usage::ColorAttachment)) |
                                (1u << static_cast<uint32_t>(Usage::Sampled)));

    const PlanResource& half = p.resources[static_cast<size_t>(p.findResource("half"))];
    EXPECT_EQ(half.width, 640u);
    EXPECT_EQ(half.height, 360u);
    EXPECT_EQ(half.firstPass, 2);
    EXPECT_EQ(half.lastPass, 3);

    const PlanResource& env = p.resources[static_cast<size_t>(p.findResource("env"))];
    EXPECT_EQ(env.layers, 6u);
    EXPECT_EQ(env.mips, 9u);
    EXPECT_TRUE(env.cube);
    // 256² texels * 8 bytes * (1 + 1/4 + ...) * 6 faces, rounded up to 64 KiB.
    uint64_t texels = 0;
    for (uint32_t m = 0; m < 9; ++m) texels += uint64_t(256 >> m) * uint64_t(256 >> m);
    EXPECT_EQ(env.memory.size, (texels * 8 * 6 + 65535) / 65536 * 65536);

    const PlanResource& lights = p.resources[static_cast<size_t>(p.findResource("lights"))];
    EXPECT_FALSE(lights.transient);
    EXPECT_EQ(lights.heap, -1);

    const PlanResource& hdr = p.resources[static_cast<size_t>(p.findResource("hdr"))];
    EXPECT_FALSE(hdr.transient);
    EXPECT_EQ(hdr.firstPass, 3);
    EXPECT_EQ(hdr.lastPass, 3);
}

TEST(CompilerLifetimes, ExportedLivesToTheLastPassAndOutputScaleFloorsAtOne) {
    GraphDesc g;
    g.resources = {exported(texture("early")), exported(texture("tiny", Format::R8Unorm, 0.0001f)),
                   exported(texture("late"))};
    g.passes = {raster("a", {color("early")}), compute("b", {storageWrite("tiny")}),
                raster("c", {color("late")})};
    Plan p = compileOk(g);
    EXPECT_EQ(p.resources[0].firstPass, 0);
    EXPECT_EQ(p.resources[0].lastPass, 2);
    EXPECT_EQ(p.resources[1].width, 1u);
    EXPECT_EQ(p.resources[1].height, 1u);
}

// ---------------------------------------------------------------------------------------------
// Aliasing

GraphDesc chainGraph() {
    // a: [0,1], b: [1,2], c: [2,3]: a and c never live together.
    GraphDesc g;
    g.resources = {texture("a"), texture("b"), texture("c"), exported(texture("out"))};
    g.passes = {raster("p0", {color("a")}), raster("p1", {sampled("a"), color("b")}),
                raster("p2", {sampled("b"), color("c")}),
                raster("p3", {sampled("c"), color("out")})};
    return g;
}

TEST(CompilerAlias, DisjointLifetimesShareMemory) {
    Plan p = compileOk(chainGraph());
    const PlanResource& a = p.resources[0];
    const PlanResource& b = p.resources[1];
    const PlanResource& c = p.resources[2];
    ASSERT_EQ(p.heaps.size(), 1u);
    EXPECT_EQ(a.heap, 0);
    EXPECT_EQ(c.heap, 0);
    EXPECT_EQ(a.offset, 0u);
    EXPECT_EQ(c.offset, 0u);
    EXPECT_EQ(b.offset, a.memory.size);  // overlaps both in time
    EXPECT_EQ(p.heaps[0].size, 2 * a.memory.size);
    EXPECT_EQ(p.transientBytesAliased, 2 * a.memory.size);
    EXPECT_EQ(p.transientBytesUnaliased, 3 * a.memory.size);
    // The first barrier of c discards a's contents.
    ASSERT_FALSE(p.passes[2].barriers.empty());
    const Barrier& first = p.passes[2].barriers.back();
    EXPECT_EQ(p.resources[first.resource].name, "c");
    EXPECT_EQ(first.aliasedFrom, 0);
    EXPECT_EQ(first.oldLayout, Layout::Undefined);
}

TEST(CompilerAlias, AReconfigurationKeepsThePreviousPlacementWhereItIsValid) {
    // CompileOptions::previous: a transient keeps its offset when nothing live beside it is there,
    // and the heap keeps its size when the new placement fits (the executor then reuses the
    // images and the passes over them); a placement no longer valid is packed anew.
    Plan fresh = compileOk(chainGraph());
    const uint64_t unit = fresh.resources[0].memory.size;
    ASSERT_EQ(fresh.resources[2].offset, 0u);  // c shares a's memory
    Plan previous = fresh;
    previous.resources[2].offset = 2 * unit;  // c had a range of its own
    previous.resources[1].offset = 0;         // b sat where a is: invalid now, a lives beside it
    previous.heaps[0].size = 3 * unit;
    previous.resources[1].usageMask |= 1u << static_cast<uint32_t>(Usage::StorageWrite);
    CompileOptions o;
    o.previous = &previous;
    Plan p = compileOk(chainGraph(), o);
    EXPECT_EQ(p.resources[0].offset, 0u);        // a: kept
    EXPECT_EQ(p.resources[2].offset, 2 * unit);  // c: kept
    EXPECT_EQ(p.resources[1].offset, unit);      // b: moved beside a
    EXPECT_EQ(p.heaps[0].size, 3 * unit);        // the heap it fits in is kept whole
    EXPECT_EQ(p.transientBytesAliased, 3 * unit);
    // b keeps the usage it had (a resource of fewer usages would be a new image).
    EXPECT_NE(p.resources[1].usageMask & (1u << static_cast<uint32_t>(Usage::StorageWrite)), 0u);
    // Without it: the tightest packing.
    EXPECT_EQ(compileOk(chainGraph()).heaps[0].size, 2 * unit);
}

TEST(CompilerAlias, OverlappingLifetimesNeverShare) {
    GraphDesc g;
    g.resources = {texture("a"), texture("b"), exported(texture("out"))};
    g.passes = {raster("p0", {color("a")}), raster("p1", {color("b")}),
                raster("p2", {sampled("a"), sampled("b"), color("out")})};
    Plan p = compileOk(g);
    EXPECT_NE(p.resources[0].offset, p.resources[1].offset);
    EXPECT_EQ(p.transientBytesAliased, p.transientBytesUnaliased);
}

TEST(CompilerAlias, AliasOffGivesEveryTransientItsOwnRange) {
    CompileOptions o;
    o.alias = false;
    Plan p = compileOk(chainGraph(), o);
    EXPECT_EQ(p.transientBytesAliased, p.transientBytesUnaliased);
    std::vector<uint64_t> offsets;
    for (const auto& r : p.resources)
        if (r.transient) offsets.push_back(r.offset);
    ASSERT_EQ(offsets.size(), 3u);
    std::sort(offsets.begin(), offsets.end());
    EXPECT_EQ(std::unique(offsets.begin(), offsets.end()), offsets.end());
    for (const auto& pass : p.passes)
        for (const auto& b : pass.barriers) EXPECT_EQ(b.aliasedFrom, -1);
}

TEST(CompilerAlias, HeapsSplitByMemoryTypeAndKind) {
    GraphDesc g;
    g.resources = {texture("a"), texture("b", Format::RGBA16F), buffer("tiles", 100000),
                   exported(texture("out"))};
    g.passes = {
        raster("p0", {color("a")}),
        compute("p1", {sampled("a"), storageWrite("b"), storageWrite("tiles")}),
        compute("p2", {sampled("b"), use("tiles", Usage::StorageRead), storageWrite("out")})};
    CompileOptions o;
    o.memoryRequirements = [](const PlanResource& r) {
        MemoryRequirements m = estimateMemoryRequirements(r);
        m.memoryTypeBits = r.format == Format::RGBA16F ? 0x2u : 0x1u;
        return m;
    };
    Plan p = compileOk(g, o);
    ASSERT_EQ(p.heaps.size(), 3u);
    EXPECT_EQ(p.heaps[0].memoryTypeBits, 0x1u);
    EXPECT_FALSE(p.heaps[0].buffers);
    EXPECT_EQ(p.heaps[1].memoryTypeBits, 0x2u);
    EXPECT_TRUE(p.heaps[2].buffers);
    EXPECT_EQ(p.resources[static_cast<size_t>(p.findResource("tiles"))].memory.size,
              100096u);  // 256-aligned
    EXPECT_EQ(p.resources[static_cast<size_t>(p.findResource("out"))].heap, -1);
}

// ---------------------------------------------------------------------------------------------
// Barriers

TEST(CompilerBarriers, Snapshot) {
    GraphDesc g;
    g.resources = {texture("gb"),
                   texture("depth", Format::D32F),
                   exported(texture("hdr", Format::RGBA16F)),
                   imported(texture("env", Format::RGBA16F)),
                   texture("post"),
                   imported(texture("backbuffer"))};
    g.passes = {raster("gbuffer", {color("gb"), depth("depth")}),
                raster("lighting", {sampled("gb"), use("depth", Usage::DepthStencilRead),
                                    sampled("env"), color("hdr")}),
                compute("post", {sampled("hdr"), storageWrite("post")}),
                pass("present", PassType::Transfer,
                     {use("post", Usage::CopySrc), use("backbuffer", Usage::CopyDst)})};
    Plan p = compileOk(g);
    EXPECT_EQ(passOrder(p), (std::vector<std::string>{"gbuffer", "lighting", "post", "present"}));
    // post reuses gb's memory (same size, gb dead after lighting); depth overlaps both in time.
    EXPECT_EQ(p.resources[4].offset, p.resources[0].offset);
    EXPECT_EQ(
        barrierSnapshot(p),
        "gbuffer gb: None/None -> ColorAttachmentOutput/ColorAttachmentWrite "
        "Undefined->ColorAttachment\n"
        "gbuffer depth: None/None -> EarlyFragmentTests|LateFragmentTests/DepthStencilWrite "
        "Undefined->DepthStencilAttachment\n"
        "lighting gb: ColorAttachmentOutput/ColorAttachmentWrite -> VertexShader|FragmentShader/"
        "ShaderSampledRead ColorAttachment->ShaderReadOnly\n"
        "lighting depth: EarlyFragmentTests|LateFragmentTests/DepthStencilWrite -> "
        "EarlyFragmentTests|LateFragmentTests/DepthStencilRead "
        "DepthStencilAttachment->DepthStencilReadOnly\n"
        "lighting env: AllCommands/MemoryWrite -> VertexShader|FragmentShader/ShaderSampledRead "
        "ShaderReadOnly->ShaderReadOnly\n"
        "lighting hdr: None/None -> ColorAttachmentOutput/ColorAttachmentWrite "
        "Undefined->ColorAttachment\n"
        "post hdr: ColorAttachmentOutput/ColorAttachmentWrite -> ComputeShader/ShaderSampledRead "
        "ColorAttachment->ShaderReadOnly\n"
        "post post: "
        "VertexShader|FragmentShader|ColorAttachmentOutput/ShaderSampledRead|ColorAttachmentWrite "
        "-> ComputeShader/ShaderStorageWrite Undefined->General aliased from gb\n"
        "present post: ComputeShader/ShaderStorageWrite -> Copy/TransferRead General->TransferSrc\n"
        "present backbuffer: AllCommands/MemoryWrite -> Copy/TransferWrite "
        "ShaderReadOnly->TransferDst\n");

    const PlanResource& hdr = p.resources[2];
    EXPECT_EQ(hdr.finalLayout, Layout::ShaderReadOnly);
    EXPECT_EQ(hdr.finalStages, stage::ColorAttachmentOutput | stage::ComputeShader);
    // The imported backbuffer goes back to ShaderReadOnly after the last pass, ready for next frame.
    EXPECT_EQ(p.resources[5].finalLayout, Layout::ShaderReadOnly);
    ASSERT_EQ(p.finalBarriers.size(), 1u);
    EXPECT_EQ(p.finalBarriers[0].resource, 5u);
    EXPECT_EQ(p.finalBarriers[0].oldLayout, Layout::TransferDst);
    EXPECT_EQ(p.finalBarriers[0].srcAccess, access::TransferWrite);

    // The accesses carry the state each one needs.
    const PlanAccess& sampledGb = p.passes[1].accesses[0];
    EXPECT_EQ(sampledGb.layout, Layout::ShaderReadOnly);
    EXPECT_EQ(sampledGb.stages, stage::VertexShader | stage::FragmentShader);
    EXPECT_EQ(sampledGb.access, access::ShaderSampledRead);
}

TEST(CompilerBarriers, ReadAfterReadNeedsNoBarrierUnlessANewStageReads) {
    GraphDesc g;
    g.resources = {texture("t"), exported(texture("o1")), exported(texture("o2")),
                   exported(texture("o3")), exported(buffer("b", 256))};
    g.passes = {raster("write", {color("t")}), raster("read1", {sampled("t"), color("o1")}),
                raster("read2", {sampled("t"), color("o2")}),
                compute("read3", {sampled("t"), storageWrite("o3")})};
    Plan p = compileOk(g);
    auto has = [&](size_t pass, const std::string& res) {
        for (const auto& b : p.passes[pass].barriers)
            if (p.resources[b.resource].name == res) return true;
        return false;
    };
    EXPECT_TRUE(has(1, "t"));
    EXPECT_FALSE(has(2, "t"));  // same stages, same layout, already visible
    EXPECT_TRUE(has(3, "t"));   // compute has not seen the write yet
    const Barrier& b = p.passes[3].barriers[0];
    EXPECT_EQ(b.srcStages, stage::ColorAttachmentOutput);
    EXPECT_EQ(b.dstStages, stage::ComputeShader);
    EXPECT_EQ(b.oldLayout, Layout::ShaderReadOnly);
    EXPECT_EQ(b.newLayout, Layout::ShaderReadOnly);
}

TEST(CompilerBarriers, BuffersHaveNoLayoutAndWarWaitsForReaders) {
    GraphDesc g;
    g.resources = {buffer("tiles", 4096), exported(texture("o1")), exported(texture("o2"))};
    g.passes = {compute("build", {storageWrite("tiles")}),
                compute("use", {use("tiles", Usage::StorageRead), storageWrite("o1")}),
                compute("rebuild", {use("tiles", Usage::StorageReadWrite)}),
                raster("use2", {use("tiles", Usage::UniformRead), color("o2")})};
    Plan p = compileOk(g);
    EXPECT_EQ(
        barrierSnapshot(p),
        "use tiles: ComputeShader/ShaderStorageWrite -> ComputeShader/ShaderStorageRead "
        "Undefined->Undefined\n"
        "use o1: None/None -> ComputeShader/ShaderStorageWrite Undefined->General\n"
        "rebuild tiles: ComputeShader/ShaderStorageWrite -> "
        "ComputeShader/ShaderStorageRead|ShaderStorageWrite "
        "Undefined->Undefined\n"
        "use2 tiles: ComputeShader/ShaderStorageWrite -> VertexShader|FragmentShader/UniformRead "
        "Undefined->Undefined\n"
        "use2 o2: None/None -> ColorAttachmentOutput/ColorAttachmentWrite "
        "Undefined->ColorAttachment\n");
}

// ---------------------------------------------------------------------------------------------
// Dumps

TEST(CompilerDump, DotShowsPassesResourcesAndCulledReasons) {
    GraphDesc g;
    g.resources = {texture("ssao", Format::R8Unorm), texture("gb"),
                   exported(texture("hdr", Format::RGBA16F))};
    g.passes = {raster("gbuffer", {color("gb")}),
                compute("ssao", {sampled("gb"), storageWrite("ssao")}),
                raster("lighting", {sampled("gb"), color("hdr")})};
    Plan p = compileOk(g);
    const std::string dot = p.toDot();
    EXPECT_EQ(dot.rfind("digraph rgraph {", 0), 0u);
    EXPECT_NE(dot.find("\"p_gbuffer\" [shape=box"), std::string::npos);
    EXPECT_NE(dot.find("\"p_lighting\" [shape=box"), std::string::npos);
    EXPECT_NE(dot.find("\"p_ssao\" [shape=box, style=dashed, color=grey"), std::string::npos);
    EXPECT_NE(dot.find("culled: writes only 'ssao', which no kept pass reads and is not exported"),
              std::string::npos);
    EXPECT_NE(dot.find("\"r_hdr\" [shape=ellipse"), std::string::npos);
    EXPECT_NE(dot.find("rgba16f 1280x720"), std::string::npos);
    EXPECT_NE(dot.find("heap 0 @ 0"), std::string::npos);
    EXPECT_NE(dot.find("\"r_gb\" -> \"p_lighting\""), std::string::npos);   // read edge
    EXPECT_NE(dot.find("\"p_lighting\" -> \"r_hdr\""), std::string::npos);  // write edge
    EXPECT_LT(dot.find("\"p_gbuffer\" [shape"), dot.find("\"p_lighting\" [shape"));
    EXPECT_EQ(dot.back(), '\n');
}

TEST(CompilerDump, JsonHasTheDocumentedShape) {
    GraphDesc g = chainGraph();
    g.resources.push_back(texture("ssao", Format::R8Unorm));
    g.passes.push_back(compute("ssao", {storageWrite("ssao")}));
    Plan p = compileOk(g);
    const auto j = nlohmann::json::parse(p.toJson());
    EXPECT_EQ(j["output"]["w"], 1280);
    EXPECT_EQ(j["output"]["h"], 720);
    ASSERT_EQ(j["passes"].size(), 4u);
    EXPECT_EQ(j["passes"][0]["name"], "p0");
    EXPECT_EQ(j["passes"][0]["type"], "raster");
    EXPECT_EQ(j["passes"][0]["kind"], "fullscreen");
    EXPECT_EQ(j["passes"][1]["accesses"][0]["resource"], "a");
    EXPECT_EQ(j["passes"][1]["accesses"][0]["usage"], "Sampled");
    EXPECT_EQ(j["passes"][1]["accesses"][0]["layout"], "ShaderReadOnly");
    EXPECT_EQ(j["passes"][1]["accesses"][0]["stages"], "VertexShader|FragmentShader");
    EXPECT_EQ(j["passes"][1]["accesses"][0]["access"], "ShaderSampledRead");
    const auto& bar = j["passes"][2]["barriers"].back();
    EXPECT_EQ(bar["resource"], "c");
    EXPECT_EQ(bar["aliasedFrom"], "a");
    EXPECT_EQ(bar["oldLayout"], "Undefined");
    EXPECT_EQ(bar["newLayout"], "ColorAttachment");
    EXPECT_EQ(bar["dstStages"], "ColorAttachmentOutput");
    EXPECT_TRUE(j["passes"][0]["barriers"][0]["aliasedFrom"].is_null());
    ASSERT_EQ(j["culled"].size(), 1u);
    EXPECT_EQ(j["culled"][0]["name"], "ssao");
    EXPECT_EQ(j["culled"][0]["reason"],
              "writes only 'ssao', which no kept pass reads and is not exported");
    ASSERT_EQ(j["resources"].size(), 4u);
    EXPECT_EQ(j["resources"][3]["name"], "out");
    EXPECT_EQ(j["resources"][3]["exported"], true);
    EXPECT_EQ(j["resources"][3]["transient"], false);
    EXPECT_EQ(j["resources"][3]["heap"], -1);
    EXPECT_EQ(j["resources"][0]["format"], "rgba8");
    EXPECT_EQ(j["resources"][0]["firstPass"], 0);
    EXPECT_EQ(j["resources"][0]["lastPass"], 1);
    EXPECT_EQ(j["resources"][2]["offset"], 0);
    EXPECT_EQ(j["heaps"].size(), 1u);
    EXPECT_EQ(j["transientBytesAliased"].get<uint64_t>(), p.transientBytesAliased);
    EXPECT_EQ(j["transientBytesUnaliased"].get<uint64_t>(), p.transientBytesUnaliased);
    ASSERT_EQ(j["timings"].size(), 6u);
    const char* steps[] = {"validate", "cull", "schedule", "lifetimes", "alias", "barriers"};
    for (size_t i = 0; i < 6; ++i) {
        EXPECT_EQ(j["timings"][i]["step"], steps[i]);
        EXPECT_GE(j["timings"][i]["ms"].get<double>(), 0.0);
    }
}

TEST(CompilerDump, MaskNames) {
    EXPECT_EQ(stageMaskName(0), "None");
    EXPECT_EQ(stageMaskName(stage::VertexShader | stage::Copy), "VertexShader|Copy");
    EXPECT_EQ(accessMaskName(access::TransferRead | access::MemoryWrite),
              "TransferRead|MemoryWrite");
    EXPECT_STREQ(layoutName(Layout::DepthStencilReadOnly), "DepthStencilReadOnly");
    EXPECT_STREQ(usageName(Usage::StorageReadWrite), "StorageReadWrite");
    EXPECT_TRUE(usageReads(Usage::ColorAttachment, true));
    EXPECT_FALSE(usageReads(Usage::ColorAttachment, false));
    EXPECT_TRUE(usageWrites(Usage::CopyDst));
    EXPECT_FALSE(usageWrites(Usage::DepthStencilRead));
}

}  // namespace
