/* sph_pictures.h: the pictures layer of sph — particle renderer, colour maps, line plots
   and animated PNG. Plain data in, status out: nothing here knows the engine's world or Lua,
   so the binding (and any C host) fills these structs from whatever it holds.

   Errors: every function that can fail returns 0 on success and -1 on failure, writing a
   message (no trailing newline) into the caller's buffer `err` of `errlen` bytes; `err` may
   be NULL. Nothing aborts, exits or prints.

   Coordinates: "world" means the simulation's units (whatever the script uses), y up;
   "pixel" means image pixels, origin at the top-left corner, y down.

   This header needs only the C library: no cairo type appears in it (linking needs
   cairo: -lcairo, or `pkg-config --libs cairo`). The functions that draw into a caller's
   cairo context are in pictures_cairo.h, internal to the engine and its tests. */
#ifndef SPH_PICTURES_H
#define SPH_PICTURES_H

#include <stddef.h>

/* ---------------------------------------------------------------- colour maps (colormap.c) */

/* A colour map is a table of sRGB colours (components in [0, 1]) ordered from low to high. */
typedef struct sph_colormap {
    const char *name;
    int n;                 /* number of entries, >= 2 */
    const float (*rgb)[3]; /* n entries */
} sph_colormap;

/* The map called `name` ("viridis"); NULL or "" gives the default (viridis); an unknown
   name gives NULL. */
const sph_colormap *sph_colormap_find(const char *name);
/* Colour at t in [0, 1] (clamped), interpolated linearly between entries. Non-finite t
   gives the "bad value" grey. */
void sph_colormap_eval(const sph_colormap *m, double t, double rgb[3]);
/* Index of the entry nearest to t in [0, 1] (clamped): 0 .. m->n - 1; -1 for non-finite t.
   The renderer groups particles by this index. */
int sph_colormap_index(const sph_colormap *m, double t);
/* Entry i (clamped to 0 .. n-1); i < 0 gives the "bad value" grey. */
void sph_colormap_entry(const sph_colormap *m, int i, double rgb[3]);

/* ------------------------------------------------------------- particle renderer (render.c) */

/* Categories for yield mode (as in the paper's figures: yielded light, unyielded dark). */
enum { SPH_RENDER_UNYIELDED = 0, SPH_RENDER_YIELDED = 1, SPH_RENDER_WALL = 2 };

typedef struct sph_render_spec {
    size_t n;            /* particles */
    const double *x, *y; /* n positions, world units; non-finite ones are skipped */
    double radius;       /* disc radius, world units, > 0 (drawn >= 0.5 px) */
    /* colour: yield mode if `category` is set, else scalar mode with `value` */
    const unsigned char *category; /* n of SPH_RENDER_UNYIELDED / _YIELDED / _WALL */
    const double *value;           /* n values; non-finite ones are drawn grey */
    const char *colormap;          /* NULL: viridis */
    int autorange;                 /* 1: [vmin, vmax] = range of the finite values */
    double vmin, vmax;             /* fixed range when autorange == 0; equal ends widen */
    int colorbar;                  /* scalar mode: draw a colour bar at the right */
    int legend;                    /* yield mode: a legend of the two colours, "yielded" and
                                      "unyielded", at the right of the band above the picture
                                      (the label's line, or a line of its own under it when
                                      both do not fit) */
    const char *field;             /* colour bar title (e.g. "p"); NULL: none */
    const double *plates;          /* nplates rectangles, 4 doubles each: x0, y0, x1, y1 */
    size_t nplates;                /* drawn filled grey over the particles */
    const char *label;             /* text above the picture (e.g. "t = 0.500"), drawn as
                                      given; NULL: none */
    int mirror;                    /* 1: also draw everything reflected about x = mirror_x */
    double mirror_x;               /* (half-domain runs with a symmetry plane) */
    int view_set;                  /* 1: show view; 0: fit particles, plates and mirror */
    double view[4];                /* x0, y0, x1, y1, world units; aspect ratio is kept */
    int width, height;             /* image size, pixels, 8 .. 16384 */
} sph_render_spec;

/* What the renderer resolved from a spec: where the world lands in the image. */
typedef struct sph_render_frame {
    double area[4];    /* picture area in pixels: x, y, w, h (excludes label and colour bar) */
    double view[4];    /* world rectangle that fills `area` (>= the requested view) */
    double scale;      /* pixels per world unit, the same along x and y */
    double ox, oy;     /* pixel = (ox + scale * x, oy - scale * y) */
    double radius_px;  /* disc radius as drawn */
    double vmin, vmax; /* resolved scalar range (scalar mode) */
    double legend[4];  /* the yield legend in pixels: x, y, w, h (all 0 without one) */
} sph_render_frame;

/* Defaults: 800 x 400, autorange, colour bar on (scalar mode), everything else off/NULL
   (no legend). */
void sph_render_defaults(sph_render_spec *s);
/* Fill colour of a category (grey for unknown ones). */
void sph_render_category_color(int category, double rgb[3]);
/* Check the spec and resolve view, scale and range without drawing. */
int sph_render_layout(const sph_render_spec *s, sph_render_frame *f, char *err, size_t errlen);
/* World point to pixel through a resolved frame. */
void sph_render_to_pixel(const sph_render_frame *f, double x, double y, double *px, double *py);
/* Draw to a new RGB image of width x height and write it as PNG to `file`. */
int sph_render_png(const sph_render_spec *s, const char *file, char *err, size_t errlen);
/* At exit, after the last drawing (no cairo object alive): free the font caches cairo and
   fontconfig keep for the whole process, so leak checkers (make check) stay quiet. */
void sph_render_release_fonts(void);

/* --------------------------------------------------------------------- line plots (plot.c) */

enum { SPH_PLOT_LINE = 0, SPH_PLOT_MARKERS = 1, SPH_PLOT_LINE_MARKERS = 2 };

typedef struct sph_plot_series {
    const double *x, *y; /* n points; non-finite ones (and <= 0 on a log axis) break the line */
    size_t n;
    const char *label; /* legend text; NULL: not in the legend */
    int style;         /* SPH_PLOT_LINE, _MARKERS or _LINE_MARKERS */
} sph_plot_series;

typedef struct sph_plot_spec {
    const sph_plot_series *series; /* drawn in order; colour and dash follow the index */
    size_t nseries;
    const char *title, *xlabel, *ylabel; /* NULL: none */
    int xlog, ylog;                      /* 1: logarithmic axis (decades, minor ticks) */
    int xrange_set, yrange_set;          /* 1: use [xmin, xmax] / [ymin, ymax] as given */
    double xmin, xmax, ymin, ymax;
    int legend;        /* 1: legend of labelled series, in the emptiest corner */
    int width, height; /* image size, pixels, 64 .. 16384 */
} sph_plot_spec;

typedef struct sph_plot_frame {
    double area[4];                /* plot area in pixels: x, y, w, h */
    double xmin, xmax, ymin, ymax; /* resolved axis ranges (data units) */
    int xlog, ylog;
} sph_plot_frame;

/* Defaults: 640 x 480, linear axes, automatic ranges, legend on. */
void sph_plot_defaults(sph_plot_spec *s);
/* Check the spec and resolve ranges and the plot area (text measured with the same font). */
int sph_plot_layout(const sph_plot_spec *s, sph_plot_frame *f, char *err, size_t errlen);
/* Data point to pixel; returns 0 when the point has no place (non-finite, <= 0 on log). */
int sph_plot_to_pixel(const sph_plot_frame *f, double x, double y, double *px, double *py);
/* "Nice" linear ticks (1, 2, 5 x 10^k) inside [lo, hi], at most about `most` of them;
   writes up to `cap` values and returns how many. */
int sph_plot_ticks(double lo, double hi, int most, double *ticks, int cap);
/* Draw to a new image and write it as PNG to `file`. */
int sph_plot_png(const sph_plot_spec *s, const char *file, char *err, size_t errlen);

/* ------------------------------------------------------------ animated PNG (animate.c) */

/* 1/fps seconds as a fraction num/den with both <= 65535 (APNG's fcTL fields). */
int sph_animate_delay(double fps, unsigned *num, unsigned *den, char *err, size_t errlen);
/* Write the PNG files `frames` (all with the same IHDR: size, depth, colour type) as one
   APNG `file` shown at `fps` frames per second, repeated `loops` times (0: forever).
   Viewers without APNG support show the first frame. */
int sph_animate_png(const char *const *frames, size_t nframes, double fps, int loops,
                    const char *file, char *err, size_t errlen);

#endif
