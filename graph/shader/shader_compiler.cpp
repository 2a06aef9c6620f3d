#include "shader/shader_compiler.h"
#include "core/hash.h"
#include "core/temp_path.h"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>
#include <glslang/build_info.h>
#include <spirv-tools/libspirv.hpp>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string_view>

namespace fs = std::filesystem;

namespace rg {

namespace {

// Bump when anything that changes the SPIR-V for the same sources changes (compiler options,
// target versions, preamble): old cache files then simply stop matching.
constexpr uint32_t kCacheFormatVersion = 1;
// Deeper nesting is almost certainly a file that includes itself.
constexpr size_t kMaxIncludeDepth = 32;
constexpr uint32_t kSpirvMagic = 0x07230203u;

void initGlslang() {
    // Static local: initialised once, thread-safe. FinalizeProcess is left to process exit.
    static const bool initialised = glslang::InitializeProcess();
    (void)initialised;
}

std::string passPrefix(const std::string& passName) {
    return passName.empty() ? std::string() : "pass '" + passName + "': ";
}

using Hasher = ContentHash;

std::string hex(uint64_t v) {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
    return buf;
}

// Absolute, lexically normal, without a trailing separator.
std::string normalPath(const fs::path& p) {
    std::error_code ec;
    fs::path abs = fs::absolute(p, ec);
    if (ec) abs = p;
    abs = abs.lexically_normal();
    if (!abs.has_filename() && abs.has_parent_path() && abs != abs.root_path())
        abs = abs.parent_path();
    return abs.string();
}

bool isFile(const fs::path& p) {
    std::error_code ec;
    return fs::is_regular_file(p, ec);
}

Result<std::string> readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return fail(ErrorCode::Io, "cannot read '" + path + "': " + std::strerror(errno));
    std::ostringstream ss;
    ss << in.rdbuf();
    if (in.bad()) return fail(ErrorCode::Io, "cannot read '" + path + "'");
    return ss.str();
}

std::string joinPaths(const std::vector<std::string>& dirs) {
    std::string s;
    for (const auto& d : dirs) s += (s.empty() ? "" : ", ") + d;
    return s.empty() ? std::string("no search roots") : s;
}

// Where an #include is looked up: the including file's folder (when that file is a real path),
// then the search roots in order. The same list is used by the hashing scan and by glslang.
class IncludePaths {
public:
    explicit IncludePaths(const std::vector<std::string>& roots) {
        for (const auto& r : roots) m_roots.push_back(normalPath(r));
    }

    std::vector<std::string> searched(const std::string& includer) const {
        std::vector<std::string> dirs;
        const fs::path inc(includer);
        if (inc.is_absolute()) dirs.push_back(normalPath(inc.parent_path()));
        for (const auto& r : m_roots)
            if (std::find(dirs.begin(), dirs.end(), r) == dirs.end()) dirs.push_back(r);
        return dirs;
    }

    // The absolute path of `name` included from `includer`, or "" when no folder has it.
    std::string resolve(const std::string& name, const std::string& includer) const {
        if (fs::path(name).is_absolute()) return isFile(name) ? normalPath(name) : std::string();
        for (const auto& dir : searched(includer)) {
            fs::path candidate = fs::path(dir) / name;
            if (isFile(candidate)) return normalPath(candidate);
        }
        return {};
    }

    const std::vector<std::string>& roots() const { return m_roots; }

private:
    std::vector<std::string> m_roots;
};

// The text of the source and of every file it includes, read once: what is hashed is exactly
// what glslang compiles, even if a file changes on disk in between.
struct SourceSet {
    std::string rootName;  // absolute path of the source file, or the virtual name
    std::string rootText;
    std::vector<std::string> files;                      // for hot reload, source first
    std::unordered_map<std::string, std::string> texts;  // absolute path -> text (includes)
};

// The `name` of an `#include "name"` / `#include <name>` line, or nullopt.
std::optional<std::string> includeName(std::string_view line) {
    size_t i = line.find_first_not_of(" \t");
    if (i == std::string_view::npos || line[i] != '#') return std::nullopt;
    i = line.find_first_not_of(" \t", i + 1);
    if (i == std::string_view::npos || line.substr(i, 7) != "include") return std::nullopt;
    i = line.find_first_not_of(" \t", i + 7);
    if (i == std::string_view::npos || (line[i] != '"' && line[i] != '<')) return std::nullopt;
    const char close = line[i] == '"' ? '"' : '>';
    const size_t end = line.find(close, i + 1);
    if (end == std::string_view::npos) return std::nullopt;
    return std::string(line.substr(i + 1, end - i - 1));
}

// Hashes the #include tree of `text` without running the preprocessor: every #include line
// counts, whatever #if it sits under, so the key over-approximates what glslang reads. A file
// that cannot be found is hashed as missing; glslang reports it if it is really needed.
void scanIncludes(const std::string& text, const std::string& includer, const IncludePaths& paths,
                  SourceSet& set, Hasher& h, size_t depth) {
    size_t pos = 0;
    while (pos < text.size()) {
        size_t end = text.find('\n', pos);
        if (end == std::string::npos) end = text.size();
        const auto name = includeName(std::string_view(text).substr(pos, end - pos));
        pos = end + 1;
        if (!name) continue;
        h.str(*name);
        const std::string resolved = paths.resolve(*name, includer);
        if (resolved.empty()) {
            h.str("<missing>");
            continue;
        }
        const auto seen = std::find(set.files.begin(), set.files.end(), resolved);
        if (seen != set.files.end()) {
            // Already hashed: its position in the list stands for its content.
            h.str("<seen>");
            h.u64(static_cast<uint64_t>(seen - set.files.begin()));
            continue;
        }
        auto content = readFile(resolved);
        if (!content) {
            h.str("<unreadable>");
            continue;
        }
        set.files.push_back(resolved);
        h.str(*content);
        auto& stored = set.texts[resolved] = std::move(*content);
        if (depth < kMaxIncludeDepth) scanIncludes(stored, resolved, paths, set, h, depth + 1);
    }
}

// Hands glslang the texts the scan read; a file the scan did not see is read here.
class Includer final : public glslang::TShader::Includer {
public:
    Includer(const IncludePaths& paths, SourceSet& set) : m_paths(paths), m_set(set) {}

    IncludeResult* includeLocal(const char* name, const char* includer, size_t depth) override {
        return include(name, includer, depth);
    }
    // <name> and "name" are searched alike: the including folder, then the roots.
    IncludeResult* includeSystem(const char* name, const char* includer, size_t depth) override {
        return include(name, includer, depth);
    }
    void releaseInclude(IncludeResult* r) override { delete r; }

private:
    IncludeResult* failure(std::string message) {
        // glslang prints headerData of a result with an empty headerName as the error.
        const std::string& m = m_messages.emplace_back(std::move(message));
        return new IncludeResult(std::string(), m.data(), m.size(), nullptr);
    }

    IncludeResult* include(const char* name, const char* includer, size_t depth) {
        if (depth > kMaxIncludeDepth)
            return failure("includes nest deeper than " + std::to_string(kMaxIncludeDepth) +
                           " levels at '" + name + "' (does a file include itself?)");
        const std::string resolved = m_paths.resolve(name, includer);
        if (resolved.empty())
            return failure(std::string("cannot find include '") + name +
                           "' (searched: " + joinPaths(m_paths.searched(includer)) + ")");
        auto it = m_set.texts.find(resolved);
        if (it == m_set.texts.end()) {
            auto content = readFile(resolved);
            if (!content) return failure(content.error().message);
            it = m_set.texts.emplace(resolved, std::move(*content)).first;
            if (std::find(m_set.files.begin(), m_set.files.end(), resolved) == m_set.files.end())
                m_set.files.push_back(resolved);
        }
        return new IncludeResult(resolved, it->second.data(), it->second.size(), nullptr);
    }

    const IncludePaths& m_paths;
    SourceSet& m_set;
    std::deque<std::string> m_messages;  // stable addresses for failure results
};

// glslang's info log -> one `path:line: message` line per error, with the file glslang was in
// (an include's absolute path inside an include). Warnings and the summary line are dropped.
std::vector<std::string> parseInfoLog(const std::string& log, const SourceSet& set) {
    std::vector<std::string> known = {set.rootName};
    for (const auto& [path, text] : set.texts) known.push_back(path);
    // Longest first so that "/a/b.glsl" is not taken for "/a/b" followed by text.
    std::sort(known.begin(), known.end(),
              [](const auto& a, const auto& b) { return a.size() > b.size(); });

    std::vector<std::string> out;
    std::istringstream in(log);
    std::string line;
    while (std::getline(in, line)) {
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
        std::string_view rest(line);
        if (rest.starts_with("ERROR: "))
            rest.remove_prefix(7);
        else if (rest.starts_with("INTERNAL ERROR: "))
            rest.remove_prefix(16);
        else
            continue;
        if (rest.find("compilation errors.") != std::string_view::npos ||
            rest.find("No code generated") != std::string_view::npos)
            continue;

        std::string file, lineNo;
        for (const auto& name : known) {
            if (!rest.starts_with(name) || rest.size() <= name.size() || rest[name.size()] != ':')
                continue;
            size_t i = name.size() + 1, j = i;
            while (j < rest.size() && rest[j] >= '0' && rest[j] <= '9') ++j;
            if (j == i || j >= rest.size() || rest[j] != ':') continue;
            file = name;
            lineNo = std::string(rest.substr(i, j - i));
            rest.remove_prefix(j + 1);
            break;
        }
        while (rest.starts_with(' ')) rest.remove_prefix(1);
        // glslang names the offending token first; an empty one says nothing.
        if (rest.starts_with("'' :")) {
            rest.remove_prefix(4);
            while (rest.starts_with(' ')) rest.remove_prefix(1);
        }

        std::string message(rest);
        // A failed include: glslang wraps the includer's text in "'#include' : ... for header
        // name: x"; keep only the includer's text.
        if (auto at = message.find("cannot find include '"); at != std::string::npos) {
            message = message.substr(at);
            if (auto tail = message.find(") for header name:"); tail != std::string::npos)
                message.resize(tail + 1);
        } else if (auto nest = message.find("includes nest deeper"); nest != std::string::npos) {
            message = message.substr(nest);
            if (auto tail = message.find(" for header name:"); tail != std::string::npos)
                message.resize(tail);
        }

        std::string formatted =
            file.empty() ? set.rootName + ": " + message : file + ":" + lineNo + ": " + message;
        if (std::find(out.begin(), out.end(), formatted) == out.end())
            out.push_back(std::move(formatted));
    }
    return out;
}

bool isIdentifier(std::string_view s) {
    if (s.empty()) return false;
    for (size_t i = 0; i < s.size(); ++i) {
        const char c = s[i];
        const bool alpha = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
        const bool digit = c >= '0' && c <= '9';
        if (!alpha && !(digit && i > 0)) return false;
    }
    return true;
}

EShLanguage toGlslang(ShaderStage s) {
    switch (s) {
        case ShaderStage::Vertex:
            return EShLangVertex;
        case ShaderStage::Fragment:
            return EShLangFragment;
        case ShaderStage::Compute:
            return EShLangCompute;
    }
    return EShLangCompute;
}

std::vector<uint32_t> loadCached(const std::string& path) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) return {};
    const std::streamoff size = in.tellg();
    if (size <= 0 || size % 4 != 0) return {};
    std::vector<uint32_t> words(static_cast<size_t>(size) / 4);
    in.seekg(0);
    if (!in.read(reinterpret_cast<char*>(words.data()), size)) return {};
    if (words.size() < 5 || words[0] != kSpirvMagic) return {};
    return words;
}

// Writes to a unique temporary name, then renames: readers (other processes too) see either no
// file or a whole one. A cache that cannot be written is not an error, only a slower next run.
void storeCached(const std::string& dir, const std::string& path,
                 const std::vector<uint32_t>& spirv) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    const std::string tmp = tempPathBeside(path);
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out) return;
        out.write(reinterpret_cast<const char*>(spirv.data()),
                  static_cast<std::streamsize>(spirv.size() * sizeof(uint32_t)));
        if (!out) {
            out.close();
            fs::remove(tmp, ec);
            return;
        }
    }
    fs::rename(tmp, path, ec);
    if (ec) fs::remove(tmp, ec);
}

}  // namespace

Result<void> validateSpirv(std::span<const uint32_t> spirv) {
    spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_3);
    std::vector<std::string> messages;
    tools.SetMessageConsumer(
        [&](spv_message_level_t, const char*, const spv_position_t& pos, const char* message) {
            messages.push_back("word " + std::to_string(pos.index) + ": " + message);
        });
    if (tools.Validate(spirv.data(), spirv.size())) return {};
    return fail(ErrorCode::InvalidInput, "SPIR-V does not validate for Vulkan 1.3",
                std::move(messages));
}

ShaderCompiler::ShaderCompiler(Options options) : m_options(std::move(options)) { initGlslang(); }

Result<ShaderModule> ShaderCompiler::compile(const ShaderRequest& req) {
    const std::string prefix = passPrefix(req.passName);
    std::vector<std::string> roots = m_options.includeDirs;
    if (!m_options.generatedDir.empty()) roots.push_back(m_options.generatedDir);
    const IncludePaths paths(roots);

    // Find and read the source.
    SourceSet set;
    const bool fromMemory = !req.source.empty();
    if (fromMemory) {
        set.rootName = req.virtualName.empty() ? std::string("<generated>") : req.virtualName;
        if (fs::path(set.rootName).is_absolute()) set.rootName = normalPath(set.rootName);
        set.rootText = req.source;
    } else {
        if (req.path.empty())
            return fail(ErrorCode::InvalidInput,
                        prefix + "shader request has neither a path nor a source");
        std::string found;
        if (fs::path(req.path).is_absolute()) {
            if (isFile(req.path)) found = normalPath(req.path);
        } else {
            for (const auto& root : paths.roots())
                if (isFile(fs::path(root) / req.path)) {
                    found = normalPath(fs::path(root) / req.path);
                    break;
                }
        }
        if (found.empty())
            return fail(ErrorCode::NotFound,
                        prefix + "cannot find shader '" + req.path + "'" +
                            (fs::path(req.path).is_absolute()
                                 ? std::string()
                                 : " (searched: " + joinPaths(paths.roots()) + ")"));
        auto text = readFile(found);
        if (!text) return fail(text.error().code, prefix + text.error().message);
        set.rootName = found;
        set.rootText = std::move(*text);
        set.files.push_back(found);
    }

    // Stage, entry point and defines.
    const std::optional<ShaderStage> stage = req.stage ? req.stage : stageFromPath(set.rootName);
    if (!stage)
        return fail(ErrorCode::InvalidInput,
                    prefix + "cannot tell the shader stage of '" + set.rootName +
                        "' from its extension (expected .vert, .frag or .comp, then .hlsl for "
                        "HLSL); set ShaderRequest::stage");
    if (!isIdentifier(req.entry))
        return fail(ErrorCode::InvalidInput,
                    prefix + "entry point '" + req.entry + "' is not a GLSL identifier");
    // HLSL through glslang's HLSL front end (its own #include; the preamble's defines alike).
    const bool hlsl = set.rootName.ends_with(".hlsl");
    std::string preamble = hlsl ? "" : "#extension GL_GOOGLE_include_directive : require\n";
    for (const auto& [name, value] : req.defines) {
        if (!isIdentifier(name))
            return fail(ErrorCode::InvalidInput,
                        prefix + "define '" + name + "' is not a GLSL identifier");
        if (value.find_first_of("\r\n") != std::string::npos)
            return fail(ErrorCode::InvalidInput,
                        prefix + "define '" + name + "' has a line break in its value");
        preamble += "#define " + name + " " + value + "\n";
    }

    // Cache key: everything that decides the SPIR-V.
    Hasher h;
    h.u64(kCacheFormatVersion);
    h.u64(GLSLANG_VERSION_MAJOR * 10000 + GLSLANG_VERSION_MINOR * 100 + GLSLANG_VERSION_PATCH);
    h.u64(static_cast<uint64_t>(*stage));
    if (hlsl) h.str("hlsl");
    h.str(req.entry);
    h.u64(m_options.debugInfo ? 1 : 0);
    if (m_options.debugInfo) h.str(set.rootName);  // debug info embeds the file name
    h.str(preamble);
    h.str(set.rootText);
    scanIncludes(set.rootText, set.rootName, paths, set, h, 0);
    if (m_options.debugInfo)
        for (const auto& f : set.files) h.str(f);  // so do the includes' names

    ShaderModule module;
    module.stage = *stage;
    module.entry = req.entry;
    module.hash = h.value();

    if (auto it = m_memory.find(module.hash); it != m_memory.end()) {
        module = it->second;
        module.files = set.files;
        module.fromCache = true;
        ++m_stats.hits;
        return module;
    }

    const std::string cachePath =
        m_options.cacheDir.empty()
            ? std::string()
            : (fs::path(m_options.cacheDir) / (hex(module.hash) + ".spv")).string();
    if (!cachePath.empty()) {
        if (auto words = loadCached(cachePath); !words.empty()) {
            // A damaged or foreign file fails here and is simply recompiled and overwritten.
            auto reflection = reflectSpirv(words);
            if (reflection && reflection->stageMask == stageBit(*stage)) {
                module.spirv = std::move(words);
                module.reflection = std::move(*reflection);
                module.files = set.files;
                m_memory[module.hash] = module;
                module.fromCache = true;
                ++m_stats.hits;
                return module;
            }
        }
    }

    // glslang.
    ++m_stats.misses;
    const auto start = std::chrono::steady_clock::now();
    const auto elapsed = [&] {
        m_stats.compileMs +=
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
    };
    const auto compileFailure = [&](const std::string& log) {
        std::vector<std::string> lines = parseInfoLog(log, set);
        if (lines.empty()) lines.push_back(set.rootName + ": " + (log.empty() ? "failed" : log));
        std::string message;
        for (const auto& l : lines) message += (message.empty() ? "" : "\n") + prefix + l;
        return fail(ErrorCode::InvalidInput, std::move(message));
    };
    if (set.rootText.size() > static_cast<size_t>(std::numeric_limits<int>::max()))
        return fail(ErrorCode::InvalidInput, prefix + set.rootName + ": source too large");

    const EShLanguage lang = toGlslang(*stage);
    glslang::TShader shader(lang);
    const char* strings[] = {set.rootText.c_str()};
    const int lengths[] = {static_cast<int>(set.rootText.size())};
    const char* names[] = {set.rootName.c_str()};
    shader.setStringsWithLengthsAndNames(strings, lengths, names, 1);
    shader.setPreamble(preamble.c_str());
    shader.setEntryPoint(req.entry.c_str());
    if (req.entry != "main") shader.setSourceEntryPoint(req.entry.c_str());
    shader.setEnvInput(hlsl ? glslang::EShSourceHlsl : glslang::EShSourceGlsl, lang,
                       glslang::EShClientVulkan, 100);
    if (hlsl) {
        // Resources are bound by name, so their registers may be left out: glslang numbers
        // what has none. A Texture2D and the SamplerState it is sampled with become one combined
        // image sampler, as rgraph binds them (the sampler's filter is the pass's `filter`).
        shader.setAutoMapBindings(true);
        shader.setAutoMapLocations(true);
        shader.setTextureSamplerTransformMode(EShTexSampTransUpgradeTextureRemoveSampler);
    }
    shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_3);
    shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_6);
    if (m_options.debugInfo) shader.setDebugInfo(true);
    // Cascading errors: report every error, not only the first (glslang otherwise stops at the
    // first one, and inside an include that early stop shows up as a bogus syntax error in the
    // including file).
    int flags = EShMsgSpvRules | EShMsgVulkanRules | EShMsgCascadingErrors;
    if (hlsl) flags |= EShMsgReadHlsl;
    if (m_options.debugInfo) flags |= EShMsgDebugInfo;
    const auto messages = static_cast<EShMessages>(flags);
    Includer includer(paths, set);
    if (!shader.parse(GetDefaultResources(), /* defaultVersion= */ hlsl ? 100 : 460, ENoProfile,
                      /* forceDefaultVersionAndProfile= */ false, /* forwardCompatible= */ false,
                      messages, includer)) {
        elapsed();
        return compileFailure(shader.getInfoLog());
    }
    glslang::TProgram program;
    program.addShader(&shader);
    if (!program.link(messages)) {
        elapsed();
        return compileFailure(program.getInfoLog());
    }
    if (hlsl && !program.mapIO()) {  // numbers the resources that name no register
        elapsed();
        return compileFailure(program.getInfoLog());
    }
    glslang::SpvOptions spvOptions;
    spvOptions.generateDebugInfo = m_options.debugInfo;
    spvOptions.disableOptimizer = true;  // drivers optimise; keeps reflection names intact
    spv::SpvBuildLogger logger;
    std::vector<unsigned int> words;
    glslang::GlslangToSpv(*program.getIntermediate(lang), words, &logger, &spvOptions);
    elapsed();
    if (words.empty())
        return fail(
            ErrorCode::InvalidInput,
            prefix + set.rootName + ": SPIR-V generation failed: " + logger.getAllMessages());
    module.spirv.assign(words.begin(), words.end());

    auto reflection = reflectSpirv(module.spirv);
    if (!reflection)
        return fail(reflection.error().code,
                    prefix + set.rootName + ": " + reflection.error().message);
    module.reflection = std::move(*reflection);
    module.files = set.files;

    if (!cachePath.empty()) storeCached(m_options.cacheDir, cachePath, module.spirv);
    m_memory[module.hash] = module;
    return module;
}

}  // namespace rg
