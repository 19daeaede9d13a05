/* render.c: particles to pictures. A view maps world to pixels (aspect kept, y up);
   particles are grouped by colour with a counting sort and each group is ONE cairo path
   and ONE fill (STYLE.md, after Cairo's samples: per-particle fills cost a rasterizer pass
   each); plates, label and colour bar are drawn on top. */
#include <dlfcn.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "atomic.h"
#include "message.h"
#include "pictures_cairo.h"

#define MIN_SIZE 8
#define MAX_SIZE 16384
#define BATCH 1024 /* particles per fill, see draw_particles */

/* yield mode: yielded light, unyielded dark blue (the paper's figures), walls grey */
static const double category_rgb[3][3] = {
    {0.10, 0.20, 0.50}, /* SPH_RENDER_UNYIELDED */
    {0.80, 0.88, 0.96}, /* SPH_RENDER_YIELDED */
    {0.60, 0.60, 0.60}, /* SPH_RENDER_WALL */
};
static const double plate_rgb[3] = {0.45, 0.45, 0.45};

void sph_render_defaults(sph_render_spec *s) {
    memset(s, 0, sizeof *s);
    s->width = 800;
    s->height = 400;
    s->autorange = 1;
    s->colorbar = 1;
}

void sph_render_category_color(int category, double rgb[3]) {
    int k;
    for (k = 0; k < 3; k++)
        rgb[k] = category >= 0 && category < 3 ? category_rgb[category][k] : plate_rgb[k];
}

/* Text size follows the image so labels stay readable from 200 to 2000 pixels. */
static double font_px(const sph_render_spec *s) {
    double fs = (s->width < s->height ? s->width : s->height) / 28.0;
    return fs < 9 ? 9 : fs > 18 ? 18 : fs;
}

static int scalar_mode(const sph_render_spec *s) { return !s->category; }

static int has_label(const sph_render_spec *s) { return s->label && *s->label; }

static int has_colorbar(const sph_render_spec *s) { return scalar_mode(s) && s->colorbar; }

static int has_legend(const sph_render_spec *s) { return !scalar_mode(s) && s->legend; }

static const char *const legend_text[2] = {"yielded", "unyielded"};
static const int legend_category[2] = {SPH_RENDER_YIELDED, SPH_RENDER_UNYIELDED};

static void set_font(cairo_t *cr, double fs) {
    cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, fs);
}

/* Widths of the label and of each legend entry's text, in pixels, measured with the font
   they are drawn in (on a scratch surface, so the layout needs no picture). */
static void text_widths(const sph_render_spec *s, double fs, double *label, double entry[2]) {
    cairo_surface_t *scratch = cairo_image_surface_create(CAIRO_FORMAT_A8, 1, 1);
    cairo_t *cr = cairo_create(scratch);
    cairo_text_extents_t te;
    int k;
    set_font(cr, fs);
    *label = 0, entry[0] = entry[1] = 0;
    if (has_label(s)) {
        cairo_text_extents(cr, s->label, &te);
        *label = te.x_advance;
    }
    for (k = 0; k < 2; k++) {
        cairo_text_extents(cr, legend_text[k], &te);
        entry[k] = te.x_advance;
    }
    cairo_destroy(cr);
    cairo_surface_destroy(scratch);
}

/* The legend's geometry: swatch side, gap from swatch to text, space between entries. */
static double swatch_px(double fs) { return floor(0.9 * fs); }

/* Grow box b (x0, y0, x1, y1) to hold [x0, x1] x [y0, y1]. */
static void grow(double b[4], double x0, double y0, double x1, double y1) {
    b[0] = fmin(b[0], x0), b[1] = fmin(b[1], y0);
    b[2] = fmax(b[2], x1), b[3] = fmax(b[3], y1);
}

/* Bounding box of everything drawn, mirror images included, with a 3% margin. */
static void fit_view(const sph_render_spec *s, double v[4]) {
    double b[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY}, r = s->radius, m, w, h;
    size_t i;
    for (i = 0; i < s->n; i++) {
        if (!isfinite(s->x[i]) || !isfinite(s->y[i]))
            continue;
        grow(b, s->x[i] - r, s->y[i] - r, s->x[i] + r, s->y[i] + r);
        if (s->mirror) {
            double xm = 2 * s->mirror_x - s->x[i];
            grow(b, xm - r, s->y[i] - r, xm + r, s->y[i] + r);
        }
    }
    for (i = 0; i < s->nplates; i++) {
        const double *p = s->plates + 4 * i;
        grow(b, p[0], p[1], p[2], p[3]);
        if (s->mirror)
            grow(b, 2 * s->mirror_x - p[2], p[1], 2 * s->mirror_x - p[0], p[3]);
    }
    if (!(b[2] >= b[0]) || !(b[3] >= b[1])) { /* nothing to show */
        b[0] = b[1] = 0, b[2] = b[3] = 1;
    }
    w = b[2] - b[0], h = b[3] - b[1];
    m = 0.03 * fmax(w, h);
    if (m <= 0)
        m = 0.5;
    v[0] = b[0] - m, v[1] = b[1] - m, v[2] = b[2] + m, v[3] = b[3] + m;
}

static void value_range(const sph_render_spec *s, double *lo, double *hi) {
    double a = INFINITY, b = -INFINITY, d;
    size_t i;
    if (s->autorange) {
        for (i = 0; i < s->n; i++)
            if (isfinite(s->value[i]))
                a = fmin(a, s->value[i]), b = fmax(b, s->value[i]);
        if (a > b) /* no finite value at all */
            a = 0, b = 1;
    } else {
        a = s->vmin, b = s->vmax;
    }
    if (a == b) { /* a constant field still needs a range to map onto */
        d = a != 0 ? 0.5 * fabs(a) : 0.5;
        a -= d, b += d;
    }
    *lo = a, *hi = b;
}

int sph_render_layout(const sph_render_spec *s, sph_render_frame *f, char *err, size_t errlen) {
    double fs, top, right, pad = 4, v[4], vw, vh, aw, ah;
    size_t i;
    memset(f, 0, sizeof *f);
    if (s->width < MIN_SIZE || s->width > MAX_SIZE || s->height < MIN_SIZE || s->height > MAX_SIZE)
        return sph_message_set(err, errlen, "image size %dx%d is outside %d..%d pixels", s->width, s->height,
                    MIN_SIZE, MAX_SIZE);
    if (s->n && (!s->x || !s->y))
        return sph_message_set(err, errlen, "particle positions x and y are missing");
    if (!(s->radius > 0) || !isfinite(s->radius))
        return sph_message_set(err, errlen, "radius must be a positive number (got %g)", s->radius);
    if (s->n && !s->category && !s->value)
        return sph_message_set(err, errlen, "need a category or a value per particle");
    if (scalar_mode(s) && !sph_colormap_find(s->colormap))
        return sph_message_set(err, errlen, "unknown colour map '%s'", s->colormap);
    if (scalar_mode(s) && !s->autorange &&
        (!isfinite(s->vmin) || !isfinite(s->vmax) || s->vmin > s->vmax))
        return sph_message_set(err, errlen, "value range [%g, %g] must be finite with vmin <= vmax", s->vmin,
                    s->vmax);
    if (s->nplates && !s->plates)
        return sph_message_set(err, errlen, "plate rectangles are missing");
    for (i = 0; i < 4 * s->nplates; i++)
        if (!isfinite(s->plates[i]))
            return sph_message_set(err, errlen, "plate %zu has a non-finite coordinate", i / 4 + 1);
    if (s->mirror && !isfinite(s->mirror_x))
        return sph_message_set(err, errlen, "mirror line x = %g is not finite", s->mirror_x);
    if (s->category)
        for (i = 0; i < s->n; i++)
            if (s->category[i] > SPH_RENDER_WALL)
                return sph_message_set(err, errlen, "category of particle %zu is %d, not 0, 1 or 2", i + 1,
                            s->category[i]);
    if (s->view_set) {
        for (i = 0; i < 4; i++)
            v[i] = s->view[i];
        if (!(v[2] > v[0]) || !(v[3] > v[1]) || !isfinite(v[2] - v[0]) || !isfinite(v[3] - v[1]))
            return sph_message_set(err, errlen, "view {%g, %g, %g, %g} needs x0 < x1 and y0 < y1", v[0], v[1],
                        v[2], v[3]);
    } else {
        fit_view(s, v);
    }
    fs = font_px(s);
    top = has_label(s) || has_legend(s) ? ceil(1.6 * fs) : 0;
    if (has_legend(s)) {
        /* right-aligned on the label's line; on a second line when the two do not fit */
        double lw, ew[2], sw = swatch_px(fs), line = 0;
        text_widths(s, fs, &lw, ew);
        f->legend[2] = 2 * (sw + 0.4 * fs) + ew[0] + ew[1] + fs;
        if (has_label(s) && pad + lw + 1.5 * fs + f->legend[2] > s->width - pad)
            line = ceil(1.6 * fs), top += line;
        f->legend[0] = floor(fmax(pad, s->width - pad - f->legend[2]));
        f->legend[1] = line + floor(0.39 * fs); /* text on the label's baseline, 1.2 fs */
        f->legend[3] = sw;
    }
    right = has_colorbar(s) ? ceil(7 * fs) : 0;
    aw = s->width - right - 2 * pad, ah = s->height - top - 2 * pad;
    if (aw < 2 || ah < 2)
        return sph_message_set(err, errlen, "image %dx%d is too small for its label and colour bar", s->width,
                    s->height);
    f->area[0] = pad, f->area[1] = top + pad, f->area[2] = aw, f->area[3] = ah;
    /* letterbox: the whole requested view fits, centred; the other direction shows more */
    vw = v[2] - v[0], vh = v[3] - v[1];
    f->scale = fmin(aw / vw, ah / vh);
    f->ox = f->area[0] + 0.5 * (aw - f->scale * vw) - f->scale * v[0];
    f->oy = f->area[1] + ah - 0.5 * (ah - f->scale * vh) + f->scale * v[1];
    f->view[0] = (f->area[0] - f->ox) / f->scale;
    f->view[2] = (f->area[0] + aw - f->ox) / f->scale;
    f->view[3] = (f->oy - f->area[1]) / f->scale;
    f->view[1] = (f->oy - f->area[1] - ah) / f->scale;
    f->radius_px = fmax(0.5, s->radius * f->scale);
    if (scalar_mode(s) && s->value)
        value_range(s, &f->vmin, &f->vmax);
    else if (scalar_mode(s))
        f->vmin = 0, f->vmax = 1;
    return 0;
}

void sph_render_to_pixel(const sph_render_frame *f, double x, double y, double *px, double *py) {
    *px = f->ox + f->scale * x;
    *py = f->oy - f->scale * y;
}

/* Add one disc to the current path unless it lies wholly outside the picture area.
   A disc is four cubic Beziers (kappa = 4(sqrt 2 - 1)/3, radial error 0.03%): cairo_arc
   would spend a sincos and a tan per particle. Below a pixel in radius a square of the same
   area looks the same after anti-aliasing, and cairo fills a path of boxes without scan
   conversion (several times faster at 100 000 particles). */
static void add_disc(cairo_t *cr, const sph_render_frame *f, double x, double y) {
    double px = f->ox + f->scale * x, py = f->oy - f->scale * y, r = f->radius_px, k;
    if (px + r < f->area[0] || px - r > f->area[0] + f->area[2] || py + r < f->area[1] ||
        py - r > f->area[1] + f->area[3])
        return;
    if (r < 1) {
        k = 0.886226925452758 * r; /* half side: (2k)^2 = pi r^2 */
        cairo_rectangle(cr, px - k, py - k, 2 * k, 2 * k);
        return;
    }
    k = 0.552284749830794 * r;
    cairo_move_to(cr, px + r, py);
    cairo_curve_to(cr, px + r, py + k, px + k, py + r, px, py + r);
    cairo_curve_to(cr, px - k, py + r, px - r, py + k, px - r, py);
    cairo_curve_to(cr, px - r, py - k, px - k, py - r, px, py - r);
    cairo_curve_to(cr, px + k, py - r, px + r, py - k, px + r, py);
    cairo_close_path(cr);
}

/* Group of particle i: its category, or its colour-table entry (ntab = bad value). */
static int group_of(const sph_render_spec *s, const sph_render_frame *f, const sph_colormap *m,
                    size_t i) {
    int k;
    if (s->category)
        return s->category[i];
    k = sph_colormap_index(m, (s->value[i] - f->vmin) / (f->vmax - f->vmin));
    return k < 0 ? m->n : k;
}

static int draw_particles(const sph_render_spec *s, const sph_render_frame *f, cairo_t *cr,
                          char *err, size_t errlen) {
    const sph_colormap *m = sph_colormap_find(s->colormap);
    int ngroups = s->category ? 3 : m->n + 1, g;
    size_t *start, *order, i;
    int *group;
    double rgb[3];
    if (!s->n)
        return 0;
    /* counting sort by group: a stable order, O(n), and each group contiguous */
    start = calloc((size_t)ngroups + 1, sizeof *start);
    order = malloc(s->n * sizeof *order);
    group = malloc(s->n * sizeof *group);
    if (!start || !order || !group) {
        free(start), free(order), free(group);
        return sph_message_set(err, errlen, "out of memory rendering %zu particles", s->n);
    }
    for (i = 0; i < s->n; i++) {
        group[i] = group_of(s, f, m, i);
        start[group[i] + 1]++;
    }
    for (g = 0; g < ngroups; g++)
        start[g + 1] += start[g];
    for (i = 0; i < s->n; i++)
        order[start[group[i]]++] = i;
    /* start[g] now holds the end of group g; the beginning is the previous end */
    /* One path and one fill per colour, in batches: cairo's rasterizer costs more than
       linearly in the size of one path (100 000 discs fill four times faster in batches of
       BATCH than in two paths: tests/bench/bench_render.c), so a large group is filled
       every BATCH particles. Same colour, so the picture is the same. */
    for (g = 0; g < ngroups; g++) {
        size_t a = g ? start[g - 1] : 0, b = start[g], k;
        if (a == b)
            continue;
        if (s->category)
            sph_render_category_color(g, rgb);
        else
            sph_colormap_entry(m, g < m->n ? g : -1, rgb);
        cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
        cairo_new_path(cr);
        for (k = a; k < b; k++) {
            size_t j = order[k];
            if (!isfinite(s->x[j]) || !isfinite(s->y[j]))
                continue;
            add_disc(cr, f, s->x[j], s->y[j]);
            if (s->mirror)
                add_disc(cr, f, 2 * s->mirror_x - s->x[j], s->y[j]);
            if ((k - a) % BATCH == BATCH - 1)
                cairo_fill(cr);
        }
        cairo_fill(cr);
    }
    free(start), free(order), free(group);
    return 0;
}

static void plate_rect(cairo_t *cr, const sph_render_frame *f, double x0, double y0, double x1,
                       double y1) {
    double ax, ay, bx, by;
    sph_render_to_pixel(f, fmin(x0, x1), fmax(y0, y1), &ax, &ay);
    sph_render_to_pixel(f, fmax(x0, x1), fmin(y0, y1), &bx, &by);
    /* keep coordinates in cairo's fixed-point range when a plate reaches far outside */
    ax = fmax(ax, -1e5), ay = fmax(ay, -1e5), bx = fmin(bx, 1e5), by = fmin(by, 1e5);
    if (bx > ax && by > ay)
        cairo_rectangle(cr, ax, ay, bx - ax, by - ay);
}

static void draw_plates(const sph_render_spec *s, const sph_render_frame *f, cairo_t *cr) {
    size_t i;
    if (!s->nplates)
        return;
    cairo_new_path(cr);
    for (i = 0; i < s->nplates; i++) {
        const double *p = s->plates + 4 * i;
        plate_rect(cr, f, p[0], p[1], p[2], p[3]);
        if (s->mirror)
            plate_rect(cr, f, 2 * s->mirror_x - p[0], p[1], 2 * s->mirror_x - p[2], p[3]);
    }
    cairo_set_source_rgb(cr, plate_rgb[0], plate_rgb[1], plate_rgb[2]);
    cairo_fill(cr);
}

static void draw_colorbar(const sph_render_spec *s, const sph_render_frame *f, cairo_t *cr,
                          double fs) {
    const sph_colormap *m = sph_colormap_find(s->colormap);
    double x = f->area[0] + f->area[2] + 0.8 * fs, w = fs;
    double y0 = f->area[1] + 1.8 * fs, y1 = f->area[1] + f->area[3] - 0.6 * fs;
    double ticks[16], rgb[3];
    cairo_pattern_t *pat;
    char buf[32];
    int i, nt;
    if (y1 - y0 < 2 * fs)
        return;
    /* one gradient through every table entry: exactly the colours the particles use */
    pat = cairo_pattern_create_linear(0, y1, 0, y0);
    for (i = 0; i < m->n; i++) {
        sph_colormap_entry(m, i, rgb);
        cairo_pattern_add_color_stop_rgb(pat, (double)i / (m->n - 1), rgb[0], rgb[1], rgb[2]);
    }
    cairo_rectangle(cr, x, y0, w, y1 - y0);
    cairo_set_source(cr, pat);
    cairo_fill_preserve(cr);
    cairo_pattern_destroy(pat);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1);
    cairo_stroke(cr);
    nt = sph_plot_ticks(f->vmin, f->vmax, 6, ticks, 16);
    for (i = 0; i < nt; i++) {
        double ty = y1 - (ticks[i] - f->vmin) / (f->vmax - f->vmin) * (y1 - y0);
        cairo_text_extents_t te;
        cairo_move_to(cr, x + w, ty);
        cairo_line_to(cr, x + w + 0.3 * fs, ty);
        cairo_stroke(cr);
        snprintf(buf, sizeof buf, "%.4g", ticks[i]);
        cairo_text_extents(cr, buf, &te);
        cairo_move_to(cr, x + w + 0.45 * fs, ty - te.y_bearing - 0.5 * te.height);
        cairo_show_text(cr, buf);
    }
    if (s->field && *s->field) {
        cairo_text_extents_t te;
        cairo_text_extents(cr, s->field, &te);
        cairo_move_to(cr, fmax(x + 0.5 * w - 0.5 * te.x_advance, x - 0.6 * fs), y0 - 0.6 * fs);
        cairo_show_text(cr, s->field);
    }
}

/* Two swatches of the yield colours, outlined, each followed by its name. */
static void draw_legend(const sph_render_frame *f, cairo_t *cr, double fs) {
    double x = f->legend[0], y = f->legend[1], sw = f->legend[3], rgb[3];
    int k;
    cairo_set_line_width(cr, 1);
    for (k = 0; k < 2; k++) {
        cairo_text_extents_t te;
        sph_render_category_color(legend_category[k], rgb);
        cairo_rectangle(cr, x, y, sw, sw);
        cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
        cairo_fill(cr);
        cairo_rectangle(cr, x - 0.5, y - 0.5, sw + 1, sw + 1); /* just outside: the swatch stays pure */
        cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
        cairo_stroke(cr);
        cairo_set_source_rgb(cr, 0, 0, 0);
        cairo_move_to(cr, x + sw + 0.4 * fs, y + 0.5 * sw + 0.36 * fs);
        cairo_show_text(cr, legend_text[k]);
        cairo_text_extents(cr, legend_text[k], &te);
        x += sw + 0.4 * fs + te.x_advance + fs;
    }
}

int sph_render_draw(const sph_render_spec *s, cairo_t *cr, char *err, size_t errlen) {
    sph_render_frame f;
    double fs = font_px(s);
    cairo_status_t st;
    if (sph_render_layout(s, &f, err, errlen))
        return -1;
    cairo_save(cr);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_rectangle(cr, 0, 0, s->width, s->height);
    cairo_fill(cr);
    /* particles and plates stay inside the picture area, off the label and colour bar */
    cairo_save(cr);
    cairo_rectangle(cr, f.area[0], f.area[1], f.area[2], f.area[3]);
    cairo_clip(cr);
    cairo_set_fill_rule(cr, CAIRO_FILL_RULE_WINDING); /* overlapping discs: union */
    if (draw_particles(s, &f, cr, err, errlen)) {
        cairo_restore(cr), cairo_restore(cr);
        return -1;
    }
    draw_plates(s, &f, cr);
    cairo_restore(cr);
    set_font(cr, fs);
    cairo_set_source_rgb(cr, 0, 0, 0);
    if (has_label(s)) {
        cairo_move_to(cr, f.area[0], 1.2 * fs);
        cairo_show_text(cr, s->label);
    }
    if (has_legend(s))
        draw_legend(&f, cr, fs);
    if (has_colorbar(s))
        draw_colorbar(s, &f, cr, fs);
    cairo_restore(cr);
    st = cairo_status(cr);
    if (st != CAIRO_STATUS_SUCCESS)
        return sph_message_set(err, errlen, "drawing failed: %s", cairo_status_to_string(st));
    return 0;
}

static cairo_status_t write_chunk(void *closure, const unsigned char *data, unsigned int length) {
    return fwrite(data, 1, length, (FILE *)closure) == length ? CAIRO_STATUS_SUCCESS
                                                              : CAIRO_STATUS_WRITE_ERROR;
}

/* Our own file so a failure says why (cairo's write_to_png only says "error while
   writing to output stream"). Written to a temporary file renamed into place (atomic.h):
   a failed write leaves an earlier picture at that path as it was. */
int sph_render_write_png(cairo_surface_t *surface, const char *file, char *err, size_t errlen) {
    sph_atomic_file af;
    cairo_status_t st;
    int e;
    if (sph_atomic_open(&af, file, err, errlen))
        return -1;
    errno = 0;
    st = cairo_surface_write_to_png_stream(surface, write_chunk, af.fp);
    e = errno;
    if (st != CAIRO_STATUS_SUCCESS) {
        sph_atomic_abort(&af);
        if (st == CAIRO_STATUS_WRITE_ERROR && e)
            return sph_message_set(err, errlen, "cannot write '%s': %s", file, strerror(e));
        return sph_message_set(err, errlen, "cannot write '%s': %s", file, cairo_status_to_string(st));
    }
    return sph_atomic_commit(&af, err, errlen);
}

int sph_render_png(const sph_render_spec *s, const char *file, char *err, size_t errlen) {
    cairo_surface_t *surf;
    cairo_t *cr;
    int rc;
    if (s->width < MIN_SIZE || s->width > MAX_SIZE || s->height < MIN_SIZE ||
        s->height > MAX_SIZE) { /* say why before allocating a surface of that size */
        sph_render_frame f;
        return sph_render_layout(s, &f, err, errlen);
    }
    /* RGB24: the background is opaque, and a PNG without alpha is smaller and faster */
    surf = cairo_image_surface_create(CAIRO_FORMAT_RGB24, s->width, s->height);
    cr = cairo_create(surf);
    rc = sph_render_draw(s, cr, err, errlen);
    cairo_destroy(cr);
    if (rc == 0)
        rc = sph_render_write_png(surf, file, err, errlen);
    cairo_surface_destroy(surf);
    return rc;
}

/* cairo keeps font caches for the life of the process and fontconfig its parsed
   configuration; LeakSanitizer reports both at exit. cairo_debug_reset_static_data frees
   cairo's; FcFini frees fontconfig's, looked up at run time so that sph links with cairo
   alone. RTLD_NOLOAD: only if cairo already loaded fontconfig. */
void sph_render_release_fonts(void) {
    void (*fini)(void);
    void *lib, *sym;
    cairo_debug_reset_static_data();
#ifdef RTLD_NOLOAD
    lib = dlopen("libfontconfig.so.1", RTLD_LAZY | RTLD_NOLOAD);
    if (!lib)
        return;
    sym = dlsym(lib, "FcFini");
    if (sym) {
        memcpy(&fini, &sym, sizeof fini); /* POSIX: a dlsym result may be a function */
        fini();
    }
    dlclose(lib);
#else
    (void)fini, (void)lib, (void)sym;
#endif
}
