/* The world object and the engine's internal interfaces (not part of the public API). */
#ifndef SPH_INTERNAL_H
#define SPH_INTERNAL_H

#include "sph.h"

#include <stdint.h>
#include <stdio.h>

#define SPH_FLUID (-1) /* kind[] of a fluid particle; walls hold their plate index */
#define SPH_MAX_MATERIALS 64
#define SPH_MAX_PLATES 64
#define SPH_MAX_LOADED 4 /* plates under a load law, coupled implicitly */
/* C_s: the free surface's stress is explicit (viscous.c, surface_pressure), so dt <=
 * C_s rho h^2 / eta (timestep.c). It is stable to 3.2 rho h^2 / eta (beyond, a particle-scale
 * mode of the surface row grows); 2 keeps a margin. */
#define SPH_SURFACE_CS 2.0

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
    int count;           /* real particles                                            */
    int doubled;         /* straddles a symmetry plane: whole = 2 x simulated half   */
    int face_side;       /* +1: fluid on the high side of the axis, -1: low, 0: ?    */
} sph_plate;

/* A compressed row-wise sparse matrix (CSR). */
typedef struct sph_csr {
    int n, nnz, cap;
    int *start; /* n + 1 */
    int *col;
    double *val;
    double *diag; /* n */
} sph_csr;

typedef struct sph_solve_result {
    int iterations;
    double residual; /* ||b - A x|| / ||b|| */
    int converged;
} sph_solve_result;

/* Algebraic multigrid (amg.c): smoothed aggregation, used as a symmetric cycle
 * preconditioner inside CG. Level 0 is the caller's matrix; each level keeps its Galerkin
 * operator, the prolongation P to it from the level above and the restriction R = P^T. */
#define SPH_AMG_MAX_LEVELS 20
#define SPH_AMG_MAX_THREADS 64 /* threads of the setup's sparse products (more run as this many) */
/* A level's smoother copy (smoother.c, "The smoother's copy"): the operator's off-diagonals
 * split per row into L (earlier rows of the same thread block) in [fs[i], fm[i]) and the
 * rest, U, in [fu[i], fs[i + 1]) (between them the diagonal's slots, zeros at column i, so
 * [fs[i], fs[i + 1]) is the whole row); values in float (rounded toward zero), columns as 16-bit
 * offsets from the row when they fit, the inverse diagonal in double. */
typedef struct sph_smoother {
    int n;              /* rows it holds (0: none) */
    int *fs, *fm, *fu;
    int16_t *fofs;      /* columns as offsets j - i (f16), or                              */
    int *fcol;          /* as indices when an offset does not fit in 16 bits               */
    long fcolcap;
    int f16;
    float *fval;
    double *fdinv;
    int fcap_n;
    long fcap_nnz;
    int fblocks;        /* thread blocks the split was made for (1: plain Gauss-Seidel) */
    /* a second system of the same structure (sph_amg_second: the viscous v component),
     * its values and inverse diagonal; has2: they are of the current structure */
    float *fval2;
    double *fdinv2;
    long fcap2_nnz;
    int fcap2_n, has2;
} sph_smoother;
/* The hot vectorised loops (the neighbour build's rows, the shifting's kernel sums) compiled
 * twice, for x86-64-v3 (AVX2, FMA) and the build's baseline, the one run chosen when the
 * program loads (GCC 11+ on x86-64 Linux, ifunc; not under AddressSanitizer): the build
 * stays runnable on any x86-64-v2 machine, and those loops run about a fifth faster with
 * AVX2. The rest of the engine gains nothing from x86-64-v3: the solves' sweeps are bound
 * by memory. */
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 11 && defined(__linux__) && \
    !defined(__SANITIZE_ADDRESS__)
#define SPH_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define SPH_CLONES
#endif
#define SPH_AMG_PAR_MIN 4000 /* rows below which a level's sweeps and products run on one thread */

/* smoother.c: build the copy of a (with a2's values as the second system's when given);
 * add a second system's values later; the sweeps (forward from x = 0 with r = b - A x
 * after it, backward, residual) on one system or on two at once; free. */
int sph_smoother_build(sph_smoother *S, const sph_csr *a, const sph_csr *a2, int threads);
int sph_smoother_second(sph_smoother *S, const sph_csr *a2, int threads);
void sph_smoother_forward(const sph_smoother *S, int n, const double *b, double *x, double *r, int threads);
void sph_smoother_backward(const sph_smoother *S, int n, const double *b, double *x, double *tmp, int threads);
void sph_smoother_residual(const sph_smoother *S, int n, const double *b, const double *x, double *r, int threads);
/* A level's values for two systems (level 0 with a second system: its own values). */
typedef struct sph_smoother_pair {
    const float *v1, *v2;
    const double *d1, *d2;
} sph_smoother_pair;
sph_smoother_pair sph_smoother_pair_of(const sph_smoother *S, int l);
void sph_smoother_forward2(const sph_smoother *S, sph_smoother_pair q, int n, const double *b1, const double *b2,
                           double *x1, double *x2, double *r1, double *r2, int threads);
void sph_smoother_backward2(const sph_smoother *S, sph_smoother_pair q, int n, const double *b1, const double *b2,
                            double *x1, double *x2, double *t1, double *t2, int threads);
void sph_smoother_residual2(const sph_smoother *S, sph_smoother_pair q, int n, const double *b1, const double *b2,
                            const double *x1, const double *x2, double *r1, double *r2, int threads);
void sph_smoother_free(sph_smoother *S);

typedef struct sph_amg_level {
    sph_csr A;          /* operator (level 0: the fine matrix with duplicate columns merged) */
    sph_csr P, R;       /* to the next level: n x nc and nc x n (unused on the coarsest) */
    double *x, *b, *r, *t; /* work vectors, n each */
    double *x2, *b2, *r2, *t2; /* the same for a second right-hand side (sph_amg_apply2) */
    int vcap;
    sph_smoother S;    /* the smoother's copy of the operator (level 0: of the caller's matrix) */
} sph_amg_level;

typedef struct sph_amg {
    int levels;         /* 0: not set up */
    sph_amg_level lev[SPH_AMG_MAX_LEVELS];
    double *chol;       /* dense Cholesky factor of the coarsest operator (NULL: sweeps) */
    int chol_n;
    long chol_cap;
    int *agg, *mark, *sstart, *sj; /* setup scratch: aggregates, markers, strong graph */
    int icap;
    long sjcap;
    sph_csr AP;         /* setup scratch: A P */
    int *pmark;         /* setup scratch of the sparse products: a marker and an */
    double *pacc;       /* accumulator per thread                                */
    long pcap;
    int *tcol[SPH_AMG_MAX_THREADS];   /* setup scratch: each thread's rows of a product */
    double *tval[SPH_AMG_MAX_THREADS];
    long tcap[SPH_AMG_MAX_THREADS];
    /* knobs (0: default) */
    double theta;       /* strength of connection |a_ij| >= theta sqrt(a_ii a_jj); 0.08  */
    int sweeps;         /* Gauss-Seidel sweeps before and after the coarse correction; 1 */
    int coarse_max;     /* stop coarsening at this many rows; 100                        */
    int wcycle_from;    /* levels from this one down visit the next twice (W-cycle); 1   */
    /* reuse across steps (sph_amg_reuse): the particle id of each fine row at the last
     * setup or reuse, and a scratch map id -> row (-1 between uses) */
    int *rid, ridcap;
    int *idmap, idmapcap;
    int age;            /* reuses since the last setup                                   */
    int it_fresh;       /* iterations of the first solve after the last setup (-1: none) */
    int it_recent;      /* iterations of the first solve after the last setup or reuse   */
    const void *built_for; /* the matrix (the caller's) it was built for                   */
    /* what the last setup built */
    int fine_n;
    long nnz_total;     /* sum of nonzeros over all levels (operator complexity x fine nnz) */
} sph_amg;

/* Scratch and statistics of the Krylov solver. */
typedef struct sph_solver {
    int cap;
    double *r, *z, *q, *d;
    double *r2, *z2, *q2, *d2, *x2; /* the second system of sph_solver_pcg2; x2: for the caller */
    sph_amg amg, amg2;      /* one hierarchy per system (pressure, viscous), kept across steps */
    sph_amg *cur;           /* the one in use                                             */
    int first_pending;      /* the next solve is the first since the last setup           */
    const sph_csr *amg_for; /* the matrix the AMG hierarchy was set up for (NULL: none) */
    long reuses;            /* setups answered by reusing a hierarchy (statistics)        */
    double setup_time, solve_time; /* seconds, accumulated */
    long solves;                   /* sph_solver_pcg calls on a non-empty system */
} sph_solver;

/* A solve's first guess (solver.c): the changes its unknown took in the last two solves,
 * per particle (permuted with the particles), with their dt and the particle count then
 * (0: none). */
typedef struct sph_guess {
    double *d, *d1; /* the last solve's change, the one before's */
    double dt, dt1;
    int n, n1;
} sph_guess;

struct sph_world {
    sph_params par;
    double h, dx, eps2, mass0;
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
    double *lxx, *lxy, *lyy;   /* kernel-gradient renormalisation (Bonet & Lok 1999) */
    double *gux, *guy, *gvx, *gvy; /* velocity gradient (du/dx, du/dy, dv/dx, dv/dy)  */
    double *xs, *ys;           /* scratch (reordering, shifting displacements)       */
    double *vol;               /* m / rho, set by the neighbour build (rho of then)  */
    double *sa, *sb;           /* scratch per particle for the sweeps (f / rho^2,
                                  the source velocity of the pressure system)        */
    double *cx, *cy;           /* positions in cell order: cx[k] = x[cell_items[k]]  */
    double *ru, *rv;           /* scratch: a first density pass's second direction   */
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
    double *nb_f;              /* r_ij . grad_i W_ij / (r_ij^2 + eps^2)             */
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
/* No-slip factor beta = 1 + dB/da (clamped) for fluid a and wall particle b. */
double sph_plate_noslip(const sph_world *w, int a, int b);
/* Velocity of wall particle b along x, y. */
void sph_plate_wall_velocity(const sph_world *w, int b, double *vx, double *vy);
void sph_plate_rigid_velocity(const sph_world *w, int b, double *vx, double *vy);
void sph_plate_prepare(sph_world *w);
void sph_plate_move(sph_world *w, int k, double dpos);
int sph_plate_check_escape(sph_world *w);
void sph_plate_contact(sph_world *w);

/* physics passes (viscous.c, pressure.c) */
void sph_viscous_rheology(sph_world *w);
/* The stress magnitude |tau| = eta gammadot of fluid particle i, and whether it has
 * yielded, |tau| > tau0: the one definition behind w:field, the statistics and the files. */
static inline double sph_particle_stress(const sph_world *w, int i) { return w->eta[i] * w->gd[i]; }
static inline int sph_particle_yielded(const sph_world *w, int i) {
    return sph_particle_stress(w, i) > w->mats[w->mat[i]].tau0;
}
/* The traction-free free surface (viscous.c) is carried for a Newtonian fluid particle
 * with the symmetric pressure gradient (the default); elsewhere the surface holds p = 0. */
static inline int sph_surface_traction(const sph_world *w, int i) {
    return w->mats[w->mat[i]].model == SPH_NEWTONIAN && w->par.pressure_gradient == SPH_GRAD_SYMMETRIC;
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
void sph_pressure_predictor(sph_world *w, double *ax, double *ay);
int sph_density_correct(sph_world *w);
/* The pressure system's pieces the density correction (density.c) shares (pressure.c) */
void sph_pressure_neg_grad_prepare(sph_world *w, const double *f, double *fr);
/* p from a solution per row; free-surface fluid particles take surface[i] (NULL: 0) */
void sph_pressure_scatter(sph_world *w, const double *sol, double *p, const double *surface);
void sph_pressure_make_compatible(sph_world *w, double pin_source);
int sph_pressure_dense_solve(int n, double *a, int lda, double *x);
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

/* solver.c */
/* The engine's iteration limit for every solve: far above what any converging one takes
 * (tens), so only a solve that cannot converge reaches it and stops the step. */
#define SPH_SOLVE_MAX_ITER 5000
/* realloc *p to count elements of elem bytes (at least one); -1 when out of memory, *p kept. */
int sph_grow(void **p, size_t elem, int count);
int sph_csr_reserve(sph_csr *a, int n, int nnz);
void sph_csr_free(sph_csr *a);
void sph_csr_matvec(const sph_csr *a, const double *x, double *y, int threads);
int sph_solver_reserve(sph_solver *s, int n);
void sph_solver_free(sph_solver *s);
/* The preconditioner for the solves on matrix a that follow (until the next setup): the
 * multigrid hierarchy of a (its values and structure now; a later change of a's values
 * keeps the hierarchy, which stays a valid SPD preconditioner). 0, or -1 when out of
 * memory or the coarse operator is not positive definite (then no hierarchy is set up, and
 * a solve on a fails). */
int sph_solver_setup(sph_solver *s, const sph_csr *a, int threads);
/* As sph_solver_setup, but the hierarchy built for a at an earlier step may be kept
 * (see solver.c, "Reuse across steps"): row r of a is particle row_of[r], whose stable id
 * is id[row_of[r]]; the finest level's smoother always takes a's current values. */
int sph_solver_setup_reuse(sph_solver *s, const sph_csr *a, int threads, const int *row_of, const int *id);
/* a's values changed since the setup (same structure and size, still SPD): the AMG
 * hierarchy is kept, the finest level's smoother takes the new values (without it the
 * cycle smooths with the old ones: still a valid preconditioner, a weaker one). 0, or -1
 * when out of memory (then no hierarchy is set up, and a solve on a fails). */
int sph_solver_refresh(sph_solver *s, const sph_csr *a, int threads);
/* Apply the hierarchy set up for a (the last setup) as a V-cycle: every level visits the
 * next once (the default is a W-cycle below the finest level; a setup restores it). For
 * the viscous systems (solver.c, sph_solver_vcycle). */
void sph_solver_vcycle(sph_solver *s, const sph_csr *a);
/* A second system a2 of the same structure as a (same start and col arrays, other values)
 * for sph_solver_pcg2: the hierarchy set up for a serves both, the finest level's smoother
 * takes a2's values for a2's system (a's keep theirs). 0, or -1 when out of memory (then
 * a2's system is smoothed with a's values: still a valid preconditioner). */
int sph_solver_second(sph_solver *s, const sph_csr *a, const sph_csr *a2, int threads);
/* sph_solver_setup for a followed by sph_solver_second for a2 (AMG), the finest smoother's
 * copies of both made in one pass; the same hierarchy and figures bit for bit. With row_of
 * and id (row r is particle id[row_of[r]]) the hierarchy is reused across steps by the
 * rules of sph_solver_setup_reuse, the finest smoother rebuilt from both matrices' values;
 * with 0, 0 it is built afresh. */
int sph_solver_setup_pair(sph_solver *s, const sph_csr *a, const sph_csr *a2, int threads, const int *row_of,
                          const int *id);
/* First guesses (the viscous and pressure solves): the change of the next solve taken as
 * a d - b d1, extrapolated per unit time from the last two solves' changes ((2 d / dt_n -
 * d1 / dt_{n-1}) dt), from the last one alone (b = 0) when only it was for the same n
 * particles; 0 and 0 when neither (then the guess is the solve's plain start).
 * sph_guess_keep makes room for this solve's change (returned: the array to fill; the
 * last one becomes the one before). */
void sph_guess_weights(const sph_guess *g, int n, double dt, double *a, double *b);
double *sph_guess_keep(sph_guess *g, int n, double dt);
/* Two independent systems a1 x1 = b1, a2 x2 = b2 of the same structure (a2 registered by
 * sph_solver_setup_pair, or by sph_solver_second after the setup for a1), solved side by
 * side: each iteration reads the structure once for both (CG's product and the multigrid
 * cycle). Each system's iterates are those of sph_solver_pcg on it alone (the same
 * arithmetic, bit for bit). res[0], res[1]: the two results (both fail, not converged after
 * 0 iterations, without such a setup). */
void sph_solver_pcg2(sph_solver *s, const sph_csr *a1, const sph_csr *a2, const double *b1, const double *b2,
                     double *x1, double *x2, double tol, int max_iter, int threads, sph_solve_result res[2]);
/* Conjugate gradients for SPD a preconditioned by the multigrid cycle of the last setup,
 * which must have been for a (else the solve fails: not converged after 0 iterations);
 * x holds the initial guess. */
sph_solve_result sph_solver_pcg(sph_solver *s, const sph_csr *a, const double *b, double *x,
                                double tol, int max_iter, int threads);

/* amg.c */
int sph_amg_setup(sph_amg *g, const sph_csr *a, int threads);
/* z = one symmetric multigrid cycle applied to r (from z = 0); a is the fine matrix (values may
 * differ from those at setup, same structure and size). */
void sph_amg_apply(sph_amg *g, const sph_csr *a, const double *r, double *z, int threads);
/* The second system's values at the finest level's smoother (a2: the structure of the
 * matrix of the setup, other values); -1 out of memory. */
int sph_amg_second(sph_amg *g, const sph_csr *a2, int threads);
/* sph_amg_setup for a, then sph_amg_second for a2, in one pass over the finest copy. */
int sph_amg_setup_pair(sph_amg *g, const sph_csr *a, const sph_csr *a2, int threads);
/* The cycle on two right-hand sides at once: z1 for a1 (the setup's values), z2 for a2
 * (sph_amg_second's), each as sph_amg_apply would give it. */
void sph_amg_apply2(sph_amg *g, const sph_csr *a1, const sph_csr *a2, const double *r1, const double *r2,
                    double *z1, double *z2, int threads);
/* The cycle for a2's system alone (the finest smoother with sph_amg_second's values). */
void sph_amg_apply_second(sph_amg *g, const sph_csr *a2, const double *r, double *z, int threads);
/* Keep the hierarchy for a new fine matrix a of the same particles (rows renumbered,
 * some come and go): the prolongation's rows follow their particles' ids (row r: particle
 * id[row_of[r]]; a new row gets none), the coarse operators stay. 0; 1 when g holds no
 * ids to map from (nothing changed); -1 out of memory (g is then not usable). */
int sph_amg_reuse(sph_amg *g, const sph_csr *a, const sph_csr *a2, const int *row_of, const int *id, int threads);
/* Record the ids of a's rows after a setup (for sph_amg_reuse); -1 out of memory. */
int sph_amg_set_ids(sph_amg *g, int n, const int *row_of, const int *id);
/* Exchange the setup-only scratch of two hierarchies (the finest level's merged copy of the
 * matrix, the products' buffers, the aggregation's arrays): the two systems' hierarchies
 * share one set, which saves about an eighth of the peak memory. */
void sph_amg_swap_scratch(sph_amg *a, sph_amg *b);
/* The finest level's smoother takes a's values (same structure as at the setup). */
int sph_amg_refresh(sph_amg *g, const sph_csr *a, int threads);
void sph_amg_free(sph_amg *g);
/* The hierarchy with a world's state (state.c; amg.c, "Saving a hierarchy"): write, -1 on
 * a write error; read into a freed or fresh g, rebuilding what is derived (for threads),
 * ids checked below next_id: 0, 1 when the file ended, -1 damaged (why says how). */
int sph_amg_write(const sph_amg *g, FILE *f);
int sph_amg_read(sph_amg *g, FILE *f, int next_id, int threads, char *why, size_t len);

#endif
