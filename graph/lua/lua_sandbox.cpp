#include "lua_sandbox.h"

#include <cstdlib>
#include <utility>

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

void countHook(lua_State* L, lua_Debug*) {
    Budget& budget = budgetOf(L);
    budget.instructions += kHookEvery;
    if (budget.instructions > budget.instructionLimit) {
        // Level 0 inside a count hook is the Lua function that was running.
        luaL_where(L, 0);
        lua_pushfstring(L, "%s stopped after %d million instructions: a runaway loop? (limit: %d million)", budget.who.c_str(),
                        static_cast<int>(budget.instructions / 1000000), static_cast<int>(budget.instructionLimit / 1000000));
        lua_concat(L, 2);
        lua_error(L);
    }
}

int messageHandler(lua_State* L) {
    const char* msg = lua_tostring(L, 1);
    if (!msg) msg = luaL_tolstring(L, 1, nullptr);
    luaL_traceback(L, L, msg, 1);
    return 1;
}

}  // namespace

lua_State* newSandboxedState(Budget& budget, bool withOs) {
    lua_State* L = lua_newstate(allocate, &budget);
    if (!L) return nullptr;
    lua_sethook(L, countHook, LUA_MASKCOUNT, kHookEvery);
    const std::pair<const char*, lua_CFunction> libs[] = {{LUA_GNAME, luaopen_base},       {LUA_TABLIBNAME, luaopen_table},
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
    const int status = lua_pcall(L, nargs, nresults, base);
    lua_remove(L, base);
    if (status == LUA_OK) return {};
    std::string msg = lua_tostring(L, -1) ? lua_tostring(L, -1) : "unknown Lua error";
    lua_pop(L, 1);
    if (status == LUA_ERRMEM || budget.memoryExceeded)
        msg = budget.who + " stopped: it used more than " + std::to_string(budget.memoryLimit >> 20) + " MiB of Lua memory";
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

}  // namespace rg::lua
