/* Rheology and the viscous step.
 * Velocity gradient: grad u_i = sum_j V_j (u_j - u_i) (x) grad_i W_ij, with a wall
 * neighbour's velocity taken from the no-slip extrapolation; shear rate
 * gammadot = sqrt(1/2 D:D), D = grad u + grad u^T; apparent viscosity from the material law.
 * Viscous acceleration (Morris, Fox & Zhu 1997):
 *   (1/rho div eta grad u)_i = sum_j m_j (eta_i + eta_j) F_ij / (rho_i rho_j) (u_i - u_j),
 *   F_ij = r_ij . grad_i W_ij / (r_ij^2 + eps^2). */
#include "internal.h"

#include <math.h>

void sph_viscous_rheology(sph_world *w) {
    int n = w->n;
#pragma omp parallel for schedule(static) num_threads(w->threads)
    for (int i = 0; i < n; i++) {
        if (w->kind[i] != SPH_FLUID) continue;
        double uxx = 0, uxy = 0, uyx = 0, uyy = 0; /* uab = d u_a / d x_b */
        double ui = w->u[i], vi = w->v[i];
        for (int k = w->nb_start[i]; k < w->nb_start[i + 1]; k++) {
            int j = w->nb_j[k];
            double du, dv;
            if (w->kind[j] == SPH_FLUID) {
                du = w->u[j] - ui;
                dv = w->v[j] - vi;
            } else {
                double wx, wy, beta = sph_plate_noslip(w, i, j);
                sph_plate_wall_velocity(w, j, &wx, &wy);
                du = -beta * (ui - wx);
                dv = -beta * (vi - wy);
            }
            double vol = w->m[j] / w->rho[j];
            uxx += vol * du * w->nb_gx[k];
            uxy += vol * du * w->nb_gy[k];
            uyx += vol * dv * w->nb_gx[k];
            uyy += vol * dv * w->nb_gy[k];
        }
        /* renormalised: grad u = (sum V du (x) grad W) L, first-order consistent near a
         * free surface where the kernel support is truncated */
        double lxx = w->lxx[i], lxy = w->lxy[i], lyy = w->lyy[i];
        double cxx = uxx * lxx + uxy * lxy, cxy = uxx * lxy + uxy * lyy;
        double cyx = uyx * lxx + uyy * lxy, cyy = uyx * lxy + uyy * lyy;
        uxx = cxx, uxy = cxy, uyx = cyx, uyy = cyy;
        w->gux[i] = uxx;
        w->guy[i] = uxy;
        w->gvx[i] = uyx;
        w->gvy[i] = uyy;
        double dxx = 2 * uxx, dyy = 2 * uyy, dxy = uxy + uyx;
        double g = sqrt(0.5 * (dxx * dxx + dyy * dyy + 2 * dxy * dxy));
        w->gd[i] = g;
        w->eta[i] = sph_rheology_eta(&w->mats[w->mat[i]], g);
    }
    sph_boundary_sync(w, w->eta, w->gd, 0);
}

/* u* = u + dt (viscous + g) for fluid; walls keep the plate velocity. The viscous force
 * each plate takes from the fluid is accumulated on the way (whole sample). */
void sph_viscous_explicit(sph_world *w, double dt) {
    int n = w->n, np = w->nplates;
    double gx = w->par.gravity[0], gy = w->par.gravity[1];
    double fplate[SPH_MAX_PLATES] = {0};
#pragma omp parallel for schedule(static) num_threads(w->threads) reduction(+ : fplate[:SPH_MAX_PLATES])
    for (int i = 0; i < n; i++) {
        if (w->kind[i] != SPH_FLUID) {
            sph_plate_wall_velocity(w, i, &w->us[i], &w->vs[i]);
            continue;
        }
        double ui = w->u[i], vi = w->v[i], etai = w->eta[i], rhoi = w->rho[i];
        double au = 0, av = 0;
        for (int k = w->nb_start[i]; k < w->nb_start[i + 1]; k++) {
            int j = w->nb_j[k];
            double du, dv, c;
            if (w->kind[j] == SPH_FLUID) {
                du = ui - w->u[j];
                dv = vi - w->v[j];
                c = w->m[j] * (etai + w->eta[j]) * w->nb_f[k] / (rhoi * w->rho[j]);
            } else {
                double wx, wy, beta = sph_plate_noslip(w, i, j);
                sph_plate_wall_velocity(w, j, &wx, &wy);
                du = beta * (ui - wx);
                dv = beta * (vi - wy);
                c = w->m[j] * 2.0 * etai * w->nb_f[k] / (rhoi * w->rho[j]);
                const sph_plate *pl = &w->plates[w->kind[j]];
                if (pl->axis >= 0) {
                    double fa = -w->m[i] * c * (pl->axis == 0 ? du * w->gsx[j] : dv * w->gsy[j]);
                    fplate[w->kind[j]] += fa;
                }
            }
            au += c * du;
            av += c * dv;
        }
        w->us[i] = ui + dt * (au + gx);
        w->vs[i] = vi + dt * (av + gy);
    }
    for (int k = 0; k < np; k++)
        w->plates[k].force_visc = fplate[k] * (w->plates[k].doubled ? 2.0 : 1.0);
    sph_boundary_sync(w, w->us, w->vs, 1);
}
