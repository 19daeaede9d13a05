/* Rheology and the viscous step.
 * Velocity gradient: grad u_i = sum_j V_j (u_j - u_i) (x) grad_i W_ij, with a wall
 * neighbour's velocity taken from the no-slip extrapolation; shear rate
 * gammadot = sqrt(1/2 D:D), D = grad u + grad u^T; apparent viscosity from the material law.
 * The free surface is traction-free (surface_pressure, transpose_accel).
 * Viscous acceleration (Morris, Fox & Zhu 1997):
 *   (1/rho div eta grad u)_i = sum_j m_j (eta_i + eta_j) F_ij / (rho_i rho_j) (u_i - u_j),
 *   F_ij = r_ij . grad_i W_ij / (r_ij^2 + eps^2). */
#include "internal.h"

#include <math.h>

/* grad u of the field (u, v) at fluid particle i, g = {du/dx, du/dy, dv/dx, dv/dy}: a wall
 * neighbour's velocity from the no-slip extrapolation, renormalised (grad u = (sum V du (x)
 * grad W) L), first-order consistent next to a free surface where the support is truncated. */
static inline void velocity_gradient(const sph_world *w, int i, const double *u, const double *v, double g[4]) {
    double uxx = 0, uxy = 0, uyx = 0, uyy = 0; /* uab = d u_a / d x_b */
    double ui = u[i], vi = v[i];
    int k0 = w->nb_start[i], km = w->nb_mid[i], k1 = w->nb_start[i + 1];
    const int *nj = w->nb_j;
    const double *gxk = w->nb_gx, *gyk = w->nb_gy, *vol = w->vol;
#pragma omp simd reduction(+ : uxx, uxy, uyx, uyy)
    for (int k = k0; k < km; k++) { /* fluid neighbours */
        int j = nj[k];
        double du = vol[j] * (u[j] - ui), dv = vol[j] * (v[j] - vi);
        uxx += du * gxk[k];
        uxy += du * gyk[k];
        uyx += dv * gxk[k];
        uyy += dv * gyk[k];
    }
    for (int k = km; k < k1; k++) { /* walls: the no-slip extrapolation */
        int j = nj[k];
        double wx, wy, beta = sph_plate_noslip(w, i, j);
        sph_plate_wall_velocity(w, j, &wx, &wy);
        double du = -vol[j] * beta * (ui - wx), dv = -vol[j] * beta * (vi - wy);
        uxx += du * gxk[k];
        uxy += du * gyk[k];
        uyx += dv * gxk[k];
        uyy += dv * gyk[k];
    }
    double lxx = w->lxx[i], lxy = w->lxy[i], lyy = w->lyy[i];
    g[0] = uxx * lxx + uxy * lxy;
    g[1] = uxx * lxy + uxy * lyy;
    g[2] = uyx * lxx + uyy * lxy;
    g[3] = uyx * lxy + uyy * lyy;
}

/* The stretching t . grad u . t along the free surface at particle i (the tangent t of the
 * support's boundary moment g_i; 0 where g_i = 0). At a traction-free surface tau_nt = 0 and,
 * incompressible, D_nn = -D_tt: n . tau . n = -2 eta e.
 * Unlike the normal rate du_n/dn it holds nothing of the particle's own normal velocity (its
 * weight in the renormalised gradient lies along g). */
static inline double surface_stretching(const sph_world *w, int i, const double g[4]) {
    double nx, ny;
    sph_boundary_moment(w, i, &nx, &ny);
    double nn = hypot(nx, ny);
    if (!(nn > 0.0)) return 0.0;
    double tx = -ny / nn, ty = nx / nn;
    return tx * tx * g[0] + tx * ty * (g[1] + g[2]) + ty * ty * g[3];
}

void sph_viscous_rheology(sph_world *w) {
    int n = w->n;
#pragma omp parallel for schedule(static) num_threads(w->threads)
    for (int i = 0; i < n; i++) {
        if (w->kind[i] != SPH_FLUID) continue;
        double g[4];
        velocity_gradient(w, i, w->u, w->v, g);
        w->gux[i] = g[0];
        w->guy[i] = g[1];
        w->gvx[i] = g[2];
        w->gvy[i] = g[3];
        double dxx = 2 * g[0], dyy = 2 * g[3], dxy = g[1] + g[2];
        double gd = sqrt(0.5 * (dxx * dxx + dyy * dyy + 2 * dxy * dxy));
        w->gd[i] = gd;
        w->eta[i] = sph_rheology_eta(&w->mats[w->mat[i]], gd);
    }
    sph_boundary_sync(w, w->eta, w->gd, 0);
}


/* The free surface is traction-free, sigma . n = 0 with sigma = -p I + tau (PHYSICS.md): its
 * normal part holds a free-surface particle at p = n . tau . n = -2 eta e, e the surface
 * stretching of (u, v) = u* before the pressure predictor's term is taken back
 * (sph_viscous_implicit), the viscous solution under the predicted pressure (on the square
 * at Re = 0.05 it gives the side pressure of FE within 3 %), eta the apparent viscosity of
 * the rheology pass (for a yielded Bingham side, p = tau0 + mu gammadot: FE's side sits at
 * 10.4-12.9 for Bn = 10, and without it the plate force is half FE's). Not the particle's
 * normal rate, which holds its own velocity (its pressure then drives it, and the run
 * diverges), nor u* after the take-back (it holds + dt grad p~ / rho). The value is explicit
 * in eta: stable for dt up to the surface's viscous time dt_s = C_s rho h^2 / eta, which
 * bounds dt for a Newtonian surface (timestep.c). A viscoplastic surface's eta is larger by
 * tau0 / gammadot and would hold dt to a few 1e-6; past dt_s the pressure moves from p^n
 * towards -2 eta e by the fraction dt_s / dt (a relaxation over dt^2 / dt_s, a few steps),
 * which keeps the explicit step's gain at its stable limit. The fraction is at least
 * mu / eta: the step criterion already holds the material's mu part (a Newtonian surface
 * is never relaxed, also where the criterion saw last step's flags). The law at u*,
 * eta(gammadot*) for the lagged eta, is noisier: square Bn = 10 at 0.94 / 0.89 of FE at
 * dx = 1/20, 1/40. */
static void surface_pressure(sph_world *w, const double *u, const double *v, double dt) {
    int n = w->n;
#pragma omp parallel for schedule(static) num_threads(w->threads)
    for (int i = 0; i < n; i++) {
        if (w->kind[i] != SPH_FLUID || !w->surf[i]) continue;
        if (!sph_surface_traction(w)) {
            w->ps[i] = 0.0;
            continue;
        }
        double g[4];
        velocity_gradient(w, i, u, v, g);
        double e = surface_stretching(w, i, g);
        /* relaxed towards -2 eta e where dt exceeds the surface's viscous time */
        double eta = w->eta[i], target = -2.0 * eta * e;
        double al = fmax(SPH_SURFACE_CS * w->rho[i] * w->h * w->h / (eta * dt), w->mats[w->mat[i]].mu / eta);
        w->ps[i] = al < 1.0 ? w->p[i] + al * (target - w->p[i]) : target;
    }
}

/* div(eta grad u^T)_i / rho_i, the part of div tau = div(eta (grad u + grad u^T)) that the
 * Morris sum (div eta grad u) leaves out, explicit from the rheology pass's gradient (u^n),
 * in the symmetric form sum_j V_j (T_i + T_j) . grad W_ij, T_ab = eta du_a/dx_b. Over a
 * truncated support the symmetric pressure gradient pushes a particle out by 2 p |g| / rho
 * (g = sum_j V_j grad W_ij) and the Morris sum pulls it in by 2 |g| eta du/dn / rho, the flux
 * of div eta grad u (half-plane moments): the traction-free p = n . tau . n = 2 eta du_n/dn
 * balances that pull only with this term's 2 |g| eta grad(u . n) / rho; without it the
 * surface row runs outwards too fast (1.7 times FE's speed on the square at Re = 0.05).
 * Away from it the term is zero for constant eta (div u = 0), so it is taken only within a
 * support of the free surface; taken everywhere it adds only the kernel sums' noise (the
 * closed cavity's error against Ghia grows by a fifth). With surface_pressure (the symmetric
 * pressure gradient, whose push it balances), with the same apparent viscosity. Walls carry
 * T_i (the gradient continued into the plate): no boundary term there. Images: T_ab times
 * s_a s_b. */
static void transpose_accel(const sph_world *w, int i, double *ax, double *ay) {
    int k0 = w->nb_start[i], km = w->nb_mid[i], k1 = w->nb_start[i + 1];
    *ax = *ay = 0.0;
    if (!sph_surface_traction(w)) return;
    int need = w->surf[i]; /* a free-surface particle in the support */
    for (int k = k0; k < km && !need; k++) need = w->surf[w->src[w->nb_j[k]]];
    if (!need) return;
    double ei = w->eta[i];
    double txx = ei * w->gux[i], txy = ei * w->guy[i], tyx = ei * w->gvx[i], tyy = ei * w->gvy[i];
    double fx = 0.0, fy = 0.0; /* (div T)_b = d_a T_ab */
    for (int k = k0; k < km; k++) {
        int j = w->nb_j[k], s = w->src[j];
        double sg = w->gsx[j] * w->gsy[j], c = w->vol[j];
        double es = w->eta[s];
        double sxx = txx + es * w->gux[s], sxy = txy + sg * es * w->guy[s];
        double syx = tyx + sg * es * w->gvx[s], syy = tyy + es * w->gvy[s];
        fx += c * (sxx * w->nb_gx[k] + syx * w->nb_gy[k]);
        fy += c * (sxy * w->nb_gx[k] + syy * w->nb_gy[k]);
    }
    for (int k = km; k < k1; k++) {
        double c = 2.0 * w->vol[w->nb_j[k]];
        fx += c * (txx * w->nb_gx[k] + tyx * w->nb_gy[k]);
        fy += c * (txy * w->nb_gx[k] + tyy * w->nb_gy[k]);
    }
    *ax = fx / w->rho[i];
    *ay = fy / w->rho[i];
}

/* The Morris coefficient of fluid pair k (i, j): c = m_j (eta_i + eta_j) F_ij / (rho_i rho_j),
 * as V_j (eta_i + eta_j) F_ij / rho_i with V_j = m_j / rho_j (w->vol, set by the
 * neighbour build: the density has not changed since). */
static inline double fluid_coeff(const sph_world *w, int i, int j, int k) {
    return w->vol[j] * (w->eta[i] + w->eta[j]) * w->nb_f[k] / w->rho[i];
}

/* A wall neighbour j (pair k) of fluid particle i enters the Morris sum as
 * cw (u_i - u_wall), cw = beta m_j 2 eta_i F_ij / (rho_i rho_j), beta the no-slip factor;
 * returns cw and the wall velocity. */
static inline double wall_coeff(const sph_world *w, int i, int j, int k, double *wx, double *wy) {
    sph_plate_wall_velocity(w, j, wx, wy);
    return sph_plate_noslip(w, i, j) * w->vol[j] * 2.0 * w->eta[i] * w->nb_f[k] / w->rho[i];
}

/* u* = u + dt (viscous + g) for fluid; walls keep the plate velocity. The viscous force
 * each plate takes from the fluid is accumulated on the way (whole sample). */
void sph_viscous_explicit(sph_world *w, double dt) {
    int n = w->n;
    double gx = w->par.gravity[0], gy = w->par.gravity[1];
    double fplate[SPH_MAX_PLATES] = {0};
#pragma omp parallel for schedule(static) num_threads(w->threads) reduction(+ : fplate[:SPH_MAX_PLATES])
    for (int i = 0; i < n; i++) {
        if (w->kind[i] != SPH_FLUID) {
            sph_plate_wall_velocity(w, i, &w->us[i], &w->vs[i]);
            continue;
        }
        double ui = w->u[i], vi = w->v[i];
        double au = 0, av = 0, ei = w->eta[i];
        int k0 = w->nb_start[i], km = w->nb_mid[i], k1 = w->nb_start[i + 1];
        const int *nj = w->nb_j;
        const double *nf = w->nb_f, *vol = w->vol, *eta = w->eta, *u = w->u, *v = w->v;
#pragma omp simd reduction(+ : au, av)
        for (int k = k0; k < km; k++) { /* fluid: c V_j (eta_i + eta_j) F_ij (u_i - u_j), c = 1 / rho_i below */
            int j = nj[k];
            double c = vol[j] * (ei + eta[j]) * nf[k];
            au += c * (ui - u[j]);
            av += c * (vi - v[j]);
        }
        double ri = 1.0 / w->rho[i];
        au *= ri;
        av *= ri;
        for (int k = km; k < k1; k++) { /* walls */
            int j = nj[k];
            double wx, wy, c = wall_coeff(w, i, j, k, &wx, &wy);
            double du = ui - wx, dv = vi - wy;
            fplate[w->kind[j]] += sph_plate_pull(w, i, j, c, ui, vi, wx, wy);
            au += c * du;
            av += c * dv;
        }
        double fx, fy;
        transpose_accel(w, i, &fx, &fy);
        w->us[i] = ui + dt * (au + gx + fx);
        w->vs[i] = vi + dt * (av + gy + fy);
    }
    sph_plate_set_viscous_forces(w, fplate);
    sph_boundary_sync(w, w->us, w->vs, 1);
    surface_pressure(w, w->us, w->vs, dt);
}

/* Implicit viscous step: for each velocity component,
 *   u*_i - dt sum_j c_ij (u*_i - u*_j) = u_i + dt g,  c_ij = m_j (eta_i + eta_j) F_ij / (rho_i rho_j),
 * with eta lagged from u^n and the same Morris operator as the explicit step: a wall
 * neighbour enters as beta (u*_i - u_wall) (its plate's velocity this step, known), a ghost
 * as its source's unknown times the image sign (a mirror reverses the normal component, so
 * the u and v systems differ in those entries), a particle's own mirror image as a diagonal
 * term. F_ij < 0, so the matrix is an M-matrix; scaling row i by m_i makes it symmetric
 * (m_i c_ij is symmetric in i, j), and CG solves it from visc_guess's first guess,
 * preconditioned by the multigrid cycle, both components at once.
 * The time step then does not depend on the viscosity but for the explicit free-surface
 * stress (timestep.c). */
static int reserve_visc(sph_world *w, int nrows) {
    if (nrows <= w->vrows_cap && w->vb) return 0;
    int cap = nrows + nrows / 4 + 64;
    if (sph_grow((void **)&w->vb, sizeof(double), cap) || sph_grow((void **)&w->vsol, sizeof(double), cap) ||
        sph_grow((void **)&w->vdiag, sizeof(double), cap) || sph_grow((void **)&w->vrhs, sizeof(double), cap) ||
        sph_grow((void **)&w->vrow_of, sizeof(int), cap))
        return sph_world_fail(w, "out of memory (%d viscous unknowns)", nrows);
    w->vrows_cap = cap;
    return 0;
}

/* Values and right-hand sides of both components; the structure is in w->V. Both have the
 * same coefficients; they differ only by the image signs of ghosts (gsx, gsy), the wall
 * velocity and the gravity: u's values, diagonal and right-hand side go to w->V and w->vb,
 * v's to vval, vdiag and vrhs. */
static void visc_assemble(sph_world *w, double dt) {
    sph_csr *A = &w->V;
    int nrows = A->n;
    /* the pressure predictor (pressure.c): -grad p~ / rho as a body force */
    double gx = w->par.gravity[0], gy = w->par.gravity[1];
    sph_pressure_predictor(w, w->xs, w->ys);
#pragma omp parallel for schedule(static) num_threads(w->threads)
    for (int r = 0; r < nrows; r++) {
        int i = w->vrow_of[r], e = A->start[r] + 1;
        double mi = w->m[i];
        double du = 1.0, dv = 1.0, ru = w->u[i] + dt * gx, rv = w->v[i] + dt * gy;
        ru += dt * w->xs[i];
        rv += dt * w->ys[i];
        double fx, fy; /* the transpose part of div tau (explicit) */
        transpose_accel(w, i, &fx, &fy);
        ru += dt * fx;
        rv += dt * fy;
        int k0 = w->nb_start[i], km = w->nb_mid[i], k1 = w->nb_start[i + 1];
        double ei = w->eta[i], dr = dt / w->rho[i];
        for (int k = k0; k < km; k++) { /* fluid: c = dt V_j (eta_i + eta_j) F_ij / rho_i */
            int j = w->nb_j[k], s = w->src[j];
            double c = dr * (w->vol[j] * (ei + w->eta[j]) * w->nb_f[k]);
            double sx = w->gsx[j], sy = w->gsy[j];
            du -= c;
            dv -= c;
            if (s == i) { /* own image: c (u_i - sg u_i) */
                du += c * sx;
                dv += c * sy;
            } else {
                A->col[e] = w->row[s];
                A->val[e] = mi * c * sx;
                w->vval[e] = mi * c * sy;
                e++;
            }
        }
        for (int k = km; k < k1; k++) { /* walls */
            int j = w->nb_j[k];
            double wx, wy, c = dt * wall_coeff(w, i, j, k, &wx, &wy);
            du -= c;
            dv -= c;
            ru -= c * wx;
            rv -= c * wy;
        }
        int d = A->start[r];
        A->col[d] = r;
        A->val[d] = mi * du;
        A->diag[r] = mi * du;
        w->vval[d] = mi * dv;
        w->vdiag[r] = mi * dv;
        w->vb[r] = mi * ru;
        w->vrhs[r] = mi * rv;
        w->vsol[r] = w->u[i];
    }
    sph_lap(w, SPH_PHASE_VISC_ASSEMBLY);
}

/* The first guess of the viscous solve (sph_guess_weights): u^n plus the change u* - u^n
 * extrapolated from the last two steps' (w->gu, w->gv; every fluid particle is a row, so a
 * row's entries are always from those steps); else u^n (visc_assemble). comp 0: u into x,
 * 1: v into x. The two-step extrapolation needs a third of the iterations a start from u^n
 * takes. */
static void visc_guess(const sph_world *w, double dt, int comp, double *x) {
    const sph_guess *g = comp ? &w->gv : &w->gu;
    double a, b;
    sph_guess_weights(g, w->n, dt, &a, &b);
    if (a == 0.0) return;
    const double *d = g->d, *d1 = g->d1;
    int nrows = w->V.n;
#pragma omp parallel for schedule(static) num_threads(w->threads)
    for (int r = 0; r < nrows; r++) {
        int i = w->vrow_of[r];
        x[r] += a * d[i] - b * d1[i];
    }
}

/* Keeps this solve's change u* - u^n for the next steps' guesses. */
static void visc_keep(sph_world *w, double dt, int comp, const double *x) {
    double *d = sph_guess_keep(comp ? &w->gv : &w->gu, w->n, dt);
    const double *u = comp ? w->v : w->u;
    int nrows = w->V.n;
#pragma omp parallel for schedule(static) num_threads(w->threads)
    for (int r = 0; r < nrows; r++) {
        int i = w->vrow_of[r];
        d[i] = x[r] - u[i];
    }
}

int sph_viscous_implicit(sph_world *w, double dt) {
    int n = w->n, nrows = 0;
    /* one unknown per fluid particle; row[] is borrowed (the pressure system rebuilds it) */
    for (int i = 0; i < n; i++) w->row[i] = w->kind[i] == SPH_FLUID ? nrows++ : -1;
    if (reserve_visc(w, nrows)) return -1;
    for (int i = 0; i < n; i++)
        if (w->row[i] >= 0) w->vrow_of[w->row[i]] = i;

    sph_csr *A = &w->V;
    if (sph_csr_reserve(A, nrows, 1)) return sph_world_fail(w, "out of memory");
    A->start[0] = 0;
#pragma omp parallel for schedule(static) num_threads(w->threads)
    for (int r = 0; r < nrows; r++) { /* the row's length: diagonal + fluid neighbours but its images */
        int i = w->vrow_of[r], c = 1;
        for (int k = w->nb_start[i]; k < w->nb_mid[i]; k++) c += w->src[w->nb_j[k]] != i;
        A->start[r + 1] = c;
    }
    for (int r = 0; r < nrows; r++) A->start[r + 1] += A->start[r];
    if (A->start[nrows] > w->vval_cap) { /* component 1's values (visc_assemble) */
        int cap = A->start[nrows] + A->start[nrows] / 4 + 64;
        if (sph_grow((void **)&w->vval, sizeof(double), cap))
            return sph_world_fail(w, "out of memory (viscous matrix)");
        w->vval_cap = cap;
    }
    if (sph_csr_reserve(A, nrows, A->start[nrows]) || sph_solver_reserve(&w->solver, nrows))
        return sph_world_fail(w, "out of memory (viscous matrix)");

    /* Both components at once: u's system in A, v's in a view of A's structure with v's
     * values (visc_assemble keeps them in vval, vdiag, vrhs), its solution in the solver's
     * x2. One multigrid setup for both: their matrices differ only in the entries of mirror
     * images, and the hierarchy stays a valid preconditioner; the finest level's smoother
     * takes each component's own values (with u's, v's solve takes about a third more
     * iterations: the images' entries change sign). sph_solver_pcg2 reads the structure
     * once for both in CG's product and the cycle, each component's iterates as when solved
     * alone (the same figures bit for bit). The hierarchy is reused across steps by the
     * pressure solve's rules (solver.c, "Reuse across steps"), the finest smoother rebuilt
     * from both components' values each step. */
    int iters = 0;
    double resid = 0.0;
    visc_assemble(w, dt);
    sph_csr V2 = *A;
    V2.val = w->vval;
    V2.diag = w->vdiag;
    double *x2 = w->solver.x2;
    for (int r = 0; r < nrows; r++) x2[r] = w->v[w->vrow_of[r]];
    visc_guess(w, dt, 0, w->vsol);
    visc_guess(w, dt, 1, x2);
    if (sph_solver_setup_pair(&w->solver, A, &V2, w->threads, w->vrow_of, w->id))
        return sph_world_fail(w, "viscous solver: multigrid setup failed at step %ld (t = %g, %d unknowns): "
                              "out of memory or a coarse operator not positive definite", w->steps, w->t, nrows);
    sph_solver_vcycle(&w->solver, A); /* a V-cycle for these systems (solver.c) */
    sph_solve_result res[2];
    sph_solver_pcg2(&w->solver, A, &V2, w->vb, w->vrhs, w->vsol, x2, w->par.tol, SPH_SOLVE_MAX_ITER, w->threads,
                    res);
    for (int comp = 0; comp < 2; comp++) {
        if (!res[comp].converged)
            return sph_world_fail(w,
                                  "viscous solver (%s) did not converge at step %ld (t = %g, dt = %g): "
                                  "relative residual %.3g after %d iterations (tolerance %g, %d unknowns)",
                                  comp ? "v" : "u", w->steps, w->t, dt, res[comp].residual, res[comp].iterations,
                                  w->par.tol, nrows);
        iters += res[comp].iterations;
        if (res[comp].residual > resid) resid = res[comp].residual;
    }
    for (int r = 0; r < nrows; r++) {
        w->us[w->vrow_of[r]] = w->vsol[r];
        w->vs[w->vrow_of[r]] = x2[r];
    }
    visc_keep(w, dt, 0, w->vsol);
    visc_keep(w, dt, 1, x2);
    sph_lap(w, SPH_PHASE_VISC_SOLVE);
    w->st.visc_iterations = iters;
    w->st.visc_residual = resid;

    sph_boundary_sync(w, w->us, w->vs, 1);
    surface_pressure(w, w->us, w->vs, dt); /* the viscous solution, before the take-back */
    /* walls keep their plate's velocity; the viscous force on each plate from u* */
    /* then the pressure predictor's term taken back: the projection applies the whole
     * -grad p^{n+1} / rho (the plates' viscous force is that of u* with it) */
    double fplate[SPH_MAX_PLATES] = {0};
#pragma omp parallel for schedule(static) num_threads(w->threads) reduction(+ : fplate[:SPH_MAX_PLATES])
    for (int i = 0; i < n; i++) {
        if (w->kind[i] != SPH_FLUID) {
            sph_plate_wall_velocity(w, i, &w->us[i], &w->vs[i]);
            continue;
        }
        for (int k = w->nb_mid[i]; k < w->nb_start[i + 1]; k++) { /* walls */
            int j = w->nb_j[k];
            if (w->plates[w->kind[j]].axis < 0) continue;
            double wx, wy, cw = wall_coeff(w, i, j, k, &wx, &wy);
            fplate[w->kind[j]] += sph_plate_pull(w, i, j, cw, w->us[i], w->vs[i], wx, wy);
        }
        w->us[i] -= dt * w->xs[i];
        w->vs[i] -= dt * w->ys[i];
    }
    sph_plate_set_viscous_forces(w, fplate);
    sph_boundary_sync(w, w->us, w->vs, 1);
    return 0;
}
