// What every sandboxed Lua state of rgraph shares (pipeline and scene scripts in lua_host.cpp,
// golden test scripts in graph/golden): a memory allowance enforced by the allocator, an
// instruction allowance per call enforced by a count hook, protected calls that return the error
// with a traceback, the safe standard libraries, and the rule that C++ exceptions never cross
// lua_error (glue functions throw ScriptError; `guarded` raises it as a Lua error after every C++
// object of the function is gone). Internal to the modules that embed Lua: it includes lua.h.
#pragma once

extern "C" {
#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>
}

#include <cstdint>
#include <exception>
#include <string>

#include "core/result.h"
#include "core/value.h"
#include "lua_host.h"

namespace rg::lua {

// A state's allowances and what it has used. `who` names the script in the messages
// ("script", "golden test script").
struct Budget {
    std::string who = "script";
    size_t memoryLimit = 256u << 20;
    uint64_t instructionLimit = 100'000'000;  // per protectedCall
    size_t memory = 0;
    uint64_t instructions = 0;
    bool memoryExceeded = false;
    // "file:line" of the Lua code last seen running (sampled by the count hook): where a script
    // that ran out of memory was, since Lua reports that error without a position.
    std::string lastWhere;
    std::string file;  // the script the state runs, named when no position is known
};

// A new state allocating against `budget` (which must outlive it), with the count hook and the
// base, table, string, math and utf8 libraries (plus os when `withOs`: the caller trims it);
// dofile, loadfile, load and collectgarbage removed. nullptr when Lua cannot start.
lua_State* newSandboxedState(Budget& budget, bool withOs = false);

// Calls the function below `nargs` arguments on the stack with a traceback handler; the error
// (or the exceeded allowance, named) comes back as InvalidInput.
Result<void> protectedCall(lua_State* L, int nargs, int nresults);

// Lua value <-> Value. Tables with keys 1..n become lists, with string keys tables; positional
// entries of mixed tables become "#1", "#2", ... keys. `path` names the value in errors.
Result<Value> toValue(lua_State* L, int idx, const std::string& path, int depth = 0);
void pushValue(lua_State* L, const Value& v);

// Calls the rg.frame-style function on top of the stack with its ctx — { frame, time, scene
// (when the pipeline draws one), params (reads and type-checked writes of `current`'s
// parameters), pass(name) (enabled and shader, read and set) } — recording what the script
// changes in `changes`. A ctx kept past the call refuses to be used.
Result<void> callFrame(lua_State* L, const FrameContext& ctx, const PipelineDesc& current,
                       FrameChanges& changes);

// What glue code throws for a script error; `guarded` prefixes the script position unless the
// message already starts with one ("file.lua:12: ...").
struct ScriptError {
    std::string message;
};

std::string withPosition(lua_State* L, const std::string& message);

template <int (*F)(lua_State*)>
int guarded(lua_State* L) {
    {
        std::string message;
        try {
            return F(L);
        } catch (const ScriptError& e) {
            message = e.message;
        } catch (const std::exception& e) {
            message = std::string("internal error: ") + e.what();
        } catch (...) {
            message = "internal error";
        }
        message = withPosition(L, message);
        lua_pushlstring(L, message.data(), message.size());
    }
    return lua_error(L);
}

}  // namespace rg::lua
