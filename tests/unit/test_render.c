/* Renderer: draw known scenes, read the PNG back with cairo and look at pixels. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "atomic.h"
#include "pictures_cairo.h"
#include "unit.h"

static char dir[] = "/tmp/sph_test_render_XXXXXX";
static char path[256];

static const char *tmp(const char *name) {
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return path;
}

/* colour of pixel (x, y) of a PNG as 0..255 components; -1 if unreadable or outside */
static int pixel(const char *file, double fx, double fy, int rgb[3]) {
    cairo_surface_t *s = cairo_image_surface_create_from_png(file);
    int x = (int)fx, y = (int)fy, ok = 0;
    rgb[0] = rgb[1] = rgb[2] = -1;
    if (cairo_surface_status(s) == CAIRO_STATUS_SUCCESS && x >= 0 && y >= 0 &&
        x < cairo_image_surface_get_width(s) && y < cairo_image_surface_get_height(s)) {
        const unsigned char *row =
            cairo_image_surface_get_data(s) + (size_t)y * cairo_image_surface_get_stride(s);
        uint32_t p;
        memcpy(&p, row + 4 * x, 4);
        rgb[0] = (p >> 16) & 255, rgb[1] = (p >> 8) & 255, rgb[2] = p & 255;
        ok = 1;
    }
    cairo_surface_destroy(s);
    return ok;
}

/* every component within 2/255 of the expected colour in [0, 1] */
static int same(const int rgb[3], const double want[3]) {
    int k;
    for (k = 0; k < 3; k++)
        if (abs(rgb[k] - (int)(want[k] * 255 + 0.5)) > 2)
            return 0;
    return 1;
}

static int white(const int rgb[3]) { return rgb[0] == 255 && rgb[1] == 255 && rgb[2] == 255; }

/* two particles, one yielded at (0.25, 0.5) and one unyielded at (0.75, 0.5) */
static double px2[2] = {0.25, 0.75}, py2[2] = {0.5, 0.5};
static unsigned char cat2[2] = {SPH_RENDER_YIELDED, SPH_RENDER_UNYIELDED};

static void base_spec(sph_render_spec *s) {
    sph_render_defaults(s);
    s->n = 2, s->x = px2, s->y = py2, s->radius = 0.1;
    s->category = cat2;
    s->view_set = 1;
    s->view[0] = 0, s->view[1] = 0, s->view[2] = 1, s->view[3] = 1;
    s->width = 200, s->height = 200;
}

static void test_yield(void) {
    sph_render_spec s;
    sph_render_frame f;
    char err[256] = "";
    double ly[3], un[3], a, b, x, y;
    int c[3], rc;
    base_spec(&s);
    rc = sph_render_png(&s, tmp("yield.png"), err, sizeof err);
    CHECK(rc == 0, "render yield mode writes a PNG", "rc %d: %s", rc, err);
    CHECK(sph_render_layout(&s, &f, err, sizeof err) == 0, "layout of a fixed view", "%s", err);
    CHECK_CLOSE(f.scale, 192, 1e-9, "fixed square view fills 200 px minus padding");
    sph_render_to_pixel(&f, 0.25, 0.5, &x, &y); /* 4 px padding, y up */
    CHECK(fabs(x - (4 + 0.25 * 192)) < 1e-9 && fabs(y - (196 - 0.5 * 192)) < 1e-9,
          "world to pixel: x right, y up", "(%g, %g)", x, y);
    sph_render_category_color(SPH_RENDER_YIELDED, ly);
    sph_render_category_color(SPH_RENDER_UNYIELDED, un);
    a = 0.2126 * ly[0] + 0.7152 * ly[1] + 0.0722 * ly[2];
    b = 0.2126 * un[0] + 0.7152 * un[1] + 0.0722 * un[2];
    CHECK(a > 0.7 && b < 0.3 && un[2] > un[0], "yielded is light, unyielded dark blue",
          "luminance %.2f vs %.2f", a, b);
    sph_render_to_pixel(&f, 0.25, 0.5, &x, &y);
    pixel(tmp("yield.png"), x, y, c);
    CHECK(same(c, ly), "yielded particle centre has the light colour", "got %d %d %d at %g %g",
          c[0], c[1], c[2], x, y);
    sph_render_to_pixel(&f, 0.75, 0.5, &x, &y);
    pixel(tmp("yield.png"), x, y, c);
    CHECK(same(c, un), "unyielded particle centre has the dark colour", "got %d %d %d", c[0], c[1],
          c[2]);
    sph_render_to_pixel(&f, 0.5, 0.5, &x, &y);
    pixel(tmp("yield.png"), x, y, c);
    CHECK(white(c), "background between particles is white", "got %d %d %d", c[0], c[1], c[2]);
    pixel(tmp("yield.png"), 100, 20, c);
    CHECK(white(c), "background above particles is white", "got %d %d %d", c[0], c[1], c[2]);
    sph_render_to_pixel(&f, 0.25, 0.5 + 0.08, &x, &y); /* inside the disc, near its edge */
    pixel(tmp("yield.png"), x, y, c);
    CHECK(same(c, ly), "disc radius is in world units", "got %d %d %d", c[0], c[1], c[2]);
    sph_render_to_pixel(&f, 0.25, 0.5 + 0.12, &x, &y); /* just outside it */
    pixel(tmp("yield.png"), x, y, c);
    CHECK(white(c), "nothing drawn outside the disc", "got %d %d %d", c[0], c[1], c[2]);
}

static void test_scalar(void) {
    static const double val[2] = {0, 1}, val2[3] = {2, 5, NAN};
    static const double x3[3] = {0.2, 0.5, 0.8}, y3[3] = {0.5, 0.5, 0.5};
    const sph_colormap *m = sph_colormap_find(NULL);
    sph_render_spec s;
    sph_render_frame f;
    char err[256] = "";
    double top[3], bot[3], bad[3], x, y;
    int c[3], rc;
    base_spec(&s);
    s.category = NULL, s.value = val, s.autorange = 0, s.vmin = 0, s.vmax = 1;
    s.colorbar = 0;
    rc = sph_render_png(&s, tmp("scalar.png"), err, sizeof err);
    CHECK(rc == 0, "render scalar mode", "%s", err);
    sph_render_layout(&s, &f, err, sizeof err);
    sph_colormap_entry(m, m->n - 1, top);
    sph_colormap_entry(m, 0, bot);
    sph_render_to_pixel(&f, 0.75, 0.5, &x, &y);
    pixel(tmp("scalar.png"), x, y, c);
    CHECK(same(c, top), "value = vmax gets the colour map's top colour", "got %d %d %d", c[0], c[1],
          c[2]);
    sph_render_to_pixel(&f, 0.25, 0.5, &x, &y);
    pixel(tmp("scalar.png"), x, y, c);
    CHECK(same(c, bot), "value = vmin gets the bottom colour", "got %d %d %d", c[0], c[1], c[2]);

    /* autorange over finite values; NaN drawn grey; colour bar at the right */
    s.n = 3, s.x = x3, s.y = y3, s.value = val2, s.autorange = 1, s.radius = 0.05;
    s.colorbar = 1, s.field = "p", s.width = 300;
    rc = sph_render_png(&s, tmp("auto.png"), err, sizeof err);
    CHECK(rc == 0, "render autorange with colour bar", "%s", err);
    sph_render_layout(&s, &f, err, sizeof err);
    CHECK(f.vmin == 2 && f.vmax == 5, "autorange is the finite min and max", "[%g, %g]", f.vmin,
          f.vmax);
    sph_render_to_pixel(&f, 0.5, 0.5, &x, &y);
    pixel(tmp("auto.png"), x, y, c);
    CHECK(same(c, top), "autorange maximum gets the top colour", "got %d %d %d", c[0], c[1], c[2]);
    sph_render_to_pixel(&f, 0.8, 0.5, &x, &y);
    pixel(tmp("auto.png"), x, y, c);
    sph_colormap_entry(m, -1, bad);
    CHECK(same(c, bad), "non-finite value is drawn grey", "got %d %d %d", c[0], c[1], c[2]);
    { /* the bar: its middle row holds the map's middle colour, right of the picture */
        double mid[3];
        int found = 0, i;
        sph_colormap_eval(m, 0.5, mid);
        for (i = (int)(f.area[0] + f.area[2]); i < 300 && !found; i++) {
            pixel(tmp("auto.png"), i, f.area[1] + 0.5 * f.area[3] + 0.6 * 9, c);
            found = abs(c[1] - (int)(mid[1] * 255)) < 30 && abs(c[2] - (int)(mid[2] * 255)) < 30 &&
                    abs(c[0] - (int)(mid[0] * 255)) < 30;
        }
        CHECK(found, "colour bar drawn right of the picture", "no mid-map colour found");
    }

    s.autorange = 0, s.vmin = 3, s.vmax = 3; /* equal ends widen instead of dividing by 0 */
    CHECK(sph_render_layout(&s, &f, err, sizeof err) == 0 && f.vmin < 3 && f.vmax > 3,
          "vmin == vmax is widened", "[%g, %g]", f.vmin, f.vmax);
}

static void test_mirror_plates_label(void) {
    static const double x1[1] = {0.2}, y1[1] = {0.5}, plate[4] = {0, 0, 0.4, 0.1};
    static const unsigned char c1[1] = {SPH_RENDER_YIELDED};
    sph_render_spec s;
    sph_render_frame f;
    char err[256] = "";
    double ly[3], x, y;
    int c[3], i, j, dark = 0;
    base_spec(&s);
    s.n = 1, s.x = x1, s.y = y1, s.category = c1;
    s.mirror = 1, s.mirror_x = 0.5;
    s.plates = plate, s.nplates = 1;
    s.label = "t = 0.500  Re=1 Bn=5";
    CHECK(sph_render_png(&s, tmp("mirror.png"), err, sizeof err) == 0, "render with mirror", "%s",
          err);
    sph_render_layout(&s, &f, err, sizeof err);
    sph_render_category_color(SPH_RENDER_YIELDED, ly);
    sph_render_to_pixel(&f, 0.8, 0.5, &x, &y);
    pixel(tmp("mirror.png"), x, y, c);
    CHECK(same(c, ly), "mirrored particle appears at the mirrored pixel", "got %d %d %d", c[0],
          c[1], c[2]);
    sph_render_to_pixel(&f, 0.8, 0.05, &x, &y);
    pixel(tmp("mirror.png"), x, y, c);
    CHECK(c[0] == c[1] && c[1] == c[2] && c[0] > 60 && c[0] < 200, "mirrored plate is grey",
          "got %d %d %d", c[0], c[1], c[2]);
    sph_render_to_pixel(&f, 0.5, 0.05, &x, &y);
    pixel(tmp("mirror.png"), x, y, c);
    CHECK(white(c), "gap between plate and its mirror image is white", "got %d %d %d", c[0], c[1],
          c[2]);
    for (j = 0; j < (int)f.area[1]; j++)
        for (i = 0; i < 200; i++)
            if (pixel(tmp("mirror.png"), i, j, c) && c[0] < 128)
                dark++;
    CHECK(dark > 20, "label text above the picture", "%d dark pixels", dark);

    s.mirror = 0;
    CHECK(sph_render_png(&s, tmp("nomirror.png"), err, sizeof err) == 0, "render without mirror",
          "%s", err);
    sph_render_to_pixel(&f, 0.8, 0.5, &x, &y);
    pixel(tmp("nomirror.png"), x, y, c);
    CHECK(white(c), "no mirror: nothing at the mirrored pixel", "got %d %d %d", c[0], c[1], c[2]);
}

static void test_autofit(void) {
    enum { N = 60 };
    double x[N], y[N], px, py;
    unsigned char cat[N];
    sph_render_spec s;
    sph_render_frame f;
    char err[256] = "";
    unsigned seed = 12345;
    int i, c[3], inside = 0, coloured = 0;
    for (i = 0; i < N; i++) { /* a fixed pseudo-random cloud over [-3, 7] x [2, 4] */
        seed = seed * 1103515245u + 12345u;
        x[i] = -3 + 10.0 * (seed >> 8) / (1u << 24);
        seed = seed * 1103515245u + 12345u;
        y[i] = 2 + 2.0 * (seed >> 8) / (1u << 24);
        cat[i] = (unsigned char)(i % 3);
    }
    x[0] = -3, x[1] = 7, y[2] = 2, y[3] = 4; /* the extremes */
    sph_render_defaults(&s);
    s.n = N, s.x = x, s.y = y, s.radius = 0.05, s.category = cat;
    s.width = 400, s.height = 300;
    CHECK(sph_render_png(&s, tmp("fit.png"), err, sizeof err) == 0, "render auto-fit", "%s", err);
    sph_render_layout(&s, &f, err, sizeof err);
    for (i = 0; i < N; i++) {
        int ok;
        sph_render_to_pixel(&f, x[i], y[i], &px, &py);
        ok = px >= f.area[0] + 1 && px <= f.area[0] + f.area[2] - 1 && py >= f.area[1] + 1 &&
             py <= f.area[1] + f.area[3] - 1;
        inside += ok;
        if (ok && pixel(tmp("fit.png"), px, py, c) && !white(c))
            coloured++;
    }
    CHECK(inside == N, "auto-fit puts every particle inside the image", "%d of %d", inside, N);
    CHECK(coloured == N, "every particle drawn", "%d of %d", coloured, N);
    CHECK(f.view[0] < -3.05 && f.view[2] > 7.05 && f.view[1] < 1.95 && f.view[3] > 4.05,
          "fitted view holds every disc", "{%g %g %g %g}", f.view[0], f.view[1], f.view[2],
          f.view[3]);
}

static void test_draw_to_surface(void) {
    cairo_surface_t *surf = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 200, 200);
    cairo_t *cr = cairo_create(surf);
    sph_render_spec s;
    char err[256] = "";
    int rc;
    base_spec(&s);
    rc = sph_render_draw(&s, cr, err, sizeof err);
    cairo_destroy(cr);
    CHECK(rc == 0, "draw into a caller's surface", "%s", err);
    CHECK(sph_render_write_png(surf, tmp("surface.png"), err, sizeof err) == 0,
          "write a caller's surface", "%s", err);
    cairo_surface_destroy(surf);
}

static void test_errors(void) {
    static const unsigned char bad[2] = {1, 7};
    sph_render_spec s;
    char err[256] = "", small[8];
    int rc;
    base_spec(&s);
    rc = sph_render_png(&s, "/nonexistent-dir/x.png", err, sizeof err);
    CHECK(rc == -1 && strstr(err, "/nonexistent-dir/x.png"), "unwritable file: -1 naming it",
          "rc %d, '%s'", rc, err);
    CHECK(access("/nonexistent-dir/x.png", F_OK) != 0, "nothing written on failure", "exists");
    s.radius = 0;
    rc = sph_render_png(&s, tmp("e.png"), err, sizeof err);
    CHECK(rc == -1 && strstr(err, "radius"), "radius 0 refused", "'%s'", err);
    base_spec(&s);
    s.category = bad;
    rc = sph_render_png(&s, tmp("e.png"), err, sizeof err);
    CHECK(rc == -1 && strstr(err, "category"), "bad category refused", "'%s'", err);
    base_spec(&s);
    s.category = NULL;
    rc = sph_render_png(&s, tmp("e.png"), err, sizeof err);
    CHECK(rc == -1 && strstr(err, "category or a value"), "colour source required", "'%s'", err);
    base_spec(&s);
    s.view[2] = s.view[0];
    rc = sph_render_png(&s, tmp("e.png"), small, sizeof small);
    CHECK(rc == -1 && strlen(small) == 7, "empty view refused, message truncated to buffer", "'%s'",
          small);
    base_spec(&s);
    s.width = 0;
    CHECK(sph_render_png(&s, tmp("e.png"), NULL, 0) == -1, "zero width refused, NULL err ok",
          "accepted");
    base_spec(&s);
    s.category = NULL, s.value = s.x, s.colormap = "rainbow";
    rc = sph_render_png(&s, tmp("e.png"), err, sizeof err);
    CHECK(rc == -1 && strstr(err, "rainbow"), "unknown colour map named", "'%s'", err);
}

static void test_colormap(void) {
    const sph_colormap *m = sph_colormap_find("viridis");
    double c[3];
    CHECK(m && m->n >= 256, "viridis has a full table", "missing");
    CHECK(sph_colormap_find("no-such-map") == NULL, "unknown map is NULL", "found");
    CHECK(sph_colormap_index(m, 0) == 0 && sph_colormap_index(m, 1) == m->n - 1 &&
              sph_colormap_index(m, -3) == 0 && sph_colormap_index(m, 9) == m->n - 1 &&
              sph_colormap_index(m, NAN) == -1,
          "index clamps and flags NaN", "wrong index");
    sph_colormap_eval(m, 1, c);
    CHECK(c[0] > 0.98 && c[1] > 0.9 && c[2] < 0.2, "viridis ends yellow", "%g %g %g", c[0], c[1],
          c[2]);
    sph_colormap_eval(m, 0, c);
    CHECK(c[0] < 0.3 && c[1] < 0.05 && c[2] > 0.3, "viridis starts dark purple", "%g %g %g", c[0],
          c[1], c[2]);
}

/* the first bytes of a file ("" when it cannot be read) */
static const char *contents(const char *file, char *buf, size_t cap) {
    FILE *fp = fopen(file, "rb");
    size_t n = 0;
    if (fp) {
        n = fread(buf, 1, cap - 1, fp);
        fclose(fp);
    }
    buf[n] = 0;
    return buf;
}

/* The shared replace-whole helper every writer uses (src/atomic.c): an aborted write (the
   writers' failure path) leaves the old file as it was, a committed one replaces it, a
   rename that cannot happen (the target is a directory) fails naming it; never a
   temporary file left behind. */
static void test_atomic(void) {
    char buf[64], err[512] = "", sub[512], cmd[600];
    const char *f = tmp("atomic.txt");
    sph_atomic_file af;
    FILE *fp = fopen(f, "wb");
    if (fp) {
        fputs("old", fp);
        fclose(fp);
    }
    int rc = sph_atomic_open(&af, f, err, sizeof err);
    CHECK(rc == 0 && af.fp, "atomic: open a temporary file next to the target", "'%s'", err);
    if (rc == 0) {
        fputs("half a new fi", af.fp);
        sph_atomic_abort(&af);
    }
    CHECK(!strcmp(contents(f, buf, sizeof buf), "old"), "atomic: an aborted write leaves the old file", "'%s'", buf);
    rc = sph_atomic_open(&af, f, err, sizeof err);
    if (rc == 0) {
        fputs("new", af.fp);
        rc = sph_atomic_commit(&af, err, sizeof err);
    }
    CHECK(rc == 0 && !strcmp(contents(f, buf, sizeof buf), "new"), "atomic: a committed write replaces the file",
          "rc %d '%s' '%s'", rc, buf, err);
    snprintf(sub, sizeof sub, "%s/adir", dir);
    mkdir(sub, 0700);
    rc = sph_atomic_open(&af, sub, err, sizeof err);
    if (rc == 0) {
        fputs("x", af.fp);
        rc = sph_atomic_commit(&af, err, sizeof err);
    }
    CHECK(rc == -1 && strstr(err, "cannot replace") && strstr(err, sub), "atomic: a rename onto a directory fails, naming it",
          "rc %d '%s'", rc, err);
    rmdir(sub);
    rc = sph_atomic_open(&af, "/nonexistent-sph-dir/x.png", err, sizeof err);
    CHECK(rc == -1 && strstr(err, "cannot open '/nonexistent-sph-dir/x.png' for writing: No such file or directory"),
          "atomic: a missing directory fails, naming the file and why", "'%s'", err);
    snprintf(cmd, sizeof cmd, "ls -A '%s' | grep -c tmp", dir);
    FILE *p = popen(cmd, "r");
    int left = -1;
    if (p) {
        if (fscanf(p, "%d", &left) != 1)
            left = -1;
        pclose(p);
    }
    CHECK(left == 0, "atomic: no temporary file left behind", "%d", left);
    remove(f);
}

int main(void) {
    const char *names[] = {"yield.png",    "scalar.png", "auto.png",    "mirror.png",
                           "nomirror.png", "fit.png",    "surface.png", "e.png"};
    size_t i;
    if (!mkdtemp(dir)) {
        printf("not ok - temporary directory: cannot create %s\n", dir);
        return 1;
    }
    test_colormap();
    test_yield();
    test_scalar();
    test_mirror_plates_label();
    test_autofit();
    test_draw_to_surface();
    test_errors();
    test_atomic();
    for (i = 0; i < sizeof names / sizeof names[0]; i++)
        remove(tmp(names[i]));
    rmdir(dir);
    sph_render_release_fonts();
    UNIT_END();
}
