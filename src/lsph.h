/* Shared by the Lua binding files (lsph.c, lpictures.c); not part of the C API. */
#ifndef SPH_LSPH_H
#define SPH_LSPH_H

#include <lua.h>

#include "sph.h"

#define SPH_LUA_WORLD "sph.world"

/* The open world at stack index idx, or a Lua error ("attempt to use a closed sph.world"). */
sph_world *sph_lua_checkworld(lua_State *L, int idx);

/* Pictures (lpictures.c): with the module table on top, add sph.plot, sph.animate and the
   world method render. */
void sph_lua_pictures_open(lua_State *L);

/* Options tables (loptions.c). Errors name the function and the option. */
/* Reject keys of the table at idx that are not in the NULL-terminated keys. */
void sph_lua_opt_only(lua_State *L, int idx, const char *fname, const char *const *keys);
/* Numeric field key of the table at idx, or def when absent. */
double sph_lua_opt_number(lua_State *L, int idx, const char *fname, const char *key, double def);
int sph_lua_opt_present(lua_State *L, int idx, const char *key);

#endif
