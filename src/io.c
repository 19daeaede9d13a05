/* Particle output: CSV (one row per particle) and legacy VTK polydata (ParaView). */
#include "internal.h"
#include "atomic.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static double yielded(const sph_world *w, int i) {
    return w->kind[i] == SPH_FLUID && w->eta[i] * w->gd[i] > w->mats[w->mat[i]].tau0;
}

/* Both writers go through a temporary file renamed into place (atomic.h): a failed write
 * leaves an earlier file at that path as it was. */
static int openf(sph_world *w, sph_atomic_file *af, const char *file) {
    char why[512];
    if (sph_atomic_open(af, file, why, sizeof why)) return sph_world_fail(w, "%s", why);
    return 0;
}

static int closef(sph_world *w, sph_atomic_file *af) {
    char why[512];
    if (sph_atomic_commit(af, why, sizeof why)) return sph_world_fail(w, "%s", why);
    return 0;
}

int sph_io_write_csv(sph_world *w, const char *file);
int sph_io_write_vtk(sph_world *w, const char *file);

int sph_io_write_csv(sph_world *w, const char *file) {
    sph_atomic_file af;
    if (openf(w, &af, file)) return -1;
    FILE *f = af.fp;
    fprintf(f, "id,kind,x,y,u,v,p,rho,eta,gammadot,stress,yielded,surface\n");
    for (int i = 0; i < w->n; i++) {
        int fl = w->kind[i] == SPH_FLUID;
        fprintf(f, "%d,%d,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%d,%d\n", w->id[i] + 1,
                fl ? 0 : w->kind[i] + 1, w->x[i], w->y[i], w->u[i], w->v[i], w->p[i], w->rho[i],
                fl ? w->eta[i] : 0.0, fl ? w->gd[i] : 0.0, fl ? w->eta[i] * w->gd[i] : 0.0,
                (int)yielded(w, i), fl ? (int)w->surf[i] : 0);
    }
    return closef(w, &af);
}

int sph_io_write_vtk(sph_world *w, const char *file) {
    sph_atomic_file af;
    if (openf(w, &af, file)) return -1;
    FILE *f = af.fp;
    int n = w->n;
    fprintf(f, "# vtk DataFile Version 3.0\nsph particles t=%.10g\nASCII\nDATASET POLYDATA\n", w->t);
    fprintf(f, "POINTS %d double\n", n);
    for (int i = 0; i < n; i++) fprintf(f, "%.10g %.10g 0\n", w->x[i], w->y[i]);
    fprintf(f, "VERTICES %d %d\n", n, 2 * n);
    for (int i = 0; i < n; i++) fprintf(f, "1 %d\n", i);
    fprintf(f, "POINT_DATA %d\n", n);
    fprintf(f, "VECTORS velocity double\n");
    for (int i = 0; i < n; i++) fprintf(f, "%.10g %.10g 0\n", w->u[i], w->v[i]);
    const char *names[] = {"pressure", "density", "viscosity", "shear_rate", "stress", "yielded", "kind"};
    for (int q = 0; q < 7; q++) {
        fprintf(f, "SCALARS %s double 1\nLOOKUP_TABLE default\n", names[q]);
        for (int i = 0; i < n; i++) {
            int fl = w->kind[i] == SPH_FLUID;
            double v = 0;
            switch (q) {
            case 0: v = w->p[i]; break;
            case 1: v = w->rho[i]; break;
            case 2: v = fl ? w->eta[i] : 0; break;
            case 3: v = fl ? w->gd[i] : 0; break;
            case 4: v = fl ? w->eta[i] * w->gd[i] : 0; break;
            case 5: v = yielded(w, i); break;
            case 6: v = fl ? 0 : w->kind[i] + 1; break;
            }
            fprintf(f, "%.10g\n", v);
        }
    }
    return closef(w, &af);
}

int sph_world_write_csv(sph_world *w, const char *file) { return sph_io_write_csv(w, file); }
int sph_world_write_vtk(sph_world *w, const char *file) { return sph_io_write_vtk(w, file); }
