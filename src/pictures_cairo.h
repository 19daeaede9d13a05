/* pictures_cairo.h: the part of the pictures layer that takes cairo objects (drawing into a
   caller's context, writing a caller's surface). Internal: used by render.c, plot.c, the
   unit tests and the renderer benchmark; not installed. The public sph_pictures.h keeps to
   plain data in, PNG out, so that it (and sph.h) compile without cairo's headers. Errors as
   in sph_pictures.h: 0 on success, -1 with a message in `err`. */
#ifndef SPH_PICTURES_CAIRO_H
#define SPH_PICTURES_CAIRO_H

#include <cairo.h>
#include <stddef.h>

#include "sph_pictures.h"

/* Draw into the rectangle (0, 0, width, height) of the caller's context: background,
   particles (one path and one fill per colour), plates, label, colour bar. */
int sph_render_draw(const sph_render_spec *s, cairo_t *cr, char *err, size_t errlen);
/* Write any cairo surface as PNG, with a message naming the file when it fails. */
int sph_render_write_png(cairo_surface_t *surface, const char *file, char *err, size_t errlen);
/* Draw a plot into the rectangle (0, 0, width, height) of the caller's context. */
int sph_plot_draw(const sph_plot_spec *s, cairo_t *cr, char *err, size_t errlen);

#endif
