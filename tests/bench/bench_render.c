/* Renderer benchmark (not a test): 100 000 particles to 800x400 and 1600x800 PNGs,
   median of 5 runs, split into drawing (paths + fills) and PNG encoding + writing.

   make build/bench_render && build/bench_render [DIR]     (also run by `make bench`)  */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "pictures_cairo.h"

#define RUNS 5

static double now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static int cmp(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *t) {
    qsort(t, RUNS, sizeof *t, cmp);
    return t[RUNS / 2];
}

static int bench(const sph_render_spec *s, const char *file, const char *what) {
    double tdraw[RUNS], tpng[RUNS], ttotal[RUNS], t0;
    char err[256];
    int r;
    for (r = 0; r < RUNS; r++) {
        cairo_surface_t *surf;
        cairo_t *cr;
        t0 = now();
        surf = cairo_image_surface_create(CAIRO_FORMAT_RGB24, s->width, s->height);
        cr = cairo_create(surf);
        if (sph_render_draw(s, cr, err, sizeof err)) {
            fprintf(stderr, "bench_render: %s\n", err);
            return -1;
        }
        cairo_destroy(cr);
        cairo_surface_flush(surf);
        tdraw[r] = now() - t0;
        t0 = now();
        if (sph_render_write_png(surf, file, err, sizeof err)) {
            fprintf(stderr, "bench_render: %s\n", err);
            return -1;
        }
        tpng[r] = now() - t0;
        cairo_surface_destroy(surf);
        t0 = now();
        if (sph_render_png(s, file, err, sizeof err)) {
            fprintf(stderr, "bench_render: %s\n", err);
            return -1;
        }
        ttotal[r] = now() - t0;
    }
    printf("%-8s %5dx%-5d %8zu %10.1f %10.1f %10.1f\n", what, s->width, s->height, s->n,
           1e3 * median(tdraw), 1e3 * median(tpng), 1e3 * median(ttotal));
    return 0;
}

int main(int argc, char **argv) {
    enum { NX = 500, NY = 200, N = NX * NY };
    static double x[N], y[N], v[N];
    static unsigned char cat[N];
    static const double plates[8] = {-0.1, -0.1, 2.6, 0, -0.1, 1, 2.6, 1.1};
    const char *dir = argc > 1 ? argv[1] : "/tmp";
    char file[512];
    sph_render_spec s;
    int i, j, k = 0, sz;
    double dx = 1.0 / NY;
    for (j = 0; j < NY; j++)
        for (i = 0; i < NX; i++, k++) {
            x[k] = (i + 0.5) * dx, y[k] = (j + 0.5) * dx;
            /* a smooth field (every colour used) and a wedge of unyielded material */
            v[k] = sin(3 * x[k]) * cos(5 * y[k]);
            cat[k] =
                fabs(y[k] - 0.5) < 0.4 - 0.3 * x[k] ? SPH_RENDER_UNYIELDED : SPH_RENDER_YIELDED;
        }
    snprintf(file, sizeof file, "%s/bench_render.png", dir);
    printf("median of %d runs, milliseconds\n", RUNS);
    printf("%-8s %11s %8s %10s %10s %10s\n", "mode", "image", "n", "draw", "png", "total");
    for (sz = 1; sz <= 2; sz++) {
        sph_render_defaults(&s);
        s.n = N, s.x = x, s.y = y, s.radius = 0.5 * dx;
        s.plates = plates, s.nplates = 2, s.label = "t = 0.500  Re=1 Bn=5";
        s.width = 800 * sz, s.height = 400 * sz;
        s.category = cat;
        if (bench(&s, file, "yield"))
            return 1;
        s.category = NULL, s.value = v, s.field = "p";
        if (bench(&s, file, "scalar"))
            return 1;
        s.mirror = 1, s.mirror_x = 0; /* 200 000 discs drawn */
        if (bench(&s, file, "mirror"))
            return 1;
    }
    remove(file);
    return 0;
}
