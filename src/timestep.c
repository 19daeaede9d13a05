/* Adaptive time step (PHYSICS.md):
 *   dt = min(C_u h / max|u|, C_eta rho h^2 / max eta (explicit viscosity only),
 *            C_f sqrt(h / max|a|), C_s h^2 / max nu on a traction-free surface (time accuracy), dt_max),
 * and at most 25 % more than the last step (5 % near the density tolerance); then the
 * density-error control below.
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
/* Where the density error is within a factor 2 of its tolerance, the step is the density
 * control's and changes every step; there it grows by at most 5 % a step (it still shrinks
 * by up to 20 %). The projection's leftover divergence carries about half a squeezed
 * film's pressure to the next step, made over dt_prev and removed over dt, so the plate
 * force goes partly as dt_prev / dt: a step 25 % longer takes it down 10 % at once
 * (docs/limitations.md, "The plate force moves with the step's ratio to the last"). The
 * limit damps that; taking the leftover at its own rate is the fix still to land. */
#define DT_NEAR_TOL 1.05
/* The strain by which the plastic stress may lag the rate (below). */
#define LAG_STRAIN 0.1

/* The secant viscosity that PLUG_SHARE of the viscoplastic particles reach or exceed (the
 * upper edge of its bin in a histogram of ln eta between the smallest and the largest): a
 * plug's, where the sample has one. Not the largest: one particle's rate dipping to 0 for
 * a step puts its secant at the law's eta(0), thousands of times the flow's, and the step
 * would follow it down and back (in a film at Bn = 100, 15-fold from one step to the next,
 * the plate force jumping by 20-40 % with it). */
#define PLUG_SHARE 0.05
#define PLUG_BINS 128
static double plug_secant(const sph_world *w, double lo, double hi, int nvp) {
    if (!(lo > 0) || !(hi > lo * (1.0 + 1e-12))) return hi;
    int count[PLUG_BINS] = {0};
    double scale = PLUG_BINS / log(hi / lo);
    for (int i = 0; i < w->n; i++) {
        if (w->kind[i] != SPH_FLUID || w->mats[w->mat[i]].model == SPH_NEWTONIAN) continue;
        double b = log(w->eta[i] / lo) * scale; /* a NaN falls in the first bin */
        count[b >= PLUG_BINS - 1 ? PLUG_BINS - 1 : b > 0 ? (int)b : 0]++;
    }
    int need = (int)ceil(PLUG_SHARE * nvp), k = PLUG_BINS - 1, c = count[k];
    while (c < need && k > 0) c += count[--k];
    return lo * exp((k + 1) / scale);
}

double sph_timestep_compute(sph_world *w) {
    const sph_params *P = &w->par;
    double h = w->h, umax = 0.0, amax = 0.0, etamax = 0.0, rhomin = INFINITY, nus = 0.0;
    double secmax = 0.0, secmin = INFINITY, gd2 = 0.0, nuall = 0.0;
    int n = w->n, nvp = 0;
#pragma omp parallel for schedule(static) num_threads(w->threads) \
    reduction(max : umax, amax, etamax, nus, nuall, secmax) reduction(min : rhomin, secmin) reduction(+ : gd2, nvp)
    for (int i = 0; i < n; i++) {
        if (w->kind[i] != SPH_FLUID) continue;
        if (w->mats[w->mat[i]].model != SPH_NEWTONIAN) {
            if (w->eta[i] > secmax) secmax = w->eta[i];
            if (w->eta[i] < secmin) secmin = w->eta[i];
            gd2 += w->gd[i] * w->gd[i];
            nvp++;
        }
        double s = w->u[i] * w->u[i] + w->v[i] * w->v[i];
        double a = w->ax[i] * w->ax[i] + w->ay[i] * w->ay[i];
        if (s > umax) umax = s;
        if (a > amax) amax = a;
        if (w->visc[i] > etamax) etamax = w->visc[i];
        if (w->rho[i] < rhomin) rhomin = w->rho[i];
        if (sph_surface_traction(w)) {
            double nu = w->mats[w->mat[i]].mu / w->rho[i];
            if (nu > nuall) nuall = nu;
            if (w->surf[i] && nu > nus) nus = nu;
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
    /* time accuracy: the plastic stress's lag. With r <= SPH_ALM_CAP rho h^2 / dt (internal.h)
     * a multiplier's direction follows the rate over secant / r steps, a time
     * T = secant dt^2 / (SPH_ALM_CAP rho h^2), and a plug deforms as a fluid of viscosity r
     * until it has followed. T gammadot_rms <= LAG_STRAIN (the RMS rate of the viscoplastic particles, the
     * secant a plug's, plug_secant) keeps the strain the stress lags by small; a creeping
     * sample (small rates) hardly feels it. The square at Bn = 1000 comes to 0.967 / 0.986 of
     * FE's force at dx = 1/20, 1/40 (0.914 / 0.952 without; docs/limitations.md). */
    if (nvp > 0 && secmax > 0 && gd2 > 0) {
        double grms = sqrt(gd2 / nvp), sec = plug_secant(w, secmin, secmax, nvp);
        dt = fmin(dt, h * sqrt(LAG_STRAIN * P->rho0 * SPH_ALM_CAP / (sec * grms)));
    }
    if (P->dt_max > 0) dt = fmin(dt, P->dt_max);
    /* The density error each step leaves (mostly near a free surface, where the
     * projection is least exact) grows with dt, about in proportion. So dt also follows
     * the density error: while it exceeds density_tol, dt shrinks in proportion (by at most
     * 20 % a step), down to a twentieth of the other limits (an error that does not come
     * from dt must not stall the run). With implicit viscosity the first step, which may
     * start a plate impulsively, is that twentieth; the explicit scheme's first step is
     * already short. The free surface is marked at the step's start, after its dt is set, so
     * the first step is also bounded by the surface's stability limit over every particle
     * (SPH_SURFACE_STABLE, internal.h): a twentieth of the speed limit is 250 times rho h^2 / mu
     * on the square at Re = 1e-3, dx = 0.05, and that step put a particle through a plate. */
    double floor = 0.05 * dt;
    if (w->dt_prev <= 0) {
        if (P->viscosity == SPH_VISC_IMPLICIT) dt = floor;
        if (nuall > 0) dt = fmin(dt, SPH_SURFACE_STABLE * h * h / nuall);
    } else if (P->density_tol > 0 && w->st.max_density_error > P->density_tol) {
        dt = fmin(dt, fmax(floor, w->dt_prev * fmax(0.8, P->density_tol / w->st.max_density_error)));
    }
    int near = P->density_tol > 0 && w->st.max_density_error > 0.5 * P->density_tol;
    if (w->dt_prev > 0) dt = fmin(dt, (near ? DT_NEAR_TOL : DT_GROWTH) * w->dt_prev);
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
