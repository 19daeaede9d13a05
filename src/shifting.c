/* Particle shifting (Xu, Stansby & Laurence 2009; Lind et al. 2012), with the displacement
 * scaled by the flow's own displacement per step (Skillen et al. 2013):
 *   dr_i = -D grad C_i,  D = min(A h U dt, h^2 / 4),
 *   grad C_i = sum_j V_j (1 + R (W_ij / W(dx))^4) grad_i W_ij  (walls included),
 * U the largest fluid speed, A the `shifting` coefficient. Near a free surface (position
 * divergence below surface_div + 0.3) only the component tangent to the surface is kept,
 * so shifting never moves the surface itself. The surface normal is that of the plain
 * kernel sum, n = sum_j V_j grad W_ij / |...|, not grad C: with the anti-clustering term in
 * it, a surface particle's "normal" points at the particle crowding it, and removing that
 * component removes the very push that parts them (clumps of surface particles then sit at
 * the contact lines and hide exposed edge particles from the free-surface test).
 * The velocity is carried to the new position by a first-order Taylor step,
 * u_i += (dr_i . grad) u_i.
 * The R term (Lind et al. 2012, R = 0.2) pushes apart pairs closer than dx. Without it a
 * lattice stretched by the squeeze's extension stays uniform in concentration (grad C = 0)
 * while its columns part, and a void opens on the mid-plane whose edges are taken for free
 * surface. A minimum-distance push (pairs closer than dx/2 parted) is not used: it puts
 * particles through the plates at the contact lines. */
#include "internal.h"
#include "kernel.h"

#include <math.h>

/* grad C_i (cx, cy) and the plain kernel sum sum_j V_j grad W_ij (gx, gy) of particle i, W
 * at the particles' current positions */
static SPH_CLONES void concentration(const sph_world *w, int i, const double *vol, double wdx, double R, double *ocx,
                                     double *ocy, double *ogx, double *ogy) {
    double h = w->h, kw = 7.0 / (478.0 * SPH_PI * h * h); /* as in sph_kernel_value */
    double cx = 0.0, cy = 0.0, gx = 0.0, gy = 0.0, xi = w->x[i], yi = w->y[i];
    const int *nj = w->nb_j;
    const double *x = w->x, *y = w->y, *ngx = w->nb_gx, *ngy = w->nb_gy;
    int k0 = w->nb_start[i], k1 = w->nb_start[i + 1];
#pragma omp simd reduction(+ : cx, cy, gx, gy)
    for (int k = k0; k < k1; k++) {
        int j = nj[k];
        double ddx = xi - x[j], ddy = yi - y[j];
        double sq = sqrt(ddx * ddx + ddy * ddy) / h;
        double q = kw * sph_kernel_shape(sq) * wdx;
        q *= q;
        double v = vol[j] * (1.0 + R * q * q);
        cx += v * ngx[k];
        cy += v * ngy[k];
        gx += vol[j] * ngx[k];
        gy += vol[j] * ngy[k];
    }
    *ocx = cx;
    *ocy = cy;
    *ogx = gx;
    *ogy = gy;
}

void sph_shifting_apply(sph_world *w, double dt) {
    int n = w->n;
    double A = w->par.shifting, h = w->h, umax = 0.0, near = w->par.surface_div + 0.3;
#pragma omp parallel for schedule(static) num_threads(w->threads) reduction(max : umax)
    for (int i = 0; i < n; i++) {
        double s2 = w->kind[i] == SPH_FLUID ? w->u[i] * w->u[i] + w->v[i] * w->v[i] : 0.0;
        if (s2 > umax) umax = s2;
    }
    umax = sqrt(umax);
    /* The shifting is an explicit Fickian diffusion step: its coefficient must stay below a
     * fraction of h^2 per step or the particle distribution itself goes unstable (a
     * Newtonian squeeze blows up at D = 2.1 h^2 and runs clean at 0.5 h^2); h^2 / 4 keeps a
     * margin. With the implicit viscous step dt is large enough to reach the cap. */
    double D = fmin(A * h * umax * dt, 0.25 * h * h), cap = 0.1 * h;
    if (D <= 0) return;
    /* anti-clustering (Lind et al. 2012): pairs closer than dx count more, R = 0.2, n = 4 */
    double wdx = 1.0 / sph_kernel_value(w->dx, h), R = 0.2;
    /* V_j = m_j / rho_j with the density of now (the step has changed it since the
     * neighbour build) */
    int nt = n + w->ng;
    double *vol = w->sa;
#pragma omp parallel for schedule(static) num_threads(w->threads)
    for (int j = 0; j < nt; j++) vol[j] = w->m[j] / w->rho[j];
#pragma omp parallel for schedule(static) num_threads(w->threads)
    for (int i = 0; i < n; i++) {
        if (w->kind[i] != SPH_FLUID) continue;
        double cx, cy, gx, gy;
        concentration(w, i, vol, wdx, R, &cx, &cy, &gx, &gy);
        double sx = -D * cx, sy = -D * cy;
        if (w->divr[i] < near) { /* tangential only: n = sum V grad W / |...| */
            double c = hypot(gx, gy);
            if (c > 0) {
                double nx = gx / c, ny = gy / c, dn = sx * nx + sy * ny;
                sx -= dn * nx;
                sy -= dn * ny;
            }
        }
        double s = hypot(sx, sy);
        if (s > cap) {
            sx *= cap / s;
            sy *= cap / s;
        }
        w->xs[i] = sx;
        w->ys[i] = sy;
    }
#pragma omp parallel for schedule(static) num_threads(w->threads)
    for (int i = 0; i < n; i++) {
        if (w->kind[i] != SPH_FLUID) continue;
        double sx = w->xs[i], sy = w->ys[i];
        w->x[i] += sx;
        w->y[i] += sy;
        w->u[i] += sx * w->gux[i] + sy * w->guy[i];
        w->v[i] += sx * w->gvx[i] + sy * w->gvy[i];
    }
}
