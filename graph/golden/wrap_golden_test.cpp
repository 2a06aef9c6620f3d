// The Lua glue of golden test scripts: a small sandboxed state of its own (the pipeline's
// LuaHost knows declarations, not tests), the returned table as an rg::Value, and the test's
// frame(ctx) callback. The only file of graph/golden that sees lua.h.
#include "golden/golden_test.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>

#include "lua/declarations.h"
#include "lua/lua_sandbox.h"

namespace rg::golden {

struct GoldenScript::Impl {
    lua_State* L = nullptr;
    lua::Budget budget;  // memory and instructions (lua/lua_sandbox.h)
    int frameRef = LUA_NOREF;
    // During a frame callback.
    FrameChanges* changes = nullptr;
    const PipelineDesc* current = nullptr;

    ~Impl() {
        if (L) lua_close(L);
    }
};

namespace {

constexpr int kMaxDepth = 32;

GoldenScript::Impl& implOf(lua_State* L) { return **static_cast<GoldenScript::Impl**>(lua_getextraspace(L)); }

// Glue errors are thrown as lua::ScriptError and raised by lua::guarded (lua/lua_sandbox.h).
using lua::guarded;
using lua::ScriptError;

std::string typeName(lua_State* L, int idx) { return luaL_typename(L, idx); }

// "file: path: " (either part may be empty), the start of every conversion error.
std::string located(const std::string& where, const std::string& path) {
    return (where.empty() ? "" : where + ": ") + (path.empty() ? "" : path + ": ");
}

// The Lua value at idx as a Value: tables with keys 1..n become lists, tables with string keys
// become tables; functions are refused (only the top-level `frame` may be one).
Result<Value> toValue(lua_State* L, int idx, const std::string& path, const std::string& where, int depth) {
    idx = lua_absindex(L, idx);
    switch (lua_type(L, idx)) {
    case LUA_TNIL: return Value();
    case LUA_TBOOLEAN: return Value(lua_toboolean(L, idx) != 0);
    case LUA_TNUMBER: return Value(static_cast<double>(lua_tonumber(L, idx)));
    case LUA_TSTRING: {
        size_t n = 0;
        const char* s = lua_tolstring(L, idx, &n);
        return Value(std::string(s, n));
    }
    case LUA_TTABLE: {
        if (depth > kMaxDepth) return fail(ErrorCode::InvalidInput, located(where, path) + "tables nested too deeply");
        Value::Table table;
        std::map<lua_Integer, Value> items;
        lua_pushnil(L);
        while (lua_next(L, idx) != 0) {
            // Never lua_tostring a key: it would change the key under lua_next.
            std::string key;
            if (lua_type(L, -2) == LUA_TSTRING) {
                key = lua_tostring(L, -2);
                auto v = toValue(L, -1, path.empty() ? key : path + "." + key, where, depth + 1);
                if (!v) {
                    lua_pop(L, 2);
                    return v;
                }
                table[key] = std::move(*v);
            } else if (lua_isinteger(L, -2)) {
                const lua_Integer k = lua_tointeger(L, -2);
                auto v = toValue(L, -1, path + "[" + std::to_string(k) + "]", where, depth + 1);
                if (!v) {
                    lua_pop(L, 2);
                    return v;
                }
                items[k] = std::move(*v);
            } else {
                const std::string kt = typeName(L, -2);
                lua_pop(L, 2);
                return fail(ErrorCode::InvalidInput, located(where, path) + "a " + kt + " key; tables take names or list positions");
            }
            lua_pop(L, 1);
        }
        if (!items.empty() && !table.empty())
            return fail(ErrorCode::InvalidInput, located(where, path) + "mixes list entries and named fields");
        if (items.empty()) return Value(std::move(table));
        Value::List list;
        lua_Integer expect = 1;
        for (auto& [k, v] : items) {
            if (k != expect)
                return fail(ErrorCode::InvalidInput, located(where, path) + "a list with a hole at [" + std::to_string(expect) + "]");
            list.push_back(std::move(v));
            ++expect;
        }
        return Value(std::move(list));
    }
    default:
        return fail(ErrorCode::InvalidInput, located(where, path) + "a " + typeName(L, idx) + " is not allowed here" +
                                                 (lua_type(L, idx) == LUA_TFUNCTION ? " (only the top-level 'frame' is a function)" : ""));
    }
}

void pushValue(lua_State* L, const Value& v) {
    if (v.isBool()) lua_pushboolean(L, v.asBool());
    else if (v.isNumber()) lua_pushnumber(L, v.asNumber());
    else if (v.isString()) lua_pushlstring(L, v.asString().data(), v.asString().size());
    else if (v.isList()) {
        lua_createtable(L, static_cast<int>(v.asList().size()), 0);
        for (size_t i = 0; i < v.asList().size(); ++i) {
            pushValue(L, v.asList()[i]);
            lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
        }
    } else if (v.isTable()) {
        lua_createtable(L, 0, static_cast<int>(v.asTable().size()));
        for (const auto& [k, item] : v.asTable()) {
            pushValue(L, item);
            lua_setfield(L, -2, k.c_str());
        }
    } else
        lua_pushnil(L);
}

// ---- the frame callback's ctx (the rg.frame interface) ----

// A string argument; luaL_check* would longjmp past live C++ objects, so glue checks by hand.
std::string stringArg(lua_State* L, int idx, const char* what) {
    if (lua_type(L, idx) != LUA_TSTRING) throw ScriptError{std::string(what) + ": expected a name, got " + typeName(L, idx)};
    return lua_tostring(L, idx);
}

const ParamDesc& paramOf(GoldenScript::Impl& impl, const std::string& name) {
    const ParamDesc* p = impl.current->findParam(name);
    if (!p) {
        std::vector<std::string> names;
        for (const auto& q : impl.current->params) names.push_back(q.name);
        std::string best = closestName(name, names);
        throw ScriptError{"ctx.params: unknown parameter '" + name + "'" + (best.empty() ? "" : " (did you mean '" + best + "'?)")};
    }
    return *p;
}

int paramsIndex(lua_State* L) {
    auto& impl = implOf(L);
    const std::string name = stringArg(L, 2, "ctx.params");
    if (auto it = impl.changes->params.find(name); it != impl.changes->params.end()) {
        pushValue(L, it->second);
        return 1;
    }
    pushValue(L, paramOf(impl, name).value);
    return 1;
}

int paramsNewIndex(lua_State* L) {
    auto& impl = implOf(L);
    const std::string name = stringArg(L, 2, "ctx.params");
    const ParamDesc& p = paramOf(impl, name);
    auto v = toValue(L, 3, "ctx.params." + name, "", 0);
    if (!v) throw ScriptError{v.error().message};
    auto checked = checkParamValue(p, *v);
    if (!checked) throw ScriptError{"ctx.params: " + checked.error().message};
    impl.changes->params[name] = *checked;
    return 0;
}

const PassDesc& passOf(GoldenScript::Impl& impl, const std::string& name) {
    for (const auto& pass : impl.current->graph.passes)
        if (pass.name == name) return pass;
    std::vector<std::string> names;
    for (const auto& p : impl.current->graph.passes) names.push_back(p.name);
    std::string best = closestName(name, names);
    throw ScriptError{"ctx.pass: unknown pass '" + name + "'" + (best.empty() ? "" : " (did you mean '" + best + "'?)")};
}

int passIndex(lua_State* L) {
    auto& impl = implOf(L);
    const std::string name = lua_tostring(L, lua_upvalueindex(1));
    const std::string key = stringArg(L, 2, "ctx.pass");
    const PassDesc& p = passOf(impl, name);
    if (key == "name") {
        lua_pushstring(L, name.c_str());
    } else if (key == "enabled") {
        auto it = impl.changes->enabled.find(name);
        lua_pushboolean(L, it != impl.changes->enabled.end() ? it->second : p.enabled);
    } else if (key == "shader") {
        auto it = impl.changes->shaders.find(name);
        const std::string s = it != impl.changes->shaders.end() ? it->second : p.params["shader"].asString();
        lua_pushstring(L, s.c_str());
    } else if (key == "kind") {
        lua_pushstring(L, p.kind.c_str());
    } else {
        throw ScriptError{"ctx.pass('" + name + "'): no field '" + key + "'; expected one of: 'name', 'kind', 'enabled', 'shader'"};
    }
    return 1;
}

int passNewIndex(lua_State* L) {
    auto& impl = implOf(L);
    const std::string name = lua_tostring(L, lua_upvalueindex(1));
    const std::string key = stringArg(L, 2, "ctx.pass");
    const PassDesc& p = passOf(impl, name);
    if (key == "enabled") {
        if (!lua_isboolean(L, 3)) throw ScriptError{"ctx.pass('" + name + "').enabled: expected a boolean, got " + typeName(L, 3)};
        const bool on = lua_toboolean(L, 3) != 0;
        if (on == p.enabled) impl.changes->enabled.erase(name);
        else impl.changes->enabled[name] = on;
    } else if (key == "shader") {
        if (!p.params.has("shader")) throw ScriptError{"ctx.pass('" + name + "').shader: a '" + p.kind + "' pass has no shader"};
        if (lua_type(L, 3) != LUA_TSTRING) throw ScriptError{"ctx.pass('" + name + "').shader: expected a path, got " + typeName(L, 3)};
        const std::string shader = lua_tostring(L, 3);
        if (shader == p.params["shader"].asString()) impl.changes->shaders.erase(name);
        else impl.changes->shaders[name] = shader;
    } else {
        throw ScriptError{"ctx.pass('" + name + "'): cannot set '" + key + "'; settable: 'enabled', 'shader'"};
    }
    return 0;
}

int ctxPass(lua_State* L) {
    auto& impl = implOf(L);
    const std::string name = stringArg(L, 1, "ctx.pass");
    passOf(impl, name);  // unknown names fail here, with a suggestion
    lua_newtable(L);
    lua_newtable(L);
    lua_pushstring(L, name.c_str());
    lua_pushcclosure(L, guarded<passIndex>, 1);
    lua_setfield(L, -2, "__index");
    lua_pushstring(L, name.c_str());
    lua_pushcclosure(L, guarded<passNewIndex>, 1);
    lua_setfield(L, -2, "__newindex");
    lua_setmetatable(L, -2);
    return 1;
}

int forbidden(lua_State* L) {
    const char* name = lua_tostring(L, lua_upvalueindex(1));
    throw ScriptError{std::string(name) + " is not available to golden test scripts (sandbox)"};
}

}  // namespace

GoldenScript::GoldenScript() : m(std::make_unique<Impl>()) {}
GoldenScript::~GoldenScript() = default;

Result<std::unique_ptr<GoldenScript>> GoldenScript::load(const std::string& file, const std::string& chunkName,
                                                         const Limits& limits) {
    std::ifstream in(file, std::ios::binary);
    if (!in) return fail(ErrorCode::NotFound, "cannot open golden test script '" + file + "'");
    const std::string source((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());

    std::unique_ptr<GoldenScript> script(new GoldenScript());
    Impl& impl = *script->m;
    impl.budget = lua::Budget{"golden test script", limits.memoryBytes, limits.instructions};
    lua_State* L = lua::newSandboxedState(impl.budget);
    if (!L) return fail(ErrorCode::Io, "cannot create a Lua state");
    impl.L = L;
    *static_cast<Impl**>(lua_getextraspace(L)) = &impl;

    // Nothing that reads files or loads code; each says why when called.
    for (const char* fn : {"dofile", "loadfile", "load", "require", "collectgarbage"}) {
        lua_pushstring(L, fn);
        lua_pushcclosure(L, guarded<forbidden>, 1);
        lua_setglobal(L, fn);
    }

    const std::string chunk = "@" + chunkName;
    if (luaL_loadbufferx(L, source.data(), source.size(), chunk.c_str(), "t") != LUA_OK) {
        std::string msg = lua_tostring(L, -1) ? lua_tostring(L, -1) : "cannot load";
        return fail(ErrorCode::InvalidInput, msg);
    }
    if (auto r = lua::protectedCall(impl.L, 0, 1); !r) return std::unexpected(r.error());

    // The returned table; `frame` is kept in the registry, the rest becomes a Value.
    bool hasFrame = false;
    if (lua_type(L, -1) == LUA_TTABLE) {
        lua_getfield(L, -1, "frame");
        if (lua_isfunction(L, -1)) {
            impl.frameRef = luaL_ref(L, LUA_REGISTRYINDEX);
            hasFrame = true;
            lua_pushnil(L);
            lua_setfield(L, -2, "frame");
        } else if (!lua_isnil(L, -1)) {
            const std::string t = typeName(L, -1);
            lua_pop(L, 2);
            return fail(ErrorCode::InvalidInput, chunkName + ": frame: expected a function(ctx), got " + t);
        } else {
            lua_pop(L, 1);
        }
    }
    auto value = toValue(L, -1, "", chunkName, 0);
    lua_pop(L, 1);
    if (!value) return std::unexpected(value.error());

    std::string name = file;
    if (auto slash = name.find_last_of('/'); slash != std::string::npos) name = name.substr(slash + 1);
    if (name.size() > 4 && name.compare(name.size() - 4, 4, ".lua") == 0) name.resize(name.size() - 4);
    auto test = parseGoldenTest(*value, hasFrame, name, chunkName);
    if (!test) return std::unexpected(test.error());
    script->m_test = std::move(*test);
    return script;
}

Result<FrameChanges> GoldenScript::frame(const FrameContext& ctx, const PipelineDesc& current) {
    FrameChanges changes;
    if (m->frameRef == LUA_NOREF) return changes;
    lua_State* L = m->L;
    m->changes = &changes;
    m->current = &current;
    lua_rawgeti(L, LUA_REGISTRYINDEX, m->frameRef);
    lua_newtable(L);
    lua_pushinteger(L, static_cast<lua_Integer>(ctx.frame));
    lua_setfield(L, -2, "frame");
    lua_pushnumber(L, ctx.time);
    lua_setfield(L, -2, "time");
    lua_newtable(L);
    lua_newtable(L);
    lua_pushcfunction(L, guarded<paramsIndex>);
    lua_setfield(L, -2, "__index");
    lua_pushcfunction(L, guarded<paramsNewIndex>);
    lua_setfield(L, -2, "__newindex");
    lua_setmetatable(L, -2);
    lua_setfield(L, -2, "params");
    lua_pushcfunction(L, guarded<ctxPass>);
    lua_setfield(L, -2, "pass");
    auto r = lua::protectedCall(m->L, 1, 0);
    m->changes = nullptr;
    m->current = nullptr;
    if (!r) return std::unexpected(r.error());
    return changes;
}

}  // namespace rg::golden
