/* squeeze.c: the Bingham squeeze of squeeze_velocity.lua, from C, with no Lua.
 *
 * What it shows: the engine's C API (sph.h) and the pictures (sph_pictures.h): a world,
 * a material, a fill, two plates, a velocity law, steps that land on output times
 * (sph_world_run_until), the plate's gap and force, the particles' fields, and a
 * yield-state picture.
 *
 * Build, against an installed sph (make install; PKG_CONFIG_PATH=PREFIX/lib/pkgconfig
 * outside the system's folders), or in the tree with `make` (build/examples/squeeze):
 *   cc -std=c11 -O2 -o squeeze squeeze.c $(pkg-config --cflags --libs sph) -lm
 * (-lm for this program's own fmin: libsph.so brings what it needs itself).
 * Run:
 *   ./squeeze [steps=N] [t_end=T] [threads=N] [out=DIR]
 * steps=N (N > 0) stops after N steps whatever t_end (a quick look); t_end defaults to 0.4,
 * threads to 0 (all cores), out to out/squeeze_c.
 *
 * What you should see (about 1 s): rows "t h F" every 0.02 (the same numbers as
 * squeeze_velocity.lua: the force about 22 at first, 16 near h = 0.85, 45 at h = 0.6), then
 * DIR/series.csv and DIR/yield.png (yielded light, unyielded dark, drawn mirrored). */
#define _POSIX_C_SOURCE 200809L
#include <sph.h>
#include <sph_pictures.h>

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* mkdir -p */
static int make_dirs(const char *path) {
    char p[4096];
    snprintf(p, sizeof p, "%s", path);
    for (char *s = p + 1;; s++) {
        if (*s == '/' || *s == 0) {
            char c = *s;
            *s = 0;
            if (mkdir(p, 0777) != 0 && errno != EEXIST) return -1;
            if (!(*s = c)) return 0;
        }
    }
}

static int fail(sph_world *w) {
    fprintf(stderr, "squeeze: %s\n", sph_world_error(w));
    sph_world_free(w);
    return 1;
}

int main(int argc, char **argv) {
    long steps = 0;
    double t_end = 0.4, every = 0.02;
    int threads = 0;
    const char *out = "out/squeeze_c";
    for (int i = 1; i < argc; i++) { /* name=value arguments */
        if (!strncmp(argv[i], "steps=", 6)) steps = atol(argv[i] + 6);
        else if (!strncmp(argv[i], "t_end=", 6)) t_end = atof(argv[i] + 6);
        else if (!strncmp(argv[i], "threads=", 8)) threads = atoi(argv[i] + 8);
        else if (!strncmp(argv[i], "out=", 4)) out = argv[i] + 4;
        else {
            fprintf(stderr, "squeeze: unknown argument '%s' (steps=N t_end=T threads=N out=DIR)\n", argv[i]);
            return 1;
        }
    }
    if (make_dirs(out) != 0) {
        fprintf(stderr, "squeeze: cannot make %s: %s\n", out, strerror(errno));
        return 1;
    }

    /* the world: H = U = mu = 1, Re = 10 (rho), a mirror at x = 0, shifting 20 */
    const double dx = 0.025, T = 3 * dx;
    sph_params p;
    sph_params_default(&p);
    p.dx = dx;
    p.rho0 = 10;
    p.symmetry[0] = 1, p.sym_at[0] = 0;
    p.shifting = 20;
    p.threads = threads;
    char err[256];
    sph_world *w = sph_world_new(&p, err, sizeof err);
    if (!w) {
        fprintf(stderr, "squeeze: %s\n", err);
        return 1;
    }
    /* Bingham, Bn = 0.5, Papanastasiou exponent 100: {model, mu, tau0, m, K, n} */
    const sph_material dough = {SPH_BINGHAM, 1, 0.5, 100, 0, 0};
    const double sample[4] = {0, 0, 0.5, 1}, lower[4] = {-2, -T, 2, 0}, upper[4] = {-2, 1, 2, 1 + T};
    if (sph_world_fill(w, sample, &dough) < 0) return fail(w);
    if (sph_world_plate(w, lower, -1) < 0) return fail(w); /* fixed */
    int top = sph_world_plate(w, upper, 1);                   /* moves along y */
    if (top < 0 || sph_plate_set_velocity(w, top, -1) < 0) return fail(w);

    char file[4200];
    snprintf(file, sizeof file, "%s/series.csv", out);
    FILE *csv = fopen(file, "w");
    if (!csv) {
        fprintf(stderr, "squeeze: cannot write %s: %s\n", file, strerror(errno));
        sph_world_free(w);
        return 1;
    }
    fprintf(csv, "t,h,F\n");
    const double eps = 1e-9 * t_end; /* the clock's round-off (as sph_world_run_until's) */
    int bad = 0;                     /* a step failed */
    for (long k = 1;; k++) { /* the next output is at k * every */
        double t = sph_world_time(w);
        fprintf(csv, "%.6g,%.6g,%.6g\n", t, sph_plate_position(w, top), sph_plate_force(w, top));
        printf("t = %.3f  h = %.4f  F = %8.3f\n", t, sph_plate_position(w, top), sph_plate_force(w, top));
        if (steps > 0 ? sph_world_steps(w) >= steps : t >= t_end - eps) break;
        if (steps > 0) { /* a quick look: one adaptive step a row */
            if ((bad = sph_world_step(w, 0) < 0)) break;
            continue;
        }
        /* adaptive steps up to the next output time, landing on it exactly (the engine
         * spreads the interval left evenly over the steps it needs: w:run in Lua does the
         * same); no hook: the plate's law is a constant velocity */
        if ((bad = sph_world_run_until(w, fmin(k * every, t_end), 0, NULL, NULL) < 0)) break;
    }
    fclose(csv);
    if (bad) return fail(w);

    /* the picture: fields per fluid particle, the plates' current rectangles */
    int n = sph_world_nfluid(w);
    double *x = malloc(3 * (size_t)n * sizeof *x), *y = x + n, *yielded = y + n;
    unsigned char *cat = malloc((size_t)n);
    if (!x || !cat) {
        fprintf(stderr, "squeeze: out of memory\n");
        free(x), free(cat), sph_world_free(w);
        return 1;
    }
    sph_world_field(w, "x", x);
    sph_world_field(w, "y", y);
    sph_world_field(w, "yielded", yielded);
    double xmax = 0;
    for (int i = 0; i < n; i++) {
        cat[i] = yielded[i] > 0.5 ? SPH_RENDER_YIELDED : SPH_RENDER_UNYIELDED;
        if (x[i] > xmax) xmax = x[i];
    }
    double plates[8];
    sph_plate_rect(w, 0, plates);
    sph_plate_rect(w, top, plates + 4);
    char label[128];
    snprintf(label, sizeof label, "t = %.3f  h = %.3f  F = %.2f", sph_world_time(w), sph_plate_position(w, top),
             sph_plate_force(w, top));
    sph_render_spec s;
    sph_render_defaults(&s);
    s.n = (size_t)n, s.x = x, s.y = y, s.category = cat, s.radius = 0.55 * dx;
    s.plates = plates, s.nplates = 2, s.label = label;
    s.mirror = 1, s.mirror_x = 0;
    s.view_set = 1;
    s.view[0] = -(xmax + 0.1), s.view[1] = -T, s.view[2] = xmax + 0.1, s.view[3] = sph_plate_position(w, top) + T;
    s.width = 800;
    s.height = (int)(800 * (s.view[3] - s.view[1]) / (s.view[2] - s.view[0])) + 40;
    snprintf(file, sizeof file, "%s/yield.png", out);
    int rc = sph_render_png(&s, file, err, sizeof err);
    if (rc != 0) fprintf(stderr, "squeeze: %s\n", err);
    else printf("%ld steps; wrote %s/series.csv and %s\n", sph_world_steps(w), out, file);
    free(x), free(cat);
    sph_world_free(w);
    sph_render_release_fonts(); /* after the last picture: cairo's font caches (leak checkers) */
    return rc != 0;
}
