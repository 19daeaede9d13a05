/* Periodic edges and symmetry planes, both by ghost particles: images of the real
 * particles within one kernel support of an edge, regenerated every step after the sort.
 * A ghost keeps the index of the real particle it images (src) and the signs applied to
 * its velocity (a mirror reverses the normal component; pressure and scalars are copied),
 * so every pass reads ghosts like real neighbours and the pressure system maps a ghost's
 * unknown to its source's. Images of images fill the corners. */
#include "internal.h"
#include "kernel.h"

#include <math.h>

void sph_boundary_wrap(sph_world *w) {
    for (int a = 0; a < 2; a++) {
        if (w->par.symmetry[a]) { /* a particle that crossed a mirror is reflected back */
            double s = w->par.sym_at[a];
            double *c = a == 0 ? w->x : w->y, *vel = a == 0 ? w->u : w->v;
            for (int i = 0; i < w->n; i++)
                if (c[i] < s && w->kind[i] == SPH_FLUID) {
                    c[i] = 2.0 * s - c[i];
                    vel[i] = -vel[i];
                }
        }
        if (!w->par.periodic[a]) continue;
        double lo = w->par.period_lo[a], hi = w->par.period_hi[a], L = hi - lo;
        double *c = a == 0 ? w->x : w->y;
        for (int i = 0; i < w->n; i++) {
            if (c[i] < lo) c[i] += L * ceil((lo - c[i]) / L);
            if (c[i] >= hi) c[i] -= L * (floor((c[i] - hi) / L) + 1.0);
        }
    }
}

static int add_ghost(sph_world *w, int k, double gx, double gy, int flipx, int flipy) {
    int g = w->n + w->ng;
    if (sph_world_reserve(w, g + 1)) return -1;
    int s = w->src[k];
    w->x[g] = gx;
    w->y[g] = gy;
    w->src[g] = s;
    w->gsx[g] = (signed char)(w->gsx[k] * (flipx ? -1 : 1));
    w->gsy[g] = (signed char)(w->gsy[k] * (flipy ? -1 : 1));
    w->kind[g] = w->kind[s];
    w->mat[g] = w->mat[s];
    w->id[g] = w->id[s];
    w->m[g] = w->m[s];
    w->rho[g] = w->rho[s];
    w->p[g] = w->p[s];
    w->eta[g] = w->eta[s];
    w->gd[g] = w->gd[s];
    w->u[g] = w->gsx[g] * w->u[s];
    w->v[g] = w->gsy[g] * w->v[s];
    w->surf[g] = w->surf[s];
    w->ng++;
    return 0;
}

int sph_boundary_ghosts(sph_world *w) {
    double reach = SPH_KERNEL_SUPPORT * w->h;
    w->ng = 0;
    for (int i = 0; i < w->n; i++) {
        w->src[i] = i;
        w->gsx[i] = w->gsy[i] = 1;
    }
    for (int a = 0; a < 2; a++) {
        int count = w->n + w->ng; /* images of everything made so far (corners) */
        if (w->par.periodic[a]) {
            double lo = w->par.period_lo[a], hi = w->par.period_hi[a], L = hi - lo;
            for (int k = 0; k < count; k++) {
                double c = a == 0 ? w->x[k] : w->y[k];
                double sh = 0.0;
                if (c < lo + reach) sh = L;
                else if (c >= hi - reach) sh = -L;
                else continue;
                if (add_ghost(w, k, w->x[k] + (a == 0 ? sh : 0), w->y[k] + (a == 1 ? sh : 0), 0, 0))
                    return -1;
            }
        }
        if (w->par.symmetry[a]) {
            double s = w->par.sym_at[a];
            for (int k = 0; k < count; k++) {
                double c = a == 0 ? w->x[k] : w->y[k];
                if (c - s >= reach) continue;
                double m = 2.0 * s - c;
                if (add_ghost(w, k, a == 0 ? m : w->x[k], a == 1 ? m : w->y[k], a == 0, a == 1))
                    return -1;
            }
        }
    }
    return 0;
}

void sph_boundary_sync(sph_world *w, double *a, double *b, int vector) {
    int n = w->n, nt = n + w->ng;
    for (int g = n; g < nt; g++) {
        int s = w->src[g];
        if (vector) {
            a[g] = w->gsx[g] * a[s];
            b[g] = w->gsy[g] * b[s];
        } else {
            a[g] = a[s];
            if (b) b[g] = b[s];
        }
    }
}
