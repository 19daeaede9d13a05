/* Adaptive time step (PHYSICS.md):
 *   dt = min(C_u h / max|u|, C_eta rho h^2 / max eta (explicit viscosity only),
 *            C_f sqrt(h / max|a|), C_s h^2 / max nu on a traction-free surface (time accuracy), dt_max),
 * and at most 25 % more than the last step; then the density-error control below.
 * Plate speeds and accelerations count, so a plate driven into a fluid at rest sets the
 * first step. */
#include "internal.h"

#include <math.h>
#include <stdio.h>

/* C_f and C_eta: the force and explicit-viscosity limits of Morris, Fox & Zhu (1997). */
#define C_FORCE 0.25
#define C_VISC 0.125
/* dt grows at most 25 % a step: the density error a longer step makes shows steps late. */
#define DT_GROWTH 1.25

double sph_timestep_compute(sph_world *w) {
    const sph_params *P = &w->par;
    double h = w->h, umax = 0.0, amax = 0.0, etamax = 0.0, rhomin = INFINITY, nus = 0.0;
    int n = w->n;
#pragma omp parallel for schedule(static) num_threads(w->threads) \
    reduction(max : umax, amax, etamax, nus) reduction(min : rhomin)
    for (int i = 0; i < n; i++) {
        if (w->kind[i] != SPH_FLUID) continue;
        double s = w->u[i] * w->u[i] + w->v[i] * w->v[i];
        double a = w->ax[i] * w->ax[i] + w->ay[i] * w->ay[i];
        if (s > umax) umax = s;
        if (a > amax) amax = a;
        if (w->visc[i] > etamax) etamax = w->visc[i];
        if (w->rho[i] < rhomin) rhomin = w->rho[i];
        if (w->surf[i] && sph_surface_traction(w)) {
            double nu = w->mats[w->mat[i]].mu / w->rho[i];
            if (nu > nus) nus = nu;
        }
    }
    umax = sqrt(umax);
    amax = sqrt(amax);
    for (int k = 0; k < w->nplates; k++) {
        const sph_plate *pl = &w->plates[k];
        double vs = fabs(pl->vel) + hypot(pl->slide[0], pl->slide[1]);
        if (vs > umax) umax = vs;
        if (pl->mode == SPH_PLATE_LOAD && pl->mass > 0) {
            double a = fabs(pl->load + pl->force) / pl->mass;
            if (a > amax) amax = a;
        }
    }
    double g = hypot(P->gravity[0], P->gravity[1]);
    if (g > amax) amax = g;
    double dt = INFINITY;
    if (umax > 0) dt = fmin(dt, P->cfl * h / umax);
    if (amax > 0) dt = fmin(dt, C_FORCE * sqrt(h / amax));
    if (P->viscosity == SPH_VISC_EXPLICIT && etamax > 0 && isfinite(rhomin))
        dt = fmin(dt, C_VISC * rhomin * h * h / etamax);
    /* time accuracy: the split step's error grows with mu dt / (rho h^2), largest along a
     * free surface (SPH_SURFACE_CS, internal.h) */
    if (nus > 0) dt = fmin(dt, SPH_SURFACE_CS * h * h / nus);
    if (P->dt_max > 0) dt = fmin(dt, P->dt_max);
    /* The density error each step leaves (mostly near a free surface, where the
     * projection is least exact) grows with dt, about in proportion. So dt also follows
     * the density error: while it exceeds density_tol, dt shrinks in proportion, down to a
     * twentieth of the other limits (an error that does not come from dt must not stall
     * the run). With implicit viscosity the first step, which may start a plate
     * impulsively, is that twentieth; the explicit scheme's first step is already short. */
    double floor = 0.05 * dt;
    if (w->dt_prev <= 0) {
        if (P->viscosity == SPH_VISC_IMPLICIT) dt = floor;
    } else if (P->density_tol > 0 && w->st.max_density_error > P->density_tol) {
        dt = fmin(dt, fmax(floor, w->dt_prev * fmax(0.8, P->density_tol / w->st.max_density_error)));
    }
    if (w->dt_prev > 0) dt = fmin(dt, DT_GROWTH * w->dt_prev);
    if (!isfinite(dt)) dt = P->cfl * h; /* nothing moves: a step as if |u| = 1 */
    return dt;
}

void sph_timestep_explain(const sph_world *w, char *buf, size_t len) {
    int iu = -1, ia = -1, ir = -1;
    double umax = -1.0, amax = -1.0, emax = -1.0, rho0 = w->par.rho0;
    for (int i = 0; i < w->n; i++) {
        if (w->kind[i] != SPH_FLUID) continue;
        double s = hypot(w->u[i], w->v[i]), a = hypot(w->ax[i], w->ay[i]), e = fabs(w->rho[i] / rho0 - 1.0);
        if (!(s <= umax)) umax = s, iu = i; /* NaN wins: it is the particle to name */
        if (!(a <= amax)) amax = a, ia = i;
        if (!(e <= emax)) emax = e, ir = i;
    }
    if (iu < 0) {
        snprintf(buf, len, "no fluid particle");
        return;
    }
    int k = snprintf(buf, len,
                     "fastest fluid particle %d at (%.6g, %.6g), speed %.3g; largest acceleration %.3g "
                     "(particle %d at (%.6g, %.6g)); largest density error %.3g %% (particle %d at "
                     "(%.6g, %.6g)%s)",
                     w->id[iu], w->x[iu], w->y[iu], umax, amax, w->id[ia], w->x[ia], w->y[ia], 100.0 * emax,
                     w->id[ir], w->x[ir], w->y[ir], w->surf[ir] ? ", free surface" : "");
    double g = hypot(w->par.gravity[0], w->par.gravity[1]);
    if (g > amax && k > 0 && (size_t)k < len) snprintf(buf + k, len - (size_t)k, "; gravity %.3g", g);
}
