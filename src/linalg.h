/* Linear algebra of the engine: compressed sparse rows, a small dense solve, the
 * Gauss-Seidel smoother, smoothed-aggregation multigrid (amg.c, smoother.c) and the
 * multigrid-preconditioned conjugate gradients with their first guesses (solver.c).
 * Nothing here knows about particles but the ids that let a hierarchy follow its rows
 * across steps. */
#ifndef SPH_LINALG_H
#define SPH_LINALG_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

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
/* Small dense solve a x = b by Gaussian elimination with partial pivoting: a is n x n with
 * rows lda apart, x holds b on entry. Returns the number of zero pivots (their unknowns
 * come out 0). */
int sph_dense_solve(int n, double *a, int lda, double *x);

#endif
