/* The Lua binding of the pictures layer (sph_pictures.h): w:render{...}, sph.plot{...} and
 * sph.animate{...}. Arguments are checked first (errors name the argument); scratch arrays
 * live in userdata so a Lua error on the way leaks nothing; a spec the pictures layer
 * rejects is an error, a file that cannot be read or written is `nil, message`. */
#include "lsph.h"
#include "sph_pictures.h"

#include <lauxlib.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* ---- option helpers (the same conventions as lsph.c) ---------------------------- */

/* An integer option in [lo, hi]. */
static int opt_int(lua_State *L, int idx, const char *fname, const char *key, int def, int lo, int hi) {
    int v = def;
    if (lua_getfield(L, idx, key) != LUA_TNIL) {
        int isint = 0;
        lua_Integer k = lua_tointegerx(L, -1, &isint);
        if (!isint || k < lo || k > hi)
            luaL_error(L, "bad argument to '%s' (%s: integer in %d..%d expected, got %s)", fname, key, lo, hi,
                       lua_type(L, -1) == LUA_TNUMBER ? lua_tostring(L, -1) : luaL_typename(L, -1));
        v = (int)k;
    }
    lua_pop(L, 1);
    return v;
}

static int opt_bool(lua_State *L, int idx, const char *fname, const char *key, int def) {
    int v = def, t = lua_getfield(L, idx, key);
    if (t != LUA_TNIL) {
        if (t != LUA_TBOOLEAN)
            luaL_error(L, "bad argument to '%s' (%s: boolean expected, got %s)", fname, key, luaL_typename(L, -1));
        v = lua_toboolean(L, -1);
    }
    lua_pop(L, 1);
    return v;
}

/* A string option; the string stays alive in the options table for the whole call. */
static const char *opt_string(lua_State *L, int idx, const char *fname, const char *key, const char *def) {
    const char *v = def;
    if (lua_getfield(L, idx, key) != LUA_TNIL) {
        if (lua_type(L, -1) != LUA_TSTRING)
            luaL_error(L, "bad argument to '%s' (%s: string expected, got %s)", fname, key, luaL_typename(L, -1));
        v = lua_tostring(L, -1);
    }
    lua_pop(L, 1);
    return v;
}

/* key = {n numbers}; returns 0 when absent. */
static int opt_numbers(lua_State *L, int idx, const char *fname, const char *key, int n, const char *shape,
                       double *out) {
    int t = lua_getfield(L, idx, key);
    if (t == LUA_TNIL) {
        lua_pop(L, 1);
        return 0;
    }
    if (t != LUA_TTABLE || luaL_len(L, -1) != n)
        luaL_error(L, "bad argument to '%s' (%s: table %s expected)", fname, key, shape);
    for (int k = 0; k < n; k++) {
        lua_rawgeti(L, -1, k + 1);
        if (!lua_isnumber(L, -1) || !isfinite(lua_tonumber(L, -1)))
            luaL_error(L, "bad argument to '%s' (%s[%d]: finite number expected, got %s)", fname, key, k + 1,
                       lua_type(L, -1) == LUA_TNUMBER ? lua_tostring(L, -1) : luaL_typename(L, -1));
        out[k] = lua_tonumber(L, -1);
        lua_pop(L, 1);
    }
    lua_pop(L, 1);
    return 1;
}

/* Scratch memory owned by Lua: freed by the collector even when an error unwinds. */
static void *scratch(lua_State *L, size_t bytes) { return lua_newuserdatauv(L, bytes ? bytes : 1, 0); }

/* true, or nil and the message */
/* ---- w:render{...} -------------------------------------------------------------- */

/* a label that shows its own time: "t", optional spaces, "=" at its start */
static int has_time(const char *s) {
    if (*s != 't') return 0;
    for (s++; *s == ' '; s++) {}
    return *s == '=';
}

static int w_render(lua_State *L) {
    static const char *const keys[] = {"file",  "width", "height", "color",  "view",     "colorbar",
                                       "label", "range", "mirror", "radius", "colormap", 0};
    sph_world *w = sph_lua_checkworld(L, 1);
    luaL_checktype(L, 2, LUA_TTABLE);
    sph_lua_opt_only(L, 2, "render", keys);
    const sph_params *par = sph_world_params(w);
    sph_render_spec s;
    sph_render_defaults(&s);

    const char *file = opt_string(L, 2, "render", "file", NULL);
    if (!file) luaL_error(L, "bad argument to 'render' (file: string expected, got no value)");
    s.width = opt_int(L, 2, "render", "width", 800, 8, 16384);
    s.height = opt_int(L, 2, "render", "height", 400, 8, 16384);

    /* color: "yield" or a field name */
    const char *color = opt_string(L, 2, "render", "color", "yield");
    int yield = !strcmp(color, "yield");
    const char *const *names = sph_world_field_names();
    int known = yield;
    for (int i = 0; names[i] && !known; i++) known = !strcmp(color, names[i]);
    if (!known) {
        luaL_Buffer b;
        luaL_buffinit(L, &b);
        luaL_addstring(&b, "yield");
        for (int i = 0; names[i]; i++) {
            luaL_addstring(&b, ", ");
            luaL_addstring(&b, names[i]);
        }
        luaL_pushresult(&b);
        luaL_error(L, "bad argument to 'render' (color: unknown field '%s'; fields are %s)", color,
                   lua_tostring(L, -1));
    }
    s.colormap = opt_string(L, 2, "render", "colormap", NULL);
    if (s.colormap && !sph_colormap_find(s.colormap))
        luaL_error(L, "bad argument to 'render' (colormap: unknown colour map '%s'; maps are viridis)", s.colormap);

    if (opt_numbers(L, 2, "render", "view", 4, "{x0, y0, x1, y1}", s.view)) {
        if (!(s.view[2] > s.view[0] && s.view[3] > s.view[1]))
            luaL_error(L, "bad argument to 'render' (view: need x0 < x1 and y0 < y1, got {%f, %f, %f, %f})",
                       s.view[0], s.view[1], s.view[2], s.view[3]);
        s.view_set = 1;
    }
    double range[2];
    if (opt_numbers(L, 2, "render", "range", 2, "{vmin, vmax}", range)) {
        if (!(range[0] <= range[1]))
            luaL_error(L, "bad argument to 'render' (range: need vmin <= vmax, got {%f, %f})", range[0], range[1]);
        s.autorange = 0, s.vmin = range[0], s.vmax = range[1];
    }
    /* colorbar: a colour bar for a field (default on), the legend of the two colours for
     * "yield" (default off) */
    s.colorbar = opt_bool(L, 2, "render", "colorbar", !yield);
    s.legend = yield && s.colorbar;
    s.mirror = opt_bool(L, 2, "render", "mirror", par->symmetry[0] != 0);
    s.mirror_x = par->symmetry[0] ? par->sym_at[0] : 0;
    s.radius = sph_lua_opt_number(L, 2, "render", "radius", 0.55 * par->dx);
    if (!(s.radius > 0 && isfinite(s.radius)))
        luaL_error(L, "bad argument to 'render' (radius: positive number expected, got %f)", s.radius);

    /* label: true → "t = ...", a string → "t = ...   string", false/nil → none. The time
     * shows once: a string that begins with its own time ("t = 0.5 ...", "t=0.5") is drawn
     * as given, not after a second one. */
    int lt = lua_getfield(L, 2, "label");
    if (lt != LUA_TNIL && lt != LUA_TBOOLEAN && lt != LUA_TSTRING)
        luaL_error(L, "bad argument to 'render' (label: boolean or string expected, got %s)", luaL_typename(L, -1));
    if (lt == LUA_TSTRING || lua_toboolean(L, -1)) {
        char t[64];
        snprintf(t, sizeof t, "%.4g", sph_world_time(w));
        const char *user = lt == LUA_TSTRING ? lua_tostring(L, -1) : "";
        while (*user == ' ') user++;
        if (has_time(user))
            lua_pushstring(L, user);
        else if (*user)
            lua_pushfstring(L, "t = %s   %s", t, user);
        else
            lua_pushfstring(L, "t = %s", t);
        s.label = lua_tostring(L, -1); /* anchored on the stack until we return */
    }

    /* all arguments checked: gather the particles and plates */
    int n = sph_world_nfluid(w);
    if (n < 0) n = 0;
    double *x = scratch(L, sizeof(double) * (size_t)n);
    double *y = scratch(L, sizeof(double) * (size_t)n);
    double *v = scratch(L, sizeof(double) * (size_t)n);
    sph_world_field(w, "x", x);
    sph_world_field(w, "y", y);
    if (sph_world_field(w, yield ? "yielded" : color, v) == -2)
        luaL_error(L, "render: field '%s' needs the neighbour list of a step (call w:step() first)", color);
    s.n = (size_t)n, s.x = x, s.y = y;
    if (yield) {
        unsigned char *cat = scratch(L, (size_t)n);
        for (int i = 0; i < n; i++) cat[i] = v[i] != 0 ? SPH_RENDER_YIELDED : SPH_RENDER_UNYIELDED;
        s.category = cat;
    } else {
        s.value = v;
        s.field = color;
    }
    int np = sph_world_nplates(w);
    if (np > 0) {
        double *pr = scratch(L, sizeof(double) * 4 * (size_t)np);
        for (int k = 0; k < np; k++) sph_plate_rect(w, k, pr + 4 * k);
        s.plates = pr, s.nplates = (size_t)np;
    }

    char err[512] = "";
    sph_render_frame f;
    if (sph_render_layout(&s, &f, err, sizeof err) < 0) return luaL_error(L, "render: %s", err);
    return sph_lua_result(L, sph_render_png(&s, file, err, sizeof err), err);
}

/* ---- sph.plot{...} -------------------------------------------------------------- */

/* series[i][key]: an array of numbers (non-finite ones allowed: they break the line) */
static double *series_values(lua_State *L, int sidx, int i, const char *key, size_t *n) {
    if (lua_getfield(L, sidx, key) != LUA_TTABLE)
        luaL_error(L, "bad argument to 'plot' (series[%d].%s: table of numbers expected, got %s)", i, key,
                   luaL_typename(L, -1));
    int t = lua_gettop(L);
    lua_Integer len = luaL_len(L, t);
    double *v = scratch(L, sizeof(double) * (size_t)len);
    for (lua_Integer j = 1; j <= len; j++) {
        lua_rawgeti(L, t, j);
        if (!lua_isnumber(L, -1))
            luaL_error(L, "bad argument to 'plot' (series[%d].%s[%d]: number expected, got %s)", i, key, (int)j,
                       luaL_typename(L, -1));
        v[j - 1] = lua_tonumber(L, -1);
        lua_pop(L, 1);
    }
    lua_remove(L, t); /* the scratch userdata stays on the stack */
    *n = (size_t)len;
    return v;
}

static int l_plot(lua_State *L) {
    static const char *const keys[] = {"file",   "series", "title",  "xlabel", "ylabel", "log",
                                       "xrange", "yrange", "legend", "width",  "height", 0};
    static const char *const skeys[] = {"x", "y", "label", "style", 0};
    static const char *const styles[] = {"line", "markers", "both", 0};
    luaL_checktype(L, 1, LUA_TTABLE);
    sph_lua_opt_only(L, 1, "plot", keys);
    sph_plot_spec s;
    sph_plot_defaults(&s);
    const char *file = opt_string(L, 1, "plot", "file", NULL);
    if (!file) luaL_error(L, "bad argument to 'plot' (file: string expected, got no value)");
    s.title = opt_string(L, 1, "plot", "title", NULL);
    s.xlabel = opt_string(L, 1, "plot", "xlabel", NULL);
    s.ylabel = opt_string(L, 1, "plot", "ylabel", NULL);
    const char *log = opt_string(L, 1, "plot", "log", "");
    if (strcmp(log, "") && strcmp(log, "x") && strcmp(log, "y") && strcmp(log, "xy") && strcmp(log, "yx"))
        luaL_error(L, "bad argument to 'plot' (log: \"\", \"x\", \"y\" or \"xy\" expected, got '%s')", log);
    s.xlog = strchr(log, 'x') != NULL, s.ylog = strchr(log, 'y') != NULL;
    double r[2];
    if (opt_numbers(L, 1, "plot", "xrange", 2, "{xmin, xmax}", r)) s.xrange_set = 1, s.xmin = r[0], s.xmax = r[1];
    if (opt_numbers(L, 1, "plot", "yrange", 2, "{ymin, ymax}", r)) s.yrange_set = 1, s.ymin = r[0], s.ymax = r[1];
    s.legend = opt_bool(L, 1, "plot", "legend", 1);
    s.width = opt_int(L, 1, "plot", "width", s.width, 64, 16384);
    s.height = opt_int(L, 1, "plot", "height", s.height, 64, 16384);

    if (lua_getfield(L, 1, "series") != LUA_TTABLE)
        luaL_error(L, "bad argument to 'plot' (series: table of series expected, got %s)", luaL_typename(L, -1));
    int sl = lua_gettop(L);
    lua_Integer ns = luaL_len(L, sl);
    if (ns < 1) luaL_error(L, "bad argument to 'plot' (series: at least one series expected)");
    sph_plot_series *ser = scratch(L, sizeof *ser * (size_t)ns);
    for (lua_Integer i = 1; i <= ns; i++) {
        sph_plot_series *p = &ser[i - 1];
        luaL_checkstack(L, 8, "too many series");
        if (lua_rawgeti(L, sl, i) != LUA_TTABLE)
            luaL_error(L, "bad argument to 'plot' (series[%d]: table {x=, y=} expected, got %s)", (int)i,
                       luaL_typename(L, -1));
        int si = lua_gettop(L);
        lua_pushnil(L);
        while (lua_next(L, si)) { /* unknown keys in a series */
            lua_pop(L, 1);
            int ok = 0;
            for (int k = 0; skeys[k]; k++)
                if (lua_type(L, -1) == LUA_TSTRING && !strcmp(lua_tostring(L, -1), skeys[k])) ok = 1;
            if (!ok)
                luaL_error(L, "bad argument to 'plot' (series[%d]: unknown option '%s'; options are x, y, label, style)",
                           (int)i, lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : luaL_typename(L, -1));
        }
        size_t nx, ny;
        p->x = series_values(L, si, (int)i, "x", &nx);
        p->y = series_values(L, si, (int)i, "y", &ny);
        if (nx != ny)
            luaL_error(L, "bad argument to 'plot' (series[%d]: x has %d values but y has %d)", (int)i, (int)nx, (int)ny);
        p->n = nx;
        if (lua_getfield(L, si, "label") != LUA_TNIL && lua_type(L, -1) != LUA_TSTRING)
            luaL_error(L, "bad argument to 'plot' (series[%d].label: string expected, got %s)", (int)i,
                       luaL_typename(L, -1));
        p->label = lua_tostring(L, -1); /* NULL when absent; anchored in the series table */
        lua_pop(L, 1);
        p->style = SPH_PLOT_LINE;
        if (lua_getfield(L, si, "style") != LUA_TNIL) {
            const char *st = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : NULL;
            int k = 0;
            while (st && styles[k] && strcmp(st, styles[k])) k++;
            if (!st || !styles[k])
                luaL_error(L, "bad argument to 'plot' (series[%d].style: \"line\", \"markers\" or \"both\" expected, got %s)",
                           (int)i, st ? st : luaL_typename(L, -1));
            p->style = k == 0 ? SPH_PLOT_LINE : k == 1 ? SPH_PLOT_MARKERS : SPH_PLOT_LINE_MARKERS;
        }
        lua_pop(L, 1);
        /* the series table stays on the stack, under its two scratch arrays */
    }
    s.series = ser, s.nseries = (size_t)ns;

    char err[512] = "";
    sph_plot_frame f;
    if (sph_plot_layout(&s, &f, err, sizeof err) < 0) return luaL_error(L, "plot: %s", err);
    return sph_lua_result(L, sph_plot_png(&s, file, err, sizeof err), err);
}

/* ---- sph.animate{...} ----------------------------------------------------------- */

static int l_animate(lua_State *L) {
    static const char *const keys[] = {"frames", "file", "fps", "loop", 0};
    luaL_checktype(L, 1, LUA_TTABLE);
    sph_lua_opt_only(L, 1, "animate", keys);
    const char *file = opt_string(L, 1, "animate", "file", NULL);
    if (!file) luaL_error(L, "bad argument to 'animate' (file: string expected, got no value)");
    double fps = sph_lua_opt_number(L, 1, "animate", "fps", 25);
    int loop = opt_int(L, 1, "animate", "loop", 0, 0, 65535);
    char err[512] = "";
    unsigned num, den;
    if (sph_animate_delay(fps, &num, &den, err, sizeof err) < 0)
        luaL_error(L, "bad argument to 'animate' (fps: %s)", err);
    if (lua_getfield(L, 1, "frames") != LUA_TTABLE)
        luaL_error(L, "bad argument to 'animate' (frames: table of file names expected, got %s)", luaL_typename(L, -1));
    int fl = lua_gettop(L);
    lua_Integer n = luaL_len(L, fl);
    if (n < 1) luaL_error(L, "bad argument to 'animate' (frames: at least one frame expected)");
    const char **frames = scratch(L, sizeof *frames * (size_t)n);
    for (lua_Integer i = 1; i <= n; i++) {
        if (lua_rawgeti(L, fl, i) != LUA_TSTRING)
            luaL_error(L, "bad argument to 'animate' (frames[%d]: string expected, got %s)", (int)i,
                       luaL_typename(L, -1));
        frames[i - 1] = lua_tostring(L, -1); /* anchored in the frames table */
        lua_pop(L, 1);
    }
    return sph_lua_result(L, sph_animate_png(frames, (size_t)n, fps, loop, file, err, sizeof err), err);
}

/* ---- registration --------------------------------------------------------------- */

void sph_lua_pictures_open(lua_State *L) {
    luaL_getmetatable(L, SPH_LUA_WORLD);
    lua_getfield(L, -1, "methods");
    lua_pushcfunction(L, w_render);
    lua_setfield(L, -2, "render");
    lua_pop(L, 2);
    lua_pushcfunction(L, l_plot);
    lua_setfield(L, -2, "plot");
    lua_pushcfunction(L, l_animate);
    lua_setfield(L, -2, "animate");
}
