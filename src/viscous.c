/* Rheology and the viscous step.
 * Velocity gradient: grad u_i = sum_j V_j (u_j - u_i) (x) grad_i W_ij, with a wall
 * neighbour's velocity taken from the no-slip extrapolation; shear rate
 * gammadot = sqrt(2 d:d), d the deviatoric part of (grad u + grad u^T) / 2.
 * Viscous acceleration (Morris, Fox & Zhu 1997), implicit, with the operator's viscosity
 * visc (the material's mu for a Newtonian one):
 *   (1/rho div visc grad u)_i = sum_j m_j (visc_i + visc_j) F_ij / (rho_i rho_j) (u_i - u_j),
 *   F_ij = r_ij . grad_i W_ij / r_ij^2.
 * A viscoplastic material's stress is carried by an augmented-Lagrangian multiplier lam
 * (Glowinski & Le Tallec 1989; Saramito & Wachs 2017 review it for yield-stress fluids),
 * one iteration a step (sph_viscous_rheology): the implicit operator holds r = visc, the rest
 * of the stress, S = lam - 2 r gamma, is explicit. The free surface is traction-free
 * (surface_pressure, transpose_accel). */
#include "internal.h"
#include "kernel.h"

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
        int j = nj[k], nrm;
        double wx, wy, beta = sph_plate_noslip(w, i, j, &nrm);
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

/* The augmented-Lagrangian update of a viscoplastic particle (Glowinski & Le Tallec 1989,
 * ALG2, one iteration per step). With d the deviatoric rate and lam the multiplier (a
 * stress), Q = lam + 2 r d; the constitutive rate gamma (parallel to Q) solves
 * tau(g) + r g = |Q| (|A| = sqrt(A:A / 2), g = sqrt(2 gamma:gamma); sph_rheology_prox),
 * lam <- tau(g) Q / |Q|, the law's stress at gamma. Where |Q| < tau0 the rate comes out below
 * the Papanastasiou scale 1 / m: the particle is unyielded from a stress, not from a rate
 * that the particles' noise keeps above 1 / m (with the apparent viscosity eta(gammadot) of
 * the rate itself, the square at Bn = 10 showed no unyielded particle at any dx).
 * r: the geometric mean of the law's tangent and secant viscosities at the last step's rate
 * (a stress-controlled mode converges at the rate r / (tangent + r) per step, the direction
 * of the stress at secant / (secant + r)); at most the secant at the present rate (a rate
 * that jumped, as at an impulsive start, would leave S = lam - 2 r gamma large and of the
 * wrong sign) and at most SPH_ALM_CAP rho h^2 / dt (internal.h). */

static void plastic_update(sph_world *w, int i, double exx, double exy, double dt) {
    const sph_material *mt = &w->mats[w->mat[i]];
    double gp = w->gd[i], sl, tp = sph_rheology_stress(mt, gp, &sl);
    double sec = gp > 0 ? tp / gp : sph_rheology_eta(mt, 0.0);
    double gnow = 2.0 * hypot(exx, exy), mu = mt->model == SPH_BINGHAM ? mt->mu : 0.0;
    double r = fmax(fmin(fmin(sqrt(sl * sec), sph_rheology_eta(mt, gnow)), SPH_ALM_CAP * w->rho[i] * w->h * w->h / dt), mu);
    double qxx = w->lamxx[i] + 2.0 * r * exx, qxy = w->lamxy[i] + 2.0 * r * exy, q = hypot(qxx, qxy);
    double g = sph_rheology_prox(mt, q, r, gp), tg = sph_rheology_stress(mt, g, 0);
    double nx = q > 0 ? qxx / q : 0.0, ny = q > 0 ? qxy / q : 0.0;
    w->lamxx[i] = tg * nx;
    w->lamxy[i] = tg * ny;
    w->sxx[i] = (tg - r * g) * nx;
    w->sxy[i] = (tg - r * g) * ny;
    w->gd[i] = g;
    w->eta[i] = g > 0 ? tg / g : sph_rheology_eta(mt, 0.0);
    w->visc[i] = r;
}

/* The unit normal of free-surface particle i (sph_boundary_moment normalised); 0 where the
 * moment vanishes. */
static int surface_normal(const sph_world *w, int i, double *nx, double *ny) {
    sph_boundary_moment(w, i, nx, ny);
    double nn = hypot(*nx, *ny);
    if (!(nn > 0.0)) return 0;
    *nx /= nn;
    *ny /= nn;
    return 1;
}

/* The deviatoric rate averaged (kernel weights) over the fluid neighbours of particle i off
 * the surface: a surface particle's rate where the surface holds p = 0 (thin_film), which
 * is not traction-free, so that the form below does not hold there (with it the Bingham
 * thin film at dx = 1/30 came 0.7 % further from thin-film theory, 0.9658 against 0.9727). */
static void inner_rate(const sph_world *w, int i, double *exx, double *exy) {
    double s0 = 0.0, a = 0.0, b = 0.0;
    for (int k = w->nb_start[i]; k < w->nb_mid[i]; k++) {
        int j = w->nb_j[k], q = w->src[j];
        if (w->surf[q]) continue;
        double c = w->vol[j] * w->nb_w[k];
        s0 += c;
        a += c * 0.5 * (w->gux[q] - w->gvy[q]);
        b += c * w->gsx[j] * w->gsy[j] * 0.5 * (w->guy[q] + w->gvx[q]);
    }
    if (s0 > 0) {
        *exx = a / s0;
        *exy = b / s0;
    }
}

/* At a particle of a traction-free surface: the deviatoric rate of such a surface, e (t t - n n)
 * (tau_nt = 0, and incompressible D_nn = -D_tt), with e its stretching (surface_stretching)
 * averaged with kernel weights over itself and its free-surface neighbours. A plastic surface
 * holds p = n . tau . n = +-tau0 by the sign of e. The stretching along the surface holds
 * nothing of the surface particles' normal velocities, so that sign does not feed back on
 * itself: with the normal rate of the columns inside (whose gradients hold the surface
 * particle's velocity) the square at Bn = 1000, dx = 1/80, had two states, its free side at
 * p = +tau0 or -tau0 by how it started (FE: +tau0), 1.006 and 0.953 of FE's force. One
 * particle's stretching flips sign with a particle-scale wrinkle of the surface row, hence
 * the average along it. */
static void surface_rate(const sph_world *w, int i, double *exx, double *exy) {
    if (!sph_surface_traction(w)) { /* the thin-film scheme's surface holds p = 0 */
        inner_rate(w, i, exx, exy);
        return;
    }
    double nx, ny;
    if (!surface_normal(w, i, &nx, &ny)) return;
    double gi[4] = {w->gux[i], w->guy[i], w->gvx[i], w->gvy[i]};
    double s0 = w->vol[i] * sph_kernel_value(0.0, w->h), a = s0 * surface_stretching(w, i, gi);
    for (int k = w->nb_start[i]; k < w->nb_mid[i]; k++) {
        int j = w->nb_j[k], q = w->src[j];
        if (!w->surf[q]) continue;
        /* a mirror image's stretching is its source's (t . grad u . t is even in a reflection) */
        double gq[4] = {w->gux[q], w->guy[q], w->gvx[q], w->gvy[q]};
        double c = w->vol[j] * w->nb_w[k];
        s0 += c;
        a += c * surface_stretching(w, q, gq);
    }
    double e = a / s0;
    *exx = -e * (nx * nx - ny * ny);
    *exy = -e * 2.0 * nx * ny;
}

/* The traction-free surface has no shear stress: lam and S at a free-surface particle keep
 * their normal part, A_nn (n n - t t). */
static void surface_normal_part(const sph_world *w, int i, double *axx, double *axy) {
    double nx, ny;
    if (!surface_normal(w, i, &nx, &ny)) return;
    double c2 = nx * nx - ny * ny, s2 = 2.0 * nx * ny, ann = *axx * c2 + *axy * s2;
    *axx = ann * c2;
    *axy = ann * s2;
}

/* The stress magnitude behind the yield state and the stress field: for a viscoplastic
 * particle |<lam>|, the multiplier averaged over the kernel (Shepard, the particle and its
 * viscoplastic neighbours), for a Newtonian one mu gammadot. The multiplier carries
 * particle-scale noise, and the magnitude of a noisy tensor is biased upward: with |lam| of
 * the particle itself the square's unyielded share was 0.025 / 0.039 at dx = 1/20, 1/40
 * (FE 0.11-0.13 at Bn = 10); averaging the tensor first gives 0.080 / 0.099, and 0.435 / 0.474
 * at Bn = 1000 (FE 0.45-0.55; method.md). */
static void yield_stress(sph_world *w) {
    int n = w->n;
    double w0 = sph_kernel_value(0.0, w->h);
#pragma omp parallel for schedule(static) num_threads(w->threads)
    for (int i = 0; i < n; i++) {
        if (w->kind[i] != SPH_FLUID) continue;
        const sph_material *mt = &w->mats[w->mat[i]];
        if (mt->model == SPH_NEWTONIAN) {
            w->tau[i] = mt->mu * w->gd[i];
            continue;
        }
        double s0 = w->vol[i] * w0, a = s0 * w->lamxx[i], b = s0 * w->lamxy[i];
        for (int k = w->nb_start[i]; k < w->nb_mid[i]; k++) {
            int j = w->nb_j[k], q = w->src[j];
            if (w->mats[w->mat[q]].model == SPH_NEWTONIAN) continue; /* no multiplier */
            double c = w->vol[j] * w->nb_w[k];
            s0 += c;
            a += c * w->lamxx[q];
            b += c * w->gsx[j] * w->gsy[j] * w->lamxy[q]; /* a mirror image reverses lam_xy */
        }
        w->tau[i] = hypot(a, b) / s0;
    }
}

void sph_viscous_rheology(sph_world *w, double dt) {
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
    }
#pragma omp parallel for schedule(static) num_threads(w->threads)
    for (int i = 0; i < n; i++) {
        if (w->kind[i] != SPH_FLUID) continue;
        double exx = 0.5 * (w->gux[i] - w->gvy[i]), exy = 0.5 * (w->guy[i] + w->gvx[i]);
        const sph_material *mt = &w->mats[w->mat[i]];
        if (mt->model == SPH_NEWTONIAN) {
            w->gd[i] = 2.0 * hypot(exx, exy);
            w->eta[i] = w->visc[i] = mt->mu;
            w->sxx[i] = w->sxy[i] = 0.0;
            continue;
        }
        if (w->surf[i]) surface_rate(w, i, &exx, &exy);
        plastic_update(w, i, exx, exy, dt);
        if (w->surf[i]) {
            surface_normal_part(w, i, &w->lamxx[i], &w->lamxy[i]);
            surface_normal_part(w, i, &w->sxx[i], &w->sxy[i]);
        }
    }
    yield_stress(w);
    sph_boundary_sync(w, w->eta, w->gd, 0);
    sph_boundary_sync(w, w->visc, 0, 0);
}


/* The free surface is traction-free, sigma . n = 0 with sigma = -p I + tau (PHYSICS.md): its
 * normal part holds a free-surface particle at p = n . tau . n, tau = 2 visc d(u*) + S, with
 * n . 2 d . n = -2 e (e the surface stretching of u* before the pressure predictor's term is
 * taken back in sph_viscous_implicit: the viscous solution under the predicted pressure) and
 * S the explicit stress, whose shear part the surface does not carry (sph_viscous_rheology).
 * For a Newtonian surface p = -2 mu e: on the square at Re = 0.05 the side pressure of FE
 * within 3 %; a yielded Bingham side holds p = tau0 + mu gammadot (FE: 10.4-12.9 at Bn = 10;
 * without it the plate force is half FE's). Not the particle's normal rate, which holds its
 * own velocity (its pressure then drives it, and the run diverges), nor u* after the
 * take-back (it holds + dt grad p~ / rho). The visc part is explicit: stable for dt up to
 * the surface's viscous time dt_s = C_s rho h^2 / visc (timestep.c bounds dt by it for mu);
 * past it the pressure moves from p^n towards the target by the fraction dt_s / dt, which
 * keeps the explicit step's gain at its stable limit. */
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
        double eta = w->visc[i], target = -2.0 * eta * e, nx, ny;
        if (surface_normal(w, i, &nx, &ny)) /* n . S . n (S deviatoric) */
            target += w->sxx[i] * (nx * nx - ny * ny) + 2.0 * w->sxy[i] * nx * ny;
        /* relaxed towards the target where dt exceeds the surface's viscous time */
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
/* fp[plate of wall j] -= the share along its axis of the force (wx, wy) / rho_i that fluid
 * particle i's acceleration takes from wall neighbour j (whole sample: image signs). */
static inline void plate_reaction(const sph_world *w, int i, int j, double wx, double wy, double *fp) {
    const sph_plate *pl = &w->plates[w->kind[j]];
    if (fp && pl->axis >= 0) fp[w->kind[j]] -= w->m[i] / w->rho[i] * (pl->axis == 0 ? wx * w->gsx[j] : wy * w->gsy[j]);
}

static void transpose_accel(const sph_world *w, int i, double *ax, double *ay, double *fp) {
    int k0 = w->nb_start[i], km = w->nb_mid[i], k1 = w->nb_start[i + 1];
    *ax = *ay = 0.0;
    if (!sph_surface_traction(w)) return;
    int need = w->surf[i]; /* a free-surface particle in the support */
    for (int k = k0; k < km && !need; k++) need = w->surf[w->src[w->nb_j[k]]];
    if (!need) return;
    double ei = w->visc[i];
    double txx = ei * w->gux[i], txy = ei * w->guy[i], tyx = ei * w->gvx[i], tyy = ei * w->gvy[i];
    double fx = 0.0, fy = 0.0; /* (div T)_b = d_a T_ab */
    for (int k = k0; k < km; k++) {
        int j = w->nb_j[k], s = w->src[j];
        double sg = w->gsx[j] * w->gsy[j], c = w->vol[j];
        double es = w->visc[s];
        double sxx = txx + es * w->gux[s], sxy = txy + sg * es * w->guy[s];
        double syx = tyx + sg * es * w->gvx[s], syy = tyy + es * w->gvy[s];
        fx += c * (sxx * w->nb_gx[k] + syx * w->nb_gy[k]);
        fy += c * (sxy * w->nb_gx[k] + syy * w->nb_gy[k]);
    }
    for (int k = km; k < k1; k++) {
        int j = w->nb_j[k];
        double c = 2.0 * w->vol[j];
        double wx = c * (txx * w->nb_gx[k] + tyx * w->nb_gy[k]), wy = c * (txy * w->nb_gx[k] + tyy * w->nb_gy[k]);
        fx += wx;
        fy += wy;
        plate_reaction(w, i, j, wx, wy, fp);
    }
    *ax = fx / w->rho[i];
    *ay = fy / w->rho[i];
}

/* (div S)_i / rho_i for the explicit stress S (deviatoric: S_yy = -S_xx), in the symmetric
 * form sum_j V_j (S_i + S_j) . grad W_ij: over a truncated support its excess, 2 S_i . g,
 * meets the pressure's 2 p_i g, so that a surface holding p = n . tau . n feels no net
 * normal force from its truncation. A wall particle carries S_i whole, as it carries the
 * pressure, so that a row along a plate feels no such excess: S is mostly the multiplier,
 * a stress that no wall condition fixes (where the material is plastic against a plate its
 * normal part is what equilibrium asks), and the plate takes -p + S_nn. With S_nn held to 0
 * on the face (the walls carrying -S_nn), the first row felt 2 S_nn g along the normal (g
 * the sum over its walls of V grad W): its velocity ran into the plates (0.005 in the
 * square at rest under 0.8 F_y, plate speed 0.002, the correction taking it back), and a
 * sample below its yield load crept 5-10 times too fast (docs/limitations.md). The walls'
 * part goes into fp[k] (plate k's axis, the whole sample) when fp is given. */
static void stress_accel(const sph_world *w, int i, double *ax, double *ay, double *fp) {
    int k0 = w->nb_start[i], km = w->nb_mid[i], k1 = w->nb_start[i + 1];
    double sxx = w->sxx[i], sxy = w->sxy[i], fx = 0.0, fy = 0.0, ri = 1.0 / w->rho[i];
    for (int k = k0; k < km; k++) {
        int j = w->nb_j[k], s = w->src[j];
        double c = w->vol[j], axx = sxx + w->sxx[s], axy = sxy + w->gsx[j] * w->gsy[j] * w->sxy[s];
        fx += c * (axx * w->nb_gx[k] + axy * w->nb_gy[k]);
        fy += c * (axy * w->nb_gx[k] - axx * w->nb_gy[k]);
    }
    for (int k = km; k < k1; k++) {
        int j = w->nb_j[k];
        double c = 2.0 * w->vol[j];
        double wx = c * (sxx * w->nb_gx[k] + sxy * w->nb_gy[k]), wy = c * (sxy * w->nb_gx[k] - sxx * w->nb_gy[k]);
        fx += wx;
        fy += wy;
        plate_reaction(w, i, j, wx, wy, fp);
    }
    *ax = fx * ri;
    *ay = fy * ri;
}

/* The Morris coefficient of fluid pair k (i, j): c = m_j (visc_i + visc_j) F_ij / (rho_i rho_j),
 * as V_j (visc_i + visc_j) F_ij / rho_i with V_j = m_j / rho_j (w->vol, set by the
 * neighbour build: the density has not changed since). */
static inline double fluid_coeff(const sph_world *w, int i, int j, int k) {
    return w->vol[j] * (w->visc[i] + w->visc[j]) * w->nb_f[k] / w->rho[i];
}

/* A wall neighbour j (pair k) of fluid particle i enters the Morris sum as
 * cu (u_i - u_wall) and cv (v_i - v_wall), c = beta m_j 2 visc_i F_ij / (rho_i rho_j), beta
 * the no-slip factor, for the velocity component along the face; the component normal to
 * the face has no flux through it (c = 0): on a no-slip face du_t/dt = 0, so by continuity
 * du_n/dn = 0 and the normal stress 2 eta du_n/dn is 0. The odd extension of u_n (as for
 * u_t) gave the plate a viscous normal force that the continuum does not have, a first-order
 * error (on the square at Bn = 10, 6.5 / 4.8 / 2.7 of the 26.8 at dx = 1/20, 1/40, 1/80). */
static inline void wall_coeff(const sph_world *w, int i, int j, int k, double *wx, double *wy, double *cu,
                              double *cv) {
    int nrm;
    sph_plate_wall_velocity(w, j, wx, wy);
    double c = sph_plate_noslip(w, i, j, &nrm) * w->vol[j] * 2.0 * w->visc[i] * w->nb_f[k] / w->rho[i];
    *cu = nrm == 0 ? 0.0 : c;
    *cv = nrm == 1 ? 0.0 : c;
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
        double au = 0, av = 0, ei = w->visc[i];
        int k0 = w->nb_start[i], km = w->nb_mid[i], k1 = w->nb_start[i + 1];
        const int *nj = w->nb_j;
        const double *nf = w->nb_f, *vol = w->vol, *eta = w->visc, *u = w->u, *v = w->v;
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
            double wx, wy, cu, cv;
            wall_coeff(w, i, j, k, &wx, &wy, &cu, &cv);
            fplate[w->kind[j]] += sph_plate_pull(w, i, j, cu, cv, ui, vi, wx, wy);
            au += cu * (ui - wx);
            av += cv * (vi - wy);
        }
        double fx, fy, sx, sy;
        transpose_accel(w, i, &fx, &fy, fplate);
        stress_accel(w, i, &sx, &sy, fplate);
        w->us[i] = ui + dt * (au + gx + fx + sx);
        w->vs[i] = vi + dt * (av + gy + fy + sy);
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
static void visc_assemble(sph_world *w, double dt, double *fexp) {
    sph_csr *A = &w->V;
    int nrows = A->n;
    double fe[SPH_MAX_PLATES] = {0};
    /* the pressure predictor (pressure.c): -grad p~ / rho as a body force */
    double gx = w->par.gravity[0], gy = w->par.gravity[1];
    sph_pressure_predictor(w, w->xs, w->ys);
#pragma omp parallel for schedule(static) num_threads(w->threads) reduction(+ : fe[:SPH_MAX_PLATES])
    for (int r = 0; r < nrows; r++) {
        int i = w->vrow_of[r], e = A->start[r] + 1;
        double mi = w->m[i];
        double du = 1.0, dv = 1.0, ru = w->u[i] + dt * gx, rv = w->v[i] + dt * gy;
        ru += dt * w->xs[i];
        rv += dt * w->ys[i];
        double fx, fy, tx, ty; /* the transpose part of div tau and the stress S (explicit) */
        transpose_accel(w, i, &fx, &fy, fe);
        stress_accel(w, i, &tx, &ty, fe);
        ru += dt * (fx + tx);
        rv += dt * (fy + ty);
        int k0 = w->nb_start[i], km = w->nb_mid[i], k1 = w->nb_start[i + 1];
        double ei = w->visc[i], dr = dt / w->rho[i];
        for (int k = k0; k < km; k++) { /* fluid: c = dt V_j (visc_i + visc_j) F_ij / rho_i */
            int j = w->nb_j[k], s = w->src[j];
            double c = dr * (w->vol[j] * (ei + w->visc[j]) * w->nb_f[k]);
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
            double wx, wy, cu, cv;
            wall_coeff(w, i, j, k, &wx, &wy, &cu, &cv);
            du -= dt * cu;
            dv -= dt * cv;
            ru -= dt * cu * wx;
            rv -= dt * cv * wy;
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
    for (int k = 0; k < SPH_MAX_PLATES; k++) fexp[k] = fe[k];
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
    double fplate[SPH_MAX_PLATES]; /* the plates' share of the explicit terms, then of the Morris sum */
    visc_assemble(w, dt, fplate);
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
#pragma omp parallel for schedule(static) num_threads(w->threads) reduction(+ : fplate[:SPH_MAX_PLATES])
    for (int i = 0; i < n; i++) {
        if (w->kind[i] != SPH_FLUID) {
            sph_plate_wall_velocity(w, i, &w->us[i], &w->vs[i]);
            continue;
        }
        for (int k = w->nb_mid[i]; k < w->nb_start[i + 1]; k++) { /* walls */
            int j = w->nb_j[k];
            if (w->plates[w->kind[j]].axis < 0) continue;
            double wx, wy, cu, cv;
            wall_coeff(w, i, j, k, &wx, &wy, &cu, &cv);
            fplate[w->kind[j]] += sph_plate_pull(w, i, j, cu, cv, w->us[i], w->vs[i], wx, wy);
        }
        w->us[i] -= dt * w->xs[i];
        w->vs[i] -= dt * w->ys[i];
    }
    sph_plate_set_viscous_forces(w, fplate);
    sph_boundary_sync(w, w->us, w->vs, 1);
    return 0;
}
