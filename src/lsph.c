/* The Lua binding: module "sph" over the C engine (src/sph.h). A thin layer: it checks
 * arguments (errors name the argument), calls the engine, and turns engine errors into Lua
 * errors. Lua runs at most once per step (plate laws) and once per output. */
#include "lsph.h"

#include <lauxlib.h>
#include <lualib.h>
#include <math.h>
#include <omp.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define WORLD SPH_LUA_WORLD
#define PLATE "sph.plate"
#define MATERIAL "sph.material"

typedef struct {
    sph_world *w;
} lworld;

typedef struct {
    int index; /* plate index in the world */
} lplate;

/* ---- helpers -------------------------------------------------------------------- */

/* rect = {x0, y0, x1, y1} */
static void opt_rect(lua_State *L, int idx, const char *fname, double r[4]) {
    if (lua_getfield(L, idx, "rect") != LUA_TTABLE)
        luaL_error(L, "bad argument to '%s' (rect: table {x0, y0, x1, y1} expected, got %s)", fname,
                   luaL_typename(L, -1));
    for (int k = 0; k < 4; k++) {
        lua_rawgeti(L, -1, k + 1);
        if (!lua_isnumber(L, -1))
            luaL_error(L, "bad argument to '%s' (rect[%d]: number expected, got %s)", fname, k + 1,
                       luaL_typename(L, -1));
        r[k] = lua_tonumber(L, -1);
        lua_pop(L, 1);
    }
    lua_pop(L, 1);
    if (!(r[2] > r[0] && r[3] > r[1]))
        luaL_error(L, "bad argument to '%s' (rect: need x0 < x1 and y0 < y1, got {%f, %f, %f, %f})",
                   fname, r[0], r[1], r[2], r[3]);
}

static lworld *check_world(lua_State *L, int idx) {
    lworld *lw = luaL_checkudata(L, idx, WORLD);
    if (!lw->w) luaL_error(L, "attempt to use a closed sph.world");
    return lw;
}

sph_world *sph_lua_checkworld(lua_State *L, int idx) { return check_world(L, idx)->w; }

static int engine_error(lua_State *L, sph_world *w) { return luaL_error(L, "%s", sph_world_error(w)); }

volatile sig_atomic_t sph_lua_interrupt = 0;

const char *sph_lua_signal_name(int sig) {
    static char buf[32];
    if (sig == SIGINT) return "SIGINT";
    if (sig == SIGTERM) return "SIGTERM";
    snprintf(buf, sizeof buf, "signal %d", sig);
    return buf;
}

/* After a step: an interrupt the host caught ends w:step / w:run with a Lua error, the
 * step that was running completed (the world is consistent: save it, write its outputs). */
static void check_interrupt(lua_State *L, sph_world *w) {
    int sig = sph_lua_interrupt;
    if (sig) {
        char msg[128];
        snprintf(msg, sizeof msg, "interrupted (%s) at t = %.10g, step %ld", sph_lua_signal_name(sig),
                 sph_world_time(w), sph_world_steps(w));
        luaL_error(L, "%s", msg);
    }
}

/* sph.interrupted(): nil, or the signal's number and name ("SIGINT") */
static int l_interrupted(lua_State *L) {
    int sig = sph_lua_interrupt;
    if (!sig) {
        lua_pushnil(L);
        return 1;
    }
    lua_pushinteger(L, sig);
    lua_pushstring(L, sph_lua_signal_name(sig));
    return 2;
}

/* ---- materials ------------------------------------------------------------------ */

static int new_material(lua_State *L, sph_model model, const char *fname) {
    luaL_checktype(L, 1, LUA_TTABLE);
    static const char *const nk[] = {"mu", 0};
    static const char *const bk[] = {"mu", "tau0", "m", 0};
    static const char *const hk[] = {"K", "n", "tau0", "m", 0};
    sph_material mat;
    memset(&mat, 0, sizeof mat);
    mat.model = model;
    const char *const *keys = model == SPH_NEWTONIAN ? nk : model == SPH_BINGHAM ? bk : hk;
    sph_lua_opt_only(L, 1, fname, keys);
    for (int i = 0; keys[i]; i++)
        if (!sph_lua_opt_present(L, 1, keys[i]))
            luaL_error(L, "bad argument to '%s' (%s: number expected, got no value)", fname, keys[i]);
    mat.mu = sph_lua_opt_number(L, 1, fname, "mu", 0);
    mat.tau0 = sph_lua_opt_number(L, 1, fname, "tau0", 0);
    mat.m = sph_lua_opt_number(L, 1, fname, "m", 0);
    mat.K = sph_lua_opt_number(L, 1, fname, "K", 0);
    mat.n = sph_lua_opt_number(L, 1, fname, "n", 1);
    const char *bad = sph_rheology_check(&mat);
    if (bad) luaL_error(L, "bad argument to '%s' (%s)", fname, bad);
    sph_material *ud = lua_newuserdatauv(L, sizeof *ud, 0);
    *ud = mat;
    luaL_setmetatable(L, MATERIAL);
    return 1;
}

static int l_newtonian(lua_State *L) { return new_material(L, SPH_NEWTONIAN, "newtonian"); }
static int l_bingham(lua_State *L) { return new_material(L, SPH_BINGHAM, "bingham"); }
static int l_hb(lua_State *L) { return new_material(L, SPH_HERSCHEL_BULKLEY, "herschel_bulkley"); }

static int mat_eta(lua_State *L) {
    sph_material *m = luaL_checkudata(L, 1, MATERIAL);
    double g = luaL_checknumber(L, 2);
    luaL_argcheck(L, g >= 0, 2, "shear rate must be >= 0");
    lua_pushnumber(L, sph_rheology_eta(m, g));
    return 1;
}

static int mat_index(lua_State *L) {
    sph_material *m = luaL_checkudata(L, 1, MATERIAL);
    const char *k = luaL_checkstring(L, 2);
    static const char *const models[] = {"newtonian", "bingham", "herschel_bulkley"};
    if (!strcmp(k, "model")) lua_pushstring(L, models[m->model]);
    else if (!strcmp(k, "mu")) lua_pushnumber(L, m->mu);
    else if (!strcmp(k, "tau0")) lua_pushnumber(L, m->tau0);
    else if (!strcmp(k, "m")) lua_pushnumber(L, m->m);
    else if (!strcmp(k, "K")) lua_pushnumber(L, m->K);
    else if (!strcmp(k, "n")) lua_pushnumber(L, m->n);
    else if (!strcmp(k, "eta")) lua_pushcfunction(L, mat_eta);
    else lua_pushnil(L);
    return 1;
}

static int mat_tostring(lua_State *L) {
    sph_material *m = luaL_checkudata(L, 1, MATERIAL);
    if (m->model == SPH_NEWTONIAN) lua_pushfstring(L, "newtonian{mu = %f}", m->mu);
    else if (m->model == SPH_BINGHAM)
        lua_pushfstring(L, "bingham{mu = %f, tau0 = %f, m = %f}", m->mu, m->tau0, m->m);
    else lua_pushfstring(L, "herschel_bulkley{K = %f, n = %f, tau0 = %f, m = %f}", m->K, m->n, m->tau0, m->m);
    return 1;
}

/* ---- world ---------------------------------------------------------------------- */

static void axis_range(lua_State *L, int idx, const char *fname, const char *what, const char *axis,
                       int *on, double *lo, double *hi) {
    int t = lua_getfield(L, idx, axis);
    if (t == LUA_TTABLE) {
        lua_rawgeti(L, -1, 1);
        lua_rawgeti(L, -2, 2);
        if (!lua_isnumber(L, -2) || !lua_isnumber(L, -1))
            luaL_error(L, "bad argument to '%s' (%s.%s: {lo, hi} expected)", fname, what, axis);
        *on = 1;
        *lo = lua_tonumber(L, -2);
        *hi = lua_tonumber(L, -1);
        lua_pop(L, 2);
    } else if (t != LUA_TNIL) {
        luaL_error(L, "bad argument to '%s' (%s.%s: {lo, hi} expected, got %s)", fname, what, axis,
                   luaL_typename(L, -1));
    }
    lua_pop(L, 1);
}

/* A new world handle (its engine world still to be set) on the stack; its uservalue holds
 * [k] = law of plate k (function or nil) and the plate handles. */
static lworld *push_world(lua_State *L) {
    lworld *lw = lua_newuserdatauv(L, sizeof *lw, 1);
    lw->w = 0;
    luaL_setmetatable(L, WORLD);
    lua_newtable(L);
    lua_setiuservalue(L, -2, 1);
    return lw;
}

/* world{key = names[0] | names[1] | ...} (names ends with 0): the index of the name given,
 * def when absent; anything else is an error naming them all. */
static int opt_pick(lua_State *L, const char *key, const char *const names[], int def) {
    int t = lua_getfield(L, 1, key), r = def;
    if (t != LUA_TNIL) {
        const char *v = t == LUA_TSTRING ? lua_tostring(L, -1) : "";
        for (r = 0; names[r] && strcmp(v, names[r]); r++) {}
        if (!names[r]) {
            luaL_Buffer b;
            luaL_buffinit(L, &b);
            for (int k = 0; names[k]; k++) {
                if (k > 0) luaL_addstring(&b, names[k + 1] ? ", " : " or ");
                luaL_addchar(&b, '"');
                luaL_addstring(&b, names[k]);
                luaL_addchar(&b, '"');
            }
            luaL_pushresult(&b);
            luaL_error(L, "bad argument to 'world' (%s: %s expected)", key, lua_tostring(L, -1));
        }
    }
    lua_pop(L, 1);
    return r;
}

/* world{key = first | second}: 0 for first, 1 for second, def when absent (opt_pick). */
static int opt_choice(lua_State *L, const char *key, const char *first, const char *second, int def) {
    const char *const names[] = {first, second, 0};
    return opt_pick(L, key, names, def);
}

/* Options sph.world once took, and what the engine now always does instead: a script that
 * passes one gets this rather than the plain "unknown option". */
static const char *const REMOVED[][2] = {
    {"cvisc", "limits dt to 0.125 rho h^2 / max eta with explicit viscosity"},
    {"cforce", "limits dt to 0.25 sqrt(h / max acceleration)"},
    {"max_iter", "allows 5000 iterations a solve"},
    {"solver", "preconditions its solves with algebraic multigrid"},
    {"pressure_predictor", "carries the last step's pressure gradient in the implicit viscous step"},
    {"wall", "extrapolates the wall velocity linearly (Morris)"},
    {"projection_passes", "projects once a step"},
    {"dt_growth", "lets dt grow by at most 25 % a step (5 % near the density tolerance)"},
    {"density_relax", "aims to remove the whole density error"},
    {"density_passes", "makes up to 2 density passes a step while the error exceeds density_tol"},
    {"density_limit", "makes more passes, then descent moves, while the density error exceeds 0.8 %"},
    {"density_descent", "makes up to 20 descent moves when the density passes stall"},
    {"density_solve_tol", "solves the density correction to a relative residual of 1e-3"},
    {"density_diffusion", "leaves the density unfiltered"},
    {"density_correction", "corrects the density by passes, or by GMRES with thin_film = true"},
    {"pressure_gradient", "takes the symmetric pressure gradient, or the difference form with thin_film = true"},
    {"density_wait", "makes the passes the density error asks for at every step"},
    {"density_probe", "tries a later density pass after one that moved nothing on a loose solve first"},
    {"density_gradient", "moves the first density pass along whichever gradient lowers the error more"},
    {"visc_tol", "solves the implicit viscous step to tol, the pressure solve's tolerance"},
};

/* sph.world's options. The numbers map onto sph_params fields: their defaults are
 * sph_params_default's and their ranges are checked by sph_world_new (world.c), one message
 * for the C and the Lua caller alike; the others are read below. docs/api.md lists the
 * same keys (tests/lua/test_api.lua checks it). */
static const struct {
    const char *name;
    size_t offset; /* of the double in sph_params */
} NUMBER_OPTS[] = {
    {"dx", offsetof(sph_params, dx)},           {"rho", offsetof(sph_params, rho0)},
    {"shifting", offsetof(sph_params, shifting)}, {"dt_max", offsetof(sph_params, dt_max)},
    {"tol", offsetof(sph_params, tol)},         {"surface", offsetof(sph_params, surface_div)},
    {"density_tol", offsetof(sph_params, density_tol)}, {"h", offsetof(sph_params, h)},
    {"cfl", offsetof(sph_params, cfl)},
};
#define N_NUMBER_OPTS (sizeof NUMBER_OPTS / sizeof NUMBER_OPTS[0])
static const char *const OTHER_OPTS[] = {"gravity", "viscosity", "periodic", "symmetry", "threads", "thin_film"};
#define N_OTHER_OPTS (sizeof OTHER_OPTS / sizeof OTHER_OPTS[0])

static int l_world(lua_State *L) {
    const char *keys[N_NUMBER_OPTS + N_OTHER_OPTS + 1];
    for (size_t k = 0; k < N_NUMBER_OPTS; k++) keys[k] = NUMBER_OPTS[k].name;
    for (size_t k = 0; k < N_OTHER_OPTS; k++) keys[N_NUMBER_OPTS + k] = OTHER_OPTS[k];
    keys[N_NUMBER_OPTS + N_OTHER_OPTS] = 0;
    luaL_checktype(L, 1, LUA_TTABLE);
    for (size_t k = 0; k < sizeof REMOVED / sizeof REMOVED[0]; k++)
        if (sph_lua_opt_present(L, 1, REMOVED[k][0]))
            luaL_error(L, "bad argument to 'world' ('%s' was removed: the engine now always %s)", REMOVED[k][0],
                       REMOVED[k][1]);
    sph_lua_opt_only(L, 1, "world", keys);
    sph_params p;
    sph_params_default(&p);
    if (!sph_lua_opt_present(L, 1, "dx")) luaL_error(L, "bad argument to 'world' (dx: number expected, got no value)");
    for (size_t k = 0; k < N_NUMBER_OPTS; k++) {
        double *field = (double *)((char *)&p + NUMBER_OPTS[k].offset);
        if (field == &p.shifting) { /* "auto" (the default, SPH_SHIFTING_AUTO) or a number */
            int ts = lua_getfield(L, 1, "shifting");
            int isauto = ts == LUA_TSTRING && strcmp(lua_tostring(L, -1), "auto") == 0;
            int bad = ts == LUA_TSTRING && !isauto && !lua_isnumber(L, -1);
            lua_pop(L, 1);
            if (bad) luaL_error(L, "bad argument to 'world' (shifting: a number >= 0 or \"auto\" expected)");
            if (isauto) continue;
        }
        *field = sph_lua_opt_number(L, 1, "world", NUMBER_OPTS[k].name, *field);
    }
    /* checked as a double: converting one beyond int (threads = 1e20) is undefined */
    double threads = sph_lua_opt_number(L, 1, "world", "threads", 0);
    if (!(threads >= 0 && threads <= SPH_MAX_THREADS && threads == floor(threads))) {
        char got[32];
        snprintf(got, sizeof got, "%g", threads); /* lua_pushfstring has no %g */
        luaL_error(L, "bad argument to 'world' (threads must be 1..%d (0: all cores), got %s)", SPH_MAX_THREADS, got);
    }
    p.threads = (int)threads;
    int t = lua_getfield(L, 1, "gravity");
    if (t == LUA_TTABLE) {
        for (int k = 0; k < 2; k++) {
            lua_rawgeti(L, -1, k + 1);
            if (!lua_isnumber(L, -1)) luaL_error(L, "bad argument to 'world' (gravity: {gx, gy} expected)");
            p.gravity[k] = lua_tonumber(L, -1);
            lua_pop(L, 1);
        }
    } else if (t != LUA_TNIL) {
        luaL_error(L, "bad argument to 'world' (gravity: {gx, gy} expected, got %s)", luaL_typename(L, -1));
    }
    lua_pop(L, 1);
    p.viscosity = opt_choice(L, "viscosity", "implicit", "explicit", p.viscosity == SPH_VISC_EXPLICIT)
                      ? SPH_VISC_EXPLICIT : SPH_VISC_IMPLICIT;
    t = lua_getfield(L, 1, "thin_film");
    if (t != LUA_TNIL && t != LUA_TBOOLEAN)
        luaL_error(L, "bad argument to 'world' (thin_film: boolean expected, got %s)", luaL_typename(L, -1));
    p.thin_film = lua_toboolean(L, -1);
    lua_pop(L, 1);
    t = lua_getfield(L, 1, "periodic");
    if (t == LUA_TTABLE) {
        axis_range(L, lua_gettop(L), "world", "periodic", "x", &p.periodic[0], &p.period_lo[0], &p.period_hi[0]);
        axis_range(L, lua_gettop(L), "world", "periodic", "y", &p.periodic[1], &p.period_lo[1], &p.period_hi[1]);
    } else if (t != LUA_TNIL) {
        luaL_error(L, "bad argument to 'world' (periodic: table {x = {lo, hi}} expected)");
    }
    lua_pop(L, 1);
    t = lua_getfield(L, 1, "symmetry");
    if (t == LUA_TTABLE) {
        for (int a = 0; a < 2; a++) {
            int tt = lua_getfield(L, -1, a == 0 ? "x" : "y");
            if (tt == LUA_TNUMBER) {
                p.symmetry[a] = 1;
                p.sym_at[a] = lua_tonumber(L, -1);
            } else if (tt != LUA_TNIL) {
                luaL_error(L, "bad argument to 'world' (symmetry.%s: number expected)", a == 0 ? "x" : "y");
            }
            lua_pop(L, 1);
        }
    } else if (t != LUA_TNIL) {
        luaL_error(L, "bad argument to 'world' (symmetry: table {x = x0} expected)");
    }
    lua_pop(L, 1);
    lworld *lw = push_world(L);
    char err[256];
    lw->w = sph_world_new(&p, err, sizeof err);
    if (!lw->w) luaL_error(L, "bad argument to 'world' (%s)", err);
    return 1;
}

static int w_close(lua_State *L) {
    lworld *lw = luaL_checkudata(L, 1, WORLD);
    sph_world_free(lw->w);
    lw->w = 0;
    return 0;
}

static int w_tostring(lua_State *L) {
    lworld *lw = luaL_checkudata(L, 1, WORLD);
    if (!lw->w) lua_pushliteral(L, "sph.world (closed)");
    else
        lua_pushfstring(L, "sph.world (%d fluid particles, t = %f)", sph_world_nfluid(lw->w),
                        sph_world_time(lw->w));
    return 1;
}

static int w_fill(lua_State *L) {
    lworld *lw = check_world(L, 1);
    static const char *const keys[] = {"rect", "material", 0};
    luaL_checktype(L, 2, LUA_TTABLE);
    sph_lua_opt_only(L, 2, "fill", keys);
    double r[4];
    opt_rect(L, 2, "fill", r);
    lua_getfield(L, 2, "material");
    sph_material *m = luaL_testudata(L, -1, MATERIAL);
    if (!m)
        luaL_error(L, "bad argument to 'fill' (material: sph material expected (sph.bingham{...}, "
                      "sph.newtonian{...}), got %s)", luaL_typename(L, -1));
    int c = sph_world_fill(lw->w, r, m);
    if (c < 0) return engine_error(L, lw->w);
    lua_pushinteger(L, c);
    return 1;
}

/* The handle of plate k (0-based) of the world at idx 1, made once and kept in the world's
 * uservalue (laws get it as their second argument). */
static void push_plate(lua_State *L, int k) {
    char key[32];
    snprintf(key, sizeof key, "plate%d", k);
    lua_getiuservalue(L, 1, 1);
    if (lua_getfield(L, -1, key) != LUA_TNIL) {
        lua_remove(L, -2);
        return;
    }
    lua_pop(L, 1);
    lplate *lp = lua_newuserdatauv(L, sizeof *lp, 1);
    lp->index = k;
    luaL_setmetatable(L, PLATE);
    lua_pushvalue(L, 1); /* keep the world alive while the plate handle lives */
    lua_setiuservalue(L, -2, 1);
    lua_pushvalue(L, -1);
    lua_setfield(L, -3, key);
    lua_remove(L, -2);
}

static int w_plate(lua_State *L) {
    lworld *lw = check_world(L, 1);
    static const char *const keys[] = {"rect", "axis", "mass", "slide", 0};
    if (lua_isinteger(L, 2)) { /* w:plate(k): the k-th plate made (after sph.load too) */
        lua_Integer k = lua_tointeger(L, 2);
        if (k < 1 || k > sph_world_nplates(lw->w))
            return luaL_error(L, "bad argument to 'plate' (no plate %d: the world has %d)", (int)k,
                              sph_world_nplates(lw->w));
        push_plate(L, (int)k - 1);
        return 1;
    }
    luaL_checktype(L, 2, LUA_TTABLE);
    sph_lua_opt_only(L, 2, "plate", keys);
    double slide[2] = {0, 0};
    int ts = lua_getfield(L, 2, "slide");
    if (ts != LUA_TNIL) {
        int ok = ts == LUA_TTABLE;
        for (int q = 0; ok && q < 2; q++) {
            lua_rawgeti(L, -1, q + 1);
            ok = lua_type(L, -1) == LUA_TNUMBER && isfinite(lua_tonumber(L, -1));
            if (ok) slide[q] = lua_tonumber(L, -1);
            lua_pop(L, 1);
        }
        if (!ok) luaL_error(L, "bad argument to 'plate' (slide: {ux, uy} of finite numbers expected)");
    }
    lua_pop(L, 1);
    double r[4];
    opt_rect(L, 2, "plate", r);
    int axis = -1;
    int t = lua_getfield(L, 2, "axis");
    if (t != LUA_TNIL) {
        const char *a = lua_tostring(L, -1);
        if (t != LUA_TSTRING || (strcmp(a, "x") && strcmp(a, "y")))
            luaL_error(L, "bad argument to 'plate' (axis: \"x\" or \"y\" expected)");
        axis = a[0] == 'x' ? 0 : 1;
    }
    lua_pop(L, 1);
    double mass = sph_lua_opt_number(L, 2, "plate", "mass", 0);
    if (sph_lua_opt_present(L, 2, "mass") && !(mass > 0))
        luaL_error(L, "bad argument to 'plate' (mass: positive number expected)");
    int k = sph_world_plate(lw->w, r, axis);
    if (k < 0) return engine_error(L, lw->w);
    if (mass > 0) sph_plate_set_mass(lw->w, k, mass);
    sph_plate_set_slide(lw->w, k, slide[0], slide[1]);
    push_plate(L, k);
    return 1;
}

/* w:save(file): the state for sph.load. A plate law given as a function is not saved (the
 * plate keeps its last velocity or load): set it again on w:plate(k) after loading. */
static int w_save(lua_State *L) {
    lworld *lw = check_world(L, 1);
    const char *file = luaL_checkstring(L, 2);
    if (sph_world_save(lw->w, file)) return engine_error(L, lw->w);
    lua_settop(L, 1);
    return 1;
}

/* sph.load(file): a world from w:save's file. */
static int l_load(lua_State *L) {
    const char *file = luaL_checkstring(L, 1);
    lworld *lw = push_world(L);
    char err[512];
    lw->w = sph_world_load(file, err, sizeof err);
    if (!lw->w) return luaL_error(L, "sph.load: %s", err);
    return 1;
}

/* The world at idx again after a call into Lua: the callback (a plate law, run's each)
 * may have closed it, and its engine world is then freed; going on would use freed memory.
 * during: what was running, for the message. */
static sph_world *world_after_call(lua_State *L, int idx, const char *during) {
    lworld *lw = luaL_checkudata(L, idx, WORLD);
    if (!lw->w)
        luaL_error(L, "world closed during %s: a callback must not close the world it is called from", during);
    return lw->w;
}

/* Evaluate the Lua plate laws at time t and hand their values to the engine. Returns the
 * world, fetched again after every law (a law may close it: a Lua error then). */
static sph_world *apply_laws(lua_State *L, int widx, double t, const char *during) {
    sph_world *w = world_after_call(L, widx, during);
    int np = sph_world_nplates(w);
    lua_getiuservalue(L, widx, 1);
    int uv = lua_gettop(L);
    for (int k = 0; k < np; k++) {
        if (lua_rawgeti(L, uv, k + 1) != LUA_TFUNCTION) {
            lua_pop(L, 1);
            continue;
        }
        char key[32];
        snprintf(key, sizeof key, "plate%d", k);
        lua_pushnumber(L, t);
        lua_getfield(L, uv, key);
        lua_call(L, 2, 1);
        w = world_after_call(L, widx, during);
        int isnum;
        double v = lua_tonumberx(L, -1, &isnum);
        sph_plate_mode mode = sph_plate_mode_of(w, k);
        if (!isnum || !isfinite(v))
            luaL_error(L, "plate %d: its %s law returned %s at t = %f (a finite number expected)", k + 1,
                       mode == SPH_PLATE_LOAD ? "load" : "velocity",
                       isnum ? "a non-finite number" : luaL_typename(L, -1), t);
        if ((mode == SPH_PLATE_LOAD ? sph_plate_set_load(w, k, v) : sph_plate_set_velocity(w, k, v)) < 0)
            engine_error(L, w);
        lua_pop(L, 1);
    }
    lua_pop(L, 1);
    return w;
}

static int w_step(lua_State *L) {
    lworld *lw = check_world(L, 1);
    double dt = luaL_optnumber(L, 2, 0);
    sph_world *w = apply_laws(L, 1, sph_world_time(lw->w), "w:step (in a plate law)");
    if (sph_world_step(w, dt) < 0) return engine_error(L, w);
    check_interrupt(L, w);
    lua_pushvalue(L, 1);
    return 1;
}

static void progress(sph_world *w, double t_end, double wall0, int final) {
    sph_stats s;
    sph_world_stats(w, &s);
    double el = omp_get_wtime() - wall0, t = sph_world_time(w);
    double frac = t_end > 0 ? t / t_end : 1;
    fprintf(stderr, "\r  t = %-10.5g %5.1f%%  step %-8ld dt = %-9.3g  p-iter %-4d  rho err %-8.2e  %6.1f s%s",
            t, 100 * frac, sph_world_steps(w), sph_world_dt(w), s.solver_iterations, s.max_density_error,
            el, final ? "\n" : "   ");
    fflush(stderr);
}

/* run's each (at stack index each; nil: none) on the world at index 1: 1 when it returned
 * false (stop), else 0. *w is the world again after the call (which may close it). */
static int call_each(lua_State *L, int each, sph_world **w) {
    if (lua_isnil(L, each)) return 0;
    lua_pushvalue(L, each);
    lua_pushvalue(L, 1);
    lua_call(L, 1, 1);
    *w = world_after_call(L, 1, "w:run (in its each function)");
    int stop = lua_isboolean(L, -1) && !lua_toboolean(L, -1);
    lua_pop(L, 1);
    return stop;
}

/* What w:run's steps share with the hook the engine calls before each step. */
typedef struct {
    lua_State *L;
    int show;            /* a progress line on stderr                                */
    double until_t, wall0, last;
    int stepped;         /* steps the current sph_world_run_until call has taken       */
    int raised;          /* the hook raised a Lua error: its value is on the stack    */
} run_state;

/* After every step: the progress line (at most every 0.25 s), then an interrupt the host
 * caught ends the run with a Lua error. */
static void after_step(lua_State *L, sph_world *w, run_state *r) {
    if (r->show && omp_get_wtime() - r->last > 0.25) {
        progress(w, r->until_t, r->wall0, 0);
        r->last = omp_get_wtime();
    }
    if (sph_lua_interrupt) {
        if (r->show) progress(w, r->until_t, r->wall0, 1);
        check_interrupt(L, w);
    }
}

/* The hook's body, called protected (run_hook) with the world at index 1 and the
 * run_state at 2: the last step's after_step, then the plate laws for the next one. */
static int run_hook_body(lua_State *L) {
    run_state *r = lua_touserdata(L, 2);
    sph_world *w = world_after_call(L, 1, "w:run (in a plate law)");
    if (r->stepped++) after_step(L, w, r);
    apply_laws(L, 1, sph_world_time(w), "w:run (in a plate law)");
    return 0;
}

/* sph_world_run_until's hook (w_run is the running C function: the world at index 1). A
 * Lua error (a law that raises, a closed world, an interrupt) stops the run, its value
 * left on the stack for w_run to raise once the engine has returned. */
static int run_hook(sph_world *w, void *ctx) {
    (void)w;
    run_state *r = ctx;
    lua_State *L = r->L;
    lua_pushcfunction(L, run_hook_body);
    lua_pushvalue(L, 1);
    lua_pushlightuserdata(L, r);
    if (lua_pcall(L, 2, 0, 0) == LUA_OK) return 0;
    r->raised = 1;
    return 1;
}

/* The index k >= kmin of the first output time t0 + k every after now (beyond the clock's
 * round-off eps). A grid finer than the clock resolves there is a Lua error: its output
 * times cannot be landed on one by one. */
static long next_output(lua_State *L, double t0, double every, double now, double eps, long kmin) {
    double kk = floor((now + eps - t0) / every);
    char msg[160];
    if (!(kk < 1e15)) {
        snprintf(msg, sizeof msg, "every = %g: %g output times from t0 = %g to now", every, kk, t0);
        luaL_error(L, "bad argument to 'run' (%s)", msg);
    }
    long k = kk < kmin ? kmin : (long)kk;
    while (k > kmin && t0 + (k - 1) * every > now + eps) k--;
    for (int q = 0; q < 4 && t0 + k * every <= now + eps; q++) k++; /* round-off only */
    if (t0 + k * every <= now + eps) {
        snprintf(msg, sizeof msg, "every = %g: output times closer than the clock resolves at t = %g", every, now);
        luaL_error(L, "bad argument to 'run' (%s)", msg);
    }
    return k;
}

static int w_run(lua_State *L) {
    lworld *lw = check_world(L, 1);
    static const char *const keys[] = {"until_t", "every", "each", "progress", "dt", "t0", 0};
    luaL_checktype(L, 2, LUA_TTABLE);
    sph_lua_opt_only(L, 2, "run", keys);
    if (!sph_lua_opt_present(L, 2, "until_t")) luaL_error(L, "bad argument to 'run' (until_t: number expected, got no value)");
    double until_t = sph_lua_opt_number(L, 2, "run", "until_t", 0);
    double every = sph_lua_opt_number(L, 2, "run", "every", 0);
    double fixed_dt = sph_lua_opt_number(L, 2, "run", "dt", 0);
    if (!(every >= 0)) luaL_error(L, "bad argument to 'run' (every: number >= 0 expected)");
    if (!isfinite(fixed_dt)) { /* else an infinite dt is cut to the output interval */
        char got[32];
        snprintf(got, sizeof got, "%g", fixed_dt);
        luaL_error(L, "bad argument to 'run' (dt must be a finite positive number (or 0: adaptive), got %s)", got);
    }
    int t = lua_getfield(L, 2, "each");
    if (t != LUA_TNIL && t != LUA_TFUNCTION)
        luaL_error(L, "bad argument to 'run' (each: function expected, got %s)", luaL_typename(L, -1));
    int each = lua_gettop(L);
    run_state r = {L, isatty(fileno(stderr)), until_t, omp_get_wtime(), 0, 0, 0};
    r.last = r.wall0;
    if (lua_getfield(L, 2, "progress") != LUA_TNIL) r.show = r.show && lua_toboolean(L, -1);
    lua_pop(L, 1);
    sph_world *w = lw->w;
    /* t0: the output grid's origin (default now); a run continued from a saved state passes
     * the first run's, so the outputs fall, and the steps land, where they did in it */
    double t0 = sph_lua_opt_number(L, 2, "run", "t0", sph_world_time(w));
    if (!isfinite(t0)) luaL_error(L, "bad argument to 'run' (t0: finite number expected)");
    double eps = 1e-9 * (until_t > 0 ? until_t : 1); /* the clock's round-off */
    if (every > 0 && every < eps) { /* each output time is landed on: steps below round-off */
        char msg[128];
        snprintf(msg, sizeof msg, "every = %g is below the run's time resolution %g, 1e-9 of until_t", every, eps);
        luaL_error(L, "bad argument to 'run' (%s)", msg);
    }
    /* the output a run from t0 would take next */
    long k = every > 0 ? next_output(L, t0, every, sph_world_time(w), eps, 1) : 1;
    double next_out = every > 0 ? t0 + k * every : INFINITY;
    /* the output at the grid's origin, before the first step: a series gets its t0 row.
     * A run continued past t0 (t0 given, earlier than now) had it in the run before. */
    if (every > 0 && fabs(sph_world_time(w) - t0) <= eps && call_each(L, each, &w)) {
        lua_pushvalue(L, 1);
        return 1;
    }
    /* to each output time in turn (the engine lands on it), then its each */
    while (sph_world_time(w) < until_t - eps) {
        int rc = sph_world_run_until(w, fmin(until_t, next_out), fixed_dt, run_hook, &r);
        if (r.raised) return lua_error(L);
        if (rc < 0) {
            if (r.show) fprintf(stderr, "\n");
            return engine_error(L, w);
        }
        int stepped = r.stepped;
        r.stepped = 0;
        if (sph_world_time(w) >= next_out - eps) {
            k = next_output(L, t0, every, sph_world_time(w), eps, k + 1);
            next_out = t0 + k * every;
            if (call_each(L, each, &w)) break;
        } else if (!stepped) {
            break; /* neither a step nor an output: the time is at until_t within round-off */
        }
        if (stepped) after_step(L, w, &r); /* after the step's output, if it was an output time */
    }
    if (r.show) progress(w, until_t, r.wall0, 1);
    lua_pushvalue(L, 1);
    return 1;
}

static int w_stats(lua_State *L) {
    lworld *lw = check_world(L, 1);
    sph_stats s;
    sph_world_stats(lw->w, &s);
    lua_createtable(L, 0, 30);
#define SETI(name, v) (lua_pushinteger(L, (lua_Integer)(v)), lua_setfield(L, -2, name))
#define SETN(name, v) (lua_pushnumber(L, (v)), lua_setfield(L, -2, name))
    SETI("particles", s.particles);
    SETI("fluid", s.fluid);
    SETI("wall", s.wall);
    SETI("ghosts", s.ghosts);
    SETI("surface", s.surface);
    SETI("unknowns", s.unknowns);
    SETI("solver_iterations", s.solver_iterations);
    SETN("solver_residual", s.solver_residual);
    SETI("solver_iterations_total", s.solver_iterations_total);
    SETI("visc_iterations", s.visc_iterations);
    SETN("visc_residual", s.visc_residual);
    SETI("visc_iterations_total", s.visc_iterations_total);
    SETN("max_density_error", s.max_density_error);
    SETN("peak_density_error", s.peak_density_error);
    SETN("correction_share", s.correction_share);
    SETN("correction_sq", s.correction_sq);
    SETN("motion_sq", s.motion_sq);
    if (s.shifting_since >= 0) SETN("shifting_since", s.shifting_since); /* absent: not started by "auto" */
    SETN("density_alpha", s.density_alpha);
    SETI("density_passes", s.density_passes);
    SETI("density_fallbacks", s.density_fallbacks);
    SETI("density_descents", s.density_descents);
    SETI("density_switches", s.density_switches);
    SETI("density_probes", s.density_probes);
    SETI("density_probes_ended", s.density_probes_ended);
    SETI("wall_contacts", s.wall_contacts);
    SETI("floating_walls", s.floating_walls);
    SETN("kinetic_energy", s.kinetic_energy);
    SETN("area", s.area);
    SETN("max_speed", s.max_speed);
    SETN("max_eta", s.max_eta);
    SETI("yielded", s.yielded);
    SETN("neighbours", s.neighbours_mean);
    SETN("wall_time", s.wall_time);
    SETN("visc_setup_time", s.visc_setup_time);
    SETN("visc_solve_time", s.visc_solve_time);
    SETN("pressure_setup_time", s.pressure_setup_time);
    SETN("pressure_solve_time", s.pressure_solve_time);
    SETI("visc_solves", s.visc_solves);
    SETI("pressure_solves", s.pressure_solves);
    SETN("t", sph_world_time(lw->w));
    SETN("dt", sph_world_dt(lw->w));
    SETI("steps", sph_world_steps(lw->w));
    /* phases = {sort = seconds, ...}: cumulative wall time of each phase of the step */
    const char *const *pn = sph_phase_names();
    lua_createtable(L, 0, SPH_PHASES);
    for (int k = 0; k < SPH_PHASES && pn[k]; k++) SETN(pn[k], s.phase_time[k]);
    lua_setfield(L, -2, "phases");
#undef SETI
#undef SETN
    return 1;
}

static int w_field(lua_State *L) {
    lworld *lw = check_world(L, 1);
    const char *name = luaL_checkstring(L, 2);
    int n = sph_world_nfluid(lw->w);
    double *buf = lua_newuserdatauv(L, sizeof(double) * (size_t)(n > 0 ? n : 1), 0);
    int got = sph_world_field(lw->w, name, buf);
    if (got == -2)
        return luaL_error(L, "field '%s': no neighbour list for the current particles yet (it is the "
                             "last step's: call w:step() first, and again after w:fill or sph.load)", name);
    if (got < 0) {
        luaL_Buffer b;
        luaL_buffinit(L, &b);
        const char *const *names = sph_world_field_names();
        for (int i = 0; names[i]; i++) {
            if (i) luaL_addstring(&b, ", ");
            luaL_addstring(&b, names[i]);
        }
        luaL_pushresult(&b);
        return luaL_error(L, "bad argument #1 to 'field' (unknown field '%s'; fields are %s)", name,
                          lua_tostring(L, -1));
    }
    lua_createtable(L, n, 0);
    for (int i = 0; i < n; i++) {
        lua_pushnumber(L, buf[i]);
        lua_rawseti(L, -2, i + 1);
    }
    return 1;
}

/* w:set_velocity(us, vs): one value per fluid particle each, in the order of w:field
 * (either may be nil to keep that component). */
static int w_set_velocity(lua_State *L) {
    lworld *lw = check_world(L, 1);
    lua_settop(L, 3);
    int n = sph_world_nfluid(lw->w);
    double *buf[2] = {0, 0};
    for (int c = 0; c < 2; c++) {
        int a = c + 2;
        if (lua_isnoneornil(L, a)) continue;
        luaL_checktype(L, a, LUA_TTABLE);
        if ((int)luaL_len(L, a) != n)
            return luaL_error(L, "bad argument #%d to 'set_velocity' (%d values expected, one per fluid particle, got %d)",
                              c + 1, n, (int)luaL_len(L, a));
        buf[c] = lua_newuserdatauv(L, sizeof(double) * (size_t)(n > 0 ? n : 1), 0);
        for (int i = 0; i < n; i++) {
            lua_rawgeti(L, a, i + 1);
            if (lua_type(L, -1) != LUA_TNUMBER)
                return luaL_error(L, "bad argument #%d to 'set_velocity' (number expected at [%d], got %s)", c + 1,
                                  i + 1, luaL_typename(L, -1));
            buf[c][i] = lua_tonumber(L, -1);
            lua_pop(L, 1);
        }
    }
    if (sph_world_set_velocity(lw->w, buf[0], buf[1]) < 0) return engine_error(L, lw->w);
    lua_settop(L, 1);
    return 1;
}

static int write_result(lua_State *L, sph_world *w, int rc) {
    return sph_lua_result(L, rc, rc < 0 ? sph_world_error(w) : 0);
}

static int w_write_csv(lua_State *L) {
    lworld *lw = check_world(L, 1);
    return write_result(L, lw->w, sph_world_write_csv(lw->w, luaL_checkstring(L, 2)));
}

static int w_write_vtk(lua_State *L) {
    lworld *lw = check_world(L, 1);
    return write_result(L, lw->w, sph_world_write_vtk(lw->w, luaL_checkstring(L, 2)));
}

static int w_index(lua_State *L) {
    lworld *lw = check_world(L, 1);
    const char *k = luaL_checkstring(L, 2);
    if (!strcmp(k, "t")) lua_pushnumber(L, sph_world_time(lw->w));
    else if (!strcmp(k, "dt")) lua_pushnumber(L, sph_world_dt(lw->w));
    else if (!strcmp(k, "steps")) lua_pushinteger(L, sph_world_steps(lw->w));
    else if (!strcmp(k, "dx")) lua_pushnumber(L, sph_world_params(lw->w)->dx);
    else if (!strcmp(k, "h")) lua_pushnumber(L, sph_world_h(lw->w));
    else if (!strcmp(k, "rho")) lua_pushnumber(L, sph_world_params(lw->w)->rho0);
    else {
        luaL_getmetatable(L, WORLD);
        lua_getfield(L, -1, "methods");
        lua_getfield(L, -1, k);
    }
    return 1;
}

/* ---- plates --------------------------------------------------------------------- */

static sph_world *plate_world(lua_State *L, int idx, lplate **out) {
    lplate *lp = luaL_checkudata(L, idx, PLATE);
    lua_getiuservalue(L, idx, 1);
    lworld *lw = check_world(L, -1);
    lua_pop(L, 1);
    *out = lp;
    return lw->w;
}

/* plate:velocity(v | f) / plate:load(F | f) set the plate's law: numbers go to the engine,
 * functions are kept in the world's uservalue and called once per step; both return the
 * plate. Without an argument they read: plate:velocity() is the current velocity along
 * the axis, plate:load() the load applied this step (nil unless the plate is under a load
 * law). An explicit nil is an error, not a read: top:velocity(opts.V) with opts.V unset
 * must not pass silently. Errors name the method, also when it is called through a copy
 * (pcall(top.velocity, top, v)), where Lua itself knows no name. */
static int law(lua_State *L, int load) {
    const char *name = load ? "load" : "velocity";
    if (!luaL_testudata(L, 1, PLATE))
        return luaL_error(L, "calling '%s' on bad self (sph.plate expected, got %s: call it as plate:%s(...))",
                          name, luaL_typename(L, 1), name);
    lplate *lp;
    sph_world *w = plate_world(L, 1, &lp);
    if (lua_gettop(L) == 1) { /* the read */
        if (!load) lua_pushnumber(L, sph_plate_velocity(w, lp->index));
        else if (sph_plate_mode_of(w, lp->index) == SPH_PLATE_LOAD) lua_pushnumber(L, sph_plate_load(w, lp->index));
        else lua_pushnil(L);
        return 1;
    }
    int t = lua_type(L, 2);
    if (t != LUA_TNUMBER && t != LUA_TFUNCTION)
        return luaL_error(L, "bad argument #1 to '%s' (number or function of (t, plate) expected, got %s%s%s%s)",
                          name, luaL_typename(L, 2), t == LUA_TNIL ? "; plate:" : "", t == LUA_TNIL ? name : "",
                          t == LUA_TNIL ? "() with no argument reads it" : "");
    if (sph_plate_axis(w, lp->index) < 0)
        return luaL_error(L, "plate %d has no axis: it is fixed (give axis = \"x\" or \"y\" to move it)",
                          lp->index + 1);
    double v = t == LUA_TNUMBER ? lua_tonumber(L, 2) : 0.0;
    if (t == LUA_TNUMBER && !isfinite(v))
        return luaL_error(L, "bad argument #1 to '%s' (finite number expected, got %f)", name, v);
    if ((load ? sph_plate_set_load(w, lp->index, v) : sph_plate_set_velocity(w, lp->index, v)) < 0)
        return engine_error(L, w);
    lua_getiuservalue(L, 1, 1);
    lua_getiuservalue(L, -1, 1);
    if (t == LUA_TFUNCTION) lua_pushvalue(L, 2);
    else lua_pushnil(L);
    lua_rawseti(L, -2, lp->index + 1);
    lua_settop(L, 1);
    return 1;
}

static int p_velocity(lua_State *L) { return law(L, 0); }

/* plate:slide(ux, uy) sets the surface velocity (returns the plate); plate:slide() returns
 * ux, uy. */
static int p_slide(lua_State *L) {
    lplate *lp;
    sph_world *w = plate_world(L, 1, &lp);
    if (lua_gettop(L) == 1) {
        double s[2];
        sph_plate_slide(w, lp->index, s);
        lua_pushnumber(L, s[0]);
        lua_pushnumber(L, s[1]);
        return 2;
    }
    double sx = luaL_checknumber(L, 2), sy = luaL_checknumber(L, 3);
    if (!isfinite(sx) || !isfinite(sy)) return luaL_error(L, "bad argument to 'slide' (finite numbers expected)");
    if (sph_plate_set_slide(w, lp->index, sx, sy) < 0) return engine_error(L, w);
    lua_settop(L, 1);
    return 1;
}
static int p_load(lua_State *L) { return law(L, 1); }

static int p_index(lua_State *L) {
    lplate *lp;
    sph_world *w = plate_world(L, 1, &lp);
    const char *k = luaL_checkstring(L, 2);
    int i = lp->index;
    if (!strcmp(k, "position")) lua_pushnumber(L, sph_plate_position(w, i));
    else if (!strcmp(k, "axial_velocity")) lua_pushnumber(L, sph_plate_velocity(w, i));
    else if (!strcmp(k, "force")) lua_pushnumber(L, sph_plate_force(w, i));
    else if (!strcmp(k, "impulse")) lua_pushnumber(L, sph_plate_impulse(w, i));
    else if (!strcmp(k, "mass")) lua_pushnumber(L, sph_plate_mass(w, i));
    else if (!strcmp(k, "index")) lua_pushinteger(L, i + 1);
    else if (!strcmp(k, "axis")) {
        int a = sph_plate_axis(w, i);
        if (a < 0) lua_pushnil(L);
        else lua_pushstring(L, a == 0 ? "x" : "y");
    } else if (!strcmp(k, "mode")) {
        static const char *const modes[] = {"fixed", "velocity", "load"};
        lua_pushstring(L, modes[sph_plate_mode_of(w, i)]);
    } else if (!strcmp(k, "rect")) {
        double r[4];
        sph_plate_rect(w, i, r);
        lua_createtable(L, 4, 0);
        for (int q = 0; q < 4; q++) {
            lua_pushnumber(L, r[q]);
            lua_rawseti(L, -2, q + 1);
        }
    } else if (!strcmp(k, "velocity")) lua_pushcfunction(L, p_velocity);
    else if (!strcmp(k, "load")) lua_pushcfunction(L, p_load);
    else if (!strcmp(k, "slide")) lua_pushcfunction(L, p_slide);
    else lua_pushnil(L);
    return 1;
}

static int p_newindex(lua_State *L) {
    lplate *lp;
    sph_world *w = plate_world(L, 1, &lp);
    const char *k = luaL_checkstring(L, 2);
    if (strcmp(k, "mass")) return luaL_error(L, "plate field '%s' cannot be set (only 'mass' can)", k);
    double m = luaL_checknumber(L, 3);
    if (sph_plate_set_mass(w, lp->index, m) < 0) return engine_error(L, w);
    return 0;
}

static int p_tostring(lua_State *L) {
    lplate *lp;
    sph_world *w = plate_world(L, 1, &lp);
    lua_pushfstring(L, "sph.plate %d (position %f, velocity %f, force %f)", lp->index + 1,
                    sph_plate_position(w, lp->index), sph_plate_velocity(w, lp->index),
                    sph_plate_force(w, lp->index));
    return 1;
}

/* ---- module --------------------------------------------------------------------- */

static const luaL_Reg world_methods[] = {{"fill", w_fill},           {"plate", w_plate},
                                         {"step", w_step},           {"run", w_run},
                                         {"stats", w_stats},         {"field", w_field},
                                         {"set_velocity", w_set_velocity},
                                         {"write_csv", w_write_csv}, {"write_vtk", w_write_vtk},
                                         {"save", w_save},
                                         {"close", w_close},         {0, 0}};

static const luaL_Reg funcs[] = {{"world", l_world},
                                 {"load", l_load},
                                 {"newtonian", l_newtonian},
                                 {"bingham", l_bingham},
                                 {"herschel_bulkley", l_hb},
                                 {"interrupted", l_interrupted},
                                 {0, 0}};

int luaopen_sph(lua_State *L);

int luaopen_sph(lua_State *L) {
    luaL_checkversion(L);
    if (luaL_newmetatable(L, WORLD)) {
        luaL_newlib(L, world_methods);
        lua_setfield(L, -2, "methods");
        lua_pushcfunction(L, w_index);
        lua_setfield(L, -2, "__index");
        lua_pushcfunction(L, w_close);
        lua_setfield(L, -2, "__gc");
        lua_pushcfunction(L, w_close);
        lua_setfield(L, -2, "__close");
        lua_pushcfunction(L, w_tostring);
        lua_setfield(L, -2, "__tostring");
    }
    lua_pop(L, 1);
    if (luaL_newmetatable(L, PLATE)) {
        lua_pushcfunction(L, p_index);
        lua_setfield(L, -2, "__index");
        lua_pushcfunction(L, p_newindex);
        lua_setfield(L, -2, "__newindex");
        lua_pushcfunction(L, p_tostring);
        lua_setfield(L, -2, "__tostring");
    }
    lua_pop(L, 1);
    if (luaL_newmetatable(L, MATERIAL)) {
        lua_pushcfunction(L, mat_index);
        lua_setfield(L, -2, "__index");
        lua_pushcfunction(L, mat_tostring);
        lua_setfield(L, -2, "__tostring");
    }
    lua_pop(L, 1);
    /* nothing here touches the metatables of Lua's own types (DESIGN.md): plate.velocity
       is the method, the velocity is plate:velocity() or plate.axial_velocity */

    luaL_newlib(L, funcs);
    lua_pushliteral(L, SPH_VERSION);
    lua_setfield(L, -2, "version");
    lua_pushinteger(L, omp_get_num_procs());
    lua_setfield(L, -2, "cores");
    sph_lua_pictures_open(L);
    sph_lua_files_open(L);
    return 1;
}
