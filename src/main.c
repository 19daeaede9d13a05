/* The sph host: runs a Lua case script with the sph module preloaded.
 *   sph CASE.lua [name=value ...]
 * name=value pairs reach the script as a table (numbers as numbers), both as the
 * chunk's argument (local opt = ...) and as the global `params`; `arg` is as in lua.c.
 * SIGINT and SIGTERM do not kill a run: the handler only records the signal (and puts
 * back the default action, so a second signal kills at once); the step that is running
 * ends, then w:step / w:run raise "interrupted (SIGINT) at t = ..., step ..." (lsph.c),
 * which a script can catch to write its outputs and a state (scripts/squeeze.lua). The
 * host then exits with status 128 + the signal (130, 143). A script busy in Lua alone
 * (no step) sees the signal at its next step, or the host's exit status at its end.
 * The Lua helpers (require "sph.params" ...) come from $SPH_LUA_DIR, else from
 * PREFIX/share/lua/5.4 next to an installed PREFIX/bin/sph, else from the build tree's lua/
 * (lua_dir below). */
#include "lsph.h"
#include "sph.h"
#include "sph_pictures.h"

#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int luaopen_sph(lua_State *L);

static struct sigaction default_action; /* SIG_DFL, made before the handler is installed */

static void on_signal(int sig) {
    sph_lua_interrupt = sig;
    sigaction(SIGINT, &default_action, 0); /* async-signal-safe: a second signal kills */
    sigaction(SIGTERM, &default_action, 0);
}

static void catch_signals(void) {
    memset(&default_action, 0, sizeof default_action);
    default_action.sa_handler = SIG_DFL;
    sigemptyset(&default_action.sa_mask);
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaddset(&sa.sa_mask, SIGINT);
    sigaddset(&sa.sa_mask, SIGTERM);
    sa.sa_flags = SA_RESTART; /* a write the signal lands in goes on */
    sigaction(SIGINT, &sa, 0);
    sigaction(SIGTERM, &sa, 0);
}

static void usage(FILE *f) {
    fprintf(f,
            "usage: sph CASE.lua [name=value ...]\n"
            "       sph --help | --version\n"
            "Runs a Lua case script with the sph module (incompressible SPH for viscoplastic\n"
            "flows). name=value pairs reach the script as a table: local opt = ... (numbers as\n"
            "numbers, true/false as booleans, anything else as strings).\n");
}

static int traceback(lua_State *L) {
    const char *msg = lua_tostring(L, 1);
    if (!msg) msg = lua_pushfstring(L, "(error object is a %s value)", luaL_typename(L, 1));
    luaL_traceback(L, L, msg, 1);
    return 1;
}

/* The folder of the Lua helpers (sph/params.lua, sph/squeeze.lua, ...), first found of:
 *   $SPH_LUA_DIR;
 *   PREFIX/share/lua/5.4, for a host installed as PREFIX/bin/sph (`make install`): found from
 *   the executable's own path (/proc/self/exe, else argv[0] when it holds a slash), so an
 *   installed tree, moved or copied elsewhere, still finds its own helpers and never the
 *   build tree's;
 *   the build tree's lua/, compiled in (SPH_LUA_DIR): the host run from build/.
 * A candidate counts when it holds sph/params.lua. */
static const char *lua_dir(const char *argv0, char *buf, size_t n) {
    const char *env = getenv("SPH_LUA_DIR");
    if (env) return env;
    char exe[4096];
    ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (len > 0) exe[len] = 0;
    else if (argv0 && strchr(argv0, '/')) snprintf(exe, sizeof exe, "%s", argv0); /* no /proc */
    else exe[0] = 0;
    char *slash = strrchr(exe, '/'); /* exe = PREFIX/bin/sph: drop "/sph", then "/bin" */
    if (slash) {
        *slash = 0;
        slash = strrchr(exe, '/');
        const char *prefix = exe;
        if (slash) *slash = 0;
        else prefix = "."; /* argv[0] = bin/sph */
        int k = snprintf(buf, n, "%s/share/lua/5.4", prefix);
        char probe[4200];
        if (k > 0 && (size_t)k < n) {
            snprintf(probe, sizeof probe, "%s/sph/params.lua", buf);
            if (access(probe, R_OK) == 0) return buf;
        }
    }
    return SPH_LUA_DIR;
}

/* package.path: the helpers' folder (lua_dir) and the script's folder first. */
static void set_path(lua_State *L, const char *argv0, const char *script) {
    char buf[4096];
    const char *dir = lua_dir(argv0, buf, sizeof buf);
    char sdir[4096];
    snprintf(sdir, sizeof sdir, "%s", script);
    char *slash = strrchr(sdir, '/');
    if (slash) *slash = 0;
    else snprintf(sdir, sizeof sdir, ".");
    lua_getglobal(L, "package");
    lua_getfield(L, -1, "path");
    lua_pushfstring(L, "%s/?.lua;%s/?/init.lua;%s/?.lua;%s", dir, dir, sdir, lua_tostring(L, -1));
    lua_setfield(L, -3, "path");
    lua_pop(L, 2);
}

static void push_value(lua_State *L, const char *v) {
    if (!strcmp(v, "true")) lua_pushboolean(L, 1);
    else if (!strcmp(v, "false")) lua_pushboolean(L, 0);
    else if (!lua_stringtonumber(L, v)) lua_pushstring(L, v);
}

static int run(lua_State *L) {
    int argc = (int)lua_tointeger(L, 1);
    char **argv = lua_touserdata(L, 2);
    luaL_openlibs(L);
    luaL_requiref(L, "sph", luaopen_sph, 0);
    lua_pop(L, 1);
    set_path(L, argv[0], argv[1]);
    lua_createtable(L, argc, 1); /* arg, as in lua.c */
    for (int i = 0; i < argc; i++) {
        lua_pushstring(L, argv[i]);
        lua_rawseti(L, -2, i - 1);
    }
    lua_setglobal(L, "arg");
    lua_newtable(L); /* params */
    for (int i = 2; i < argc; i++) {
        const char *eq = strchr(argv[i], '=');
        if (!eq || eq == argv[i])
            return luaL_error(L, "argument '%s': name=value expected", argv[i]);
        lua_pushlstring(L, argv[i], (size_t)(eq - argv[i]));
        push_value(L, eq + 1);
        lua_settable(L, -3);
    }
    lua_pushvalue(L, -1);
    lua_setglobal(L, "params");
    if (luaL_loadfile(L, argv[1]) != LUA_OK) return lua_error(L);
    lua_insert(L, -2);
    lua_call(L, 1, 0);
    return 0;
}

/* OpenMP threads spin briefly at a barrier, then sleep (GOMP_SPINCOUNT = 10000), unless
 * the environment says how they wait. A step is many short parallel loops: sleeping at
 * once (passive) pays a wake-up at each, spinning long (libgomp's default) takes the cores
 * from the work on a busy machine. The headline squeeze on 2 threads (1,600 particles):
 * passive 5.6 s, bounded spin 0.9 s on an idle machine; 5.5 s against 2.2 s (active 4.2 s)
 * with both cores loaded. libgomp reads its environment once, when it is loaded, before
 * main: a setenv here alone changes nothing, so the host sets it and executes itself again
 * (Linux, /proc/self/exe; elsewhere, or if that fails, it runs on as it is). */
static void bounded_wait(char **argv) {
    if (getenv("OMP_WAIT_POLICY") || getenv("GOMP_SPINCOUNT")) return;
    if (setenv("GOMP_SPINCOUNT", "10000", 1)) return;
    execv("/proc/self/exe", argv); /* returns only on failure */
}

/* cairo's and fontconfig's caches, for leak checkers: also when a script ends by os.exit
 * (its status: squeeze.lua's 2, 130, 143), which skips the end of main */
static void release_fonts(void) {
    static int done = 0;
    if (done) return;
    done = 1;
    sph_render_release_fonts();
}

int main(int argc, char **argv) {
    bounded_wait(argv);
    atexit(release_fonts);
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
        usage(stdout);
        return 0;
    }
    if (!strcmp(argv[1], "--version")) {
        printf("sph %s (%s)\n", SPH_VERSION, LUA_RELEASE);
        return 0;
    }
    lua_State *L = luaL_newstate();
    if (!L) {
        fprintf(stderr, "sph: cannot create a Lua state (out of memory)\n");
        return 1;
    }
    lua_pushcfunction(L, traceback);
    lua_pushcfunction(L, run);
    lua_pushinteger(L, argc);
    lua_pushlightuserdata(L, argv);
    catch_signals();
    int rc = lua_pcall(L, 2, 0, 1);
    if (rc != LUA_OK) fprintf(stderr, "sph: %s\n", lua_tostring(L, -1));
    int sig = sph_lua_interrupt;
    if (sig && rc == LUA_OK) fprintf(stderr, "sph: interrupted (%s)\n", sph_lua_signal_name(sig));
    lua_close(L);
    release_fonts();
    if (sig) return 128 + sig;
    return rc == LUA_OK ? 0 : 1;
}
