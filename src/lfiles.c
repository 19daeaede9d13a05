/* Files for case scripts: sph.mkdir(path) makes a folder and its parents (mkdir -p), so that
 * a script never builds a shell command out of a user's path (a quote in it broke
 * os.execute("mkdir -p '...'")); w:write_vtu(file, opts) and sph.pvd_write(file, list), the
 * VTK XML particles and their time series for ParaView. */
#include "lsph.h"

#include <errno.h>
#include <lauxlib.h>
#include <math.h>
#include <string.h>
#include <sys/stat.h>

/* 0, or -1 with errno; an existing folder is success, an existing file is ENOTDIR */
static int make_one(const char *p) {
    if (mkdir(p, 0777) == 0) return 0;
    int e = errno;
    struct stat st;
    if (stat(p, &st) == 0) {
        if (S_ISDIR(st.st_mode)) return 0;
        errno = ENOTDIR;
        return -1;
    }
    errno = e;
    return -1;
}

/* sph.mkdir(path): true, or nil and a message naming the folder that could not be made */
static int l_mkdir(lua_State *L) {
    size_t len;
    const char *path = luaL_checklstring(L, 1, &len);
    if (len == 0) return luaL_argerror(L, 1, "empty path");
    if (strlen(path) != len) return luaL_argerror(L, 1, "path holds a zero byte");
    luaL_Buffer b;
    char *p = luaL_buffinitsize(L, &b, len + 1);
    memcpy(p, path, len + 1);
    for (size_t i = 1; i <= len; i++) { /* each parent, then the whole path */
        if (i < len && p[i] != '/') continue;
        if (i < len && p[i - 1] == '/') continue; /* "a//b" */
        char c = p[i];
        p[i] = '\0';
        int r = make_one(p);
        p[i] = c;
        if (r != 0) {
            int e = errno;
            lua_pushnil(L);
            lua_pushfstring(L, "cannot make folder '%s': %s", lua_pushlstring(L, p, i), strerror(e));
            lua_remove(L, -2);
            return 2;
        }
    }
    lua_pushboolean(L, 1);
    return 1;
}

/* opts[key]: one of names (0-terminated), its index; def when absent */
static int opt_pick(lua_State *L, int idx, const char *fname, const char *key, const char *const *names, int def) {
    int t = lua_getfield(L, idx, key), r = def;
    if (t != LUA_TNIL) {
        const char *v = t == LUA_TSTRING ? lua_tostring(L, -1) : NULL;
        for (r = 0; v && names[r] && strcmp(v, names[r]); r++) {}
        if (!v || !names[r])
            luaL_error(L, "bad argument to '%s' (%s: \"%s\" or \"%s\" expected, got %s)", fname, key, names[0],
                       names[1], v ? v : luaL_typename(L, -1));
    }
    lua_pop(L, 1);
    return r;
}

/* w:write_vtu(file [, {encoding = "base64" | "raw", header_type = "UInt64" | "UInt32",
 * mirror = bool}]): true, or nil and a message */
static int w_write_vtu(lua_State *L) {
    static const char *const keys[] = {"encoding", "header_type", "mirror", 0};
    static const char *const encodings[] = {"base64", "raw", 0};
    static const char *const headers[] = {"UInt64", "UInt32", 0};
    sph_world *w = sph_lua_checkworld(L, 1);
    size_t len;
    const char *file = luaL_checklstring(L, 2, &len);
    if (strlen(file) != len) return luaL_argerror(L, 2, "file name holds a zero byte");
    sph_vtu_options o;
    sph_vtu_defaults(w, &o);
    if (!lua_isnoneornil(L, 3)) {
        luaL_checktype(L, 3, LUA_TTABLE);
        sph_lua_opt_only(L, 3, "write_vtu", keys);
        o.appended = opt_pick(L, 3, "write_vtu", "encoding", encodings, 0);
        o.header64 = opt_pick(L, 3, "write_vtu", "header_type", headers, 0) == 0;
        int t = lua_getfield(L, 3, "mirror");
        if (t != LUA_TNIL && t != LUA_TBOOLEAN)
            luaL_error(L, "bad argument to 'write_vtu' (mirror: boolean expected, got %s)", luaL_typename(L, -1));
        if (t != LUA_TNIL) o.mirror = lua_toboolean(L, -1);
        lua_pop(L, 1);
    }
    int rc = sph_world_write_vtu(w, file, &o);
    return sph_lua_result(L, rc, rc < 0 ? sph_world_error(w) : 0);
}

/* sph.pvd_write(file, {{t = , file = }, ...}): true, or nil and a message */
static int l_pvd_write(lua_State *L) {
    size_t flen;
    const char *file = luaL_checklstring(L, 1, &flen);
    if (strlen(file) != flen) return luaL_argerror(L, 1, "file name holds a zero byte");
    luaL_checktype(L, 2, LUA_TTABLE);
    lua_Integer n = luaL_len(L, 2);
    if (n < 0 || n > 100000000) luaL_error(L, "bad argument #2 to 'pvd_write' (too many entries)");
    double *t = lua_newuserdatauv(L, sizeof(double) * (size_t)(n > 0 ? n : 1), 0);
    const char **files = lua_newuserdatauv(L, sizeof(char *) * (size_t)(n > 0 ? n : 1), 0);
    static const char *const keys[] = {"t", "file", 0};
    for (lua_Integer k = 1; k <= n; k++) {
        if (lua_rawgeti(L, 2, k) != LUA_TTABLE)
            luaL_error(L, "bad argument #2 to 'pvd_write' (entry %d: table {t = , file = } expected, got %s)", (int)k,
                       luaL_typename(L, -1));
        int e = lua_gettop(L);
        sph_lua_opt_only(L, e, "pvd_write", keys);
        if (lua_getfield(L, e, "t") != LUA_TNUMBER || !isfinite(lua_tonumber(L, -1)))
            luaL_error(L, "bad argument #2 to 'pvd_write' (entry %d: t: finite number expected, got %s)", (int)k,
                       lua_type(L, -1) == LUA_TNUMBER ? lua_tostring(L, -1) : luaL_typename(L, -1));
        t[k - 1] = lua_tonumber(L, -1);
        lua_pop(L, 1);
        if (lua_getfield(L, e, "file") != LUA_TSTRING)
            luaL_error(L, "bad argument #2 to 'pvd_write' (entry %d: file: string expected, got %s)", (int)k,
                       luaL_typename(L, -1));
        size_t len;
        files[k - 1] = lua_tolstring(L, -1, &len); /* anchored in the entry, which the list holds */
        if (strlen(files[k - 1]) != len)
            luaL_error(L, "bad argument #2 to 'pvd_write' (entry %d: file: name holds a zero byte)", (int)k);
        lua_pop(L, 2);
    }
    char err[512] = "";
    return sph_lua_result(L, sph_write_pvd(file, (size_t)n, t, files, err, sizeof err), err);
}

void sph_lua_files_open(lua_State *L) {
    lua_pushcfunction(L, l_mkdir);
    lua_setfield(L, -2, "mkdir");
    lua_pushcfunction(L, l_pvd_write);
    lua_setfield(L, -2, "pvd_write");
    luaL_getmetatable(L, SPH_LUA_WORLD);
    lua_getfield(L, -1, "methods");
    lua_pushcfunction(L, w_write_vtu);
    lua_setfield(L, -2, "write_vtu");
    lua_pop(L, 2);
}
