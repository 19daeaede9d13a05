/* Particle shifting (Xu, Stansby & Laurence 2009; Lind et al. 2012), with the displacement
 * scaled by the flow's own displacement per step (Skillen et al. 2013):
 *   dr_i = -D grad C_i,  D = min(A h U dt, h^2 / 4),   grad C_i = sum_j V_j grad_i W_ij (walls included),
 * U the largest fluid speed, A the `shifting` coefficient. Near a free surface (position
 * divergence below surface_div + 0.3) only the component tangent to the surface is kept,
 * so shifting never moves the surface itself. The velocity is carried to the new position
 * by a first-order Taylor step, u_i += (dr_i . grad) u_i. */
#include "internal.h"

#include <math.h>

void sph_shifting_apply(sph_world *w, double dt) {
    int n = w->n;
    double A = w->par.shifting, h = w->h, umax = 0.0, near = w->par.surface_div + 0.3;
    for (int i = 0; i < n; i++)
        if (w->kind[i] == SPH_FLUID) umax = fmax(umax, hypot(w->u[i], w->v[i]));
    /* The shifting is an explicit Fickian diffusion step: its coefficient must stay below a
     * fraction of h^2 per step or the particle distribution itself goes unstable (measured:
     * Newtonian squeeze, dt = 2e-3, D = 2.1 h^2 blows up in 20 steps; 0.5 h^2 and below
     * run clean). With the implicit viscous step dt is large enough to reach the cap. */
    double D = fmin(A * h * umax * dt, 0.25 * h * h), cap = 0.1 * h;
    if (D <= 0) return;
#pragma omp parallel for schedule(static) num_threads(w->threads)
    for (int i = 0; i < n; i++) {
        if (w->kind[i] != SPH_FLUID) continue;
        double cx = 0.0, cy = 0.0;
        for (int k = w->nb_start[i]; k < w->nb_start[i + 1]; k++) {
            int j = w->nb_j[k];
            double vol = w->m[j] / w->rho[j];
            cx += vol * w->nb_gx[k];
            cy += vol * w->nb_gy[k];
        }
        double sx = -D * cx, sy = -D * cy;
        if (w->divr[i] < near) { /* tangential only: n = grad C / |grad C| */
            double c = hypot(cx, cy);
            if (c > 0) {
                double nx = cx / c, ny = cy / c, dn = sx * nx + sy * ny;
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
