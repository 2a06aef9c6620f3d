// The shader module without a GPU: glslang compilation, #include and defines, error text,
// reflection from SPIR-V, pipeline-layout merging and the SPIR-V cache.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "shader/reflection.h"
#include "shader/shader_compiler.h"

namespace fs = std::filesystem;
using namespace rg;

namespace {

std::string norm(const fs::path& p) { return p.lexically_normal().string(); }

const std::string kShaders = norm(fs::path(RG_SOURCE_ROOT) / "tests/unit/shaders");

ShaderRequest request(std::string path, std::string passName = {}) {
    ShaderRequest r;
    r.path = std::move(path);
    r.passName = std::move(passName);
    return r;
}

ShaderRequest inMemory(std::string source, std::string virtualName, std::string passName = {}) {
    ShaderRequest r;
    r.source = std::move(source);
    r.virtualName = std::move(virtualName);
    r.passName = std::move(passName);
    return r;
}

ShaderCompiler::Options options(std::vector<std::string> dirs, std::string cacheDir = {}) {
    ShaderCompiler::Options o;
    o.includeDirs = std::move(dirs);
    o.cacheDir = std::move(cacheDir);
    return o;
}

// A folder of its own under RG_TEST_TMP (test cases may run as parallel processes).
fs::path freshTmp(const std::string& name) {
    fs::path dir = fs::path(RG_TEST_TMP) / ("shader_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

// A writable copy of tests/unit/shaders in `dir`/shaders.
std::string copyShaders(const fs::path& dir) {
    const fs::path dst = dir / "shaders";
    fs::copy(kShaders, dst, fs::copy_options::recursive);
    return norm(dst);
}

void writeText(const fs::path& p, const std::string& text) {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out << text;
    ASSERT_TRUE(out.good()) << p;
}

std::string readText(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// The name of the (single) OpEntryPoint of a SPIR-V module.
std::string entryPointName(const std::vector<uint32_t>& spirv) {
    for (size_t i = 5; i < spirv.size();) {
        const uint32_t count = spirv[i] >> 16, opcode = spirv[i] & 0xffffu;
        if (count == 0) break;
        if (opcode == 15 /* OpEntryPoint */ && i + 3 < spirv.size())
            return std::string(reinterpret_cast<const char*>(&spirv[i + 3]));
        i += count;
    }
    return {};
}

bool hasOpcode(const std::vector<uint32_t>& spirv, uint32_t wanted) {
    for (size_t i = 5; i < spirv.size();) {
        const uint32_t count = spirv[i] >> 16;
        if (count == 0) break;
        if ((spirv[i] & 0xffffu) == wanted) return true;
        i += count;
    }
    return false;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Compilation and reflection

TEST(ShaderCompiler, CompilesComputeShaderToValidSpirv) {
    ShaderCompiler compiler(options({kShaders}));
    auto m = compiler.compile(request("blur.comp", "blur"));
    ASSERT_TRUE(m) << m.error().describe();
    ASSERT_GE(m->spirv.size(), 5u);
    EXPECT_EQ(m->spirv[0], 0x07230203u);
    EXPECT_EQ(m->spirv[1], 0x00010600u) << "SPIR-V 1.6";
    auto valid = validateSpirv(m->spirv);
    EXPECT_TRUE(valid) << valid.error().describe();
    EXPECT_EQ(m->stage, ShaderStage::Compute);
    EXPECT_EQ(m->entry, "main");
    EXPECT_EQ(entryPointName(m->spirv), "main");
    EXPECT_FALSE(m->fromCache);
    EXPECT_EQ(m->reflection.stageMask, stageBit(ShaderStage::Compute));
}

TEST(ShaderCompiler, ReflectsComputeBindings) {
    ShaderCompiler compiler(options({kShaders}));
    auto m = compiler.compile(request("blur.comp"));
    ASSERT_TRUE(m) << m.error().describe();
    const ShaderReflection& r = m->reflection;
    const uint32_t comp = stageBit(ShaderStage::Compute);

    ASSERT_EQ(r.bindings.size(), 5u);
    const ReflectedBinding& out = r.bindings[0];
    EXPECT_EQ(out.set, 0u);
    EXPECT_EQ(out.binding, 0u);
    EXPECT_EQ(out.type, DescriptorType::StorageImage);
    EXPECT_EQ(out.name, "outImage");
    EXPECT_EQ(out.count, 1u);
    EXPECT_EQ(out.stageMask, comp);
    EXPECT_EQ(out.imageFormat, "rgba16f");
    EXPECT_FALSE(out.nonWritable);  // writeonly
    EXPECT_TRUE(out.nonReadable);

    const ReflectedBinding& tex = r.bindings[1];
    EXPECT_EQ(tex.set, 0u);
    EXPECT_EQ(tex.binding, 1u);
    EXPECT_EQ(tex.type, DescriptorType::CombinedImageSampler);
    EXPECT_EQ(tex.name, "inTex");
    EXPECT_EQ(tex.count, 1u);
    EXPECT_EQ(tex.imageFormat, "");

    const ReflectedBinding& luts = r.bindings[2];
    EXPECT_EQ(luts.binding, 2u);
    EXPECT_EQ(luts.type, DescriptorType::CombinedImageSampler);
    EXPECT_EQ(luts.name, "luts");
    EXPECT_EQ(luts.count, 3u);

    const ReflectedBinding& params = r.bindings[3];
    EXPECT_EQ(params.set, 1u);
    EXPECT_EQ(params.binding, 0u);
    EXPECT_EQ(params.type, DescriptorType::UniformBuffer);
    EXPECT_EQ(params.name, "Params");
    EXPECT_EQ(params.stageMask, comp);

    const ReflectedBinding& weights = r.bindings[4];
    EXPECT_EQ(weights.set, 1u);
    EXPECT_EQ(weights.binding, 1u);
    EXPECT_EQ(weights.type, DescriptorType::StorageBuffer);
    EXPECT_EQ(weights.name, "Weights");
    EXPECT_TRUE(weights.nonWritable);  // readonly
    EXPECT_FALSE(weights.nonReadable);
    EXPECT_EQ(weights.blockSize, 4u);  // uint count; the unsized array adds nothing
    ASSERT_EQ(weights.members.size(), 2u);
    EXPECT_EQ(weights.members[1], (BlockMember{"weights", 4, 0}));

    EXPECT_EQ(r.find("Params"), &params);
    EXPECT_EQ(r.find(0, 2), &luts);
    EXPECT_EQ(r.find(3, 0), nullptr);

    EXPECT_EQ(r.localSize, (std::array<uint32_t, 3>{8, 4, 1}));
    EXPECT_TRUE(r.colorOutputs.empty());
}

TEST(ShaderCompiler, ReflectsUniformBlockMembersAndPushConstants) {
    ShaderCompiler compiler(options({kShaders}));
    auto m = compiler.compile(request("blur.comp"));
    ASSERT_TRUE(m) << m.error().describe();
    const ReflectedBinding* params = m->reflection.find(1, 0);
    ASSERT_NE(params, nullptr);
    // std140, as commented in blur.comp.
    EXPECT_EQ(params->blockSize, 96u);
    const std::vector<BlockMember> expected = {
        {"tint", 0, 16},  {"exposure", 16, 4},   {"steps", 20, 4},
        {"texel", 24, 8}, {"transform", 32, 64},
    };
    EXPECT_EQ(params->members, expected);

    EXPECT_EQ(m->reflection.pushConstantSize, 12u);
    const std::vector<BlockMember> push = {{"size", 0, 8}, {"time", 8, 4}};
    EXPECT_EQ(m->reflection.pushConstants, push);
}

TEST(ShaderCompiler, ListsSourceAndIncludesForHotReload) {
    ShaderCompiler compiler(options({kShaders}));
    auto m = compiler.compile(request("blur.comp"));
    ASSERT_TRUE(m) << m.error().describe();
    // lib/constants.glsl is found through its includer's folder (lib/), not a search root.
    const std::vector<std::string> files = {kShaders + "/blur.comp", kShaders + "/lib/common.glsl",
                                            kShaders + "/lib/constants.glsl"};
    EXPECT_EQ(m->files, files);
}

TEST(ShaderCompiler, ReflectsVertexAndFragmentAndMerges) {
    ShaderCompiler compiler(options({kShaders}));
    auto vert = compiler.compile(request("tri.vert"));
    auto frag = compiler.compile(request("tri.frag"));
    ASSERT_TRUE(vert) << vert.error().describe();
    ASSERT_TRUE(frag) << frag.error().describe();
    EXPECT_EQ(vert->stage, ShaderStage::Vertex);
    EXPECT_EQ(frag->stage, ShaderStage::Fragment);
    EXPECT_TRUE(validateSpirv(vert->spirv));
    EXPECT_TRUE(validateSpirv(frag->spirv));

    EXPECT_EQ(vert->reflection.pushConstantSize, 64u);
    EXPECT_EQ(frag->reflection.pushConstantSize, 80u);  // layout(offset = 64) vec4
    EXPECT_EQ(frag->reflection.colorOutputs, (std::vector<uint32_t>{0, 1}));
    EXPECT_EQ(vert->reflection.localSize, (std::array<uint32_t, 3>{0, 0, 0}));

    auto merged = mergeReflections(vert->reflection, frag->reflection, "gbuffer");
    ASSERT_TRUE(merged) << merged.error().describe();
    const uint32_t both = stageBit(ShaderStage::Vertex) | stageBit(ShaderStage::Fragment);
    EXPECT_EQ(merged->stageMask, both);
    ASSERT_EQ(merged->bindings.size(), 2u);
    EXPECT_EQ(merged->bindings[0].name, "Camera");
    EXPECT_EQ(merged->bindings[0].type, DescriptorType::UniformBuffer);
    EXPECT_EQ(merged->bindings[0].stageMask, both);
    EXPECT_EQ(merged->bindings[0].blockSize, 80u);
    EXPECT_EQ(merged->bindings[1].name, "albedo");
    EXPECT_EQ(merged->bindings[1].binding, 1u);
    EXPECT_EQ(merged->bindings[1].stageMask, stageBit(ShaderStage::Fragment));
    EXPECT_EQ(merged->pushConstantSize, 80u);
    const std::vector<BlockMember> push = {{"model", 0, 64}, {"color", 64, 16}};
    EXPECT_EQ(merged->pushConstants, push);
    EXPECT_EQ(merged->colorOutputs, (std::vector<uint32_t>{0, 1}));
}

// Whether a stage can discard: a fullscreen pass whose shader cannot (and with no test or blend)
// writes every pixel and leaves its targets uncleared (passes/builtin_kinds.cpp).
TEST(ShaderCompiler, ReflectsWhetherAStageCanDiscard) {
    ShaderCompiler compiler(options({kShaders}));
    auto opaque = compiler.compile(request("tri.frag"));
    auto cutout = compiler.compile(request("cutout.frag"));
    auto vert = compiler.compile(request("tri.vert"));
    ASSERT_TRUE(opaque && cutout && vert);
    EXPECT_FALSE(opaque->reflection.discards);
    EXPECT_TRUE(cutout->reflection.discards);
    EXPECT_FALSE(vert->reflection.discards);
    auto merged = mergeReflections(vert->reflection, cutout->reflection, "cutout");
    ASSERT_TRUE(merged) << merged.error().describe();
    EXPECT_TRUE(merged->discards);
}

TEST(ShaderCompiler, MergeRejectsConflictingBindingTypes) {
    ShaderCompiler compiler(options({kShaders}));
    auto vert = compiler.compile(request("tri.vert"));
    auto frag = compiler.compile(request("conflict.frag"));
    ASSERT_TRUE(vert) << vert.error().describe();
    ASSERT_TRUE(frag) << frag.error().describe();
    auto merged = mergeReflections(vert->reflection, frag->reflection, "shadow");
    ASSERT_FALSE(merged);
    EXPECT_EQ(merged.error().code, ErrorCode::InvalidInput);
    EXPECT_EQ(merged.error().message,
              "pass 'shadow': set 0 binding 0 is 'Camera' (uniform_buffer) in the vertex stage "
              "but 'shadowMap' (combined_image_sampler) in the fragment stage: one set/binding "
              "must have one descriptor type and array size in all stages of a pipeline");
}

TEST(ShaderCompiler, DefinesChangeOutputAndHash) {
    ShaderCompiler compiler(options({kShaders}));
    auto plain = compiler.compile(request("blur.comp"));
    ShaderRequest wide = request("blur.comp");
    wide.defines = {{"GROUP_X", "16"}};
    auto defined = compiler.compile(wide);
    ShaderRequest radius = request("blur.comp");
    radius.defines = {{"RADIUS", "5"}};
    auto bigger = compiler.compile(radius);
    ASSERT_TRUE(plain) << plain.error().describe();
    ASSERT_TRUE(defined) << defined.error().describe();
    ASSERT_TRUE(bigger) << bigger.error().describe();

    EXPECT_EQ(plain->reflection.localSize[0], 8u);
    EXPECT_EQ(defined->reflection.localSize[0], 16u);  // the define reached the source
    EXPECT_NE(plain->hash, defined->hash);
    EXPECT_NE(plain->spirv, defined->spirv);
    EXPECT_NE(plain->hash, bigger->hash);
    EXPECT_NE(plain->spirv, bigger->spirv);
    EXPECT_NE(defined->hash, bigger->hash);
    EXPECT_FALSE(defined->fromCache);
    EXPECT_FALSE(bigger->fromCache);
}

TEST(ShaderCompiler, DefinesKeepSourceLineNumbers) {
    ShaderCompiler compiler(options({}));
    ShaderRequest r = inMemory(
        "#version 460\n"
        "layout(local_size_x = 1) in;\n"
        "void main() {\n"
        "    float x = SCALE * missingThing;\n"
        "}\n",
        "gen/scaled.comp", "tonemap");
    r.defines = {{"SCALE", "2.0"}, {"EMPTY", ""}};
    auto m = compiler.compile(r);
    ASSERT_FALSE(m);
    EXPECT_EQ(m.error().message,
              "pass 'tonemap': gen/scaled.comp:4: 'missingThing' : undeclared identifier");
}

TEST(ShaderCompiler, CompilesInMemorySourceWithIncludes) {
    ShaderCompiler compiler(options({}));
    // An absolute virtual name: includes are searched in its folder.
    ShaderRequest r = inMemory(
        "#version 460\n"
        "#include \"lib/common.glsl\"\n"
        "layout(local_size_x = 64) in;\n"
        "layout(set = 0, binding = 3) buffer Out { float v[]; } outBuf;\n"
        "void main() { outBuf.v[gl_GlobalInvocationID.x] = kPi; }\n",
        kShaders + "/generated.comp");
    auto m = compiler.compile(r);
    ASSERT_TRUE(m) << m.error().describe();
    EXPECT_EQ(m->stage, ShaderStage::Compute);
    EXPECT_EQ(m->reflection.localSize[0], 64u);
    ASSERT_EQ(m->reflection.bindings.size(), 1u);
    EXPECT_EQ(m->reflection.bindings[0].type, DescriptorType::StorageBuffer);
    EXPECT_FALSE(m->reflection.bindings[0].nonWritable);
    const std::vector<std::string> files = {kShaders + "/lib/common.glsl",
                                            kShaders + "/lib/constants.glsl"};
    EXPECT_EQ(m->files, files);
}

TEST(ShaderCompiler, CustomEntryPoint) {
    ShaderCompiler compiler(options({}));
    ShaderRequest r = inMemory(
        "#version 460\n"
        "layout(local_size_x = 2) in;\n"
        "layout(set = 0, binding = 0) buffer B { uint x[]; } b;\n"
        "void clearPass() { b.x[gl_GlobalInvocationID.x] = 0u; }\n",
        "gen/clear.comp");
    r.entry = "clearPass";
    auto m = compiler.compile(r);
    ASSERT_TRUE(m) << m.error().describe();
    EXPECT_EQ(m->entry, "clearPass");
    EXPECT_EQ(entryPointName(m->spirv), "clearPass");
    EXPECT_TRUE(validateSpirv(m->spirv));
    EXPECT_EQ(m->reflection.bindings.size(), 1u);
}

TEST(ShaderCompiler, DebugInfoAddsLineInformation) {
    ShaderCompiler plain(options({kShaders}));
    ShaderCompiler::Options o = options({kShaders});
    o.debugInfo = true;
    ShaderCompiler debug(o);
    auto a = plain.compile(request("blur.comp"));
    auto b = debug.compile(request("blur.comp"));
    ASSERT_TRUE(a) << a.error().describe();
    ASSERT_TRUE(b) << b.error().describe();
    EXPECT_FALSE(hasOpcode(a->spirv, 8 /* OpLine */));
    EXPECT_TRUE(hasOpcode(b->spirv, 8 /* OpLine */));
    EXPECT_NE(a->hash, b->hash);
    EXPECT_EQ(a->reflection, b->reflection);
}

// ---------------------------------------------------------------------------------------------
// Errors: each kind of bad input, exact text

TEST(ShaderErrors, ErrorInIncludeNamesTheIncludeItsLineAndThePass) {
    ShaderCompiler compiler(options({kShaders}));
    auto m = compiler.compile(request("bad_include.comp", "bloom"));
    ASSERT_FALSE(m);
    EXPECT_EQ(m.error().code, ErrorCode::InvalidInput);
    EXPECT_EQ(m.error().message, "pass 'bloom': " + kShaders +
                                     "/lib/broken.glsl:5: 'undeclaredScale' : undeclared "
                                     "identifier");
}

TEST(ShaderErrors, MissingIncludeListsTheSearchedFolders) {
    ShaderCompiler compiler(options({kShaders, kShaders + "/lib"}));
    auto m = compiler.compile(request("missing_include.comp", "bloom"));
    ASSERT_FALSE(m);
    EXPECT_EQ(m.error().code, ErrorCode::InvalidInput);
    EXPECT_EQ(m.error().message, "pass 'bloom': " + kShaders +
                                     "/missing_include.comp:3: cannot find include "
                                     "'does_not_exist.glsl' (searched: " +
                                     kShaders + ", " + kShaders + "/lib)");
}

TEST(ShaderErrors, EveryErrorOnItsOwnLine) {
    ShaderCompiler compiler(options({}));
    auto m =
        compiler.compile(inMemory("#version 460\n"
                                  "layout(local_size_x = 1) in;\n"
                                  "void main() {\n"
                                  "    float a = notDeclaredA;\n"
                                  "\n"
                                  "    notDeclaredB = 2;\n"
                                  "}\n",
                                  "gen/multi.comp", "sky"));
    ASSERT_FALSE(m);
    EXPECT_EQ(m.error().message,
              "pass 'sky': gen/multi.comp:4: 'notDeclaredA' : undeclared identifier\n"
              "pass 'sky': gen/multi.comp:6: 'notDeclaredB' : undeclared identifier");
}

TEST(ShaderErrors, SyntaxErrorWithoutPassName) {
    ShaderCompiler compiler(options({}));
    auto m =
        compiler.compile(inMemory("layout(local_size_x = 1) in;\n"
                                  "void main() { int x = 1 }\n",
                                  "gen/syntax.comp"));
    ASSERT_FALSE(m);
    EXPECT_EQ(m.error().message,
              "gen/syntax.comp:2: syntax error, unexpected RIGHT_BRACE, expecting COMMA or "
              "SEMICOLON");
}

TEST(ShaderErrors, LinkErrorsAreReported) {
    ShaderCompiler compiler(options({}));
    auto m =
        compiler.compile(inMemory("#version 460\n"
                                  "layout(local_size_x = 1) in;\n"
                                  "void notMain() {}\n",
                                  "gen/nomain.comp", "copy"));
    ASSERT_FALSE(m);
    EXPECT_EQ(m.error().code, ErrorCode::InvalidInput);
    EXPECT_EQ(m.error().message,
              "pass 'copy': gen/nomain.comp: Linking compute stage: Missing entry point: Each "
              "stage requires one entry point");
}

TEST(ShaderErrors, MissingShaderFileIsNotFound) {
    ShaderCompiler compiler(options({kShaders, kShaders + "/lib"}));
    auto m = compiler.compile(request("nope.frag", "lighting"));
    ASSERT_FALSE(m);
    EXPECT_EQ(m.error().code, ErrorCode::NotFound);
    EXPECT_EQ(m.error().message, "pass 'lighting': cannot find shader 'nope.frag' (searched: " +
                                     kShaders + ", " + kShaders + "/lib)");
}

TEST(ShaderErrors, UnknownExtensionNeedsAnExplicitStage) {
    ShaderCompiler compiler(options({kShaders}));
    auto m = compiler.compile(request("lib/common.glsl", "post"));
    ASSERT_FALSE(m);
    EXPECT_EQ(m.error().message,
              "pass 'post': cannot tell the shader stage of '" + kShaders +
                  "/lib/common.glsl' from its extension (expected .vert, .frag or .comp, then "
                  ".hlsl for HLSL); set ShaderRequest::stage");
}

TEST(ShaderErrors, RejectsBadDefines) {
    ShaderCompiler compiler(options({kShaders}));
    ShaderRequest r = request("blur.comp", "blur");
    r.defines = {{"2FAST", "1"}};
    auto m = compiler.compile(r);
    ASSERT_FALSE(m);
    EXPECT_EQ(m.error().message, "pass 'blur': define '2FAST' is not a GLSL identifier");
    r.defines = {{"MULTI", "1\n#error injected"}};
    m = compiler.compile(r);
    ASSERT_FALSE(m);
    EXPECT_EQ(m.error().message, "pass 'blur': define 'MULTI' has a line break in its value");
}

TEST(ShaderErrors, ReflectionRejectsNonSpirv) {
    const std::vector<uint32_t> junk = {0xdeadbeef, 1, 2, 3, 4, 5};
    auto r = reflectSpirv(junk);
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().code, ErrorCode::InvalidInput);
    EXPECT_EQ(r.error().message,
              "not a SPIR-V module (6 words, magic 0xdeadbeef, expected 0x07230203)");
    EXPECT_FALSE(reflectSpirv({}));
}

// ---------------------------------------------------------------------------------------------
// SPIR-V cache

TEST(ShaderCache, SameRequestCompilesOnceInProcess) {
    ShaderCompiler compiler(options({kShaders}));  // no disk cache
    auto first = compiler.compile(request("blur.comp"));
    auto second = compiler.compile(request("blur.comp"));
    ASSERT_TRUE(first) << first.error().describe();
    ASSERT_TRUE(second) << second.error().describe();
    EXPECT_FALSE(first->fromCache);
    EXPECT_TRUE(second->fromCache);
    EXPECT_EQ(first->spirv, second->spirv);
    EXPECT_EQ(first->files, second->files);
    EXPECT_EQ(compiler.stats().misses, 1u);
    EXPECT_EQ(compiler.stats().hits, 1u);
    EXPECT_GT(compiler.stats().compileMs, 0.0);
}

TEST(ShaderCache, NewCompilerHitsTheDiskCache) {
    const fs::path tmp = freshTmp("disk_hit");
    const std::string shaders = copyShaders(tmp);
    const std::string cache = (tmp / "cache").string();

    ShaderCompiler first(options({shaders}, cache));
    auto a = first.compile(request("blur.comp"));
    ASSERT_TRUE(a) << a.error().describe();
    EXPECT_FALSE(a->fromCache);
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(a->hash));
    const fs::path file = fs::path(cache) / (std::string(hex) + ".spv");
    ASSERT_TRUE(fs::exists(file));
    EXPECT_EQ(fs::file_size(file), a->spirv.size() * 4);

    ShaderCompiler second(options({shaders}, cache));
    auto b = second.compile(request("blur.comp"));
    ASSERT_TRUE(b) << b.error().describe();
    EXPECT_TRUE(b->fromCache);
    EXPECT_EQ(b->hash, a->hash);
    EXPECT_EQ(b->spirv, a->spirv);
    EXPECT_EQ(b->reflection, a->reflection);
    EXPECT_EQ(b->files, a->files);
    EXPECT_EQ(second.stats().hits, 1u);
    EXPECT_EQ(second.stats().misses, 0u);
    EXPECT_EQ(second.stats().compileMs, 0.0);
    // No temporary files are left behind.
    size_t entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(cache)) ++entries;
    EXPECT_EQ(entries, 1u);
}

TEST(ShaderCache, EditingAnIncludedFileIsAMiss) {
    const fs::path tmp = freshTmp("edit_include");
    const std::string shaders = copyShaders(tmp);
    const std::string cache = (tmp / "cache").string();

    ShaderCompiler first(options({shaders}, cache));
    auto a = first.compile(request("blur.comp"));
    ASSERT_TRUE(a) << a.error().describe();

    // constants.glsl is two includes deep (blur.comp -> lib/common.glsl -> constants.glsl).
    const fs::path constants = fs::path(shaders) / "lib/constants.glsl";
    std::string text = readText(constants);
    const auto at = text.find("3.14159265");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 10, "3.0");
    writeText(constants, text);

    ShaderCompiler second(options({shaders}, cache));
    auto b = second.compile(request("blur.comp"));
    ASSERT_TRUE(b) << b.error().describe();
    EXPECT_FALSE(b->fromCache);
    EXPECT_NE(b->hash, a->hash);
    EXPECT_NE(b->spirv, a->spirv);
    EXPECT_EQ(second.stats().misses, 1u);

    // The same instance that saw the old text also notices the edit.
    auto c = first.compile(request("blur.comp"));
    ASSERT_TRUE(c) << c.error().describe();
    EXPECT_TRUE(c->fromCache);  // compiled by `second`, found on disk
    EXPECT_EQ(c->hash, b->hash);
    EXPECT_EQ(c->spirv, b->spirv);
}

TEST(ShaderCache, DamagedCacheFileIsRecompiled) {
    const fs::path tmp = freshTmp("damaged");
    const std::string cache = (tmp / "cache").string();
    ShaderCompiler first(options({kShaders}, cache));
    auto a = first.compile(request("tri.frag"));
    ASSERT_TRUE(a) << a.error().describe();
    ASSERT_EQ(std::distance(fs::directory_iterator(cache), fs::directory_iterator()), 1);
    const fs::path file = fs::directory_iterator(cache)->path();
    writeText(file, "not spir-v at all");  // also not a multiple of 4 bytes

    ShaderCompiler second(options({kShaders}, cache));
    auto b = second.compile(request("tri.frag"));
    ASSERT_TRUE(b) << b.error().describe();
    EXPECT_FALSE(b->fromCache);
    EXPECT_EQ(b->spirv, a->spirv);
    EXPECT_EQ(fs::file_size(file), a->spirv.size() * 4);  // rewritten whole
}

TEST(ShaderErrors, SelfIncludeIsAnErrorNotAHang) {
    const fs::path tmp = freshTmp("self_include");
    writeText(tmp / "loop.glsl", "// includes itself, no guard\n#include \"loop.glsl\"\n");
    ShaderCompiler compiler(options({tmp.string()}));
    auto m =
        compiler.compile(inMemory("#version 460\n"
                                  "layout(local_size_x = 1) in;\n"
                                  "#include \"loop.glsl\"\n"
                                  "void main() {}\n",
                                  "gen/loop.comp", "loop"));
    ASSERT_FALSE(m);
    const std::string first = m.error().message.substr(0, m.error().message.find('\n'));
    EXPECT_EQ(first, "pass 'loop': " + norm(tmp / "loop.glsl") +
                         ":2: includes nest deeper than 32 levels at 'loop.glsl' (does a file "
                         "include itself?)");
}

TEST(ShaderErrors, UnsupportedResourceKindIsNamed) {
    // A storage texel buffer is refused by name; a samplerBuffer reflects as a uniform texel
    // buffer (bound only for the scene's lights: passes/shader_program.cpp).
    ShaderCompiler compiler(options({}));
    auto compile = [&](const std::string& declaration, const std::string& body) {
        return compiler.compile(inMemory("#version 460\nlayout(local_size_x = 1) in;\n" +
                                             declaration + "\nvoid main() {" + body + "}\n",
                                         "gen/texel.comp", "lut"));
    };
    auto m = compile("layout(set = 0, binding = 0, r32f) uniform imageBuffer lut;", "");
    ASSERT_FALSE(m);
    EXPECT_EQ(m.error().code, ErrorCode::Unsupported);
    EXPECT_EQ(m.error().message,
              "pass 'lut': gen/texel.comp: texel buffer 'lut' is not supported (use a storage "
              "buffer; a samplerBuffer is read only from the scene's lights)");
    auto t = compile(
        "layout(set = 0, binding = 3) uniform samplerBuffer lut;\n"
        "layout(set = 0, binding = 0) buffer Out { vec4 v; } o;",
        " o.v = texelFetch(lut, 2); ");
    ASSERT_TRUE(t.has_value()) << t.error().describe();
    const ReflectedBinding* b = t->reflection.find("lut");
    ASSERT_NE(b, nullptr);
    EXPECT_EQ(b->type, DescriptorType::UniformTexelBuffer);
    EXPECT_EQ(b->binding, 3u);
    EXPECT_STREQ(toString(b->type), "uniform_texel_buffer");
}

TEST(ShaderCompiler, ReflectsSeparateImagesSamplersAndSpecializedGroupSize) {
    ShaderCompiler compiler(options({}));
    auto m = compiler.compile(
        inMemory("#version 460\n"
                 "layout(local_size_x_id = 0, local_size_y = 2) in;\n"
                 "layout(set = 0, binding = 0) uniform texture2D colorTex;\n"
                 "layout(set = 0, binding = 1) uniform sampler linearSampler;\n"
                 "layout(set = 2, binding = 5) uniform writeonly image2D targets[2];\n"
                 "void main() {\n"
                 "    vec4 c = textureLod(sampler2D(colorTex, linearSampler), vec2(0.5), 0.0);\n"
                 "    imageStore(targets[1], ivec2(gl_GlobalInvocationID.xy), c);\n"
                 "}\n",
                 "gen/separate.comp"));
    ASSERT_TRUE(m) << m.error().describe();
    const auto& b = m->reflection.bindings;
    ASSERT_EQ(b.size(), 3u);
    EXPECT_EQ(b[0].type, DescriptorType::SampledImage);
    EXPECT_EQ(b[0].name, "colorTex");
    EXPECT_EQ(b[1].type, DescriptorType::Sampler);
    EXPECT_EQ(b[1].name, "linearSampler");
    EXPECT_EQ(b[2].type, DescriptorType::StorageImage);
    EXPECT_EQ(b[2].set, 2u);
    EXPECT_EQ(b[2].binding, 5u);
    EXPECT_EQ(b[2].count, 2u);
    EXPECT_EQ(b[2].imageFormat, "");  // no format qualifier
    // local_size_x_id: the specialization constant's default (1).
    EXPECT_EQ(m->reflection.localSize, (std::array<uint32_t, 3>{1, 2, 1}));
}
