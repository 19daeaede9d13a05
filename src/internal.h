/* The world object and the engine's internal interfaces (not part of the public API). */
#ifndef SPH_INTERNAL_H
#define SPH_INTERNAL_H

#include "linalg.h"
#include "sph.h"

#include <stdint.h>
#include <stdio.h>

#define SPH_FLUID (-1) /* kind[] of a fluid particle; walls hold their plate index */
#define SPH_MAX_MATERIALS 64
#define SPH_MAX_PLATES 64
#define SPH_MAX_LOADED 4 /* plates under a load law, coupled implicitly */
/* C_s: dt <= C_s rho h^2 / mu on a traction-free surface (timestep.c), a time-accuracy limit.
 * The split step's steady state is off by a term in mu dt / (rho h^2) (the projection's
 * divergence residual (dt / rho)(L - D G) p, largest in the pressure layer along the free
 * side): the square's force at t = 0+ is 4 % high at C_s = 2 and within 0.3-0.7 % of its
 * converged-step value at 0.25 (docs/limitations.md). Stability alone would allow 3.2. */
#define SPH_SURFACE_CS 0.25
/* The first step's bound, dt <= SPH_SURFACE_STABLE rho h^2 / mu over every particle (timestep.c):
 * below the surface's stability limit (3.2, above). Not the accuracy limit C_s: the impulsive
 * start is not resolved in time by any step, and a first step that short (1/12 of this) put
 * the film a/h = 10 at 16 rows 3.7 % under FE over t in (0.005, 0.01), against 1.6 % here. */
#define SPH_SURFACE_STABLE 3.0
/* The default of sph_params.cfl, dt <= cfl h / max speed (timestep.c): a particle moves at
 * most a quarter of h a step, so the neighbour list and kernel sums built at the step's
 * start still hold at its end (the CFL limit of Morris, Fox & Zhu 1997, with the flow
 * speed for their sound speed). A smaller cfl is a user's way to a shorter step. */
#define SPH_CFL 0.25
/* The ALM's r is at most SPH_ALM_CAP rho h^2 / dt (viscous.c, plastic_update): the part of
 * 2 r gamma above mu is explicit in the stress S, and its divergence (nested kernel sums)
 * does not damp the particle-scale modes that the implicit Morris sum does. The plate force's
 * step-to-step noise grows with r (the square at Bn = 1000, dx = 1/20: spread 0.0022 at this
 * cap, 0.0090 at 4 rho h^2 / dt), and r up to the law's secant inside a sample moves the
 * creeping cavity's vortex centre away from FE (docs/limitations.md). The time step follows
 * the lag this cap puts on a plug's stress (timestep.c). */
#define SPH_ALM_CAP 0.5

typedef struct sph_plate {
    double rect[4];      /* current rectangle (moves with the plate)                 */
    double rect0[4];     /* the rectangle at the start of the step (sph_plate_contact) */
    int axis;            /* -1 fixed, 0 x, 1 y                                        */
    sph_plate_mode mode;
    double vel;          /* velocity along the axis this step (m/s)                  */
    double slide[2];     /* surface velocity: walls carry it, particles stay put      */
    double vel_new;      /* V^{n+1} of a loaded plate, from the pressure solve        */
    double load;         /* applied load along the axis (LOAD mode), whole sample    */
    double mass;         /* whole-sample mass                                         */
    int mass_set;        /* mass given by the caller                                 */
    double force;        /* fluid force along the axis, whole sample                 */
    double force_visc;   /* its viscous part (this step)                              */
    double impulse;      /* the sum of force * dt over the steps taken: sph_plate_impulse */
    int count;           /* real particles                                            */
    int doubled;         /* straddles a symmetry plane: whole = 2 x simulated half   */
    int face_side;       /* +1: fluid on the high side of the axis, -1: low, 0: ?    */
} sph_plate;


struct sph_world {
    sph_params par;
    double h, dx, mass0;
    int threads;
    char err[1024];

    /* particles: real ones in [0, n), ghosts (mirror / periodic images) in [n, n + ng) */
    int n, ng, cap;
    double *x, *y, *u, *v;     /* position, velocity                                */
    double *us, *vs;           /* predicted velocity u*                             */
    double *ax, *ay;           /* acceleration of the last step (dt force limit)    */
    double *p, *rho, *m;       /* pressure, density, mass                           */
    double *phi;               /* density-correction potential (dt^2 p units)       */
    double *ps;                /* this step's free-surface pressure n . tau . n      */
    double *dp;                /* scratch: the density correction's later passes    */
    double *gm;                /* the GMRES density correction's vectors (density.c)  */
    size_t gm_len;             /* doubles in gm                                      */
    double *eta, *gd, *divr;   /* apparent viscosity, shear rate, position div      */
    double *visc;              /* the viscous operator's viscosity (viscous.c)       */
    double *lamxx, *lamxy;     /* stress multiplier (deviatoric: lam_yy = -lam_xx)   */
    double *tau;               /* the stress magnitude of the yield state (viscous.c)  */
    double *sxx, *sxy;         /* this step's explicit stress lam - 2 visc gamma     */
    double *lxx, *lxy, *lyy;   /* kernel-gradient renormalisation (Bonet & Lok 1999) */
    double *gux, *guy, *gvx, *gvy; /* velocity gradient (du/dx, du/dy, dv/dx, dv/dy)  */
    double *xs, *ys;           /* scratch (reordering, shifting displacements)       */
    double *vol;               /* m / rho, set by the neighbour build (rho of then)  */
    double *sa, *sb;           /* scratch per particle for the sweeps (f / rho^2,
                                  the source velocity of the pressure system)        */
    double *cx, *cy;           /* positions in cell order: cx[k] = x[cell_items[k]]  */
    double *ru, *rv;           /* scratch: a first density pass's second direction   */
    double *dcx, *dcy;         /* the density correction's displacement this step    */
    int *kind, *mat, *id;      /* SPH_FLUID or plate index; material; stable id     */
    int *src;                  /* ghosts: the real particle they image; reals: self */
    signed char *gsx, *gsy;    /* ghosts: sign applied to u, v (mirror: -1)         */
    unsigned char *surf;       /* fluid on the free surface (p = n . tau . n)       */
    unsigned char *active;     /* wall particle in the pressure system              */
    unsigned char *cellfl;     /* in cell order: the item is fluid (real or ghost)   */
    int *row;                  /* unknown index in the pressure system or -1        */
    double *psens[SPH_MAX_LOADED]; /* d p / d V of each loaded plate (warm starts)   */
    int *perm, *iscratch;
    int nfluid, next_id;

    /* cell grid (cell size = kernel support) */
    double gx0, gy0, cell;
    int ncx, ncy, ncell_cap;
    unsigned char *cellflag;   /* cells holding fluid (rows of the pressure system)  */
    int *cell_start, *cell_items, *cell_of;
    int cell_items_cap;

    /* neighbour lists of rows (fluid and active walls), compressed */
    int *nb_start;             /* n + 1                                             */
    int *nb_j;
    double *nb_gx, *nb_gy;     /* grad_i W_ij                                       */
    double *nb_f;              /* r_ij . grad_i W_ij / r_ij^2 = (dW/dr) / r         */
    double *nb_w;              /* W_ij (the pressure predictor's Shepard average)   */
    long nb_cap;
    int nb_n;                  /* the particle count the lists were built for (-1 from the
                                  sort until the build ends, 0 before the first step): a
                                  list is read outside the step (rho_sum) only if nb_n == n */
    int *nb_count;
    int *nb_mid;               /* row i: fluid (and fluid ghost) neighbours in
                                  [nb_start[i], nb_mid[i]), walls in [nb_mid[i], nb_start[i+1]) */
    int *cand_j;               /* per-thread candidate scratch of the build: 3 x (cand_cap + 1) */
    int cand_cap, cand_threads;
    sph_material mats[SPH_MAX_MATERIALS];
    int nmats;
    sph_plate plates[SPH_MAX_PLATES];
    int nplates;

    /* implicit viscous system (one per velocity component, same structure) */
    sph_csr V;
    double *vb, *vsol;         /* right-hand side and solution, per fluid unknown   */
    double *vval, *vdiag, *vrhs; /* the v component's values, diagonal and rhs      */
    int vval_cap;
    int *vrow_of;              /* unknown -> particle                               */
    sph_guess gu, gv;          /* the viscous solves' first guesses (u, v)           */
    sph_guess gp;              /* the pressure solve's                               */
    int vrows_cap;

    /* pressure system */
    sph_csr A;
    sph_solver solver;
    double *b, *sol;           /* right-hand side and solution, per row              */
    double *bk[SPH_MAX_LOADED], *solk[SPH_MAX_LOADED]; /* loaded plates' sensitivities */
    int rows_cap;
    int nrows;
    int pin;                   /* pinned pressure unknown (no free surface) or -1    */
    long fallback_after;       /* density.c: no GMRES fallback before this step      */
    int fallback_wait;         /* the last wait set (0: the last fallback helped)    */
    int later_stalled;         /* density.c: the last later pass had step length 0   */
    int first_difference;      /* density.c: the last first pass moved along the
                                  difference form's direction                        */
    int *row_of;               /* row -> particle                                   */

    double t, dt, wall_time;
    double phase_time[SPH_PHASES]; /* seconds per phase of the step (sph_lap)          */
    double lap;                /* omp_get_wtime() at the last sph_lap               */
    long steps;
    sph_stats st;
    int prepared;
    double dt_prev;
    /* unshifted runs: when fluid particles first came within half a spacing of each other
     * (cluster_step < 0: not yet), for the failure messages' hint (world.c) */
    long cluster_step;
    double cluster_t;
};

/* world.c */
/* Phase timer: the wall time since the last lap goes to phase `phase`. */
void sph_lap(sph_world *w, int phase);
int sph_world_fail(sph_world *w, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
int sph_world_reserve(sph_world *w, int need);
/* The dx lattice of rect for a fill or a plate (what names it in messages): nx x ny points.
 * -1 with a message on a rect that is not finite, inverted, holds no lattice point, or
 * would take the world past SPH_MAX_PARTICLES. */
int sph_world_lattice(sph_world *w, const double rect[4], const char *what, int *nx, int *ny);

/* surface.c: sets w->surf (fluid particles on the free surface; ghosts copy their source's
 * flag) and w->st.surface, from this step's neighbour lists and position divergence */
void sph_surface_mark(sph_world *w);

/* neighbours.c */
int sph_neighbours_sort(sph_world *w);
int sph_neighbours_build(sph_world *w);
void sph_neighbours_built_position(const sph_world *w, int i, double *x, double *y);
/* Brute-force neighbours of real particle i among all particles (for tests):
 * writes indices into out (capacity cap), returns count. */
int sph_neighbours_brute(const sph_world *w, int i, int *out, int cap);

/* boundary.c: periodic wrap and ghost images */
void sph_boundary_wrap(sph_world *w);
int sph_boundary_ghosts(sph_world *w);
void sph_boundary_sync(sph_world *w, double *a, double *b, int vector);

/* plates.c */
int sph_plate_fill(sph_world *w, const double rect[4], int axis);
/* No-slip factor beta = 1 + dB/da (clamped) for fluid a and wall particle b; *normal: the
 * axis of the normal of the face nearest to a (0: x, 1: y). */
double sph_plate_noslip(const sph_world *w, int a, int b, int *normal);
/* Velocity of wall particle b along x, y. */
void sph_plate_wall_velocity(const sph_world *w, int b, double *vx, double *vy);
void sph_plate_rigid_velocity(const sph_world *w, int b, double *vx, double *vy);
void sph_plate_prepare(sph_world *w);
void sph_plate_move(sph_world *w, int k, double dpos);
int sph_plate_check_escape(sph_world *w);
void sph_plate_contact(sph_world *w);
/* The factor from the simulated part of a plate to the whole sample: 2 for a plate that
 * straddles a symmetry plane. */
static inline double sph_plate_whole(const sph_plate *pl) { return pl->doubled ? 2.0 : 1.0; }
/* Fluid pressure force on every plate along its axis for a pressure field p (ghosts
 * synced), whole-sample values into out[k]. */
void sph_plate_pressure_force(const sph_world *w, const double *p, double *out);
int sph_plate_loaded_velocities(sph_world *w, double dt, int K, const int *loaded, const double *F0,
                                double (*Fk)[SPH_MAX_PLATES], double *x);
void sph_plate_set_viscous_forces(sph_world *w, const double *f);
/* The force along its axis that this pair puts on wall j's plate (0 for a fixed plate). */
static inline double sph_plate_pull(const sph_world *w, int i, int j, double cu, double cv, double ui, double vi,
                                double wx, double wy) {
    const sph_plate *pl = &w->plates[w->kind[j]];
    if (pl->axis < 0) return 0.0;
    return -w->m[i] * (pl->axis == 0 ? cu * (ui - wx) * w->gsx[j] : cv * (vi - wy) * w->gsy[j]);
}


/* physics passes (viscous.c, pressure.c) */
void sph_viscous_rheology(sph_world *w, double dt);
/* The stress magnitude |tau| of fluid particle i (viscous.c, yield_stress), and whether it
 * has yielded, |tau| > tau0: the one definition behind w:field, the statistics and the files. */
static inline double sph_particle_stress(const sph_world *w, int i) { return w->tau[i]; }
static inline int sph_particle_yielded(const sph_world *w, int i) {
    return sph_particle_stress(w, i) > w->mats[w->mat[i]].tau0;
}
/* The traction-free free surface (viscous.c) is carried with the symmetric pressure
 * gradient (the default), for every material law; with the thin-film scheme's difference
 * form the surface holds p = 0. */
static inline int sph_surface_traction(const sph_world *w) {
    return !w->par.thin_film;
}
/* g_i = sum_j V_j grad_i W_ij over all neighbours: zero in a full, even support, -|g| n
 * next to a free surface (the truncated support's boundary moment) */
static inline void sph_boundary_moment(const sph_world *w, int i, double *gx, double *gy) {
    double x = 0.0, y = 0.0;
    for (int k = w->nb_start[i]; k < w->nb_start[i + 1]; k++) {
        x += w->vol[w->nb_j[k]] * w->nb_gx[k];
        y += w->vol[w->nb_j[k]] * w->nb_gy[k];
    }
    *gx = x;
    *gy = y;
}
void sph_viscous_explicit(sph_world *w, double dt);
int sph_viscous_implicit(sph_world *w, double dt);
int sph_pressure_solve(sph_world *w, double dt);
void sph_pressure_correct(sph_world *w, double dt);
/* world.c: sph_world_step, with whether dt is the caller's (held to the viscous-time span) */
int sph_world_step_given(sph_world *w, double dt, int given);
void sph_pressure_predictor(sph_world *w, double *ax, double *ay);
int sph_density_correct(sph_world *w, double dt);
/* The pressure system's pieces the density correction (density.c) shares (pressure.c) */
void sph_pressure_neg_grad_prepare(sph_world *w, const double *f, double *fr);
/* p from a solution per row; free-surface fluid particles take surface[i] (NULL: 0) */
void sph_pressure_scatter(sph_world *w, const double *sol, double *p, const double *surface);
void sph_pressure_make_compatible(sph_world *w, double pin_source);

/* sum_j m_j (u_i - u_j) . L grad W_ij for the field (ru, rv) (ghosts synced): the source's
 * divergence (renormalised on fluid particles), and a fluid particle's continuity rate */
static inline double sph_field_div(const sph_world *w, const double *ru, const double *rv, int i) {
    int fl = w->kind[i] == SPH_FLUID;
    double lxx = fl ? w->lxx[i] : 1.0, lxy = fl ? w->lxy[i] : 0.0, lyy = fl ? w->lyy[i] : 1.0;
    double div = 0.0, ui = ru[i], vi = rv[i];
    const int *nj = w->nb_j;
    const double *m = w->m, *ngx = w->nb_gx, *ngy = w->nb_gy;
    int k0 = w->nb_start[i], k1 = w->nb_start[i + 1];
#pragma omp simd reduction(+ : div)
    for (int k = k0; k < k1; k++) {
        int j = nj[k];
        double gx = lxx * ngx[k] + lxy * ngy[k], gy = lxy * ngx[k] + lyy * ngy[k];
        div += m[j] * ((ui - ru[j]) * gx + (vi - rv[j]) * gy);
    }
    return div;
}

/* -(grad f)_i / rho_i, symmetric form: -sum_j m_j (fr_i + fr_j) grad_i W_ij with fr = f / rho^2
 * (sph_pressure_neg_grad_prepare; f synced on ghosts) */
static inline void sph_neg_grad(const sph_world *w, const double *fr, int i, double *ax, double *ay) {
    double fi = fr[i], gx = 0.0, gy = 0.0;
    const int *nj = w->nb_j;
    const double *m = w->m, *ngx = w->nb_gx, *ngy = w->nb_gy;
    int k0 = w->nb_start[i], k1 = w->nb_start[i + 1];
#pragma omp simd reduction(+ : gx, gy)
    for (int k = k0; k < k1; k++) {
        int j = nj[k];
        double c = m[j] * (fi + fr[j]);
        gx -= c * ngx[k];
        gy -= c * ngy[k];
    }
    *ax = gx;
    *ay = gy;
}

/* -(grad f)_i / rho_i in the renormalised difference form L_i sum_j V_j (f_j - f_i) grad W_ij
 * (Lind et al. 2012): exact for a linear f, whatever the particle disorder, and blind to a
 * uniform level of f (f synced on ghosts). */
static inline void sph_neg_grad_difference(const sph_world *w, const double *f, int i, double *ax, double *ay) {
    double gx = 0.0, gy = 0.0, fi = f[i];
    const int *nj = w->nb_j;
    const double *vol = w->vol, *ngx = w->nb_gx, *ngy = w->nb_gy;
    int k0 = w->nb_start[i], k1 = w->nb_start[i + 1];
#pragma omp simd reduction(+ : gx, gy)
    for (int k = k0; k < k1; k++) {
        double c = vol[nj[k]] * (f[nj[k]] - fi);
        gx += c * ngx[k];
        gy += c * ngy[k];
    }
    double ir = 1.0 / w->rho[i];
    *ax = -ir * (w->lxx[i] * gx + w->lxy[i] * gy);
    *ay = -ir * (w->lxy[i] * gx + w->lyy[i] * gy);
}

/* shifting.c */
void sph_shifting_apply(sph_world *w, double dt);

/* timestep.c */
double sph_timestep_compute(sph_world *w);
/* What sets the time step now, for an error message: the fastest and the most accelerated
 * fluid particles and the largest density error, with ids and positions (into buf). */
void sph_timestep_explain(const sph_world *w, char *buf, size_t len);

#endif
