// The Lua glue: the sandboxed state, `require`, limits, the rg.* declaration functions and
// the frame callback's ctx. Everything else (validation, the pipeline) is plain C++ in
// declarations.cpp and pipeline.cpp.
#include "lua_host.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "declarations.h"
#include "lua_host_impl.h"
#include "lua_sandbox.h"
#include "shaders/lib/limits.h"

namespace fs = std::filesystem;

namespace rg {

namespace {

const char* kModulesKey = "rgraph.modules";

std::string chunkName(const LuaHost::Impl& impl, const std::string& path) {
    std::error_code ec;
    fs::path abs = fs::weakly_canonical(path, ec);
    fs::path root = fs::weakly_canonical(impl.options.projectRoot, ec);
    std::string rel = fs::relative(abs, root, ec).string();
    if (ec || rel.empty() || rel.rfind("..", 0) == 0) return abs.string();
    return rel;
}

// Loads a text chunk from a file (binary chunks are refused).
Result<void> loadFile(LuaHost::Impl& impl, const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return fail(ErrorCode::NotFound, "cannot open script '" + path + "'");
    std::stringstream ss;
    ss << in.rdbuf();
    std::string text = ss.str();
    std::string name = "@" + chunkName(impl, path);
    if (luaL_loadbufferx(impl.L, text.data(), text.size(), name.c_str(), "t") != LUA_OK) {
        std::string msg = lua_tostring(impl.L, -1);
        lua_pop(impl.L, 1);
        return fail(ErrorCode::InvalidInput, msg);
    }
    std::string abs = fs::weakly_canonical(path).string();
    if (std::find(impl.files.begin(), impl.files.end(), abs) == impl.files.end())
        impl.files.push_back(abs);
    return {};
}

using host::callerOrigin;
using host::implOf;
using lua::pushValue;
using lua::toValue;

// Errors inside C functions are thrown as lua::ScriptError and raised by lua::guarded after
// every C++ object of the function is destroyed (lua_sandbox.h).
[[noreturn]] void raise(lua_State*, const std::string& msg) { throw lua::ScriptError{msg}; }
using lua::guarded;

bool validName(const std::string& n, bool allowDots) {
    if (n.empty()) return false;
    for (char c : n)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' ||
              (allowDots && c == '.')))
            return false;
    return true;
}

void recordDeclaration(lua_State* L, DeclKind kind, const std::string& module,
                       const std::string& name, const std::string& origin, int tableIndex) {
    if (!lua_istable(L, tableIndex))
        raise(L, origin + ": " + declKindName(kind) + " \"" + name +
                     "\": expected a table of fields, got " + luaL_typename(L, tableIndex));
    if (implOf(L).view && kind != DeclKind::Texture && kind != DeclKind::Buffer &&
        kind != DeclKind::Pass)
        raise(L, origin + ": " + declKindName(kind) + " \"" + name +
                     "\": a view declares passes and resources only (rg.pass, rg.resource, "
                     "rg.buffer)");
    auto value = toValue(L, tableIndex, std::string(declKindName(kind)) + " '" + name + "'");
    if (!value) raise(L, origin + ": " + value.error().message);
    implOf(L).decls.push_back({kind, name, module, *value, origin});
}

// The second half of rg.pass "name" { ... } — upvalues: kind, module, name, origin.
int declareBody(lua_State* L) {
    recordDeclaration(L, static_cast<DeclKind>(lua_tointeger(L, lua_upvalueindex(1))),
                      lua_tostring(L, lua_upvalueindex(2)), lua_tostring(L, lua_upvalueindex(3)),
                      lua_tostring(L, lua_upvalueindex(4)), 1);
    return 0;
}

// rg.pass "name" — upvalues: kind, module. Returns the function that takes the body, or
// records it at once for rg.pass("name", { ... }).
int declare(lua_State* L) {
    auto kind = static_cast<DeclKind>(lua_tointeger(L, lua_upvalueindex(1)));
    std::string module = lua_tostring(L, lua_upvalueindex(2));
    std::string origin = callerOrigin(L);
    if (lua_type(L, 1) != LUA_TSTRING)
        raise(L, origin + ": rg." + declKindName(kind) + ": expected a name, e.g. rg." +
                     declKindName(kind) + " \"name\" { ... }");
    std::string name = lua_tostring(L, 1);
    if (!validName(name, false))
        raise(L, origin + ": rg." + declKindName(kind) + ": '" + name +
                     "' is not a valid name (letters, digits, '_' and '-')");
    if (lua_gettop(L) >= 2) {
        recordDeclaration(L, kind, module, name, origin, 2);
        return 0;
    }
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_pushvalue(L, lua_upvalueindex(2));
    lua_pushstring(L, name.c_str());
    lua_pushstring(L, origin.c_str());
    lua_pushcclosure(L, guarded<declareBody>, 4);
    return 1;
}

// rg.output "name" or rg.output { display = "name", hdr = "hdr", exposure = "exposure" }.
int setOutput(lua_State* L) {
    OutputNames names;
    names.origin = callerOrigin(L);
    if (implOf(L).view)
        raise(L, names.origin +
                     ": rg.output: a view writes debug_view; the output stays the "
                     "pipeline's");
    if (lua_type(L, 1) == LUA_TSTRING) {
        names.display = lua_tostring(L, 1);
    } else if (lua_istable(L, 1)) {
        auto v = toValue(L, 1, "rg.output");
        if (!v) raise(L, v.error().message);
        for (const auto& [key, value] : v->asTable()) {
            if (key != "display" && key != "hdr" && key != "exposure")
                raise(L, names.origin + ": rg.output." + key +
                             ": unknown field; expected one of: 'display', 'hdr', 'exposure'");
            if (!value.isString())
                raise(L, names.origin + ": rg.output." + key + ": expected a resource name");
        }
        names.display = (*v)["display"].asString();
        names.hdr = (*v)["hdr"].asString();
        names.exposure = (*v)["exposure"].asString();
        if (names.display.empty())
            raise(L, names.origin + ": rg.output.display: missing (expected the display image)");
    } else {
        raise(L, names.origin +
                     ": rg.output: expected a resource name or { display = , hdr = , exposure = }");
    }
    const OutputNames& before = implOf(L).output;
    if (!before.display.empty()) {
        auto fields = [](const OutputNames& n) {
            std::string s = "display '" + n.display + "'";
            if (!n.hdr.empty()) s += ", hdr '" + n.hdr + "'";
            if (!n.exposure.empty()) s += ", exposure '" + n.exposure + "'";
            return s;
        };
        names.replaced = names.origin + ": rg.output (" + fields(names) + ") replaces the one at " +
                         before.origin + " (" + fields(before) + ")";
    }
    implOf(L).output = names;
    return 0;
}

void pushDeclarers(lua_State* L, const std::string& module);

int declareModule(lua_State* L) {
    std::string origin = callerOrigin(L);
    if (lua_type(L, 1) != LUA_TSTRING || !validName(lua_tostring(L, 1), false))
        raise(L, origin + ": rg.module: expected a module name (letters, digits, '_' and '-')");
    pushDeclarers(L, lua_tostring(L, 1));
    return 1;
}

// A table with resource/buffer/pass/... declaring functions bound to `module`.
void pushDeclarers(lua_State* L, const std::string& module) {
    lua_newtable(L);
    const std::pair<const char*, DeclKind> fns[] = {
        {"resource", DeclKind::Texture}, {"buffer", DeclKind::Buffer},
        {"pass", DeclKind::Pass},        {"param", DeclKind::Param},
        {"layout", DeclKind::Layout},    {"stencil", DeclKind::Stencil},
        {"path", DeclKind::Path},        {"material", DeclKind::Material},
        {"history", DeclKind::History}};
    for (const auto& [name, kind] : fns) {
        lua_pushinteger(L, static_cast<lua_Integer>(kind));
        lua_pushstring(L, module.c_str());
        lua_pushcclosure(L, guarded<declare>, 2);
        lua_setfield(L, -2, name);
    }
    lua_pushstring(L, module.c_str());
    lua_setfield(L, -2, "name");
}

// require "name": the pipeline's folder, then the search dirs; "a.b" is a/b.lua.
int requireModule(lua_State* L) {
    if (lua_type(L, 1) != LUA_TSTRING)
        raise(L, std::string("require: expected a module name, got ") + luaL_typename(L, 1));
    std::string name = lua_tostring(L, 1);
    auto& impl = implOf(L);
    // Module names are dotted identifiers: no path tricks ("..", "/") to leave the search dirs.
    bool valid = !name.empty() && name.front() != '.' && name.back() != '.' &&
                 name.find("..") == std::string::npos;
    for (char c : name)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'))
            valid = false;
    if (!valid)
        raise(L, "require: '" + name +
                     "' is not a module name (dotted names of letters, digits, '_' and '-')");
    lua_getfield(L, LUA_REGISTRYINDEX, kModulesKey);
    lua_getfield(L, -1, name.c_str());
    if (!lua_isnil(L, -1)) return 1;
    lua_pop(L, 1);
    std::string rel = name;
    std::replace(rel.begin(), rel.end(), '.', '/');
    rel += ".lua";
    std::vector<std::string> dirs;
    if (!impl.pipelineDir.empty()) dirs.push_back(impl.pipelineDir);
    for (const auto& d : impl.options.searchDirs) dirs.push_back(d);
    std::string found;
    for (const auto& d : dirs) {
        std::error_code ec;
        if (fs::is_regular_file(fs::path(d) / rel, ec)) {
            found = (fs::path(d) / rel).string();
            break;
        }
    }
    if (found.empty()) {
        std::string searched;
        for (const auto& d : dirs) searched += (searched.empty() ? "" : ", ") + chunkName(impl, d);
        raise(L, "module '" + name + "' not found (searched " + searched + " for " + rel + ")");
    }
    auto loaded = loadFile(impl, found);
    if (!loaded) raise(L, loaded.error().message);
    lua_pushstring(L, name.c_str());
    if (lua_pcall(L, 1, 1, 0) != LUA_OK) {
        std::string msg =
            lua_tostring(L, -1) ? lua_tostring(L, -1) : "error in module '" + name + "'";
        lua_pop(L, 1);
        raise(L, msg);
    }
    if (lua_isnil(L, -1)) {
        lua_pop(L, 1);
        lua_pushboolean(L, 1);
    }
    lua_pushvalue(L, -1);
    lua_setfield(L, -3, name.c_str());
    return 1;
}

// Indexing a removed library function explains the sandbox instead of "attempt to call nil".
int sandboxIndex(lua_State* L) {
    std::string lib = lua_tostring(L, lua_upvalueindex(1));
    std::string key = lua_type(L, 2) == LUA_TSTRING ? lua_tostring(L, 2) : "?";
    raise(L,
          lib + (lib.empty() ? "" : ".") + key + " is not available to rgraph scripts (sandbox)");
}

void pushSandboxGuard(lua_State* L, const char* lib) {
    lua_newtable(L);
    lua_pushstring(L, lib);
    lua_pushcclosure(L, guarded<sandboxIndex>, 1);
    lua_setfield(L, -2, "__index");
}

}  // namespace

LuaHost::LuaHost(LuaHostOptions options) : m(std::make_unique<Impl>()) {
    m->options = std::move(options);
}
LuaHost::~LuaHost() = default;

Result<PipelineDesc> LuaHost::load(const std::string& file) {
    auto decls = loadDeclarations(file);
    if (!decls) return std::unexpected(decls.error());
    BuildOptions bo;
    bo.kinds = m->options.kinds;
    bo.projectRoot = m->options.projectRoot;
    auto pipeline = buildPipeline(m->decls, m->output, bo);
    if (!pipeline) return pipeline;
    pipeline->file = file;
    pipeline->files = m->files;
    return pipeline;
}

Result<std::vector<Declaration>> LuaHost::loadDeclarations(const std::string& file,
                                                           std::vector<std::string>* files) {
    m->close();
    m->decls.clear();
    m->files.clear();
    m->output = {};
    std::error_code ec;
    if (!fs::is_regular_file(file, ec))
        return fail(ErrorCode::NotFound, "cannot open pipeline script '" + file + "'");
    m->pipelineDir = fs::absolute(file).parent_path().string();

    m->budget = lua::Budget{"script", m->options.memoryBytes, m->options.instructions};
    m->budget.file = file;
    lua_State* L = lua::newSandboxedState(m->budget, /*withOs=*/true);
    if (!L) return fail(ErrorCode::Io, "cannot create a Lua state");
    m->L = L;
    *static_cast<Impl**>(lua_getextraspace(L)) = m.get();

    // os keeps clock/time/date; every other os.* explains the sandbox.
    lua_getglobal(L, "os");
    for (const char* fn :
         {"execute", "exit", "getenv", "remove", "rename", "tmpname", "setlocale"}) {
        lua_pushnil(L);
        lua_setfield(L, -2, fn);
    }
    pushSandboxGuard(L, "os");
    lua_setmetatable(L, -2);
    lua_pop(L, 1);
    for (const char* lib : {"io", "package", "debug"}) {
        lua_newtable(L);
        pushSandboxGuard(L, lib);
        lua_setmetatable(L, -2);
        lua_setglobal(L, lib);
    }

    // Module cache and require.
    lua_newtable(L);
    lua_setfield(L, LUA_REGISTRYINDEX, kModulesKey);
    lua_pushcfunction(L, guarded<requireModule>);
    lua_setglobal(L, "require");

    // The rg table: declarations, output, module; also what `require "rg"` returns.
    pushDeclarers(L, "");
    lua_pushcfunction(L, guarded<setOutput>);
    lua_setfield(L, -2, "output");
    lua_pushcfunction(L, guarded<declareModule>);
    lua_setfield(L, -2, "module");
    lua_pushcfunction(L, guarded<host::declareView>);
    lua_setfield(L, -2, "view");
    lua_newtable(L);
    for (size_t i = 0; i < m->options.kinds.size(); ++i) {
        lua_pushstring(L, m->options.kinds[i].name.c_str());
        lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
    }
    lua_setfield(L, -2, "kinds");
    // The limits the C++ core and the shaders share (shaders/lib/limits.h), for scripts that size
    // buffers by them: written once there.
    lua_newtable(L);
    lua_pushinteger(L, RG_MAX_LIGHTS);
    lua_setfield(L, -2, "max_lights");
    lua_pushinteger(L, RG_MAX_SHADOW_VIEWS);
    lua_setfield(L, -2, "max_shadow_views");
    lua_setfield(L, -2, "limits");
    lua_pushvalue(L, -1);
    lua_setglobal(L, "rg");
    lua_getfield(L, LUA_REGISTRYINDEX, kModulesKey);
    lua_insert(L, -2);
    lua_setfield(L, -2, "rg");
    lua_pop(L, 1);

    // The scene table: what `require "scene"` returns (also the global `scene`).
    lua_newtable(L);
    const std::pair<const char*, DeclKind> sceneFns[] = {{"material", DeclKind::SceneMaterial},
                                                         {"sphere", DeclKind::Sphere},
                                                         {"plane", DeclKind::Plane},
                                                         {"box", DeclKind::Box},
                                                         {"gltf", DeclKind::Gltf},
                                                         {"light", DeclKind::Light},
                                                         {"camera", DeclKind::Camera},
                                                         {"environment", DeclKind::Environment},
                                                         {"decal", DeclKind::Decal},
                                                         {"probe", DeclKind::Probe},
                                                         {"lightmap", DeclKind::Lightmap}};
    for (const auto& [name, kind] : sceneFns) {
        lua_pushinteger(L, static_cast<lua_Integer>(kind));
        lua_pushstring(L, "");
        lua_pushcclosure(L, guarded<declare>, 2);
        lua_setfield(L, -2, name);
    }
    lua_newtable(L);
    for (const auto& [name, value] : m->options.sceneArgs) {
        char* end = nullptr;
        const double number = std::strtod(value.c_str(), &end);
        if (!value.empty() && end && *end == '\0' && std::isfinite(number)) {
            if (number == std::floor(number) && std::abs(number) < 9e15)
                lua_pushinteger(L, static_cast<lua_Integer>(number));
            else
                lua_pushnumber(L, number);
        } else
            lua_pushstring(L, value.c_str());
        lua_setfield(L, -2, name.c_str());
    }
    lua_setfield(L, -2, "args");
    lua_pushvalue(L, -1);
    lua_setglobal(L, "scene");
    lua_getfield(L, LUA_REGISTRYINDEX, kModulesKey);
    lua_insert(L, -2);
    lua_setfield(L, -2, "scene");
    lua_pop(L, 1);

    if (auto r = loadFile(*m, file); !r) return std::unexpected(r.error());
    if (auto r = lua::protectedCall(m->L, 0, 0); !r) return std::unexpected(r.error());
    if (files) *files = m->files;
    return m->decls;
}

bool LuaHost::hasFrameCallback() const {
    if (!m->L) return false;
    lua_getglobal(m->L, "rg");
    lua_getfield(m->L, -1, "frame");
    bool has = lua_isfunction(m->L, -1);
    lua_pop(m->L, 2);
    return has;
}

Result<FrameChanges> LuaHost::frame(const FrameContext& ctx, const PipelineDesc& current) {
    FrameChanges changes;
    if (!hasFrameCallback()) return changes;
    lua_State* L = m->L;
    lua_getglobal(L, "rg");
    lua_getfield(L, -1, "frame");
    lua_remove(L, -2);
    auto r = lua::callFrame(L, ctx, current, changes);
    if (!r)
        return std::unexpected(Error(ErrorCode::InvalidInput, "rg.frame: " + r.error().message));
    return changes;
}

}  // namespace rg
