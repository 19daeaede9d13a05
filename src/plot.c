/* plot.c: line plots to PNG with Cairo. Ranges and the plot area are resolved first
   (sph_plot_layout, text measured on a scratch surface so the result does not depend on
   the target), then series, axes, ticks, labels and legend are drawn. Segments are clipped
   in double precision before they reach cairo, whose fixed-point coordinates overflow for
   points far outside a fixed range. */
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "message.h"
#include "pictures_cairo.h"

#define MAX_TICKS 160
#define TWO_PI 6.28318530717958647692

/* Okabe & Ito (2008), "Color Universal Design": distinguishable by colour-blind viewers;
   their yellow is left out (too faint on white). */
static const double palette[][3] = {
    {0.000, 0.447, 0.698}, {0.835, 0.369, 0.000}, {0.000, 0.620, 0.451}, {0.902, 0.624, 0.000},
    {0.800, 0.475, 0.655}, {0.337, 0.706, 0.914}, {0.000, 0.000, 0.000},
};
#define NPALETTE (int)(sizeof palette / sizeof palette[0])
/* dash patterns in line widths; 4 is prime to the 7 colours, so 28 series stay distinct */
static const double dashes[4][4] = {{0}, {6, 3}, {1, 2.5}, {6, 2.5, 1, 2.5}};
static const int ndashes[4] = {0, 2, 2, 4};

typedef struct {
    double v[MAX_TICKS];
    int major[MAX_TICKS]; /* 1: tick with a label */
    int n;
    int decades; /* log axis with labels at 10^k */
    double step; /* linear label step, for the number of decimals */
} tickset;

typedef struct {
    sph_plot_frame f;
    double fs;
    tickset xt, yt;
} layout_t;

void sph_plot_defaults(sph_plot_spec *s) {
    memset(s, 0, sizeof *s);
    s->width = 640;
    s->height = 480;
    s->legend = 1;
}

/* smallest 1, 2 or 5 x 10^k >= raw (raw below DBL_MIN taken as DBL_MIN: log10 of 0 is -inf) */
static double nice_step(double raw) {
    if (!(raw >= DBL_MIN))
        raw = DBL_MIN;
    double p = pow(10, floor(log10(raw))), f = raw / p;
    return (f <= 1 ? 1 : f <= 2 ? 2 : f <= 5 ? 5 : 10) * p;
}

int sph_plot_ticks(double lo, double hi, int most, double *ticks, int cap) {
    static const double mantissa[3] = {1, 2, 5};
    double step, k, k1, e, span;
    int n = 0, i = 0, tries;
    if (!isfinite(lo) || !isfinite(hi) || !(hi > lo) || most < 2 || cap < 1)
        return 0;
    /* Any finite range ends here. hi - lo may overflow (take the largest double: the step
     * grows past it anyway). A span whose tick step would be below 1e-307 has no ticks:
     * there log10 of it is -inf or pow(10, e) underflows to 0, and a step of 0 never gives
     * few enough ticks (the search spun forever). The search is bounded besides. */
    span = hi - lo;
    if (!isfinite(span))
        span = DBL_MAX;
    e = floor(log10(span / (2.0 * most)));
    if (!(e >= -307))
        return 0;
    for (tries = 0;; tries++) {
        step = mantissa[i] * pow(10, e);
        if (floor(hi / step + 1e-9) - ceil(lo / step - 1e-9) + 1 <= most)
            break;
        if (tries > 3 * 700) /* past 1e308 the step is inf and the test above holds */
            return 0;
        if (++i == 3)
            i = 0, e++;
    }
    k1 = floor(hi / step + 1e-9);
    for (k = ceil(lo / step - 1e-9); k <= k1 && n < cap; k++) {
        double v = fabs(k) < 0.5 ? 0 : k * step; /* exact 0, never -0 */
        if (n > 0 && !(v > ticks[n - 1]))
            break; /* k beyond 2^53: k + 1 == k, no new tick */
        ticks[n++] = v;
    }
    return n;
}

static int usable(double v, int lg) { return isfinite(v) && (!lg || v > 0); }

static int check_range(const char *axis, int lg, double lo, double hi, char *err, size_t errlen) {
    if (!isfinite(lo) || !isfinite(hi) || !(lo < hi))
        return sph_message_set(err, errlen, "%s range [%g, %g] must be finite with min < max", axis, lo, hi);
    if (lg && lo <= 0)
        return sph_message_set(err, errlen, "%s range [%g, %g] must be positive on a log axis", axis, lo, hi);
    return 0;
}

/* Automatic range: the data's, widened to whole ticks (linear) or whole decades (log). */
static void auto_range(const sph_plot_spec *s, int axis, double *lo, double *hi) {
    int lg = axis ? s->ylog : s->xlog;
    double a = INFINITY, b = -INFINITY, d, step;
    size_t i, j;
    for (i = 0; i < s->nseries; i++) {
        const sph_plot_series *p = &s->series[i];
        for (j = 0; j < p->n; j++) {
            double v = axis ? p->y[j] : p->x[j];
            if (usable(p->x[j], s->xlog) && usable(p->y[j], s->ylog))
                a = fmin(a, v), b = fmax(b, v);
        }
    }
    if (a > b) { /* no data */
        *lo = lg ? 1 : 0, *hi = lg ? 10 : 1;
        return;
    }
    if (lg) {
        /* whole decades, within the normal doubles: 5e-324 rounds down to 10^-324 = 0 and
         * 1.7e308 up to 10^309 = inf, whose logarithms no tick loop can count from */
        a = pow(10, floor(log10(a))), b = pow(10, ceil(log10(b)));
        if (!(a >= 1e-307)) a = 1e-307;
        if (!(b <= 1e308)) b = 1e308;
        *lo = a, *hi = b > a ? b : 10 * a;
        return;
    }
    if (a == b || !isnormal(b - a)) { /* one value, or two no step can tell apart */
        d = fabs(a) >= 1e-300 ? 0.1 * fabs(a) : 1;
        a -= d, b += d;
    }
    step = nice_step(b / 5 - a / 5); /* not (b - a) / 5: it overflows for data near +-DBL_MAX */
    *lo = floor(a / step + 1e-9) * step, *hi = ceil(b / step - 1e-9) * step;
}

static void add_tick(tickset *t, double v, int major) {
    if (t->n < MAX_TICKS)
        t->v[t->n] = v, t->major[t->n++] = major;
}

static void axis_ticks(double lo, double hi, int lg, int most, tickset *t) {
    double lin[32];
    int i, n, k, k0, k1, every, m;
    memset(t, 0, sizeof *t);
    if (lg) {
        k0 = (int)ceil(log10(lo) - 1e-9), k1 = (int)floor(log10(hi) + 1e-9);
        if (k1 - k0 + 1 >= 2) { /* labels at decades, every few when they are many */
            t->decades = 1;
            every = (k1 - k0 + most) / most;
            for (k = k0; k <= k1; k++)
                add_tick(t, pow(10, k), (k - k0) % every == 0);
            if (every > 1)
                return; /* minor ticks would be a smear */
        } else {        /* less than two decades: labelled linear ticks */
            n = sph_plot_ticks(lo, hi, most, lin, 32);
            for (i = 0; i < n; i++)
                add_tick(t, lin[i], 1);
            t->step = n > 1 ? lin[1] - lin[0] : hi - lo;
        }
        for (k = (int)floor(log10(lo)) - 1; k <= (int)floor(log10(hi)); k++)
            for (m = 2; m <= 9; m++)
                if (m * pow(10, k) >= lo && m * pow(10, k) <= hi)
                    add_tick(t, m * pow(10, k), 0);
        return;
    }
    n = sph_plot_ticks(lo, hi, most, lin, 32);
    for (i = 0; i < n; i++)
        add_tick(t, lin[i], 1);
    t->step = n > 1 ? lin[1] - lin[0] : hi - lo;
}

/* A tick label as base text and optional superscript (10 with exponent k). */
static void tick_text(const tickset *t, double v, char base[32], char sup[8]) {
    int dec;
    sup[0] = 0;
    if (t->decades) {
        int k = (int)lround(log10(v));
        if (k >= -3 && k <= 4) {
            snprintf(base, 32, "%g", pow(10, k));
        } else {
            snprintf(base, 32, "10");
            snprintf(sup, 8, "%d", k);
        }
        return;
    }
    dec = t->step < 1 ? (int)ceil(-log10(t->step) - 1e-9) : 0;
    if (dec > 6 || fabs(v) >= 1e6)
        snprintf(base, 32, "%.3g", v);
    else
        snprintf(base, 32, "%.*f", dec, v);
}

/* Width of a tick label, and draw it when `draw`: anchored at (x, y) with alignment
   ax in {0, 0.5, 1} (left, centre, right) and the text's middle at y. */
static double tick_label(cairo_t *cr, const tickset *t, double v, double fs, double x, double y,
                         double ax, int draw) {
    char base[32], sup[8];
    cairo_text_extents_t a, b;
    double w;
    tick_text(t, v, base, sup);
    cairo_set_font_size(cr, fs);
    cairo_text_extents(cr, base, &a);
    w = a.x_advance;
    if (sup[0]) {
        cairo_set_font_size(cr, 0.7 * fs);
        cairo_text_extents(cr, sup, &b);
        w += b.x_advance;
    }
    if (draw) {
        double x0 = x - ax * w, yb = y + 0.36 * fs; /* baseline: digits are ~0.72 fs tall */
        cairo_set_font_size(cr, fs);
        cairo_move_to(cr, x0, yb);
        cairo_show_text(cr, base);
        if (sup[0]) {
            cairo_set_font_size(cr, 0.7 * fs);
            cairo_move_to(cr, x0 + a.x_advance, yb - 0.45 * fs);
            cairo_show_text(cr, sup);
        }
        cairo_set_font_size(cr, fs);
    }
    return w;
}

static void set_font(cairo_t *cr, double fs) {
    cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, fs);
}

static int layout(const sph_plot_spec *s, layout_t *L, char *err, size_t errlen) {
    sph_plot_frame *f = &L->f;
    double fs, pad = 6, tl, left, right, top, bottom, yw = 0, xw = 0;
    cairo_surface_t *scratch;
    cairo_t *cr;
    size_t i;
    int k;
    memset(L, 0, sizeof *L);
    if (s->width < 64 || s->width > 16384 || s->height < 64 || s->height > 16384)
        return sph_message_set(err, errlen, "plot size %dx%d is outside 64..16384 pixels", s->width,
                    s->height);
    if (s->nseries && !s->series)
        return sph_message_set(err, errlen, "series are missing");
    for (i = 0; i < s->nseries; i++) {
        const sph_plot_series *p = &s->series[i];
        if (p->n && (!p->x || !p->y))
            return sph_message_set(err, errlen, "series %zu has no x or y values", i + 1);
        if (p->style < SPH_PLOT_LINE || p->style > SPH_PLOT_LINE_MARKERS)
            return sph_message_set(err, errlen, "series %zu has unknown style %d", i + 1, p->style);
    }
    f->xlog = s->xlog != 0, f->ylog = s->ylog != 0;
    if (s->xrange_set) {
        if (check_range("x", f->xlog, s->xmin, s->xmax, err, errlen))
            return -1;
        f->xmin = s->xmin, f->xmax = s->xmax;
    } else {
        auto_range(s, 0, &f->xmin, &f->xmax);
    }
    if (s->yrange_set) {
        if (check_range("y", f->ylog, s->ymin, s->ymax, err, errlen))
            return -1;
        f->ymin = s->ymin, f->ymax = s->ymax;
    } else {
        auto_range(s, 1, &f->ymin, &f->ymax);
    }
    fs = (s->width < s->height ? s->width : s->height) / 32.0;
    L->fs = fs = fs < 9 ? 9 : fs > 16 ? 16 : fs;
    axis_ticks(f->xmin, f->xmax, f->xlog, s->width > 500 ? 8 : 5, &L->xt);
    axis_ticks(f->ymin, f->ymax, f->ylog, s->height > 400 ? 8 : 5, &L->yt);
    scratch = cairo_image_surface_create(CAIRO_FORMAT_A8, 1, 1);
    cr = cairo_create(scratch);
    set_font(cr, fs);
    for (k = 0; k < L->yt.n; k++)
        if (L->yt.major[k])
            yw = fmax(yw, tick_label(cr, &L->yt, L->yt.v[k], fs, 0, 0, 0, 0));
    for (k = L->xt.n - 1; k >= 0; k--)
        if (L->xt.major[k]) { /* the rightmost label sticks out by half its width */
            xw = tick_label(cr, &L->xt, L->xt.v[k], fs, 0, 0, 0, 0);
            break;
        }
    cairo_destroy(cr);
    cairo_surface_destroy(scratch);
    tl = 0.5 * fs;
    left = pad + (s->ylabel && *s->ylabel ? 1.5 * fs : 0) + yw + 0.4 * fs + tl;
    bottom = pad + (s->xlabel && *s->xlabel ? 1.5 * fs : 0) + 1.2 * fs + tl;
    top = pad + (s->title && *s->title ? 1.8 * fs : 0.6 * fs);
    right = pad + fmax(0.8 * fs, 0.5 * xw);
    f->area[0] = floor(left), f->area[1] = floor(top);
    f->area[2] = floor(s->width - right - f->area[0]);
    f->area[3] = floor(s->height - bottom - f->area[1]);
    if (f->area[2] < 16 || f->area[3] < 16)
        return sph_message_set(err, errlen, "plot %dx%d is too small for its labels", s->width, s->height);
    return 0;
}

int sph_plot_layout(const sph_plot_spec *s, sph_plot_frame *f, char *err, size_t errlen) {
    layout_t L;
    int rc = layout(s, &L, err, errlen);
    *f = L.f;
    return rc;
}

static double frac(double v, double lo, double hi, int lg) {
    return lg ? (log10(v) - log10(lo)) / (log10(hi) - log10(lo)) : (v - lo) / (hi - lo);
}

int sph_plot_to_pixel(const sph_plot_frame *f, double x, double y, double *px, double *py) {
    if (!usable(x, f->xlog) || !usable(y, f->ylog))
        return 0;
    *px = f->area[0] + frac(x, f->xmin, f->xmax, f->xlog) * f->area[2];
    *py = f->area[1] + f->area[3] - frac(y, f->ymin, f->ymax, f->ylog) * f->area[3];
    return 1;
}

/* Liang-Barsky: clip segment p->q to box b (x0, y0, x1, y1); 0 if nothing is left. */
static int clip(const double b[4], double *px, double *py, double *qx, double *qy) {
    double t0 = 0, t1 = 1, dx = *qx - *px, dy = *qy - *py;
    double p[4] = {-dx, dx, -dy, dy}, q[4] = {*px - b[0], b[2] - *px, *py - b[1], b[3] - *py};
    int i;
    for (i = 0; i < 4; i++) {
        if (p[i] == 0) {
            if (q[i] < 0)
                return 0;
        } else {
            double r = q[i] / p[i];
            if (p[i] < 0)
                t0 = fmax(t0, r);
            else
                t1 = fmin(t1, r);
        }
    }
    if (t0 > t1)
        return 0;
    *qx = *px + t1 * dx, *qy = *py + t1 * dy;
    *px += t0 * dx, *py += t0 * dy;
    return 1;
}

static void series_style(cairo_t *cr, size_t i, double lw) {
    const double *c = palette[i % NPALETTE];
    double d[4];
    int k, nd = ndashes[i % 4];
    for (k = 0; k < nd; k++)
        d[k] = dashes[i % 4][k] * lw;
    cairo_set_source_rgb(cr, c[0], c[1], c[2]);
    cairo_set_line_width(cr, lw);
    cairo_set_dash(cr, d, nd, 0);
}

static void draw_series(const sph_plot_frame *f, const sph_plot_series *p, size_t i, cairo_t *cr,
                        double fs) {
    double lw = fmax(1.5, fs / 9), mr = 0.28 * fs, box[4], ax = 0, ay = 0, bx, by;
    double lastx = NAN, lasty = NAN;
    int have = 0;
    size_t j;
    box[0] = f->area[0] - 4, box[1] = f->area[1] - 4;
    box[2] = f->area[0] + f->area[2] + 4, box[3] = f->area[1] + f->area[3] + 4;
    series_style(cr, i, lw);
    cairo_new_path(cr);
    if (p->style != SPH_PLOT_MARKERS) {
        for (j = 0; j < p->n; j++) {
            if (!sph_plot_to_pixel(f, p->x[j], p->y[j], &bx, &by)) {
                have = 0; /* a hole in the data breaks the line */
                continue;
            }
            if (have) {
                double cx = ax, cy = ay, dx = bx, dy = by;
                if (clip(box, &cx, &cy, &dx, &dy)) {
                    if (cx != lastx || cy != lasty)
                        cairo_move_to(cr, cx, cy);
                    cairo_line_to(cr, dx, dy);
                    lastx = dx, lasty = dy;
                }
            }
            ax = bx, ay = by, have = 1;
        }
        cairo_stroke(cr);
    }
    if (p->style != SPH_PLOT_LINE) {
        for (j = 0; j < p->n; j++) {
            if (!sph_plot_to_pixel(f, p->x[j], p->y[j], &bx, &by) || bx < box[0] || bx > box[2] ||
                by < box[1] || by > box[3])
                continue;
            cairo_new_sub_path(cr);
            cairo_arc(cr, bx, by, mr, 0, TWO_PI);
        }
        cairo_fill(cr);
    }
}

static void draw_axes(const sph_plot_spec *s, const layout_t *L, cairo_t *cr) {
    const sph_plot_frame *f = &L->f;
    double fs = L->fs, x0 = f->area[0], y0 = f->area[1], w = f->area[2], h = f->area[3];
    double px, py, len;
    int k;
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1);
    cairo_set_dash(cr, NULL, 0, 0);
    cairo_rectangle(cr, x0 - 0.5, y0 - 0.5, w + 1, h + 1); /* crisp: on pixel centres */
    cairo_stroke(cr);
    for (k = 0; k < L->xt.n; k++) {
        px = floor(x0 + frac(L->xt.v[k], f->xmin, f->xmax, f->xlog) * w) + 0.5;
        len = L->xt.major[k] ? 0.5 * fs : 0.3 * fs;
        cairo_move_to(cr, px, y0 + h + 0.5);
        cairo_line_to(cr, px, y0 + h + 0.5 + len);
        cairo_stroke(cr);
        if (L->xt.major[k])
            tick_label(cr, &L->xt, L->xt.v[k], fs, px, y0 + h + 1.2 * fs, 0.5, 1);
    }
    for (k = 0; k < L->yt.n; k++) {
        py = floor(y0 + h - frac(L->yt.v[k], f->ymin, f->ymax, f->ylog) * h) + 0.5;
        len = L->yt.major[k] ? 0.5 * fs : 0.3 * fs;
        cairo_move_to(cr, x0 - 0.5, py);
        cairo_line_to(cr, x0 - 0.5 - len, py);
        cairo_stroke(cr);
        if (L->yt.major[k])
            tick_label(cr, &L->yt, L->yt.v[k], fs, x0 - 0.9 * fs, py, 1, 1);
    }
    if (s->xlabel && *s->xlabel) {
        cairo_text_extents_t te;
        cairo_text_extents(cr, s->xlabel, &te);
        cairo_move_to(cr, x0 + 0.5 * (w - te.x_advance), s->height - 6 - 0.3 * fs);
        cairo_show_text(cr, s->xlabel);
    }
    if (s->ylabel && *s->ylabel) {
        cairo_text_extents_t te;
        cairo_text_extents(cr, s->ylabel, &te);
        cairo_save(cr);
        cairo_move_to(cr, 6 + 1.1 * fs, y0 + 0.5 * (h + te.x_advance));
        cairo_rotate(cr, -0.25 * TWO_PI);
        cairo_show_text(cr, s->ylabel);
        cairo_restore(cr);
    }
    if (s->title && *s->title) {
        cairo_text_extents_t te;
        cairo_set_font_size(cr, 1.1 * fs);
        cairo_text_extents(cr, s->title, &te);
        cairo_move_to(cr, x0 + 0.5 * (w - te.x_advance), 6 + 1.2 * fs);
        cairo_show_text(cr, s->title);
        cairo_set_font_size(cr, fs);
    }
}

/* Legend in the corner of the plot area that covers the fewest data points. */
static void draw_legend(const sph_plot_spec *s, const layout_t *L, cairo_t *cr) {
    const sph_plot_frame *f = &L->f;
    double fs = L->fs, tw = 0, bw, bh, row = 1.4 * fs, sample = 2.2 * fs, bx = 0, by = 0;
    size_t i, j, nl = 0, best = (size_t)-1;
    int c;
    for (i = 0; i < s->nseries; i++)
        if (s->series[i].label && *s->series[i].label) {
            cairo_text_extents_t te;
            cairo_text_extents(cr, s->series[i].label, &te);
            tw = fmax(tw, te.x_advance), nl++;
        }
    if (!nl)
        return;
    bw = sample + tw + 1.2 * fs, bh = nl * row + 0.6 * fs;
    for (c = 0; c < 4; c++) { /* upper right, upper left, lower right, lower left */
        double cx = c % 2 ? f->area[0] + 0.5 * fs : f->area[0] + f->area[2] - 0.5 * fs - bw;
        double cy = c < 2 ? f->area[1] + 0.5 * fs : f->area[1] + f->area[3] - 0.5 * fs - bh;
        size_t count = 0;
        for (i = 0; i < s->nseries; i++)
            for (j = 0; j < s->series[i].n; j++) {
                double px, py;
                if (sph_plot_to_pixel(f, s->series[i].x[j], s->series[i].y[j], &px, &py) &&
                    px >= cx && px <= cx + bw && py >= cy && py <= cy + bh)
                    count++;
            }
        if (count < best)
            best = count, bx = cx, by = cy;
    }
    cairo_set_dash(cr, NULL, 0, 0);
    cairo_rectangle(cr, floor(bx) + 0.5, floor(by) + 0.5, floor(bw), floor(bh));
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.6, 0.6, 0.6);
    cairo_set_line_width(cr, 1);
    cairo_stroke(cr);
    by += 0.3 * fs + 0.5 * row;
    for (i = 0; i < s->nseries; i++) {
        const sph_plot_series *p = &s->series[i];
        if (!p->label || !*p->label)
            continue;
        series_style(cr, i, fmax(1.5, fs / 9));
        if (p->style != SPH_PLOT_MARKERS) {
            cairo_move_to(cr, bx + 0.4 * fs, by);
            cairo_line_to(cr, bx + 0.4 * fs + sample - 0.6 * fs, by);
            cairo_stroke(cr);
        }
        if (p->style != SPH_PLOT_LINE) {
            cairo_arc(cr, bx + 0.1 * fs + 0.5 * sample, by, 0.28 * fs, 0, TWO_PI);
            cairo_fill(cr);
        }
        cairo_set_source_rgb(cr, 0, 0, 0);
        cairo_move_to(cr, bx + sample + 0.4 * fs, by + 0.36 * fs);
        cairo_show_text(cr, p->label);
        by += row;
    }
}

int sph_plot_draw(const sph_plot_spec *s, cairo_t *cr, char *err, size_t errlen) {
    layout_t L;
    cairo_status_t st;
    size_t i;
    if (layout(s, &L, err, errlen))
        return -1;
    cairo_save(cr);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_rectangle(cr, 0, 0, s->width, s->height);
    cairo_fill(cr);
    cairo_save(cr);
    cairo_rectangle(cr, L.f.area[0], L.f.area[1], L.f.area[2], L.f.area[3]);
    cairo_clip(cr);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    for (i = 0; i < s->nseries; i++)
        draw_series(&L.f, &s->series[i], i, cr, L.fs);
    cairo_restore(cr);
    set_font(cr, L.fs);
    draw_axes(s, &L, cr);
    if (s->legend)
        draw_legend(s, &L, cr);
    cairo_restore(cr);
    st = cairo_status(cr);
    if (st != CAIRO_STATUS_SUCCESS)
        return sph_message_set(err, errlen, "drawing failed: %s", cairo_status_to_string(st));
    return 0;
}

int sph_plot_png(const sph_plot_spec *s, const char *file, char *err, size_t errlen) {
    cairo_surface_t *surf;
    cairo_t *cr;
    int rc;
    if (s->width < 64 || s->width > 16384 || s->height < 64 || s->height > 16384)
        return sph_message_set(err, errlen, "plot size %dx%d is outside 64..16384 pixels", s->width,
                    s->height);
    surf = cairo_image_surface_create(CAIRO_FORMAT_RGB24, s->width, s->height);
    cr = cairo_create(surf);
    rc = sph_plot_draw(s, cr, err, errlen);
    cairo_destroy(cr);
    if (rc == 0)
        rc = sph_render_write_png(surf, file, err, errlen);
    cairo_surface_destroy(surf);
    return rc;
}
