/* Files for case scripts: sph.mkdir(path) makes a folder and its parents (mkdir -p), so that
 * a script never builds a shell command out of a user's path (a quote in it broke
 * os.execute("mkdir -p '...'")). */
#include "lsph.h"

#include <errno.h>
#include <lauxlib.h>
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

void sph_lua_files_open(lua_State *L) {
    lua_pushcfunction(L, l_mkdir);
    lua_setfield(L, -2, "mkdir");
}
