// What the Lua glue files share (lua_host.cpp: the state, require and the declarations;
// lua_views.cpp: rg.view and LuaHost::addView): the host's state behind a lua_State. Internal to
// graph/lua; it includes lua.h.
#pragma once

#include <string>
#include <tuple>
#include <vector>

#include "declarations.h"
#include "lua_host.h"
#include "lua_sandbox.h"

namespace rg {

// While a view's function runs (LuaHost::addView): the view asked for, the pipeline it is added
// to, what it asked to compile into the pipeline's passes (v.define) and the error it stopped
// with (v.fail), which is the user's, not the script's: it comes back without a traceback.
struct ViewCall {
    std::string view;
    const PipelineDesc* loaded = nullptr;
    const ViewFacts* scene = nullptr;                                  // nullptr: no scene
    std::vector<std::tuple<std::string, std::string, Value>> defines;  // pass, define, value
    std::string error;
    bool found = false;
};

struct LuaHost::Impl {
    LuaHostOptions options;
    lua_State* L = nullptr;
    lua::Budget budget;  // memory and instructions (lua_sandbox.h)
    std::vector<Declaration> decls;
    OutputNames output;
    std::vector<std::string> files;
    std::string pipelineDir;
    ViewCall* view = nullptr;  // set while a view's function runs

    ~Impl() { close(); }
    void close() {
        if (L) lua_close(L);
        L = nullptr;
    }
};

namespace host {

inline LuaHost::Impl& implOf(lua_State* L) {
    return **static_cast<LuaHost::Impl**>(lua_getextraspace(L));
}

// "file:line" of the Lua code that called the running C function.
inline std::string callerOrigin(lua_State* L) {
    lua_Debug ar;
    for (int level = 1; lua_getstack(L, level, &ar); ++level) {
        lua_getinfo(L, "Sl", &ar);
        if (ar.currentline > 0)
            return std::string(ar.short_src) + ":" + std::to_string(ar.currentline);
    }
    return "?";
}

// rg.view "name" { ... } (lua_views.cpp), set on the rg table by LuaHost::loadDeclarations.
int declareView(lua_State* L);

}  // namespace host

}  // namespace rg
