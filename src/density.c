/* The density correction (sph_density_correct): after the projection, the continuity
 * density's error is removed by moving the particles, with the pressure system's matrix
 * (pressure.c, whose top comment gives the scheme): the passes (density_pass), the density
 * descent when they stall, the GMRES fallback, or density_correction = "gmres" on its own. */
#include "internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Passes a step while the error exceeds density_tol: a second pass about halves what the
 * first leaves; more would remove the error that shortens dt, and the loaded plates' time
 * error would show (sph_density_correct). */
#define DENSITY_PASSES 2
/* Above this error (0.8 %) after those passes, more passes follow, then the descent and
 * the GMRES fallback: it holds the 1 % criterion of the stability suite with a margin. */
#define DENSITY_LIMIT 0.008
#define MAX_DENSITY_PASSES 10 /* passes a step in all: each further one removes less */
#define MAX_GMRES 8 /* GMRES directions a correction at most: each is a solve and 3 vectors */
#define DESCENT_MOVES 20 /* steepest-descent moves a step at most: each two sweeps, no solve */
/* The correction's solves' relative residual: the density follows the displacement
 * actually made, so a looser phi only removes a little less error per pass, for a third
 * fewer pressure-type iterations (correction_solve). */
#define DENSITY_SOLVE_TOL 1e-3
/* The probe's loose solve (density_pass): at 0.1 a probe of step length 0 is one whose
 * full pass moves nothing too. */
#define PROBE_TOL 0.1

/* The density correction (see the top of pressure.c): the pressure system's matrix, the
 * source (rho0 - rho_i) / rho0, warm-started from the last phi; the particles move by
 * -grad phi / rho (the pressure's symmetric gradient) and their density follows by
 * continuity. Walls stay; free-surface particles hold phi = 0. */
static int density_pass(sph_world *w, int pass, double *alpha);
static int correct(sph_world *w);
static void motion_share(sph_world *w, double dt);

/* Up to DENSITY_PASSES corrections while the error stays above density_tol. One pass
 * removes the smooth part of the error, not all of it: the matrix is the compact Laplacian
 * and the displacement's divergence the wide SPH one, so a short-wavelength error (the
 * column-to-column pattern a squeeze leaves next to the plate/free-surface corner) is only
 * partly removed and builds up; a second pass about halves what the first leaves. Each
 * further pass removes less (a mode that the displacement's divergence barely sees).
 * So the extra passes come only where the error would break the 1 % criterion: after
 * DENSITY_PASSES, passes go on (up to MAX_DENSITY_PASSES) while the error is above
 * DENSITY_LIMIT (0.8 %); that holds the stability suite under it and barely moves the
 * validation squeezes. */
/* Steepest descent on the continuity density error (see sph_density_correct). With
 * e = rho / rho0 - 1 over interior fluid (0 on the free surface and walls) and d = D r the continuity change of a displacement r (D the renormalised
 * wide divergence, sph_field_div), the gradient of 1/2 sum (e_i + d_i)^2 is D^T e, which is,
 * up to the renormalisation matrix taken at the particle itself and its neighbours' masses,
 * the symmetric SPH gradient of e: the move -grad e (particles go from where the density
 * is high to where it is low) lowers the squared error for a short enough step, whatever
 * the mode. The passes' direction -G L^-1 e (the compact Laplacian's potential) does not:
 * next to a free surface D G and L disagree on the row-to-row modes, the passes' step
 * length goes to 0 and the error stays. Each move takes the least-squares length along
 * its direction, at most DESCENT_MAX_MOVE dx for the particle moved furthest, and the
 * density follows by continuity (displace); moves go on while the error is above
 * DENSITY_LIMIT, up to K, and stop when the move would not lower the error (the
 * approximate transpose, or nothing left to move).
 * It is what holds the error under DENSITY_LIMIT where the passes' step length is 0: the
 * rows next to a thin film's free front, off both plates, and the closed cavity's corners
 * (whose error would otherwise hold the time step down). Where the passes
 * reach DENSITY_LIMIT (the other stability cases, the headline squeeze) it does not run. */
#define DESCENT_MAX_MOVE 0.05
static double displace(sph_world *w, const double *dx, const double *dy, const double *d, double alpha);
static int density_descent(sph_world *w, int K) {
    int n = w->n, nt = n + w->ng;
    double rho0 = w->par.rho0, *e = w->dp, *dx = w->xs, *dy = w->ys, *d = w->sb;
    int done = 0;
    for (int it = 0; it < K; it++) {
#pragma omp parallel for schedule(static) num_threads(w->threads)
        for (int i = 0; i < n; i++) e[i] = (w->kind[i] == SPH_FLUID && !w->surf[i]) ? w->rho[i] / rho0 - 1.0 : 0.0;
        sph_boundary_sync(w, e, 0, 0);
        for (int g = n; g < nt; g++) if (w->kind[w->src[g]] != SPH_FLUID) e[g] = 0.0;
        double gmax = 0.0;
#pragma omp parallel for schedule(static) num_threads(w->threads) reduction(max : gmax)
        for (int i = 0; i < n; i++) {
            dx[i] = dy[i] = 0.0;
            if (w->kind[i] != SPH_FLUID) continue;
            double gx, gy; /* -sum_j m_j (e_i + e_j) grad W_ij: the symmetric gradient of e */
            sph_neg_grad(w, e, i, &gx, &gy);
            dx[i] = w->lxx[i] * gx + w->lxy[i] * gy;
            dy[i] = w->lxy[i] * gx + w->lyy[i] * gy;
            double g2 = dx[i] * dx[i] + dy[i] * dy[i];
            if (g2 > gmax) gmax = g2;
        }
        if (!(gmax > 0.0)) break;
        sph_boundary_sync(w, dx, dy, 1);
        double num = 0.0, den = 0.0;
#pragma omp parallel for schedule(static) num_threads(w->threads) reduction(+ : num, den)
        for (int i = 0; i < n; i++) {
            d[i] = 0.0;
            if (w->kind[i] != SPH_FLUID || w->surf[i]) continue;
            d[i] = sph_field_div(w, dx, dy, i);
            num -= e[i] * d[i];
            den += d[i] * d[i] / rho0;
        }
        if (!(num > 0.0 && den > 0.0)) break;
        double alpha = fmin(num / den, DESCENT_MAX_MOVE * w->dx / sqrt(gmax));
        w->st.max_density_error = displace(w, dx, dy, d, alpha);
        done++;
        if (w->st.max_density_error <= DENSITY_LIMIT) break;
    }
    return done;
}
static int density_gmres(sph_world *w);
/* the density descent when the error is above DENSITY_LIMIT */
static void descend_if_above(sph_world *w) {
    if (w->st.max_density_error > DENSITY_LIMIT) w->st.density_descents += density_descent(w, DESCENT_MOVES);
}
#define FALLBACK_USELESS 0.95
#define FALLBACK_WAIT 10
#define FALLBACK_WAIT_MAX 640
int sph_density_correct(sph_world *w, double dt) {
    int err = correct(w);
    motion_share(w, dt);
    return err;
}

/* The sums behind sph_stats.correction_share for this step of length dt: the correction's
 * displacement (dcx, dcy, accumulated by displace; read and cleared here, so they are zero
 * between steps) against the whole move, the velocity's part from u^{n+1} and the step's
 * acceleration (u^n = u^{n+1} - dt a). */
static void motion_share(sph_world *w, double dt) {
    int n = w->n;
    double c2 = 0.0, m2 = 0.0;
#pragma omp parallel for schedule(static) num_threads(w->threads) reduction(+ : c2, m2)
    for (int i = 0; i < n; i++) {
        double cx = w->dcx[i], cy = w->dcy[i];
        w->dcx[i] = w->dcy[i] = 0.0;
        if (w->kind[i] != SPH_FLUID) continue;
        double mx = dt * (w->u[i] - 0.5 * dt * w->ax[i]) + cx;
        double my = dt * (w->v[i] - 0.5 * dt * w->ay[i]) + cy;
        c2 += cx * cx + cy * cy;
        m2 += mx * mx + my * my;
    }
    if (!(dt > 0.0)) return;
    w->st.correction_sq += c2 / dt; /* time-weighted: sum over steps of dt |d / dt|^2 */
    w->st.motion_sq += m2 / dt;
}

static int correct(sph_world *w) {
    /* the thin-film scheme: GMRES's directions, then the descent (below) when they
     * leave the error above DENSITY_LIMIT: its eight directions can leave a step above 1 %
     * (next to the symmetry plane, or at a film's front), and the descent brings it to the
     * limit. */
    if (w->par.thin_film) {
        if (density_gmres(w)) return -1;
        descend_if_above(w);
        return 0;
    }
    w->st.density_alpha = 1.0;
    w->st.density_passes = 0;
    /* Passes after the first whose step length is 0 move nothing, and the next one would
     * repeat the same solve from the same error (later passes start from phi = 0): such a
     * pass ends the step's passes (the step is the same bit for bit). */
    for (int q = 0; q < MAX_DENSITY_PASSES; q++) {
        double e = w->st.max_density_error;
        if (q > 0 && e <= w->par.density_tol) break;
        if (q >= DENSITY_PASSES && !(e > DENSITY_LIMIT)) break;
        double alpha;
        if (density_pass(w, q, &alpha)) return -1;
        w->st.density_passes++;
        if (q > 0) w->later_stalled = alpha == 0.0;
        if (q > 0 && alpha == 0.0) break;
    }
    /* Every pass used and the error still above DENSITY_LIMIT: the passes have stalled
     * (their step length goes to 0 where the displacement's continuity rate is mostly
     * row-to-row noise). First the descent (density_descent, above: it always lowers the
     * error); if that leaves it above DENSITY_LIMIT, one GMRES correction (density_gmres)
     * combines directions instead. When it removes less than 5 % of the error (L2) the next
     * fallback waits FALLBACK_WAIT steps, doubling with each useless one up to
     * FALLBACK_WAIT_MAX; one that helps resets the wait. A few corrections do the work, and a
     * fallback at every stalled step would double the cost of a case whose corners no pass
     * clears (the closed cavity). */
    descend_if_above(w);
    if (w->st.max_density_error > DENSITY_LIMIT && w->steps >= w->fallback_after) {
        int passes = w->st.density_passes;
        double alpha = w->st.density_alpha;
        if (density_gmres(w)) return -1;
        double left = w->st.density_alpha; /* L2 error left over the error before */
        if (left > FALLBACK_USELESS) { /* waits 10, 20, 40, ..., 640, 640, ... steps */
            int wait = w->fallback_wait;
            w->fallback_wait = wait == 0 ? FALLBACK_WAIT : wait < FALLBACK_WAIT_MAX ? 2 * wait : wait;
            w->fallback_after = w->steps + w->fallback_wait;
        } else {
            w->fallback_wait = 0;
        }
        w->st.density_passes += passes;
        w->st.density_alpha = alpha; /* the passes' step length, as documented in sph.h */
        w->st.density_fallbacks++;
    }
    return 0;
}
/* One correction; pass 0 warm-starts from the last step's phi and keeps its solution for
 * the next step, later passes start from zero in a scratch array. The solve stops at
 * DENSITY_SOLVE_TOL (1e-3), not the pressure's tol (1e-6). */
/* x += alpha (dx, dy) for fluid, rho += alpha d for interior fluid (d: the continuity
 * change of the whole displacement); returns the max density error left. */
static double displace(sph_world *w, const double *dx, const double *dy, const double *d, double alpha) {
    int n = w->n;
    double rho0 = w->par.rho0, maxerr = 0.0;
#pragma omp parallel for schedule(static) num_threads(w->threads) reduction(max : maxerr)
    for (int i = 0; i < n; i++) {
        if (w->kind[i] != SPH_FLUID) continue;
        w->x[i] += alpha * dx[i];
        w->y[i] += alpha * dy[i];
        w->dcx[i] += alpha * dx[i];
        w->dcy[i] += alpha * dy[i];
        if (w->surf[i]) continue;
        w->rho[i] += alpha * d[i];
        double e = fabs(w->rho[i] / rho0 - 1.0);
        if (e > maxerr) maxerr = e;
    }
    return maxerr;
}

/* The displacement -grad f / rho of every fluid particle into (dx, dy), ghosts synced: the
 * renormalised difference form (diff) or the symmetric one (its f / rho^2 in w->sa). */
static void displacement(sph_world *w, const double *f, int diff, double *dx, double *dy) {
    int n = w->n;
    if (!diff) sph_pressure_neg_grad_prepare(w, f, w->sa);
#pragma omp parallel for schedule(static) num_threads(w->threads)
    for (int i = 0; i < n; i++) {
        dx[i] = dy[i] = 0.0;
        if (w->kind[i] != SPH_FLUID) continue;
        if (diff) sph_neg_grad_difference(w, f, i, &dx[i], &dy[i]);
        else sph_neg_grad(w, w->sa, i, &dx[i], &dy[i]);
    }
    sph_boundary_sync(w, dx, dy, 1);
}

/* The density correction's solve: the pressure matrix with the right-hand side and start in
 * w->b and w->sol, to the relative residual tol; the solution into f (ghosts synced) and the
 * displacement -grad f / rho of every fluid particle into (dx, dy), in the difference form
 * (diff) or the symmetric one. */
static int correction_solve(sph_world *w, double tol, double *f, int diff, double *dx, double *dy) {
    sph_solve_result res = sph_solver_pcg(&w->solver, &w->A, w->b, w->sol, tol, SPH_SOLVE_MAX_ITER, w->threads);
    if (!res.converged)
        return sph_world_fail(w,
                              "density correction solver did not converge at step %ld (t = %g): "
                              "relative residual %.3g after %d iterations (tolerance %g, %d unknowns)",
                              w->steps, w->t, res.residual, res.iterations, tol, w->nrows);
    w->st.solver_iterations += res.iterations;
    w->st.solver_iterations_total += res.iterations;
    sph_lap(w, SPH_PHASE_PRESSURE_SOLVE);
    sph_pressure_scatter(w, w->sol, f, 0);
    /* The symmetric form (the first passes' until one falls short, see density_pass; the
     * later passes' and the GMRES directions' always) carries phi_i sum_j m_j grad W_ij,
     * which does not vanish where the support is cut (the free surface) or the particles
     * are disordered. At 10^6 particles phi is large against its source and that term
     * decides the direction: the first pass's step length falls to about 0.3 and the error
     * stays near DENSITY_LIMIT. The renormalised difference form keeps the step length at 1,
     * but taken everywhere it worsens the thin-film validations and the cavity, mostly
     * through the longer time step its lower error allows. */
    displacement(w, f, diff, dx, dy);
    return 0;
}

/* The step length along the displacement (dx, dy) (density_pass), its continuity change
 * into d; *gain (if not NULL): how much it lowers the squared error, sum e_i^2 - sum
 * (e_i + alpha d_i / rho0)^2 (times rho0, over interior fluid). */
static double step_length(sph_world *w, const double *dx, const double *dy, double *d, double *gain) {
    int n = w->n;
    double rho0 = w->par.rho0, num = 0.0, den = 0.0;
#pragma omp parallel for schedule(static) num_threads(w->threads) reduction(+ : num, den)
    for (int i = 0; i < n; i++) {
        d[i] = 0.0;
        if (w->kind[i] != SPH_FLUID || w->surf[i]) continue;
        d[i] = sph_field_div(w, dx, dy, i);
        num -= (w->rho[i] / rho0 - 1.0) * d[i];
        den += d[i] * d[i] / rho0;
    }
    double alpha = den > 0.0 ? fmax(0.0, fmin(1.0, num / den)) : 0.0;
    if (gain) *gain = alpha * (2.0 * num - alpha * den);
    return alpha;
}

/* *alpha: the pass's step length (1 when there was nothing to move). A later pass after
 * one of step length 0 tries the direction of a loose solve first (the probe, below). */
static int density_pass(sph_world *w, int pass, double *alpha_out) {
    double rho0 = w->par.rho0;
    int nrows = w->nrows;
    *alpha_out = 1.0;
    if (nrows == 0) return 0;
    double bmax = 0.0;
#pragma omp parallel for schedule(static) num_threads(w->threads) reduction(max : bmax)
    for (int r = 0; r < nrows; r++) {
        int i = w->row_of[r];
        double s = w->kind[i] == SPH_FLUID ? (rho0 - w->rho[i]) / rho0 : 0.0;
        w->b[r] = -w->m[i] * s;
        w->sol[r] = pass ? 0.0 : w->phi[i];
        if (fabs(s) > bmax) bmax = fabs(s);
    }
    sph_lap(w, SPH_PHASE_CORRECTION);
    if (bmax == 0.0) return 0;
    if (w->pin >= 0) sph_pressure_make_compatible(w, -w->m[w->pin] * (rho0 - w->rho[w->pin]) / rho0);
    double *f = pass ? w->dp : w->phi, *dx = w->xs, *dy = w->ys, *d = w->sb;
    /* the form of the displacement: symmetric, but a first pass starts from the form that
     * won the last one (below) */
    int first = pass == 0;
    int diff = first && w->first_difference;
    /* The probe: a later pass after one of step length 0 is likely to get 0 again (the
     * error left lives in modes the passes cannot reach); a loose solve (relative residual
     * PROBE_TOL, from zero) gives its direction's step length first. 0: the pass ends (it
     * would have moved nothing); else the full solve from zero, the pass exactly as without
     * the probe. At 10^6 particles it saves about a seventh of the pressure-type iterations. */
    if (pass > 0 && w->later_stalled) {
        w->st.density_probes++;
        if (correction_solve(w, PROBE_TOL, f, diff, dx, dy)) return -1;
        if (step_length(w, dx, dy, d, NULL) == 0.0) {
            w->st.density_probes_ended++;
            *alpha_out = 0.0;
            w->st.density_alpha = 0.0;
            return 0;
        }
        for (int r = 0; r < nrows; r++) w->sol[r] = 0.0; /* the full solve, as without the probe */
    }
    if (correction_solve(w, DENSITY_SOLVE_TOL, f, diff, dx, dy)) return -1;
    /* The step length: the density change is linear in the displacement, d_i =
     * sph_field_div(dx, dy), so alpha = -sum e_i d_i / sum d_i^2 (clamped to [0, 1]; e
     * the density error, over interior fluid) is the one that leaves the least squared
     * error. A full pass (alpha = 1) can make the error grow: the displacement's divergence
     * is the wide SPH one and the matrix the compact Laplacian, and on the modes where the
     * first exceeds twice the second each pass amplifies them (in a film started thin the
     * error then grows from step to step until a particle goes through a plate). Where
     * those modes are absent alpha stays 1. */
    double gain, alpha = step_length(w, dx, dy, d, &gain);
    /* The form: a step's first pass moves along the symmetric gradient's direction until
     * one falls short (step length under 1); that pass also tries the difference form's
     * direction of the same phi (one gradient and one divergence sweep, no solve) and moves
     * along the one that lowers the squared error more. The winner is the next first pass's starting form, and the other is tried only
     * when it falls short in turn: switching back at once makes the two forms alternate and
     * loses the first pass's warm start. Where the symmetric form works nothing changes (at
     * 10^4 and 10^5 particles it never falls short); at 10^6 the difference direction wins
     * from the start and keeps winning (docs/performance.md). Only the first pass: a later
     * pass whose symmetric direction moves nothing is where the thin films' error stays
     * above density_tol and holds their time step down, which is what keeps their force
     * accurate. The second direction lives in the scratch ru, rv and the later passes' dp. */
    if (first && alpha < 1.0) {
        double *hx = w->ru, *hy = w->rv, *hd = w->dp, gain2;
        displacement(w, f, !diff, hx, hy);
        double alpha2 = step_length(w, hx, hy, hd, &gain2);
        if (gain2 > gain) {
            w->first_difference = !diff;
            alpha = alpha2;
            dx = hx;
            dy = hy;
            d = hd;
        }
    }
    if (first && w->first_difference) w->st.density_switches++;
    *alpha_out = alpha;
    w->st.max_density_error = displace(w, dx, dy, d, alpha);
    w->st.density_alpha = fmin(w->st.density_alpha, alpha);
    return 0;
}

/* density_correction = "gmres": the passes above as right-preconditioned GMRES. With e the
 * continuity density error (rho / rho0 - 1 over interior fluid) and B the map from a
 * density-error field v to the continuity change of the displacement -G phi / rho, phi
 * solving the pressure matrix's system with the source v (the compact Laplacian as the
 * preconditioner), one correction minimises || e + B y || over the Krylov space
 * {e, B e, B^2 e, ...} (Arnoldi, modified Gram-Schmidt; the small least-squares problem by
 * its normal equations), then moves the particles once by the combined displacement and
 * updates their density by its continuity rate. The passes of density_pass take one
 * direction at a time, with a step length in [0, 1]; where the displacement's continuity
 * rate is mostly row-to-row noise (a thin film a few rows across, sheared: the compact
 * Laplacian against the wide divergence) each pass gets step length 0 and the error
 * stays; a combination of two or three directions cancels much of the noise.
 * On a Newtonian film started thin (dx = 1/80) it holds the error under 0.8 % where the
 * passes, at step length 0, leave 8.6 %.
 * The iterations follow DENSITY_PASSES (at least that many while the error is above
 * density_tol) and DENSITY_LIMIT (more, up to MAX_GMRES, while the error left would
 * still exceed it); density_passes in the stats counts the directions, density_alpha
 * is the L2 error left over the error before (1: nothing removed). */
static int density_gmres(sph_world *w) {
    double rho0 = w->par.rho0, tol = w->par.density_tol;
    int n = w->n, nt = w->n + w->ng, nrows = w->nrows, th = w->threads;
    int K = DENSITY_PASSES, Kmax = MAX_GMRES;
    w->st.density_alpha = 1.0;
    w->st.density_passes = 0;
    if (nrows == 0 || w->st.max_density_error <= tol) return 0;
    size_t N = (size_t)w->cap, need = (size_t)(3 * Kmax + 1) * N;
    if (w->gm_len < need) {
        double *q = realloc(w->gm, need * sizeof(double));
        if (!q) return sph_world_fail(w, "out of memory (density correction, %d particles)", w->cap);
        w->gm = q;
        w->gm_len = need;
    }
    double *V = w->gm, *DX = V + (size_t)(Kmax + 1) * N, *DY = DX + (size_t)Kmax * N;
    double H[MAX_GMRES + 1][MAX_GMRES] = {{0}}, y[MAX_GMRES] = {0};
    double beta = 0.0;
#pragma omp parallel for schedule(static) num_threads(th) reduction(+ : beta)
    for (int i = 0; i < n; i++) {
        double e = (w->kind[i] == SPH_FLUID && !w->surf[i]) ? w->rho[i] / rho0 - 1.0 : 0.0;
        V[i] = e;
        beta += e * e;
    }
    beta = sqrt(beta);
    if (!(beta > 0.0)) return 0;
#pragma omp parallel for schedule(static) num_threads(th)
    for (int i = 0; i < n; i++) V[i] /= beta;
    int m = 0;
    while (m < Kmax) {
        double *vk = V + (size_t)m * N, *dx = DX + (size_t)m * N, *dy = DY + (size_t)m * N;
        /* phi = L^{-1} (m v): the first direction warm-starts from the last step's phi */
#pragma omp parallel for schedule(static) num_threads(th)
        for (int r = 0; r < nrows; r++) {
            int i = w->row_of[r];
            w->b[r] = w->kind[i] == SPH_FLUID ? w->m[i] * vk[i] : 0.0;
            w->sol[r] = m == 0 ? w->phi[i] / beta : 0.0;
        }
        sph_lap(w, SPH_PHASE_CORRECTION);
        if (w->pin >= 0) sph_pressure_make_compatible(w, w->m[w->pin] * vk[w->pin]);
        if (correction_solve(w, DENSITY_SOLVE_TOL, w->dp, 0, dx, dy)) return -1;
        if (m == 0) {
#pragma omp parallel for schedule(static) num_threads(th)
            for (int i = 0; i < nt; i++) w->phi[i] = beta * w->dp[i];
        }
        /* the next Krylov vector B v_m, orthogonalised against v_0 .. v_m */
        double *vn = V + (size_t)(m + 1) * N;
#pragma omp parallel for schedule(static) num_threads(th)
        for (int i = 0; i < n; i++)
            vn[i] = (w->kind[i] == SPH_FLUID && !w->surf[i]) ? sph_field_div(w, dx, dy, i) / rho0 : 0.0;
        for (int j = 0; j <= m; j++) {
            const double *vj = V + (size_t)j * N;
            double h = 0.0;
#pragma omp parallel for schedule(static) num_threads(th) reduction(+ : h)
            for (int i = 0; i < n; i++) h += vn[i] * vj[i];
            H[j][m] = h;
#pragma omp parallel for schedule(static) num_threads(th)
            for (int i = 0; i < n; i++) vn[i] -= h * vj[i];
        }
        double hn = 0.0;
#pragma omp parallel for schedule(static) num_threads(th) reduction(+ : hn)
        for (int i = 0; i < n; i++) hn += vn[i] * vn[i];
        hn = sqrt(hn);
        H[m + 1][m] = hn;
        if (hn > 0.0) {
#pragma omp parallel for schedule(static) num_threads(th)
            for (int i = 0; i < n; i++) vn[i] /= hn;
        }
        m++;
        /* min || beta e_1 + Hbar y ||: normal equations Hbar^T Hbar y = -beta Hbar^T e_1 */
        double a[MAX_GMRES][MAX_GMRES];
        for (int r = 0; r < m; r++) {
            for (int c = 0; c < m; c++) {
                double sum = 0.0;
                for (int q = 0; q <= m; q++) sum += H[q][r] * H[q][c];
                a[r][c] = sum;
            }
            y[r] = -beta * H[0][r];
        }
        sph_dense_solve(m, &a[0][0], MAX_GMRES, y);
        /* the error left, e + B V y = V_{0..m} g with g = beta e_1 + Hbar y */
        double g[MAX_GMRES + 1], gg = 0.0, maxe = 0.0;
        for (int q = 0; q <= m; q++) {
            g[q] = q == 0 ? beta : 0.0;
            for (int c = 0; c < m; c++) g[q] += H[q][c] * y[c];
            gg += g[q] * g[q];
        }
#pragma omp parallel for schedule(static) num_threads(th) reduction(max : maxe)
        for (int i = 0; i < n; i++) {
            double e = 0.0;
            for (int q = 0; q <= m; q++) e += g[q] * V[(size_t)q * N + i];
            maxe = fmax(maxe, fabs(e));
        }
        w->st.density_alpha = sqrt(gg) / beta;
        if (hn == 0.0 || maxe <= tol) break;
        if (m >= K && !(maxe > DENSITY_LIMIT)) break;
    }
    w->st.density_passes = m;
    /* move once by the combined displacement; the density follows its continuity rate */
    double *cx = w->xs, *cy = w->ys, *d = w->sb;
#pragma omp parallel for schedule(static) num_threads(th)
    for (int i = 0; i < nt; i++) {
        double ax = 0.0, ay = 0.0;
        for (int q = 0; q < m; q++) {
            ax += y[q] * DX[(size_t)q * N + i];
            ay += y[q] * DY[(size_t)q * N + i];
        }
        cx[i] = ax;
        cy[i] = ay;
    }
#pragma omp parallel for schedule(static) num_threads(th)
    for (int i = 0; i < n; i++)
        d[i] = (w->kind[i] == SPH_FLUID && !w->surf[i]) ? sph_field_div(w, cx, cy, i) : 0.0;
    w->st.max_density_error = displace(w, cx, cy, d, 1.0);
    return 0;
}
