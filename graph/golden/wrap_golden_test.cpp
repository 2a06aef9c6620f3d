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

    ~Impl() {
        if (L) lua_close(L);
    }
};

namespace {

constexpr int kMaxDepth = 32;

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
Result<Value> toValue(lua_State* L, int idx, const std::string& path, const std::string& where,
                      int depth) {
    idx = lua_absindex(L, idx);
    switch (lua_type(L, idx)) {
        case LUA_TNIL:
            return Value();
        case LUA_TBOOLEAN:
            return Value(lua_toboolean(L, idx) != 0);
        case LUA_TNUMBER:
            return Value(static_cast<double>(lua_tonumber(L, idx)));
        case LUA_TSTRING: {
            size_t n = 0;
            const char* s = lua_tolstring(L, idx, &n);
            return Value(std::string(s, n));
        }
        case LUA_TTABLE: {
            if (depth > kMaxDepth)
                return fail(ErrorCode::InvalidInput,
                            located(where, path) + "tables nested too deeply");
            Value::Table table;
            std::map<lua_Integer, Value> items;
            lua_pushnil(L);
            while (lua_next(L, idx) != 0) {
                // Never lua_tostring a key: it would change the key under lua_next.
                std::string key;
                if (lua_type(L, -2) == LUA_TSTRING) {
                    key = lua_tostring(L, -2);
                    auto v =
                        toValue(L, -1, path.empty() ? key : path + "." + key, where, depth + 1);
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
                    return fail(ErrorCode::InvalidInput,
                                located(where, path) + "a " + kt +
                                    " key; tables take names or list positions");
                }
                lua_pop(L, 1);
            }
            if (!items.empty() && !table.empty())
                return fail(ErrorCode::InvalidInput,
                            located(where, path) + "mixes list entries and named fields");
            if (items.empty()) return Value(std::move(table));
            Value::List list;
            lua_Integer expect = 1;
            for (auto& [k, v] : items) {
                if (k != expect)
                    return fail(ErrorCode::InvalidInput, located(where, path) +
                                                             "a list with a hole at [" +
                                                             std::to_string(expect) + "]");
                list.push_back(std::move(v));
                ++expect;
            }
            return Value(std::move(list));
        }
        default:
            return fail(ErrorCode::InvalidInput,
                        located(where, path) + "a " + typeName(L, idx) + " is not allowed here" +
                            (lua_type(L, idx) == LUA_TFUNCTION
                                 ? " (only the top-level 'frame' is a function)"
                                 : ""));
    }
}

// The frame callback's ctx is the rg.frame one (lua::callFrame).

int forbidden(lua_State* L) {
    const char* name = lua_tostring(L, lua_upvalueindex(1));
    throw ScriptError{std::string(name) + " is not available to golden test scripts (sandbox)"};
}

}  // namespace

GoldenScript::GoldenScript() : m(std::make_unique<Impl>()) {}
GoldenScript::~GoldenScript() = default;

Result<std::unique_ptr<GoldenScript>> GoldenScript::load(const std::string& file,
                                                         const std::string& chunkName,
                                                         const Limits& limits) {
    std::ifstream in(file, std::ios::binary);
    if (!in) return fail(ErrorCode::NotFound, "cannot open golden test script '" + file + "'");
    const std::string source((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());

    std::unique_ptr<GoldenScript> script(new GoldenScript());
    Impl& impl = *script->m;
    impl.budget = lua::Budget{"golden test script", limits.memoryBytes, limits.instructions};
    impl.budget.file = file;
    lua_State* L = lua::newSandboxedState(impl.budget);
    if (!L) return fail(ErrorCode::Io, "cannot create a Lua state");
    impl.L = L;

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
            return fail(ErrorCode::InvalidInput,
                        chunkName + ": frame: expected a function(ctx), got " + t);
        } else {
            lua_pop(L, 1);
        }
    }
    auto value = toValue(L, -1, "", chunkName, 0);
    lua_pop(L, 1);
    if (!value) return std::unexpected(value.error());

    std::string name = file;
    if (auto slash = name.find_last_of('/'); slash != std::string::npos)
        name = name.substr(slash + 1);
    if (name.size() > 4 && name.compare(name.size() - 4, 4, ".lua") == 0)
        name.resize(name.size() - 4);
    auto test = parseGoldenTest(*value, hasFrame, name, chunkName);
    if (!test) return std::unexpected(test.error());
    script->m_test = std::move(*test);
    return script;
}

Result<FrameChanges> GoldenScript::frame(const FrameContext& ctx, const PipelineDesc& current) {
    FrameChanges changes;
    if (m->frameRef == LUA_NOREF) return changes;
    lua_State* L = m->L;
    lua_rawgeti(L, LUA_REGISTRYINDEX, m->frameRef);
    if (auto r = lua::callFrame(L, ctx, current, changes); !r) return std::unexpected(r.error());
    return changes;
}

}  // namespace rg::golden
