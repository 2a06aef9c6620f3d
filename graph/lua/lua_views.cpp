// rg.view: the debug views of `--view NAME`, registered by scripts (the standard ones in
// scripts/views.lua) and added to a loaded pipeline on request (LuaHost::addView). A view's
// function declares its passes and resources with rg.pass / rg.resource like any script, after
// the pipeline's own, with what the pipeline and the scene hold at hand in its argument `v`.
#include <algorithm>
#include <cctype>

#include "lua_host_impl.h"

namespace rg {

namespace {

// The registry's list of views, in declaration order: { name, doc, pattern, build, origin }.
const char* kViewsKey = "rgraph.views";

using host::callerOrigin;
using host::implOf;
using lua::guarded;
using lua::ScriptError;

ViewCall& viewCallOf(lua_State* L) {
    ViewCall* call = implOf(L).view;
    if (!call) throw ScriptError{"v is only valid during the view function that received it"};
    return *call;
}

// Names: letters, digits, '_', '-' and ':' (shadow:LIGHT).
bool validViewName(const std::string& n) {
    return !n.empty() && std::all_of(n.begin(), n.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == ':';
    });
}

// Checks the body of rg.view "name" { doc = , pattern = , build = } at `body` and adds the view
// to the registry's list.
void registerView(lua_State* L, const std::string& name, const std::string& origin, int body) {
    const std::string where = origin + ": rg.view \"" + name + "\"";
    if (implOf(L).view) throw ScriptError{where + ": views cannot be declared inside a view"};
    if (!lua_istable(L, body))
        throw ScriptError{where + ": expected a table of fields, got " + luaL_typename(L, body)};
    static const std::vector<std::string> fields = {"doc", "pattern", "build"};
    lua_pushnil(L);
    while (lua_next(L, body)) {
        lua_pop(L, 1);
        const std::string key = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : "";
        if (std::find(fields.begin(), fields.end(), key) == fields.end()) {
            lua_pop(L, 1);
            throw ScriptError{where + ": " +
                              (key.empty()
                                   ? "positional values are not fields"
                                   : "unknown field '" + key + "'" + suggestion(key, fields)) +
                              "; expected: " + joinQuoted(fields)};
        }
    }
    lua_getfield(L, body, "build");
    if (!lua_isfunction(L, -1))
        throw ScriptError{where +
                          ".build: expected the function that declares the view's "
                          "passes, got " +
                          luaL_typename(L, -1)};
    lua_pop(L, 1);
    for (const char* field : {"doc", "pattern"}) {
        lua_getfield(L, body, field);
        if (!lua_isnil(L, -1) && lua_type(L, -1) != LUA_TSTRING)
            throw ScriptError{where + "." + field + ": expected a string, got " +
                              luaL_typename(L, -1)};
        lua_pop(L, 1);
    }
    lua_getfield(L, LUA_REGISTRYINDEX, kViewsKey);
    if (lua_isnil(L, -1)) {
        lua_pop(L, 1);
        lua_newtable(L);
        lua_pushvalue(L, -1);
        lua_setfield(L, LUA_REGISTRYINDEX, kViewsKey);
    }
    const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, -1));
    for (lua_Integer i = 1; i <= n; ++i) {
        lua_rawgeti(L, -1, i);
        lua_getfield(L, -1, "name");
        const bool same = name == lua_tostring(L, -1);
        lua_getfield(L, -2, "origin");
        const std::string before = lua_tostring(L, -1);
        lua_pop(L, 3);
        if (same) throw ScriptError{where + ": already declared at " + before};
    }
    lua_newtable(L);
    lua_pushstring(L, name.c_str());
    lua_setfield(L, -2, "name");
    lua_pushstring(L, origin.c_str());
    lua_setfield(L, -2, "origin");
    for (const char* field : {"doc", "pattern", "build"}) {
        lua_getfield(L, body, field);
        lua_setfield(L, -2, field);
    }
    lua_rawseti(L, -2, n + 1);
    lua_pop(L, 1);
}

// The second half of rg.view "name" { ... } — upvalues: name, origin.
int declareViewBody(lua_State* L) {
    registerView(L, lua_tostring(L, lua_upvalueindex(1)), lua_tostring(L, lua_upvalueindex(2)), 1);
    return 0;
}

// v.fail(message): stops the view with "--view NAME: message".
int viewFail(lua_State* L) {
    ViewCall& call = viewCallOf(L);
    const char* msg = lua_tostring(L, 1);
    call.error = "--view " + call.view + ": " + (msg ? msg : "cannot be shown");
    throw ScriptError{call.error};
}

// v.define(pass, NAME, value): compiles NAME = value into the pipeline's pass `pass`.
int viewDefine(lua_State* L) {
    ViewCall& call = viewCallOf(L);
    if (lua_type(L, 1) != LUA_TSTRING || lua_type(L, 2) != LUA_TSTRING)
        throw ScriptError{
            "v.define: expected (pass, define, value), e.g. v.define(\"gbuffer\", "
            "\"RG_VIEW\", 1)"};
    const std::string pass = lua_tostring(L, 1), define = lua_tostring(L, 2);
    const auto& passes = call.loaded->graph.passes;
    if (std::none_of(passes.begin(), passes.end(),
                     [&](const PassDesc& p) { return p.name == pass; })) {
        call.error = "--view " + call.view + ": the pipeline has no pass '" + pass + "'";
        throw ScriptError{call.error};
    }
    if (!lua_isboolean(L, 3) && !lua_isnumber(L, 3))
        throw ScriptError{"v.define: " + define + ": expected a number or a boolean, got " +
                          luaL_typename(L, 3)};
    const Value value = lua_isboolean(L, 3) ? Value(lua_toboolean(L, 3) != 0)
                                            : Value(static_cast<double>(lua_tonumber(L, 3)));
    call.defines.emplace_back(pass, define, value);
    return 0;
}

// Pushes a set { NAME = true } of `names`' members' `name`.
template <typename T>
void pushNameSet(lua_State* L, const std::vector<T>& items) {
    lua_createtable(L, 0, static_cast<int>(items.size()));
    for (const T& item : items) {
        lua_pushboolean(L, 1);
        lua_setfield(L, -2, item.name.c_str());
    }
}

// Finds the view (by name, or by pattern with its captures) and calls its function with v,
// inside the protected call: no C++ object with a destructor lives here (errors longjmp).
int viewTrampoline(lua_State* L) {
    ViewCall& call = *static_cast<ViewCall*>(lua_touserdata(L, lua_upvalueindex(1)));
    lua_getfield(L, LUA_REGISTRYINDEX, kViewsKey);
    if (lua_isnil(L, -1)) return 0;
    const int views = lua_gettop(L);
    const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, views));
    for (lua_Integer i = 1; i <= n && !call.found; ++i) {
        lua_settop(L, views);
        lua_rawgeti(L, views, i);
        const int entry = lua_gettop(L);
        lua_getfield(L, entry, "build");
        lua_getfield(L, entry, "pattern");
        if (lua_isnil(L, -1)) {
            lua_pop(L, 1);
            lua_getfield(L, entry, "name");
            call.found = call.view == lua_tostring(L, -1);
            lua_pop(L, 1);
        } else {
            // string.match(view, pattern): its captures become the function's arguments.
            lua_getglobal(L, "string");
            lua_getfield(L, -1, "match");
            lua_remove(L, -2);
            lua_insert(L, -2);
            lua_pushstring(L, call.view.c_str());
            lua_insert(L, -2);
            const int before = lua_gettop(L) - 3;
            lua_call(L, 2, LUA_MULTRET);
            call.found = !lua_isnil(L, before + 1);
        }
    }
    if (!call.found) return 0;
    // The stack: views, entry, build, captures...; v goes before the captures.
    const int build = views + 2;
    lua_newtable(L);
    lua_pushstring(L, call.view.c_str());
    lua_setfield(L, -2, "name");
    pushNameSet(L, call.loaded->graph.resources);
    lua_setfield(L, -2, "resources");
    pushNameSet(L, call.loaded->graph.passes);
    lua_setfield(L, -2, "passes");
    const auto& classes = call.loaded->stencilClasses;
    lua_createtable(L, static_cast<int>(classes.size()), 0);
    for (size_t i = 0; i < classes.size(); ++i) {
        lua_createtable(L, 0, 4);
        lua_pushstring(L, classes[i].name.c_str());
        lua_setfield(L, -2, "name");
        lua_pushinteger(L, classes[i].value);
        lua_setfield(L, -2, "value");
        lua_pushinteger(L, classes[i].mask);
        lua_setfield(L, -2, "mask");
        if (!classes[i].base.empty()) {
            lua_pushstring(L, classes[i].base.c_str());
            lua_setfield(L, -2, "base");
        }
        lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
    }
    lua_setfield(L, -2, "stencil_classes");
    if (call.scene) {
        lua_newtable(L);
        const auto& lights = call.scene->lights;
        lua_createtable(L, static_cast<int>(lights.size()), 0);
        for (size_t i = 0; i < lights.size(); ++i) {
            lua_createtable(L, 0, 2);
            lua_pushstring(L, lights[i].name.c_str());
            lua_setfield(L, -2, "name");
            lua_pushboolean(L, lights[i].shadow);
            lua_setfield(L, -2, "shadow");
            lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
        }
        lua_setfield(L, -2, "lights");
        if (call.scene->lightmapLobes) {
            lua_createtable(L, 0, 1);
            lua_pushinteger(L, *call.scene->lightmapLobes);
            lua_setfield(L, -2, "lobes");
            lua_setfield(L, -2, "lightmap");
        }
        lua_setfield(L, -2, "scene");
    }
    lua_pushcfunction(L, guarded<viewFail>);
    lua_setfield(L, -2, "fail");
    lua_pushcfunction(L, guarded<viewDefine>);
    lua_setfield(L, -2, "define");
    lua_insert(L, build + 1);
    lua_call(L, lua_gettop(L) - build, 0);
    return 0;
}

// The names of the views declared so far, quoted ("'normals', 'stencil', ...").
std::string viewNames(lua_State* L) {
    std::vector<std::string> names;
    lua_getfield(L, LUA_REGISTRYINDEX, kViewsKey);
    const lua_Integer n = lua_istable(L, -1) ? static_cast<lua_Integer>(lua_rawlen(L, -1)) : 0;
    for (lua_Integer i = 1; i <= n; ++i) {
        lua_rawgeti(L, -1, i);
        lua_getfield(L, -1, "name");
        names.push_back(lua_tostring(L, -1));
        lua_pop(L, 2);
    }
    lua_pop(L, 1);
    return joinQuoted(names);
}

// Runs the view's function (when one has the name): false when no view has it.
Result<bool> callView(lua_State* L, ViewCall& call) {
    lua_pushlightuserdata(L, &call);
    lua_pushcclosure(L, viewTrampoline, 1);
    implOf(L).view = &call;
    auto r = lua::protectedCall(L, 0, 0);
    implOf(L).view = nullptr;
    if (!r) {
        if (!call.error.empty()) return fail(ErrorCode::InvalidInput, call.error);
        return std::unexpected(r.error());
    }
    return call.found;
}

}  // namespace

namespace host {

// rg.view "name" — returns the function that takes the body, or records it at once for
// rg.view("name", { ... }).
int declareView(lua_State* L) {
    const std::string origin = callerOrigin(L);
    if (lua_type(L, 1) != LUA_TSTRING || !validViewName(lua_tostring(L, 1)))
        throw ScriptError{origin +
                          ": rg.view: expected a name (letters, digits, '_', '-' and ':'), e.g. "
                          "rg.view \"name\" { build = function(v) ... end }"};
    if (lua_gettop(L) >= 2) {
        registerView(L, lua_tostring(L, 1), origin, 2);
        return 0;
    }
    lua_pushvalue(L, 1);
    lua_pushstring(L, origin.c_str());
    lua_pushcclosure(L, guarded<declareViewBody>, 2);
    return 1;
}

}  // namespace host

Result<PipelineDesc> LuaHost::addView(const std::string& view, const PipelineDesc& loaded,
                                      const ViewFacts* scene) {
    lua_State* L = m->L;
    if (!L) return fail(ErrorCode::InvalidInput, "--view " + view + ": no pipeline is loaded");
    ViewCall call;
    call.view = view;
    call.loaded = &loaded;
    call.scene = scene;
    // The view's declarations go into the pipeline returned, not into the host's: it goes on
    // as load() left it (another view may be added to the same pipeline).
    struct Restore {
        std::vector<Declaration>& decls;
        size_t declared = decls.size();
        ~Restore() { decls.resize(declared); }
    } restore{m->decls};
    auto found = callView(L, call);
    if (!found) return std::unexpected(found.error());
    if (!*found) {
        // The standard views, unless the pipeline's scripts have loaded them already.
        lua_getglobal(L, "require");
        lua_pushstring(L, "views");
        if (auto r = lua::protectedCall(L, 1, 0); !r) return std::unexpected(r.error());
        found = callView(L, call);
        if (!found) return std::unexpected(found.error());
    }
    if (!*found)
        return fail(ErrorCode::InvalidInput,
                    "--view: unknown view '" + view + "'; expected one of: " + viewNames(L));
    BuildOptions bo;
    bo.kinds = m->options.kinds;
    bo.projectRoot = m->options.projectRoot;
    auto pipeline = buildPipeline(m->decls, m->output, bo);
    if (!pipeline) return pipeline;
    if (!pipeline->graph.findResource("debug_view"))
        return fail(ErrorCode::InvalidInput,
                    "--view " + view +
                        ": the view declared no 'debug_view' image (a view writes it; "
                        "scripts/views.lua's views.target() declares it)");
    for (const auto& [pass, define, value] : call.defines)
        for (PassDesc& p : pipeline->graph.passes) {
            if (p.name != pass) continue;
            Value::Table params = p.params.isTable() ? p.params.asTable() : Value::Table{};
            Value::Table defines =
                params["defines"].isTable() ? params["defines"].asTable() : Value::Table{};
            defines[define] = value;
            params["defines"] = Value(defines);
            p.params = Value(params);
        }
    pipeline->file = loaded.file;
    pipeline->files = m->files;
    return pipeline;
}

}  // namespace rg
