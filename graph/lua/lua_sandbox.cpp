#include "lua_sandbox.h"

#include <cstdlib>
#include <utility>
#include <vector>

#include "declarations.h"

namespace rg::lua {

namespace {

constexpr int kHookEvery = 1000;

Budget& budgetOf(lua_State* L) {
    void* ud = nullptr;
    lua_getallocf(L, &ud);
    return *static_cast<Budget*>(ud);
}

void* allocate(void* ud, void* ptr, size_t osize, size_t nsize) {
    auto* budget = static_cast<Budget*>(ud);
    const size_t old = ptr ? osize : 0;
    if (nsize == 0) {
        budget->memory -= old;
        std::free(ptr);
        return nullptr;
    }
    if (nsize > old && budget->memory + (nsize - old) > budget->memoryLimit) {
        budget->memoryExceeded = true;
        return nullptr;  // Lua raises "not enough memory"
    }
    void* p = std::realloc(ptr, nsize);
    if (p) budget->memory = budget->memory - old + nsize;
    return p;
}

void countHook(lua_State* L, lua_Debug* ar) {
    Budget& budget = budgetOf(L);
    budget.instructions += kHookEvery;
    if (lua_getinfo(L, "Sl", ar) && ar->currentline > 0)
        budget.lastWhere = std::string(ar->short_src) + ":" + std::to_string(ar->currentline);
    if (budget.instructions > budget.instructionLimit) {
        // Level 0 inside a count hook is the Lua function that was running.
        luaL_where(L, 0);
        lua_pushfstring(
            L, "%s stopped after %d million instructions: a runaway loop? (limit: %d million)",
            budget.who.c_str(), static_cast<int>(budget.instructions / 1000000),
            static_cast<int>(budget.instructionLimit / 1000000));
        lua_concat(L, 2);
        lua_error(L);
    }
}

int messageHandler(lua_State* L) {
    const char* msg = lua_tostring(L, 1);
    if (!msg) {
        // error(value) with a table, nil, a boolean...: where it was raised and what it was.
        const char* type = luaL_typename(L, 1);
        for (int level = 1; level <= 3; ++level) {
            luaL_where(L, level);
            if (lua_rawlen(L, -1) > 0) break;
            lua_pop(L, 1);
            if (level == 3) lua_pushliteral(L, "");
        }
        lua_pushfstring(L,
                        "the script raised an error with a %s value, not a message (error(\"...\") "
                        "takes a string)",
                        type);
        lua_concat(L, 2);
        msg = lua_tostring(L, -1);
    }
    luaL_traceback(L, L, msg, 1);
    return 1;
}

}  // namespace

lua_State* newSandboxedState(Budget& budget, bool withOs) {
    lua_State* L = lua_newstate(allocate, &budget);
    if (!L) return nullptr;
    lua_sethook(L, countHook, LUA_MASKCOUNT, kHookEvery);
    const std::pair<const char*, lua_CFunction> libs[] = {
        {LUA_GNAME, luaopen_base},        {LUA_TABLIBNAME, luaopen_table},
        {LUA_STRLIBNAME, luaopen_string}, {LUA_MATHLIBNAME, luaopen_math},
        {LUA_UTF8LIBNAME, luaopen_utf8},  {LUA_OSLIBNAME, luaopen_os}};
    for (const auto& [name, open] : libs) {
        if (open == luaopen_os && !withOs) continue;
        luaL_requiref(L, name, open, 1);
        lua_pop(L, 1);
    }
    // Base functions that reach files or load code.
    for (const char* fn : {"dofile", "loadfile", "load", "collectgarbage"}) {
        lua_pushnil(L);
        lua_setglobal(L, fn);
    }
    return L;
}

Result<void> protectedCall(lua_State* L, int nargs, int nresults) {
    Budget& budget = budgetOf(L);
    const int base = lua_gettop(L) - nargs;
    lua_pushcfunction(L, messageHandler);
    lua_insert(L, base);
    budget.instructions = 0;
    budget.memoryExceeded = false;
    budget.lastWhere.clear();
    const int status = lua_pcall(L, nargs, nresults, base);
    lua_remove(L, base);
    if (status == LUA_OK) return {};
    std::string msg = lua_tostring(L, -1) ? lua_tostring(L, -1) : "unknown Lua error";
    lua_pop(L, 1);
    if (status == LUA_ERRMEM || budget.memoryExceeded)
        msg = (!budget.lastWhere.empty() ? budget.lastWhere + ": "
               : !budget.file.empty()    ? budget.file + ": "
                                         : "") +
              budget.who + " stopped: it used more than " +
              std::to_string(budget.memoryLimit >> 20) + " MiB of Lua memory" +
              (budget.lastWhere.empty() ? "" : " (last running here)");
    return fail(ErrorCode::InvalidInput, msg);
}

std::string withPosition(lua_State* L, const std::string& message) {
    // Say where in the script, unless the message already starts with a position.
    const size_t space = message.find(' ');
    const size_t lua = message.find(".lua:");
    if (lua != std::string::npos && (space == std::string::npos || lua < space)) return message;
    luaL_where(L, 1);
    std::string out = std::string(lua_tostring(L, -1)) + message;
    lua_pop(L, 1);
    return out;
}

// Lua value -> Value. Tables with keys 1..n become lists, with string keys tables; positional
// entries of mixed tables become "#1", "#2", ... keys.
Result<Value> toValue(lua_State* L, int idx, const std::string& path, int depth) {
    idx = lua_absindex(L, idx);
    switch (lua_type(L, idx)) {
        case LUA_TNIL:
            return Value();
        case LUA_TBOOLEAN:
            return Value(static_cast<bool>(lua_toboolean(L, idx)));
        case LUA_TNUMBER:
            return Value(static_cast<double>(lua_tonumber(L, idx)));
        case LUA_TSTRING:
            return Value(std::string(lua_tostring(L, idx)));
        case LUA_TTABLE: {
            if (depth > 32)
                return fail(ErrorCode::InvalidInput,
                            path + ": tables nested too deep (or a cycle)");
            const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, idx));
            Value::List list;
            Value::Table table;
            bool hasStrings = false;
            lua_pushnil(L);
            while (lua_next(L, idx)) {
                std::string key;
                if (lua_type(L, -2) == LUA_TSTRING) {
                    key = lua_tostring(L, -2);
                    hasStrings = true;
                } else if (lua_isinteger(L, -2) && lua_tointeger(L, -2) >= 1 &&
                           lua_tointeger(L, -2) <= n) {
                    key = "#" + std::to_string(lua_tointeger(L, -2));
                } else {
                    lua_pop(L, 2);
                    return fail(ErrorCode::InvalidInput,
                                path + ": keys must be names or list positions");
                }
                auto v =
                    toValue(L, -1, path + (key[0] == '#' ? "[" + key.substr(1) + "]" : "." + key),
                            depth + 1);
                if (!v) {
                    lua_pop(L, 2);
                    return v;
                }
                table[key] = *v;
                lua_pop(L, 1);
            }
            if (!hasStrings && n > 0) {
                for (lua_Integer i = 1; i <= n; ++i) list.push_back(table["#" + std::to_string(i)]);
                return Value(list);
            }
            return Value(table);
        }
        default:
            return fail(ErrorCode::InvalidInput,
                        path + ": expected data, got a " + std::string(luaL_typename(L, idx)));
    }
}

void pushValue(lua_State* L, const Value& v) {
    if (v.isBool())
        lua_pushboolean(L, v.asBool());
    else if (v.isNumber())
        lua_pushnumber(L, v.asNumber());
    else if (v.isString())
        lua_pushstring(L, v.asString().c_str());
    else if (v.isList()) {
        lua_createtable(L, static_cast<int>(v.asList().size()), 0);
        for (size_t i = 0; i < v.asList().size(); ++i) {
            pushValue(L, v.asList()[i]);
            lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
        }
    } else if (v.isTable()) {
        lua_newtable(L);
        for (const auto& [k, e] : v.asTable()) {
            pushValue(L, e);
            lua_setfield(L, -2, k.c_str());
        }
    } else
        lua_pushnil(L);
}

// ---- The rg.frame ctx -----------------------------------------------------------------------

namespace {

const char* kFrameKey = "rgraph.frame";

// What the ctx proxies work on, valid during callFrame only (the registry holds its address).
struct FrameBinding {
    const PipelineDesc* current = nullptr;
    FrameChanges* changes = nullptr;
};

FrameBinding& bindingOf(lua_State* L) {
    lua_getfield(L, LUA_REGISTRYINDEX, kFrameKey);
    auto* b = static_cast<FrameBinding*>(lua_touserdata(L, -1));
    lua_pop(L, 1);
    if (!b) throw ScriptError{"ctx is only valid during the frame callback that received it"};
    return *b;
}

// A string argument; luaL_check* would longjmp past live C++ objects, so glue checks by hand.
std::string stringArg(lua_State* L, int idx, const char* what) {
    if (lua_type(L, idx) != LUA_TSTRING)
        throw ScriptError{std::string(what) + ": expected a name, got " + luaL_typename(L, idx)};
    return lua_tostring(L, idx);
}

const ParamDesc& paramOf(const PipelineDesc& current, const std::string& name) {
    if (const ParamDesc* p = current.findParam(name)) return *p;
    std::vector<std::string> names;
    for (const auto& q : current.params) names.push_back(q.name);
    const std::string best = closestName(name, names);
    throw ScriptError{"ctx.params: unknown parameter '" + name + "'" +
                      (best.empty() ? "" : " (did you mean '" + best + "'?)")};
}

const PassDesc& passOf(const PipelineDesc& current, const std::string& name) {
    for (const auto& pass : current.graph.passes)
        if (pass.name == name) return pass;
    std::vector<std::string> names;
    for (const auto& p : current.graph.passes) names.push_back(p.name);
    const std::string best = closestName(name, names);
    throw ScriptError{"ctx.pass: unknown pass '" + name + "'" +
                      (best.empty() ? "" : " (did you mean '" + best + "'?)")};
}

int paramsIndex(lua_State* L) {
    FrameBinding& b = bindingOf(L);
    const std::string name = stringArg(L, 2, "ctx.params");
    if (auto it = b.changes->params.find(name); it != b.changes->params.end()) {
        pushValue(L, it->second);
        return 1;
    }
    pushValue(L, paramOf(*b.current, name).value);
    return 1;
}

int paramsNewIndex(lua_State* L) {
    FrameBinding& b = bindingOf(L);
    const std::string name = stringArg(L, 2, "ctx.params");
    const ParamDesc& p = paramOf(*b.current, name);
    auto v = toValue(L, 3, "ctx.params." + name);
    if (!v) throw ScriptError{v.error().message};
    auto checked = checkParamValue(p, *v);
    if (!checked) throw ScriptError{"ctx.params: " + checked.error().message};
    b.changes->params[name] = *checked;
    return 0;
}

int passIndex(lua_State* L) {
    FrameBinding& b = bindingOf(L);
    const std::string name = lua_tostring(L, lua_upvalueindex(1));
    const std::string key = stringArg(L, 2, "ctx.pass");
    const PassDesc& p = passOf(*b.current, name);
    if (key == "name") {
        lua_pushstring(L, name.c_str());
    } else if (key == "enabled" || key == "auto_enabled") {
        // What the pass will be: an explicit switch this frame, else an automatic one, else now.
        auto it = b.changes->enabled.find(name);
        auto automatic = b.changes->automatic.find(name);
        lua_pushboolean(L, it != b.changes->enabled.end()            ? it->second
                           : automatic != b.changes->automatic.end() ? automatic->second
                                                                     : p.enabled);
    } else if (key == "shader") {
        auto it = b.changes->shaders.find(name);
        const std::string s =
            it != b.changes->shaders.end() ? it->second : p.params["shader"].asString();
        lua_pushstring(L, s.c_str());
    } else if (key == "kind") {
        lua_pushstring(L, p.kind.c_str());
    } else {
        throw ScriptError{"ctx.pass('" + name + "'): no field '" + key +
                          "'; expected one of: 'name', 'kind', 'enabled', 'auto_enabled', "
                          "'shader'"};
    }
    return 1;
}

int passNewIndex(lua_State* L) {
    FrameBinding& b = bindingOf(L);
    const std::string name = lua_tostring(L, lua_upvalueindex(1));
    const std::string key = stringArg(L, 2, "ctx.pass");
    const PassDesc& p = passOf(*b.current, name);
    if (key == "enabled" || key == "auto_enabled") {
        if (!lua_isboolean(L, 3))
            throw ScriptError{"ctx.pass('" + name + "')." + key + ": expected a boolean, got " +
                              luaL_typename(L, 3)};
        // Recorded even when the pass is already so: an explicit switch holds from now on.
        (key == "enabled" ? b.changes->enabled : b.changes->automatic)[name] =
            lua_toboolean(L, 3) != 0;
    } else if (key == "shader") {
        if (!p.params.has("shader"))
            throw ScriptError{"ctx.pass('" + name + "').shader: a '" + p.kind +
                              "' pass has no shader"};
        if (lua_type(L, 3) != LUA_TSTRING)
            throw ScriptError{"ctx.pass('" + name + "').shader: expected a path, got " +
                              luaL_typename(L, 3)};
        const std::string shader = lua_tostring(L, 3);
        if (shader == p.params["shader"].asString())
            b.changes->shaders.erase(name);
        else
            b.changes->shaders[name] = shader;
    } else {
        throw ScriptError{"ctx.pass('" + name + "'): cannot set '" + key +
                          "'; settable: 'enabled', 'auto_enabled', 'shader'"};
    }
    return 0;
}

int ctxPass(lua_State* L) {
    FrameBinding& b = bindingOf(L);
    const std::string name = stringArg(L, 1, "ctx.pass");
    passOf(*b.current, name);  // unknown names fail here, with a suggestion
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

int ctxCut(lua_State* L) {
    bindingOf(L).changes->cut = true;
    return 0;
}

// Builds the ctx and calls the function below it, inside the protected call: a memory error
// while building the ctx is then an ordinary script error, not a panic. No C++ object lives here.
int frameTrampoline(lua_State* L) {
    const auto& ctx = *static_cast<const FrameContext*>(lua_touserdata(L, lua_upvalueindex(1)));
    lua_newtable(L);
    lua_pushinteger(L, static_cast<lua_Integer>(ctx.frame));
    lua_setfield(L, -2, "frame");
    lua_pushnumber(L, ctx.time);
    lua_setfield(L, -2, "time");
    lua_pushinteger(L, static_cast<lua_Integer>(ctx.width));
    lua_setfield(L, -2, "width");
    lua_pushinteger(L, static_cast<lua_Integer>(ctx.height));
    lua_setfield(L, -2, "height");
    if (ctx.scene) {
        lua_newtable(L);
        lua_pushinteger(L, ctx.scene->draws);
        lua_setfield(L, -2, "draws");
        lua_pushinteger(L, ctx.scene->lights);
        lua_setfield(L, -2, "lights");
        lua_pushinteger(L, ctx.scene->decals);
        lua_setfield(L, -2, "decals");
        lua_pushinteger(L, ctx.scene->suns);
        lua_setfield(L, -2, "suns");
        lua_pushinteger(L, ctx.scene->probes);
        lua_setfield(L, -2, "probes");
        lua_pushinteger(L, ctx.scene->blended);
        lua_setfield(L, -2, "blended");
        lua_pushinteger(L, ctx.scene->lines);
        lua_setfield(L, -2, "lines");
        lua_newtable(L);
        for (const auto& [cls, draws] : ctx.scene->classes) {
            lua_pushinteger(L, draws);
            lua_setfield(L, -2, cls.c_str());
        }
        lua_setfield(L, -2, "classes");
        lua_setfield(L, -2, "scene");
    }
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
    lua_pushcfunction(L, guarded<ctxCut>);
    lua_setfield(L, -2, "cut");
    lua_call(L, 1, 0);  // the script's function (below the ctx)
    return 0;
}

}  // namespace

Result<void> callFrame(lua_State* L, const FrameContext& ctx, const PipelineDesc& current,
                       FrameChanges& changes) {
    FrameBinding binding{&current, &changes};
    lua_pushlightuserdata(L, &binding);
    lua_setfield(L, LUA_REGISTRYINDEX, kFrameKey);
    lua_pushlightuserdata(L, const_cast<FrameContext*>(&ctx));
    lua_pushcclosure(L, frameTrampoline, 1);
    lua_insert(L, -2);  // trampoline(fn)
    auto r = protectedCall(L, 1, 0);
    lua_pushnil(L);
    lua_setfield(L, LUA_REGISTRYINDEX, kFrameKey);
    return r;
}

}  // namespace rg::lua
