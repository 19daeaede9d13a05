/* Running to a time (sph_world_run_until, sph.h): the steps up to t_end, landing on it. */
#include "internal.h"

#include <math.h>

/* The interval left is spread evenly over the steps it needs, rather than the last step
 * cut short: the pressure source div u* / dt (pressure.c) carries the divergence the
 * approximate projection left in u^n, so a step much shorter than the one before shows as
 * a jump in the plate force. Beyond this many steps to go the steps are taken as the
 * limits give them: the spread would change them by less than the round-off. */
#define SPREAD_MAX_STEPS 1e6

int sph_world_run_until(sph_world *w, double t_end, double dt, sph_step_hook before_step, void *ctx) {
    if (!isfinite(t_end)) return sph_world_fail(w, "run until t = %g: the end time must be finite", t_end);
    if (!isfinite(dt))
        return sph_world_fail(w, "run until t = %g: dt must be a finite number (<= 0: adaptive), got %g", t_end, dt);
    /* the clock's round-off: a time this close below t_end is at it */
    double eps = 1e-9 * (t_end > 0 ? t_end : 1.0);
    while (w->t < t_end - eps) {
        /* nothing of w is read after a hook that stops: it may have freed the world (a Lua
         * plate law that closed it) */
        if (before_step && before_step(w, ctx)) return 1;
        double r = t_end - w->t, step = dt > 0 ? dt : sph_world_next_dt(w);
        int last = step >= r - eps;
        if (last) step = r;
        else if (r < SPREAD_MAX_STEPS * step) step = r / ceil(r / step);
        if (sph_world_step_given(w, step, dt > 0) < 0) return -1;
        if (last) w->t = t_end; /* t + (t_end - t) may miss t_end by an ulp */
    }
    return 0;
}
