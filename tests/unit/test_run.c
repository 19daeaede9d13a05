/* sph_world_run_until (run.c): it lands on t_end exactly, adaptively and with a fixed dt
 * that does not divide the interval, spreads the interval left evenly over the last steps
 * (no sliver of a step at the end), calls its hook before every step and stops when the
 * hook says so, takes no step when the time is already there, and fails with the
 * world's message. Public API only (sph.h). */
#include "sph.h"
#include "unit.h"

#include <string.h>

/* A Newtonian block on a fixed plate under gravity: it moves, so the adaptive dt changes. */
static sph_world *block(void) {
    sph_params p;
    sph_params_default(&p);
    p.dx = 0.1;
    p.gravity[1] = -1.0;
    p.threads = 1;
    char err[256];
    sph_world *w = sph_world_new(&p, err, sizeof err);
    sph_material water = {SPH_NEWTONIAN, 1, 0, 0, 0, 0};
    sph_world_fill(w, (double[4]){0, 0, 1, 1}, &water);
    sph_world_plate(w, (double[4]){-0.5, -0.4, 1.5, 0}, -1);
    return w;
}

/* The hook: counts the calls, records the time and the adaptive dt at each, stops at call
 * `stop` (0: never). */
#define LOG 4096
typedef struct {
    int calls, stop;
    double t[LOG], a[LOG];
} hook_log;

static int hook(sph_world *w, void *ctx) {
    hook_log *h = ctx;
    if (h->calls < LOG) {
        h->t[h->calls] = sph_world_time(w);
        h->a[h->calls] = sph_world_next_dt(w);
    }
    h->calls++;
    return h->stop > 0 && h->calls >= h->stop;
}

int main(void) {
    sph_world *w = block();
    hook_log h;
    memset(&h, 0, sizeof h);

    /* adaptive steps to three end times in turn: each reached exactly */
    const double ends[3] = {0.01, 0.025, 0.04};
    int ok = 1, last[3] = {0};
    for (int k = 0; k < 3 && ok; k++) {
        int rc = sph_world_run_until(w, ends[k], 0, hook, &h);
        ok = rc == 0 && sph_world_time(w) == ends[k];
        last[k] = h.calls - 1; /* the hook call before the run's last step */
        CHECK(ok, "run_until lands on the end time exactly", "rc %d, t = %.17g against %.17g (%s)", rc,
              sph_world_time(w), ends[k], sph_world_error(w));
    }
    long steps = sph_world_steps(w);
    CHECK(steps > 6 && h.calls == steps && steps < LOG, "the hook runs once before every step", "%d calls, %ld steps",
          h.calls, steps);
    /* step i goes from t[i] to t[i + 1] (the last one to the end time) */
    double s[LOG];
    int mono = h.t[0] == 0.0, within = 1;
    for (int i = 0; i < h.calls && i < LOG; i++) {
        s[i] = (i + 1 < h.calls ? h.t[i + 1] : sph_world_time(w)) - h.t[i];
        mono = mono && s[i] > 0;
        within = within && s[i] <= h.a[i] * (1 + 1e-12);
    }
    CHECK(mono, "the hook sees the clock before each step, from t = 0 on", "t[0] = %g", h.t[0]);
    CHECK(within, "no step is longer than the adaptive dt the engine gives before it", " ");
    /* no sliver at the end: the interval left is spread evenly over the steps it needs, so
     * a run's last step is about the one before it (cut short, it would be any fraction of
     * it); a half allows for the adaptive dt's own changes from step to step (measured:
     * 1.0000 at worst, the last steps equal) */
    double worst = 1e300;
    for (int k = 0; k < 3; k++)
        if (last[k] > 0 && s[last[k]] / s[last[k] - 1] < worst) worst = s[last[k]] / s[last[k] - 1];
    printf("# last step over the one before it, worst of the three runs: %.4f\n", worst);
    CHECK(worst >= 0.5, "each run's last step is at least half the step before it", "ratio %g", worst);

    /* already there: no step, no hook call, status 0 */
    int calls = h.calls;
    CHECK(sph_world_run_until(w, 0.04, 0, hook, &h) == 0 && sph_world_steps(w) == steps && h.calls == calls,
          "run_until to the current time takes no step", "%ld steps", sph_world_steps(w) - steps);
    CHECK(sph_world_run_until(w, 0.03, 0, NULL, NULL) == 0 && sph_world_time(w) == 0.04,
          "run_until to a time already past takes no step and leaves the clock", "t = %g", sph_world_time(w));

    /* a fixed dt that does not divide the interval: 0.01 in steps of at most 0.003 is 4
     * steps of 0.0025, the last landing on 0.05 exactly */
    steps = sph_world_steps(w);
    int rc = sph_world_run_until(w, 0.05, 0.003, NULL, NULL);
    CHECK(rc == 0 && sph_world_time(w) == 0.05 && sph_world_steps(w) == steps + 4,
          "a fixed dt of 0.003 over 0.01: 4 steps, landing on the end time exactly", "rc %d, t = %.17g, %ld steps",
          rc, sph_world_time(w), sph_world_steps(w) - steps);
    CHECK_CLOSE(sph_world_dt(w), 0.0025, 1e-15, "the fixed dt spread evenly: each step 0.0025");

    /* the hook stops the run before a step */
    memset(&h, 0, sizeof h);
    h.stop = 3;
    steps = sph_world_steps(w);
    rc = sph_world_run_until(w, 1.0, 0, hook, &h);
    CHECK(rc == 1 && h.calls == 3 && sph_world_steps(w) == steps + 2,
          "a hook returning nonzero stops the run before that step (status 1)", "rc %d, %d calls, %ld steps", rc,
          h.calls, sph_world_steps(w) - steps);

    /* the error path: the world's message */
    rc = sph_world_run_until(w, 0.0 / 0.0, 0, NULL, NULL);
    CHECK(rc == -1 && strstr(sph_world_error(w), "end time must be finite"), "a NaN end time fails with a message",
          "rc %d: %s", rc, sph_world_error(w));
    double t = sph_world_time(w);
    /* steps of 5e4 (the interval 1e5 spread over two) beyond the bound on a given dt, 10^6
     * viscous times rho h^2 / max eta = 1e4 here */
    rc = sph_world_run_until(w, t + 1e5, 5e4, NULL, NULL);
    CHECK(rc == -1 && strstr(sph_world_error(w), "exceeds the bound") && sph_world_time(w) == t,
          "a step the engine refuses fails the run with the step's message, the clock unchanged", "rc %d: %s", rc,
          sph_world_error(w));
    sph_world_free(w);

    sph_params p;
    sph_params_default(&p);
    p.dx = 0.1;
    char err[256];
    w = sph_world_new(&p, err, sizeof err);
    rc = sph_world_run_until(w, 1.0, 0, NULL, NULL);
    CHECK(rc == -1 && strstr(sph_world_error(w), "no fluid"), "a world without fluid fails with the engine's message",
          "rc %d: %s", rc, sph_world_error(w));
    sph_world_free(w);
    UNIT_END();
}
