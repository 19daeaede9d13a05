/* Shared by the Lua binding files (lsph.c, lpictures.c); not part of the C API. */
#ifndef SPH_LSPH_H
#define SPH_LSPH_H

#include <lua.h>
#include <signal.h>

#include "sph.h"

#define SPH_LUA_WORLD "sph.world"

/* The open world at stack index idx, or a Lua error ("attempt to use a closed sph.world"). */
sph_world *sph_lua_checkworld(lua_State *L, int idx);

/* Pictures (lpictures.c): with the module table on top, add sph.plot, sph.animate and the
   world method render. */
void sph_lua_pictures_open(lua_State *L);

/* Files (lfiles.c): with the module table on top, add sph.mkdir. */
void sph_lua_files_open(lua_State *L);

/* The result of a function that writes a file (loptions.c): true, or, when rc < 0, nil and
   the message err (files are written whole or not at all, so nothing else to report). */
int sph_lua_result(lua_State *L, int rc, const char *err);

/* Options tables (loptions.c). Errors name the function and the option. */
/* Reject keys of the table at idx that are not in the NULL-terminated keys. */
void sph_lua_opt_only(lua_State *L, int idx, const char *fname, const char *const *keys);
/* Numeric field key of the table at idx, or def when absent. */
double sph_lua_opt_number(lua_State *L, int idx, const char *fname, const char *key, double def);
int sph_lua_opt_present(lua_State *L, int idx, const char *key);

/* Interrupts (the sph host, main.c): the number of the signal (SIGINT, SIGTERM) that asked
 * the run to stop, set by the host's handler, 0 while none came. w:step and w:run check it
 * after each step and raise "interrupted (SIGINT) at t = ..., step ..."; it stays set, so
 * every later step raises too, and sph.interrupted() returns it (and its name). */
extern volatile sig_atomic_t sph_lua_interrupt;
/* "SIGINT", "SIGTERM" or "signal N" */
const char *sph_lua_signal_name(int sig);

#endif
