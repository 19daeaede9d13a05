/* Line plots: a known straight line lands on the pixels the mapping predicts and nowhere
   else; log axes survive zeros; holes break lines; bad input and unwritable files fail. */
#include <cairo.h>
#include <float.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sph_pictures.h"
#include "unit.h"

static char dir[] = "/tmp/sph_test_plot_XXXXXX";
static char path[256];

static const char *tmp(const char *name) {
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return path;
}

typedef struct {
    cairo_surface_t *s;
    int w, h, stride;
    const unsigned char *data;
} image;

static int load(const char *file, image *im) {
    im->s = cairo_image_surface_create_from_png(file);
    if (cairo_surface_status(im->s) != CAIRO_STATUS_SUCCESS)
        return 0;
    im->w = cairo_image_surface_get_width(im->s);
    im->h = cairo_image_surface_get_height(im->s);
    im->stride = cairo_image_surface_get_stride(im->s);
    im->data = cairo_image_surface_get_data(im->s);
    return 1;
}

/* sum of the three components, 0 (black) .. 765 (white); 765 outside the image */
static int level(const image *im, int x, int y) {
    uint32_t p;
    if (x < 0 || y < 0 || x >= im->w || y >= im->h)
        return 765;
    memcpy(&p, im->data + (size_t)y * im->stride + 4 * x, 4);
    return (int)((p >> 16) & 255) + (int)((p >> 8) & 255) + (int)(p & 255);
}

/* darkest level in the 3x3 block around (x, y) */
static int darkest(const image *im, double fx, double fy) {
    int x = (int)fx, y = (int)fy, i, j, m = 765;
    for (j = -1; j <= 1; j++)
        for (i = -1; i <= 1; i++)
            if (level(im, x + i, y + j) < m)
                m = level(im, x + i, y + j);
    return m;
}

#define DARK 500 /* the first series' blue sums to 292; anti-aliased edges stay below this */

static void line_spec(sph_plot_spec *p, sph_plot_series *s, const double *x, const double *y,
                      size_t n) {
    sph_plot_defaults(p);
    memset(s, 0, sizeof *s);
    s->x = x, s->y = y, s->n = n;
    p->series = s, p->nseries = 1;
    p->xrange_set = p->yrange_set = 1;
    p->xmin = p->ymin = 0, p->xmax = p->ymax = 1;
    p->width = p->height = 400;
}

static void test_straight_line(void) {
    static const double xy[2] = {0, 1};
    sph_plot_spec p;
    sph_plot_series s;
    sph_plot_frame f;
    image im;
    char err[256] = "";
    double ax, ay, bx, by, px, py, t;
    int rc, on = 0, ntest = 0, stray = 0, x, y;
    line_spec(&p, &s, xy, xy, 2);
    p.xlabel = "x", p.ylabel = "y", p.title = "y = x";
    rc = sph_plot_png(&p, tmp("line.png"), err, sizeof err);
    CHECK(rc == 0, "plot y = x", "%s", err);
    CHECK(sph_plot_layout(&p, &f, err, sizeof err) == 0 && f.xmin == 0 && f.xmax == 1,
          "fixed ranges kept", "[%g, %g]", f.xmin, f.xmax);
    if (!load(tmp("line.png"), &im)) {
        CHECK(0, "read plot back", "cannot read %s", tmp("line.png"));
        cairo_surface_destroy(im.s);
        return;
    }
    for (t = 0.05; t < 0.96; t += 0.05, ntest++) {
        /* the mapping worked out by hand from the plot area, not through the library */
        px = f.area[0] + t * f.area[2], py = f.area[1] + (1 - t) * f.area[3];
        on += darkest(&im, px, py) < DARK;
    }
    sph_plot_to_pixel(&f, 0.3, 0.6, &ax, &ay);
    CHECK(fabs(ax - (f.area[0] + 0.3 * f.area[2])) < 1e-9 &&
              fabs(ay - (f.area[1] + 0.4 * f.area[3])) < 1e-9,
          "sph_plot_to_pixel is the linear map onto the area", "%g %g", ax, ay);
    CHECK(on == ntest, "line pixels are dark where the mapping says", "%d of %d", on, ntest);
    /* everywhere else inside the frame: white */
    ax = f.area[0], ay = f.area[1] + f.area[3], bx = f.area[0] + f.area[2], by = f.area[1];
    for (y = (int)f.area[1] + 3; y < (int)(f.area[1] + f.area[3]) - 3; y++)
        for (x = (int)f.area[0] + 3; x < (int)(f.area[0] + f.area[2]) - 3; x++) {
            /* distance of the pixel centre from the line through a and b */
            double d = fabs((bx - ax) * (ay - (y + 0.5)) - (ax - (x + 0.5)) * (by - ay)) /
                       hypot(bx - ax, by - ay);
            if (d > 3 && level(&im, x, y) < 760)
                stray++;
        }
    CHECK(stray == 0, "no ink elsewhere in the plot area", "%d stray pixels", stray);
    CHECK(darkest(&im, f.area[0] - 1, f.area[1] + 0.5 * f.area[3]) < 100,
          "frame drawn at the area's edge", "no frame");
    cairo_surface_destroy(im.s);
}

static void test_holes_and_markers(void) {
    double x[11], y[11], px, py;
    sph_plot_spec p;
    sph_plot_series s[2];
    sph_plot_frame f;
    image im;
    char err[256] = "";
    static const double mx[2] = {0.25, 0.75}, my[2] = {0.25, 0.25};
    int i;
    for (i = 0; i < 11; i++)
        x[i] = 0.1 * i, y[i] = 0.5;
    y[5] = NAN; /* hole at x = 0.5 */
    line_spec(&p, &s[0], x, y, 11);
    memset(&s[1], 0, sizeof s[1]);
    s[1].x = mx, s[1].y = my, s[1].n = 2, s[1].style = SPH_PLOT_MARKERS;
    p.nseries = 2;
    CHECK(sph_plot_png(&p, tmp("holes.png"), err, sizeof err) == 0, "plot with a NaN hole", "%s",
          err);
    sph_plot_layout(&p, &f, err, sizeof err);
    if (!load(tmp("holes.png"), &im)) {
        CHECK(0, "read plot back", "cannot read");
        cairo_surface_destroy(im.s);
        return;
    }
    sph_plot_to_pixel(&f, 0.2, 0.5, &px, &py);
    CHECK(darkest(&im, px, py) < DARK, "line drawn away from the hole", "white at x = 0.2");
    sph_plot_to_pixel(&f, 0.5, 0.5, &px, &py);
    CHECK(level(&im, (int)px, (int)py) > 760, "NaN breaks the line", "ink at x = 0.5 (%d)",
          level(&im, (int)px, (int)py));
    sph_plot_to_pixel(&f, 0.25, 0.25, &px, &py);
    CHECK(level(&im, (int)px, (int)py) < 700, "marker drawn at its point", "white marker");
    sph_plot_to_pixel(&f, 0.5, 0.25, &px, &py);
    CHECK(level(&im, (int)px, (int)py) > 760, "marker-only series has no line",
          "ink between markers");
    cairo_surface_destroy(im.s);
}

static void test_log(void) {
    static const double x[6] = {0, 1, 10, 100, 1000, -5}, y[6] = {1, 1, 1e-3, 0, 0.5, 0.5};
    sph_plot_spec p;
    sph_plot_series s;
    sph_plot_frame f;
    char err[256] = "";
    double px, py;
    int rc;
    line_spec(&p, &s, x, y, 6);
    p.xrange_set = p.yrange_set = 0;
    p.xlog = p.ylog = 1;
    s.label = "zeros and negatives";
    rc = sph_plot_png(&p, tmp("log.png"), err, sizeof err);
    CHECK(rc == 0, "log axes with zeros and negatives do not crash", "%s", err);
    sph_plot_layout(&p, &f, err, sizeof err);
    CHECK(f.xmin == 1 && f.xmax == 1000 && f.ymin == 1e-3 && f.ymax == 1,
          "log auto range: whole decades of the positive data", "x [%g, %g] y [%g, %g]", f.xmin,
          f.xmax, f.ymin, f.ymax);
    sph_plot_to_pixel(&f, 10, 1, &px, &py);
    CHECK_CLOSE(px, f.area[0] + f.area[2] / 3, 1e-9, "10 sits a third along 1..1000");
    CHECK(sph_plot_to_pixel(&f, 0, 1, &px, &py) == 0, "0 has no place on a log axis", "mapped");
    p.xrange_set = 1, p.xmin = 0, p.xmax = 10;
    rc = sph_plot_png(&p, tmp("log2.png"), err, sizeof err);
    CHECK(rc == -1 && strstr(err, "positive"), "log range through 0 refused", "'%s'", err);
    p.xrange_set = 1, p.xmin = 2, p.xmax = 3; /* under a decade: linear labels */
    p.ylog = 0, p.yrange_set = 0;
    rc = sph_plot_png(&p, tmp("log3.png"), err, sizeof err);
    CHECK(rc == 0, "log axis spanning less than a decade", "%s", err);
}

static void test_ticks_and_ranges(void) {
    double t[32];
    int n = sph_plot_ticks(0, 1, 6, t, 32);
    CHECK(n == 6 && t[0] == 0 && fabs(t[5] - 1) < 1e-12 && fabs(t[1] - 0.2) < 1e-12,
          "ticks 0, 0.2, ..., 1", "n %d", n);
    n = sph_plot_ticks(-0.3, 1.7, 5, t, 32);
    CHECK(n == 4 && t[0] == 0 && !signbit(t[0]) && t[3] == 1.5, "ticks 0 .. 1.5 by 0.5",
          "n %d first %g", n, n ? t[0] : 0);
    n = sph_plot_ticks(1234, 5678, 5, t, 32);
    CHECK(n == 4 && t[0] == 2000 && t[3] == 5000, "ticks in thousands", "n %d", n);
    CHECK(sph_plot_ticks(1, 1, 5, t, 32) == 0 && sph_plot_ticks(0, 1, 5, t, 2) == 2,
          "empty range gives no ticks; cap respected", "wrong count");
    {
        /* any finite range ends with a few increasing ticks inside it: the widest spans
         * (hi - lo overflows), ranges far beyond 2^53 steps from 0; and a span too narrow
         * for a normal step (below 1e-307, where the step underflows to 0 and a naive search
         * never ends) ends with none */
        static const double r[][2] = {{-DBL_MAX, DBL_MAX}, {-1e308, 1e308}, {1e17, 1e17 + 16},
                                      {1e300, 1.000000000000001e300}, {-1, 1e-300}, {0, 1e-290}};
        for (size_t q = 0; q < sizeof r / sizeof r[0]; q++) {
            n = sph_plot_ticks(r[q][0], r[q][1], 6, t, 32);
            int ok = n >= 1 && n <= 6;
            for (int k = 0; ok && k < n; k++)
                ok = isfinite(t[k]) && t[k] >= r[q][0] && t[k] <= r[q][1] && (k == 0 || t[k] > t[k - 1]);
            CHECK(ok, "ticks of a finite range end: between 1 and 6, increasing, inside it", "[%g, %g]: n %d",
                  r[q][0], r[q][1], n);
        }
        static const double tiny[][2] = {{0, 5e-324}, {5e-324, 1e-323}, {-1e-310, 1e-310}, {1, 1 + 2e-16}};
        for (size_t q = 0; q < sizeof tiny / sizeof tiny[0]; q++) {
            n = sph_plot_ticks(tiny[q][0], tiny[q][1], 6, t, 32);
            CHECK(n >= 0 && n <= 6, "ticks of a tiny range end, at most 6", "[%g, %g]: n %d", tiny[q][0], tiny[q][1], n);
        }
        CHECK(sph_plot_ticks(0, 5e-324, 6, t, 32) == 0, "a span below a normal step gives no ticks", "n %d",
              sph_plot_ticks(0, 5e-324, 6, t, 32));
        CHECK(sph_plot_ticks(5e-324, 5e-324, 6, t, 32) == 0, "a subnormal range of equal ends gives no ticks",
              "n %d", sph_plot_ticks(5e-324, 5e-324, 6, t, 32));
    }
    {
        static const double x[2] = {0.03, 0.97};
        sph_plot_spec p;
        sph_plot_series s;
        sph_plot_frame f;
        char err[128];
        line_spec(&p, &s, x, x, 2);
        p.xrange_set = p.yrange_set = 0;
        sph_plot_layout(&p, &f, err, sizeof err);
        CHECK(f.xmin == 0 && fabs(f.xmax - 1) < 1e-12, "auto range widened to whole ticks",
              "[%g, %g]", f.xmin, f.xmax);
    }
}

static void test_many_series_legend(void) {
    enum { NS = 10, NP = 50 };
    static double x[NP], y[NS][NP];
    sph_plot_spec p;
    sph_plot_series s[NS];
    char err[256] = "", label[NS][24];
    int i, j, rc;
    sph_plot_defaults(&p);
    for (i = 0; i < NS; i++) {
        for (j = 0; j < NP; j++)
            x[j] = j, y[i][j] = i * 1e6 + j * j;
        snprintf(label[i], sizeof label[i], "series %d", i);
        memset(&s[i], 0, sizeof s[i]);
        s[i].x = x, s[i].y = y[i], s[i].n = NP, s[i].label = label[i];
        s[i].style = i % 3;
    }
    p.series = s, p.nseries = NS, p.title = "ten series", p.xlabel = "t", p.ylabel = "h";
    rc = sph_plot_png(&p, tmp("many.png"), err, sizeof err);
    CHECK(rc == 0, "ten series with legend and labels", "%s", err);
    /* points far outside a fixed range are clipped, not handed to cairo as huge numbers */
    x[1] = 1e300, y[0][1] = 1e300, s[0].n = 2, p.nseries = 1;
    x[0] = 0, y[0][0] = 0;
    p.xrange_set = p.yrange_set = 1, p.xmin = p.ymin = 0, p.xmax = p.ymax = 1;
    rc = sph_plot_png(&p, tmp("huge.png"), err, sizeof err);
    CHECK(rc == 0, "segment to 1e300 with a fixed range", "%s", err);
    p.nseries = 0;
    rc = sph_plot_png(&p, tmp("empty.png"), err, sizeof err);
    CHECK(rc == 0, "no series: empty axes", "%s", err);
}

static void test_errors(void) {
    static const double xy[2] = {0, 1};
    sph_plot_spec p;
    sph_plot_series s;
    char err[256] = "";
    int rc;
    line_spec(&p, &s, xy, xy, 2);
    rc = sph_plot_png(&p, "/nonexistent-dir/x.png", err, sizeof err);
    CHECK(rc == -1 && strstr(err, "/nonexistent-dir/x.png"), "unwritable file: -1 naming it",
          "rc %d, '%s'", rc, err);
    p.xmax = 0;
    rc = sph_plot_png(&p, tmp("e.png"), err, sizeof err);
    CHECK(rc == -1 && strstr(err, "x range"), "empty fixed range refused", "'%s'", err);
    line_spec(&p, &s, xy, xy, 2);
    s.x = NULL;
    rc = sph_plot_png(&p, tmp("e.png"), err, sizeof err);
    CHECK(rc == -1 && strstr(err, "series 1"), "series without x refused", "'%s'", err);
    line_spec(&p, &s, xy, xy, 2);
    s.style = 9;
    rc = sph_plot_png(&p, tmp("e.png"), err, sizeof err);
    CHECK(rc == -1 && strstr(err, "style"), "unknown style refused", "'%s'", err);
    line_spec(&p, &s, xy, xy, 2);
    p.width = 10;
    rc = sph_plot_png(&p, tmp("e.png"), err, sizeof err);
    CHECK(rc == -1 && strstr(err, "10x400"), "tiny plot refused", "'%s'", err);
    CHECK(access(tmp("e.png"), F_OK) != 0, "no file left by failed plots", "exists");
}

int main(void) {
    const char *names[] = {"line.png", "holes.png", "log.png",   "log2.png", "log3.png",
                           "many.png", "huge.png",  "empty.png", "e.png"};
    size_t i;
    if (!mkdtemp(dir)) {
        printf("not ok - temporary directory: cannot create %s\n", dir);
        return 1;
    }
    test_straight_line();
    test_holes_and_markers();
    test_log();
    test_ticks_and_ranges();
    test_many_series_legend();
    test_errors();
    for (i = 0; i < sizeof names / sizeof names[0]; i++)
        remove(tmp(names[i]));
    rmdir(dir);
    sph_render_release_fonts();
    UNIT_END();
}
