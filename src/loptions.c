/* Options tables for the Lua binding files: unknown keys are errors (a misspelt option is
 * never a silent default) and a wrong type names the function and the option. */
#include "lsph.h"

#include <lauxlib.h>
#include <string.h>

void sph_lua_opt_only(lua_State *L, int idx, const char *fname, const char *const *keys) {
    lua_pushnil(L);
    while (lua_next(L, idx)) {
        lua_pop(L, 1);
        int ok = 0;
        if (lua_type(L, -1) == LUA_TSTRING) {
            const char *k = lua_tostring(L, -1);
            for (int i = 0; keys[i]; i++)
                if (!strcmp(k, keys[i])) ok = 1;
        }
        if (!ok) {
            luaL_Buffer b;
            luaL_buffinit(L, &b);
            for (int i = 0; keys[i]; i++) {
                if (i) luaL_addstring(&b, ", ");
                luaL_addstring(&b, keys[i]);
            }
            luaL_pushresult(&b);
            luaL_error(L, "bad argument to '%s' (unknown option '%s'; options are %s)", fname,
                       lua_type(L, -2) == LUA_TSTRING ? lua_tostring(L, -2) : luaL_typename(L, -2),
                       lua_tostring(L, -1));
        }
    }
}

double sph_lua_opt_number(lua_State *L, int idx, const char *fname, const char *key, double def) {
    double v = def;
    if (lua_getfield(L, idx, key) != LUA_TNIL) {
        if (!lua_isnumber(L, -1))
            luaL_error(L, "bad argument to '%s' (%s: number expected, got %s)", fname, key, luaL_typename(L, -1));
        v = lua_tonumber(L, -1);
    }
    lua_pop(L, 1);
    return v;
}

int sph_lua_opt_present(lua_State *L, int idx, const char *key) {
    int t = lua_getfield(L, idx, key);
    lua_pop(L, 1);
    return t != LUA_TNIL;
}

int sph_lua_result(lua_State *L, int rc, const char *err) {
    if (rc < 0) {
        luaL_pushfail(L);
        lua_pushstring(L, err);
        return 2;
    }
    lua_pushboolean(L, 1);
    return 1;
}
