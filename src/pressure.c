/* The pressure Poisson equation and the projection (Cummins & Rudman 1999; Shao & Lo 2003),
 * with the density error corrected apart from the pressure:
 *   div((1/rho) grad p)_i = -sum_j m_j (u*_i - u*_j) . grad_i W_ij / (rho0 dt)
 * (the divergence-free source), u^{n+1} = u* - dt grad p / rho; then, with the same matrix,
 *   div((1/rho) grad phi)_i = (rho0 - rho_i) / rho0,   x_i -= grad phi_i / rho_i.
 * phi = dt^2 p_rel is the part of the paper's density-invariant source (rho0 - rho*) /
 * (rho0 dt^2) (PHYSICS.md allows the blend) that corrects the density error of earlier
 * steps. Inside the pressure it would scale as 1 / dt^2 for a given error, so a step
 * shorter than the one before would make the plate force jump and a shrinking dt could run
 * away; as a separate displacement it moves the particles by the same amount whatever dt
 * is, and the pressure, the velocity and the plate force are the flow's own.
 * The divergence uses the renormalised kernel gradient L grad W (Bonet & Lok 1999), so
 * it stays first-order consistent next to a free surface.
 * Laplacian: sum_j m_j 8 / (rho_i + rho_j)^2 (p_i - p_j) F_ij. Rows: fluid particles and
 * the wall particles near fluid (mark_unknowns); free-surface particles are held at
 * p = n . tau . n (the traction-free surface: viscous.c, surface_pressure). Each row is
 * scaled by m_i so that the matrix is symmetric positive definite; ghosts map to the
 * unknown of the particle they image.
 * Plates under a load are coupled implicitly: the pressure is linear in their velocities,
 * p = p0 + sum_k V_k p_k, so one extra solve per loaded plate gives dp/dV and the plate
 * equations M (V - V^n) / dt = F_load + F_fluid(p(V)) become a small dense system. This is
 * stable whatever the plate's mass against the fluid's added mass.
 *
 * Pressure predictor (implicit viscosity only): the viscous step solves
 * (rho / dt - div eta grad) u* = rho u^n / dt - grad p~, with p~ the last step's pressure
 * at the current positions, kernel-averaged (see sph_pressure_predictor), and takes
 * dt grad p~ / rho back before the projection, which then solves for the whole p^{n+1}.
 * Away from walls the two terms cancel; at a no-slip wall the viscous solve turns the
 * pressure-driven part of the flow into its shear profile inside the step. Without it the
 * projection's -dt grad p / rho slides along the wall and the next viscous step takes the
 * slip back: a splitting error of order dt eta / (rho h^2), which makes the squeeze forces
 * depend on dt. The projection does not
 * solve for an increment p - p~: with the wide divergence of the symmetric gradient against
 * the compact Laplacian (DG != L) an incremental scheme feeds p^n into itself, and where
 * the viscous solve is stiff it cannot restore the pressure the kernel average erodes a
 * little every step.
 *
 * Thin films (docs/limitations.md) have a scheme of their own, off by default (thin_film,
 * sph.h): the density correction (density.c, density_gmres) minimises the continuity density
 * error over the Krylov space of its passes, and the projection takes its gradient in the
 * renormalised difference form L sum_j V_j (p_j - p_i) grad W_ij (Lind et al. 2012), which
 * has no term in p_i. That term scales with a thin film's large
 * pressure level and drives a residual-divergence mode with DG / L > 2, amplified by
 * 1 - DG / L < -1 each step: the plate force alternates from step to step and grows. The
 * plate force stays the symmetric sum over fluid-wall pairs, a measure of the pressure on
 * the plate's face. Not the default: the difference form does not conserve momentum (a
 * loaded plate does not meet the fluid's reaction exactly) and cannot carry the
 * traction-free surface, whose normal stress is a large share of a thick sample's force. */
#include "internal.h"
#include "kernel.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int reserve_rows(sph_world *w, int nrows) {
    if (nrows <= w->rows_cap && w->b) return 0;
    int cap = nrows + nrows / 4 + 64;
    double **arr[2 + 2 * SPH_MAX_LOADED];
    int na = 0;
    arr[na++] = &w->b;
    arr[na++] = &w->sol;
    for (int k = 0; k < SPH_MAX_LOADED; k++) {
        arr[na++] = &w->bk[k];
        arr[na++] = &w->solk[k];
    }
    for (int a = 0; a < na; a++) {
        double *q = realloc(*arr[a], sizeof(double) * (size_t)cap);
        if (!q) return sph_world_fail(w, "out of memory (%d pressure unknowns)", nrows);
        *arr[a] = q;
    }
    int *ro = realloc(w->row_of, sizeof(int) * (size_t)cap);
    if (!ro) return sph_world_fail(w, "out of memory (%d pressure unknowns)", nrows);
    w->row_of = ro;
    w->rows_cap = cap;
    return 0;
}

/* The unknowns: fluid particles off the free surface (but the pin) and the active wall
 * particles (mark_rows in neighbours.c: walls in the 3 x 3 cells around any fluid
 * particle, a superset of the walls within the support of fluid) that the fluid's
 * unknowns reach: a wall with a fluid unknown (real or image; not a free-surface particle)
 * in its support, or one joined to such a wall through other active walls. The rest are
 * blocks of walls coupled among themselves and at most to free-surface particles (p = 0;
 * e.g. plate walls within 3 x 3 cells of a sheet thrown off a contact line): singular or
 * nearly so (a Neumann block, or one held by a single Dirichlet neighbour), they make the
 * multigrid cycle indefinite and stop CG, and their pressure matters to no unknown. Left
 * out, they take p = 0, the pressure of the free surface they touch at most; no unknown
 * kept is coupled to them. Marks w->row[i] > 0 (unknown) or -1 (not) and returns how many
 * active walls were left out; w->row_of (n entries) is the search's queue. */
static int mark_unknowns(sph_world *w, int pin) {
    int n = w->n, *queue = w->row_of, tail = 0, walls = 0;
    for (int i = 0; i < n; i++) {
        int cand = w->active[i] && !(w->kind[i] == SPH_FLUID && w->surf[i]) && i != pin;
        w->row[i] = cand ? (w->kind[i] == SPH_FLUID ? 1 : 0) : -1;
    }
    for (int i = 0; i < n; i++) {
        if (w->row[i] != 0) continue;
        walls++;
        for (int k = w->nb_start[i]; k < w->nb_start[i + 1]; k++) {
            int s = w->src[w->nb_j[k]];
            if (w->kind[s] == SPH_FLUID && w->row[s] == 1) {
                w->row[i] = 2; /* reached; 1 once searched from */
                queue[tail++] = i;
                break;
            }
        }
    }
    for (int head = 0; head < tail; head++) {
        int i = queue[head];
        for (int k = w->nb_start[i]; k < w->nb_start[i + 1]; k++) {
            int s = w->src[w->nb_j[k]];
            if (w->row[s] == 0) {
                w->row[s] = 2;
                queue[tail++] = s;
            }
        }
    }
    return walls - tail;
}

/* Velocity of particle j as the source term sees it; loaded plates count as still (their
 * velocity enters through the sensitivities). */
static inline void src_velocity(const sph_world *w, int j, double *vx, double *vy) {
    if (w->kind[j] == SPH_FLUID) {
        *vx = w->us[j];
        *vy = w->vs[j];
        return;
    }
    const sph_plate *pl = &w->plates[w->kind[j]];
    if (pl->mode == SPH_PLATE_LOAD) {
        *vx = *vy = 0.0;
        return;
    }
    sph_plate_rigid_velocity(w, j, vx, vy);
}


/* Without a free surface (closed or periodic) the matrix has the constants as its null
 * space and one unknown, w->pin, is held at 0. The system is solvable only if the sources
 * sum to zero over all rows and the pin; otherwise the pin's own equation is violated by
 * that sum, and it acts as a point source or sink (in the lid-driven cavity the pinned
 * corner particle is sucked through the wall). The discrete sum is not zero (a kernel sum
 * is not exactly a divergence; a closed box cannot change its volume, so the mean density
 * error cannot be corrected either), so the mean source is removed: fluid rows get
 * b_r -= m_i S / sum(m_fluid), S = sum of all rows' sources plus pin_source (the pin's, in
 * the same mass-scaled form). */
void sph_pressure_make_compatible(sph_world *w, double pin_source) {
    double S = pin_source, M = w->m[w->pin];
    for (int r = 0; r < w->nrows; r++) {
        int i = w->row_of[r];
        S += w->b[r];
        if (w->kind[i] == SPH_FLUID) M += w->m[i];
    }
    double s = S / M;
    for (int r = 0; r < w->nrows; r++) {
        int i = w->row_of[r];
        if (w->kind[i] == SPH_FLUID) w->b[r] -= w->m[i] * s;
    }
}

/* d(velocity of j)/d V_k */
static inline void sens_velocity(const sph_world *w, int j, int k, double *vx, double *vy) {
    *vx = *vy = 0.0;
    if (w->kind[j] != k) return;
    const sph_plate *pl = &w->plates[k];
    if (pl->axis == 0) *vx = w->gsx[j];
    else if (pl->axis == 1) *vy = w->gsy[j];
}

void sph_pressure_scatter(sph_world *w, const double *sol, double *p, const double *surface) {
    for (int i = 0; i < w->n; i++) p[i] = surface && w->kind[i] == SPH_FLUID && w->surf[i] ? surface[i] : 0.0;
    for (int r = 0; r < w->nrows; r++) p[w->row_of[r]] = sol[r];
    sph_boundary_sync(w, p, 0, 0);
}

/* SELF_TERM: the symmetric gradient's term in p_i itself. The projection moves particle i
 * by -dt (G p)_i with (G p)_i = sum_j m_j (p_i / rho_i^2 + p_j / rho_j^2) grad W_ij, which
 * holds p_i g_i / rho_i^2, g_i = sum_j m_j grad W_ij (zero in a full, even support; not in
 * a disordered or truncated one). The continuity change it makes at i, sph_field_div of that
 * term, is (p_i / rho_i^2) g_i . L_i g_i: a diagonal term of the wide operator D G that the
 * compact Laplacian does not have. Left out, D G = L + K with K >= 0 diagonal; the
 * projection solves with L and leaves (1 - (L + K) / L) of the divergence: on the
 * film-wide pressure mode of a long thin film, where L is small (1 / a^2) and K is not
 * (the stretched lattice's g), that factor is below -1 and the pressure alternates from
 * step to step and grows. So with the symmetric gradient the matrix's diagonal takes
 * m_i g_i . L_i g_i / (rho_i^2 rho0) on fluid rows (the source's scaling: b = m_i
 * sph_field_div(u*) / (rho0 dt)), the whole term (half of it does not stop the mode); the
 * difference form has no such term. */
int sph_pressure_solve(sph_world *w, double dt) {
    int n = w->n, threads = w->threads;
    double rho0 = w->par.rho0;

    /* loaded plates */
    int loaded[SPH_MAX_LOADED], K = 0;
    for (int k = 0; k < w->nplates; k++)
        if (w->plates[k].mode == SPH_PLATE_LOAD) {
            if (K == SPH_MAX_LOADED)
                return sph_world_fail(w, "at most %d plates can be under a load law", SPH_MAX_LOADED);
            loaded[K++] = k;
        }

    /* unknowns */
    int nrows = 0, nsurf = 0, pin = -1;
    for (int i = 0; i < n; i++) {
        if (w->kind[i] == SPH_FLUID && w->surf[i]) nsurf++;
    }
    if (nsurf == 0) { /* closed or periodic domain: pressure is defined up to a constant */
        for (int i = 0; i < n && pin < 0; i++)
            if (w->kind[i] == SPH_FLUID) pin = i;
    }
    if (reserve_rows(w, n)) return -1;
    int floating = mark_unknowns(w, pin);
    for (int i = 0; i < n; i++) w->row[i] = w->row[i] > 0 ? nrows++ : -1;
    w->st.floating_walls = floating;
    for (int i = 0; i < n; i++)
        if (w->row[i] >= 0) w->row_of[w->row[i]] = i;
    w->nrows = nrows;
    w->pin = pin;

    /* structure: one diagonal plus one entry per neighbour with an unknown */
    sph_csr *A = &w->A;
    if (sph_csr_reserve(A, nrows, 1)) return sph_world_fail(w, "out of memory");
    A->start[0] = 0;
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int r = 0; r < nrows; r++) {
        int i = w->row_of[r], c = 1;
        for (int k = w->nb_start[i]; k < w->nb_start[i + 1]; k++) {
            int s = w->src[w->nb_j[k]];
            c += s != i && w->row[s] >= 0;
        }
        A->start[r + 1] = c;
    }
    for (int r = 0; r < nrows; r++) A->start[r + 1] += A->start[r];

    /* the velocity each particle has in the source term (sa, sb), once per particle */
    int ntot = n + w->ng;
    double *svx = w->sa, *svy = w->sb;
    /* The first guess of the flow's solve: p^n (less the loaded plates' parts) plus the
     * change extrapolated from the last two solves' (w->gp, kept below; 0 where a particle
     * was no unknown; sph_guess_weights), as the viscous guess: it saves about a quarter of
     * the pressure iterations a step. */
    double pg, pg1;
    sph_guess_weights(&w->gp, n, dt, &pg, &pg1);
    const double *gd = w->gp.d, *gd1 = w->gp.d1;
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int j = 0; j < ntot; j++) src_velocity(w, j, &svx[j], &svy[j]);
    if (sph_csr_reserve(A, nrows, A->start[nrows]) || sph_solver_reserve(&w->solver, nrows))
        return sph_world_fail(w, "out of memory (pressure matrix)");

#pragma omp parallel for schedule(static) num_threads(threads)
    for (int r = 0; r < nrows; r++) {
        int i = w->row_of[r], e = A->start[r] + 1;
        double mi = w->m[i], rhoi = w->rho[i], diag = 0.0, bsurf = 0.0;
        double sens[SPH_MAX_LOADED] = {0};
        double div = sph_field_div(w, svx, svy, i); /* the source: sum_j m_j (u*_i - u*_j) . L grad W */
        int fl = w->kind[i] == SPH_FLUID;
        double lxx = fl ? w->lxx[i] : 1.0, lxy = fl ? w->lxy[i] : 0.0, lyy = fl ? w->lyy[i] : 1.0;
        int k0 = w->nb_start[i], k1 = w->nb_start[i + 1];
        const int *nj = w->nb_j;
        const double *m = w->m, *ngx = w->nb_gx, *ngy = w->nb_gy;
        for (int q = 0; q < K; q++) { /* loaded plates: d source / d V_q */
            double ax, ay;
            sens_velocity(w, i, loaded[q], &ax, &ay);
            for (int k = k0; k < k1; k++) {
                int j = nj[k];
                double bx, by;
                sens_velocity(w, j, loaded[q], &bx, &by);
                double gx = lxx * ngx[k] + lxy * ngy[k], gy = lxy * ngx[k] + lyy * ngy[k];
                sens[q] += m[j] * ((ax - bx) * gx + (ay - by) * gy);
            }
        }
        /* the matrix row; g = sum_j m_j grad W_ij over all neighbours (own images too) */
        double gx = 0.0, gy = 0.0;
        for (int k = k0; k < k1; k++) {
            int j = nj[k], s = w->src[j];
            gx += m[j] * ngx[k];
            gy += m[j] * ngy[k];
            if (s == i) continue;
            double rs = rhoi + w->rho[j];
            double c = mi * m[j] * 8.0 / (rs * rs) * (-w->nb_f[k]);
            if (w->row[s] >= 0) {
                diag += c;
                A->col[e] = w->row[s];
                A->val[e] = -c;
                e++;
            } else if (w->kind[s] == SPH_FLUID) { /* Dirichlet neighbour, p = n . tau . n */
                diag += c;
                bsurf += c * w->ps[s];
            }
        }
        A->col[A->start[r]] = r;
        if (fl && !w->par.thin_film) /* see SELF_TERM above */
            diag += mi * (gx * (lxx * gx + lxy * gy) + gy * (lxy * gx + lyy * gy)) / (rhoi * rhoi * rho0);
        if (diag <= 0.0) diag = mi; /* isolated: p = 0 */
        A->val[A->start[r]] = diag;
        A->diag[r] = diag;
        /* A = -Laplacian (scaled by m_i): b = -m_i s_i */
        w->b[r] = mi * div / (rho0 * dt) + bsurf;
        for (int q = 0; q < K; q++) w->bk[q][r] = -mi * (-dt * sens[q]) / (rho0 * dt * dt);
        /* warm starts */
        double p0 = w->p[i];
        for (int q = 0; q < K; q++) {
            p0 -= w->plates[loaded[q]].vel * w->psens[q][i];
            w->solk[q][r] = w->psens[q][i];
        }
        w->sol[r] = p0 + pg * gd[i] - pg1 * gd1[i];
    }
    sph_lap(w, SPH_PHASE_PRESSURE_ASSEMBLY);

    if (pin >= 0) sph_pressure_make_compatible(w, w->m[pin] * sph_field_div(w, svx, svy, pin) / (rho0 * dt));

    if (sph_solver_setup_reuse(&w->solver, A, threads, w->row_of, w->id))
        return sph_world_fail(w, "pressure solver: multigrid setup failed at step %ld (t = %g, %d unknowns): "
                              "out of memory or a coarse operator not positive definite", w->steps, w->t, nrows);
    double tol = w->par.tol;
    int iters = 0;
    sph_solve_result res = sph_solver_pcg(&w->solver, A, w->b, w->sol, tol, SPH_SOLVE_MAX_ITER, threads);
    iters += res.iterations;
    if (!res.converged)
        return sph_world_fail(w,
                              "pressure solver did not converge at step %ld (t = %g, dt = %g): "
                              "relative residual %.3g after %d iterations (tolerance %g, %d unknowns)",
                              w->steps, w->t, dt, res.residual, res.iterations, tol, nrows);
    double resid = res.residual;
    for (int q = 0; q < K; q++) {
        sph_solve_result rk = sph_solver_pcg(&w->solver, A, w->bk[q], w->solk[q], tol, SPH_SOLVE_MAX_ITER, threads);
        iters += rk.iterations;
        if (!rk.converged)
            return sph_world_fail(w,
                                  "pressure solver (plate %d sensitivity) did not converge at step "
                                  "%ld (t = %g): residual %.3g after %d iterations",
                                  loaded[q] + 1, w->steps, w->t, rk.residual, rk.iterations);
    }
    w->st.solver_iterations = iters;
    w->st.solver_residual = resid;
    w->st.solver_iterations_total += iters;
    w->st.unknowns = nrows;
    sph_lap(w, SPH_PHASE_PRESSURE_SOLVE);

    /* plates: pressure forces, loaded plates' velocities */
    double F0[SPH_MAX_PLATES], Fk[SPH_MAX_LOADED][SPH_MAX_PLATES];
    double *chg = sph_guess_keep(&w->gp, n, dt);
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int i = 0; i < n; i++) { /* the change this solve made, for the next one's guess */
        int r = w->row[i];
        double p0 = w->p[i];
        for (int q = 0; q < K; q++) p0 -= w->plates[loaded[q]].vel * w->psens[q][i];
        chg[i] = r >= 0 ? w->sol[r] - p0 : 0.0;
    }
    sph_pressure_scatter(w, w->sol, w->p, w->ps);
    sph_plate_pressure_force(w, w->p, F0);
    if (K > 0) {
        double x[SPH_MAX_LOADED];
        for (int q = 0; q < K; q++) {
            sph_pressure_scatter(w, w->solk[q], w->psens[q], 0);
            sph_plate_pressure_force(w, w->psens[q], Fk[q]);
        }
        if (sph_plate_loaded_velocities(w, dt, K, loaded, F0, Fk, x)) return -1;
        int nt = n + w->ng;
        for (int i = 0; i < nt; i++) {
            double pi = w->p[i];
            for (int q = 0; q < K; q++) pi += x[q] * w->psens[q][i];
            w->p[i] = pi;
        }
        sph_plate_pressure_force(w, w->p, F0);
    }
    for (int k = 0; k < w->nplates; k++) w->plates[k].force = F0[k] + w->plates[k].force_visc;
    return 0;
}

/* -(grad f)_i / rho_i in the symmetric, momentum-conserving form
 * -sum_j m_j (f_i / rho_i^2 + f_j / rho_j^2) grad_i W_ij (f synced on ghosts).
 * fr holds f / rho^2 per particle; sph_neg_grad (internal.h) takes the sum. */
void sph_pressure_neg_grad_prepare(sph_world *w, const double *f, double *fr) {
    int nt = w->n + w->ng;
#pragma omp parallel for schedule(static) num_threads(w->threads)
    for (int j = 0; j < nt; j++) fr[j] = f[j] / (w->rho[j] * w->rho[j]);
}

/* -grad p~ / rho of every fluid particle for the viscous step's pressure predictor
 * (sph_pressure_predictor, below), p~ the last step's pressure at the current positions,
 * kernel-averaged (Shepard) over fluid and wall particles and held at n . tau . n on the
 * free surface, its gradient the renormalised difference form
 * L sum_j V_j (p~_j - p~_i) grad W_ij. The average keeps particle-scale pressure modes out
 * of the predictor: where the viscous solve is stiff (dt eta / (rho dx^2) >> 1) it returns
 * almost nothing of a particle-scale force, so what the predictor takes back is the whole
 * force, whose divergence makes the next pressure: a loop with the gain of DG / L on those
 * modes, above 1 on some. With p^n itself the stiff cases of the stability suite (Bn = 100
 * under a load, Re = 0.01) lose their density control. */
/* pt = p kernel-averaged (Shepard) over fluid and active wall particles, p itself on the free
 * surface (n . tau . n) and on inactive walls (p and pt synced on ghosts). */
static void shepard(sph_world *w, double *p, double *pt) {
    int n = w->n;
    double h = w->h, w0 = sph_kernel_value(0.0, h);
    sph_boundary_sync(w, p, 0, 0);
#pragma omp parallel for schedule(static) num_threads(w->threads)
    for (int i = 0; i < n; i++) {
        if (!w->active[i] || (w->kind[i] == SPH_FLUID && w->surf[i])) {
            /* free surface: its n . tau . n (0 where it holds p = 0, whatever this particle's
             * pressure was before it came to the surface); inactive walls: not a pressure */
            pt[i] = w->kind[i] == SPH_FLUID && !sph_surface_traction(w) ? 0.0 : p[i];
            continue;
        }
        double s = w->vol[i] * w0, sp = s * p[i];
        const int *nj = w->nb_j, *src = w->src;
        const double *vol = w->vol, *nw = w->nb_w;
        const unsigned char *act = w->active;
        int k0 = w->nb_start[i], k1 = w->nb_start[i + 1];
#pragma omp simd reduction(+ : s, sp)
        for (int k = k0; k < k1; k++) {
            int j = nj[k];
            /* wall particles outside the pressure system hold p = 0, not a pressure: out;
             * W_ij from the neighbour build (the positions have not moved since) */
            double c = act[src[j]] * vol[j] * nw[k];
            s += c;
            sp += c * p[j];
        }
        pt[i] = sp / s;
    }
    sph_boundary_sync(w, pt, 0, 0);
}

void sph_pressure_predictor(sph_world *w, double *ax, double *ay) {
    int n = w->n;
    double *pt = w->dp;
    shepard(w, w->p, pt);
#pragma omp parallel for schedule(static) num_threads(w->threads)
    for (int i = 0; i < n; i++)
        if (w->kind[i] == SPH_FLUID) sph_neg_grad_difference(w, pt, i, &ax[i], &ay[i]);
}

/* Continuity over the step, rho_i += dt * sph_field_div(u^{n+1}) for interior fluid;
 * free-surface particles are reset to rho0. Returns the max |rho / rho0 - 1| over interior
 * fluid. (The density passes apply their own change, scaled by their step length.) */
static double advance_density(sph_world *w, const double *ax, const double *ay, double dt) {
    int n = w->n;
    double rho0 = w->par.rho0, maxerr = 0.0;
#pragma omp parallel for schedule(static) num_threads(w->threads) reduction(max : maxerr)
    for (int i = 0; i < n; i++) {
        if (w->kind[i] != SPH_FLUID) continue;
        if (w->surf[i]) {
            w->rho[i] = rho0;
            continue;
        }
        w->rho[i] += dt * sph_field_div(w, ax, ay, i);
        double e = fabs(w->rho[i] / rho0 - 1.0);
        if (e > maxerr) maxerr = e;
    }
    return maxerr;
}

/* u^{n+1} = u* - dt (grad p / rho); continuity with u^{n+1}; x^{n+1} = x^n + dt (u^n + u^{n+1}) / 2.
 * The gradient is the symmetric form by default; the thin-film scheme takes the
 * renormalised difference form (see sph.h and the thin-film notes at the top). The plate
 * force is the symmetric sum of the fluid-wall pairs either way: a measure of the pressure
 * on the plate's face. */
void sph_pressure_correct(sph_world *w, double dt) {
    int n = w->n, diff = w->par.thin_film;
    if (!diff) sph_pressure_neg_grad_prepare(w, w->p, w->sa);
#pragma omp parallel for schedule(static) num_threads(w->threads)
    for (int i = 0; i < n; i++) {
        if (w->kind[i] != SPH_FLUID) {
            sph_plate_rigid_velocity(w, i, &w->us[i], &w->vs[i]);
            continue;
        }
        double au, av;
        if (diff) sph_neg_grad_difference(w, w->p, i, &au, &av);
        else sph_neg_grad(w, w->sa, i, &au, &av);
        w->us[i] += dt * au;
        w->vs[i] += dt * av;
    }
    sph_boundary_sync(w, w->us, w->vs, 1);
    w->st.max_density_error = advance_density(w, w->us, w->vs, dt);
#pragma omp parallel for schedule(static) num_threads(w->threads)
    for (int i = 0; i < n; i++) {
        if (w->kind[i] != SPH_FLUID) continue;
        w->ax[i] = (w->us[i] - w->u[i]) / dt;
        w->ay[i] = (w->vs[i] - w->v[i]) / dt;
        w->x[i] += 0.5 * dt * (w->u[i] + w->us[i]);
        w->y[i] += 0.5 * dt * (w->v[i] + w->vs[i]);
        w->u[i] = w->us[i];
        w->v[i] = w->vs[i];
    }
}

