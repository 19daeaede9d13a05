/* The multigrid smoother (amg.c's cycle): a level's copy of its operator, split per row for
 * Gauss-Seidel sweeps that read it once per visit, with float values and 16-bit column
 * offsets, and the forward / backward sweeps and residuals on one or two systems (the
 * viscous u and v) at once. */
/* Code placement: the hot loops on 64-byte boundaries (amg.c says why: the sweeps' speed
 * moves with where their loops fall by up to 12 %). GCC only. */
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC optimize("align-loops=64", "align-functions=64")
#endif
#include "linalg.h"

#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* The smoother's copy (every level but the coarsest; "finest level" below, the same
 * holds on the coarse levels, whose operators are ours: on a W-cycle level the second
 * visit's residual is a full product on the copy, b - D x - (L + U) x).
 * The finest level's cycle reads the fine matrix three times (forward sweep, residual, backward sweep) and
 * CG reads it once more per iteration: at 10^5 rows (27 nonzeros a row, 33 MB) the step is
 * bound by that traffic. Three savings:
 *   - the forward sweep starts from x = 0, so it needs only L (the entries of earlier rows of
 *     the same thread block), and after it b - A x = -U x (the other off-diagonals): the
 *     forward sweep and the residual read the matrix once between them, not twice;
 *   - the smoother's copy holds the off-diagonals in float (the diagonal stays double).
 *     They are rounded toward zero, which keeps a diagonally dominant row dominant, so the
 *     copy stays positive (semi)definite like the matrix and the cycle a symmetric positive
 *     definite preconditioner (CG's own product is in double). The engine's fine matrices
 *     are diagonally dominant; a Galerkin coarse operator need not be, and there the
 *     rounding (a relative 6e-8 of each entry) is far below its smallest eigenvalue. The
 *     copy's diagonal is the smoother's (spgemm: a zero-operator cluster's is its
 *     off-diagonal sum), also in the W-cycle's second residual: the cycle is that of the
 *     copy's symmetric operator throughout;
 *   - its columns are 16-bit offsets from the row when they all fit (rows in cell order:
 *     a row's neighbours are a few rows of cells away), int32 otherwise: 6 bytes a nonzero
 *     instead of 12.
 * The copy is made at setup from the matrix of then (and by sph_amg_refresh / reuse).
 * Together the three take about a quarter off the solves' time at 10^5 particles. */
/* Gauss-Seidel, not a polynomial (Chebyshev) smoother: a sweep on this copy is not bound by
 * its recurrence (about 0.5 ns a nonzero, as a product), and a Chebyshev smoother that
 * reaches the same iterations costs twice the sweeps. */
#if defined(__GNUC__)
#define SMOOTHER_LIKELY(c) __builtin_expect(!!(c), 1)
#define SMOOTHER_NOINLINE __attribute__((noinline))
#else
#define SMOOTHER_LIKELY(c) (c)
#define SMOOTHER_NOINLINE
#endif
/* v tiny, huge or not finite: rounded to nearest, then one unit in the last place back
 * when that was away from zero */
static SMOOTHER_NOINLINE float to_float0_rare(double v) {
    float f = (float)v;
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    u -= (uint32_t)(fabsf(f) > fabs(v));
    memcpy(&f, &u, sizeof f);
    return f;
}

static inline float to_float0(double v) {
    uint64_t b;
    memcpy(&b, &v, sizeof b);
    if (SMOOTHER_LIKELY(((b >> 52) & 0x7ff) - 897u < 254u)) { /* |v| in float's normal range: */
        b &= ~(uint64_t)0x1fffffff; /* the 29 mantissa bits a float does not hold, dropped: */
        double t;                   /* toward zero, and exact in float */
        memcpy(&t, &b, sizeof t);
        return (float)t;
    }
    return to_float0_rare(v);
}

/* Rows lo..hi-1 of a thread block into the copy (f16: a constant where it is inlined);
 * with a2 (a second system of a's structure) its values into fval2 and fdinv2 in the same
 * pass. */
static inline int split_rows(sph_smoother *S, const sph_csr *a, const sph_csr *a2, int lo, int hi, int f16,
                             float *fval, double *fdinv) {
    const int *st = a->start, *col = a->col;
    const double *val = a->val, *val2 = a2 ? a2->val : 0;
    int16_t *fofs = S->fofs;
    float *fval2 = S->fval2;
    int *fcol = S->fcol, *fs = S->fs, *fm = S->fm, *fu = S->fu, ovf = 0;
    for (int i = lo; i < hi; i++) { /* L from the row's start up, U from its end down */
        int el = st[i], eu = st[i + 1];
        fs[i] = el;
        for (int k = st[i]; k < st[i + 1]; k++) {
            int j = col[k];
            if (j == i) continue;
            int low = (j >= lo) & (j < i); /* branch-free: L or U is data-dependent */
            eu -= 1 - low;
            int e = low ? el : eu;
            el += low;
            if (f16) {
                int d = j - i;
                ovf |= d != (int16_t)d;
                fofs[e] = (int16_t)d;
            } else {
                fcol[e] = j;
            }
            fval[e] = to_float0(val[k]);
            if (a2) fval2[e] = to_float0(val2[k]);
        }
        /* the diagonal's slots between L and U: zeros (column i), so that the backward sweep
         * and the residual run over the row as one range (one loop exit a row instead of
         * two, which counts where row lengths vary as the SPH neighbour counts do;
         * s - 0 x_i = s: the same figures bit for bit). */
        for (int e = el; e < eu; e++) {
            if (f16) fofs[e] = 0;
            else fcol[e] = i;
            fval[e] = 0.0f;
            if (a2) fval2[e] = 0.0f;
        }
        fm[i] = el;
        fu[i] = eu;
        fdinv[i] = 1.0 / a->diag[i];
        if (a2) S->fdinv2[i] = 1.0 / a2->diag[i];
    }
    return ovf;
}

/* split_rows with f16 and the presence of a2 constants */
static int split_block(sph_smoother *S, const sph_csr *a, const sph_csr *a2, int lo, int hi, int f16, float *fval,
                       double *fdinv) {
    if (a2) return f16 ? split_rows(S, a, a2, lo, hi, 1, fval, fdinv) : split_rows(S, a, a2, lo, hi, 0, fval, fdinv);
    return f16 ? split_rows(S, a, 0, lo, hi, 1, fval, fdinv) : split_rows(S, a, 0, lo, hi, 0, fval, fdinv);
}

/* Fill the split copy; columns as int16 offsets j - i when all fit (the rows are in cell
 * order, so a row's neighbours are within a few rows of cells of it), else as int32. The
 * copies are a third of the viscous setup at 10^5 particles (the fine level's, the v
 * component's, the pressure hierarchy's at each reuse), hence the column format a constant
 * in each loop, no parallel region for one block, and the rounding toward zero done by
 * dropping the mantissa bits a float does not hold (to_float0). */
static int split_fill(sph_smoother *S, const sph_csr *a, const sph_csr *a2, int threads, int nb, int f16,
                      float *fval, double *fdinv) {
    int n = a->n, ovf = 0;
    if (nb == 1) return split_block(S, a, a2, 0, n, f16, fval, fdinv);
#pragma omp parallel for schedule(static) num_threads(threads) reduction(| : ovf)
    for (int t = 0; t < nb; t++) {
        int lo = (int)((long)n * t / nb), hi = (int)((long)n * (t + 1) / nb);
        ovf |= split_block(S, a, a2, lo, hi, f16, fval, fdinv);
    }
    return ovf;
}

/* room for a second system's values (sph_amg_second, sph_amg_setup_pair) */
static int grow2(sph_smoother *S, int n, int nnz) {
    if (n + 1 > S->fcap2_n) {
        int cap = n + 1 + n / 4 + 16;
        if (sph_grow((void **)&S->fdinv2, sizeof(double), cap)) return -1;
        S->fcap2_n = cap;
    }
    if (nnz > S->fcap2_nnz) {
        long cap = nnz + nnz / 4 + 16;
        float *v = realloc(S->fval2, sizeof(float) * (size_t)cap);
        if (!v) return -1;
        S->fval2 = v;
        S->fcap2_nnz = cap;
    }
    return 0;
}

/* The copy of a (and of a2's values when a2 is given: the copy's second system). */
int sph_smoother_build(sph_smoother *S, const sph_csr *a, const sph_csr *a2, int threads) {
    int n = a->n, nnz = a->start[n];
    if (a2 && grow2(S, n, nnz)) return -1;
    if (n + 1 > S->fcap_n) {
        int cap = n + 1 + n / 4 + 16;
        if (sph_grow((void **)&S->fs, sizeof(int), cap) || sph_grow((void **)&S->fm, sizeof(int), cap) ||
            sph_grow((void **)&S->fu, sizeof(int), cap) || sph_grow((void **)&S->fdinv, sizeof(double), cap))
            return -1;
        S->fcap_n = cap;
    }
    if (nnz > S->fcap_nnz) {
        long cap = nnz + nnz / 4 + 16;
        int16_t *o = realloc(S->fofs, sizeof(int16_t) * (size_t)cap);
        if (!o) return -1;
        S->fofs = o;
        float *v = realloc(S->fval, sizeof(float) * (size_t)cap);
        if (!v) return -1;
        S->fval = v;
        S->fcap_nnz = cap;
    }
    int nb = n < SPH_AMG_PAR_MIN || threads < 1 ? 1 : threads;
    S->fblocks = nb;
    S->n = n;
    S->fs[n] = nnz;
    S->f16 = 1;
    S->has2 = a2 != 0;
    if (!split_fill(S, a, a2, threads, nb, 1, S->fval, S->fdinv)) return 0;
    /* an offset beyond int16: int32 columns */
    S->f16 = 0;
    if (nnz > S->fcolcap) {
        long cap = nnz + nnz / 4 + 16;
        int *q = realloc(S->fcol, sizeof(int) * (size_t)cap);
        if (!q) return -1;
        S->fcol = q;
        S->fcolcap = cap;
    }
    split_fill(S, a, a2, threads, nb, 0, S->fval, S->fdinv);
    return 0;
}

/* A second system of the copy's structure (a2: other values, the same start and col): its
 * values beside the first's, for the two-system sweeps. 0, or -1 out of memory. */
int sph_smoother_second(sph_smoother *S, const sph_csr *a2, int threads) {
    int n = a2->n, nnz = a2->start[n];
    if (grow2(S, n, nnz)) return -1;
    /* the same structure: the columns are rewritten with what they hold */
    split_fill(S, a2, 0, threads, S->fblocks, S->f16, S->fval2, S->fdinv2);
    S->has2 = 1;
    return 0;
}

/* The sweeps, for either column format: COL(k) is the column of entry k of row i. */
#define FINE_SWEEPS(SUF, IT, COL)                                                                          \
    /* x = forward sweep from x = 0 on the L part; r = -U x (= b - A x). */                                \
    static void fine_forward_##SUF(const sph_smoother *S, int n, const double *b, double *x, double *r,      \
                                   const IT *fc, int threads) {                                          \
        int nb = S->fblocks;                                                                               \
        const int *fs = S->fs, *fm = S->fm, *fu = S->fu;                                                   \
        const float *fv = S->fval;                                                                         \
        const double *dinv = S->fdinv;                                                                     \
        _Pragma("omp parallel num_threads(nb > 1 ? threads : 1)") {                                       \
            _Pragma("omp for schedule(static)") for (int t = 0; t < nb; t++) {                             \
                int lo = (int)((long)n * t / nb), hi = (int)((long)n * (t + 1) / nb);                      \
                for (int i = lo; i < hi; i++) {                                                            \
                    double s = b[i];                                                                       \
                    for (int k = fs[i]; k < fm[i]; k++) s -= fv[k] * x[COL(k)];                            \
                    x[i] = s * dinv[i];                                                                    \
                }                                                                                          \
            }                                                                                              \
            _Pragma("omp for schedule(static)") for (int i = 0; i < n; i++) {                              \
                double s = 0.0;                                                                            \
                for (int k = fu[i]; k < fs[i + 1]; k++) s -= fv[k] * x[COL(k)];                            \
                r[i] = s;                                                                                  \
            }                                                                                              \
        }                                                                                                  \
    }                                                                                                      \
    /* Backward sweep on the whole copy (hybrid across blocks: other blocks' values of before). */        \
    static void fine_backward_##SUF(const sph_smoother *S, int n, const double *b, double *x, double *tmp,   \
                                    const IT *fc, int threads) {                                         \
        int nb = S->fblocks;                                                                               \
        const int *fs = S->fs, *fm = S->fm, *fu = S->fu;                                                   \
        const float *fv = S->fval;                                                                         \
        const double *dinv = S->fdinv;                                                                     \
        if (nb <= 1) {                                                                                     \
            for (int i = n - 1; i >= 0; i--) {                                                             \
                double s = b[i];                                                                           \
                for (int k = fs[i]; k < fs[i + 1]; k++) s -= fv[k] * x[COL(k)];                            \
                x[i] = s * dinv[i];                                                                        \
            }                                                                                              \
            return;                                                                                        \
        }                                                                                                  \
        memcpy(tmp, x, sizeof(double) * (size_t)n);                                                        \
        _Pragma("omp parallel for schedule(static) num_threads(threads)") for (int t = 0; t < nb; t++) {  \
            int lo = (int)((long)n * t / nb), hi = (int)((long)n * (t + 1) / nb);                          \
            for (int i = hi - 1; i >= lo; i--) {                                                           \
                double s = b[i];                                                                           \
                for (int k = fs[i]; k < fm[i]; k++) s -= fv[k] * x[COL(k)]; /* same block */               \
                for (int k = fu[i]; k < fs[i + 1]; k++) {                                                  \
                    int j = COL(k);                                                                        \
                    s -= fv[k] * (j >= lo && j < hi ? x[j] : tmp[j]);                                      \
                }                                                                                          \
                x[i] = s * dinv[i];                                                                        \
            }                                                                                              \
        }                                                                                                  \
    }

/* r = b - A x on the copy (the second visit of a W-cycle level: x is no longer zero) */
#define SPLIT_RESIDUAL(SUF, IT, COL)                                                                       \
    static void residual_##SUF(const sph_smoother *S, int n, const double *b, const double *x,  \
                                     double *r, const IT *fc, int threads) {                             \
        const int *fs = S->fs;                                                                             \
        const float *fv = S->fval;                                                                         \
        const double *dinv = S->fdinv;                                                                     \
        _Pragma("omp parallel for schedule(static) num_threads(n < SPH_AMG_PAR_MIN ? 1 : threads)")           \
        for (int i = 0; i < n; i++) {                                                                      \
            double s = b[i] - x[i] / dinv[i];                                                              \
            for (int k = fs[i]; k < fs[i + 1]; k++) s -= fv[k] * x[COL(k)];                                \
            r[i] = s;                                                                                      \
        }                                                                                                  \
    }

#define COL16(k) (i + fc[k])
#define COL32(k) (fc[k])
FINE_SWEEPS(16, int16_t, COL16)
FINE_SWEEPS(32, int, COL32)
SPLIT_RESIDUAL(16, int16_t, COL16)
SPLIT_RESIDUAL(32, int, COL32)

void sph_smoother_forward(const sph_smoother *S, int n, const double *b, double *x, double *r, int threads) {
    if (S->f16) fine_forward_16(S, n, b, x, r, S->fofs, threads);
    else fine_forward_32(S, n, b, x, r, S->fcol, threads);
}

void sph_smoother_backward(const sph_smoother *S, int n, const double *b, double *x, double *tmp, int threads) {
    if (S->f16) fine_backward_16(S, n, b, x, tmp, S->fofs, threads);
    else fine_backward_32(S, n, b, x, tmp, S->fcol, threads);
}

void sph_smoother_residual(const sph_smoother *S, int n, const double *b, const double *x, double *r, int threads) {
    if (S->f16) residual_16(S, n, b, x, r, S->fofs, threads);
    else residual_32(S, n, b, x, r, S->fcol, threads);
}

/* Two right-hand sides at once (sph_amg_apply2): the same sweeps, each system with its own
 * values (v1, d1 and v2, d2: the finest level's two systems; on the coarse levels both are
 * the level's own), the structure read once for both. Per system, the arithmetic is that
 * of the one-system sweeps above, in the same order. */
#define FINE_SWEEPS2(SUF, IT, COL)                                                                         \
    /* s1 -= sum v1[k] x1[col k], s2 likewise, over the entries [k0, k1) of row i, in order */             \
    static inline void row2_##SUF(const IT *fc, int i, int k0, int k1, const float *v1, const float *v2,   \
                                  const double *x1, const double *x2, double *s1, double *s2) {             \
        double a1 = *s1, a2 = *s2;                                                                         \
        (void)i; /* COL32 does not need it */                                                              \
        for (int k = k0; k < k1; k++) {                                                                    \
            int j = COL(k);                                                                                \
            a1 -= v1[k] * x1[j];                                                                           \
            a2 -= v2[k] * x2[j];                                                                           \
        }                                                                                                  \
        *s1 = a1;                                                                                          \
        *s2 = a2;                                                                                          \
    }                                                                                                      \
    /* the same over the row's L, then its U */                                                            \
    static inline void row2_lu_##SUF(const sph_smoother *S, const IT *fc, int i, const float *v1,         \
                                     const float *v2, const double *x1, const double *x2, double *s1,      \
                                     double *s2) {                                                         \
        row2_##SUF(fc, i, S->fs[i], S->fs[i + 1], v1, v2, x1, x2, s1, s2);                                 \
    }                                                                                                      \
    static void fine_forward2_##SUF(const sph_smoother *S, int n, const float *v1, const float *v2,       \
                                    const double *d1, const double *d2, const double *b1, const double *b2, \
                                    double *x1, double *x2, double *r1, double *r2, const IT *fc, int threads) { \
        int nb = S->fblocks;                                                                               \
        const int *fs = S->fs, *fm = S->fm, *fu = S->fu;                                                   \
        _Pragma("omp parallel num_threads(nb > 1 ? threads : 1)") {                                       \
            _Pragma("omp for schedule(static)") for (int t = 0; t < nb; t++) {                             \
                int lo = (int)((long)n * t / nb), hi = (int)((long)n * (t + 1) / nb);                      \
                for (int i = lo; i < hi; i++) {                                                            \
                    double s1 = b1[i], s2 = b2[i];                                                         \
                    row2_##SUF(fc, i, fs[i], fm[i], v1, v2, x1, x2, &s1, &s2);                             \
                    x1[i] = s1 * d1[i];                                                                    \
                    x2[i] = s2 * d2[i];                                                                    \
                }                                                                                          \
            }                                                                                              \
            _Pragma("omp for schedule(static)") for (int i = 0; i < n; i++) {                              \
                double s1 = 0.0, s2 = 0.0;                                                                 \
                row2_##SUF(fc, i, fu[i], fs[i + 1], v1, v2, x1, x2, &s1, &s2);                             \
                r1[i] = s1;                                                                                \
                r2[i] = s2;                                                                                \
            }                                                                                              \
        }                                                                                                  \
    }                                                                                                      \
    static void fine_backward2_##SUF(const sph_smoother *S, int n, const float *v1, const float *v2,      \
                                     const double *d1, const double *d2, const double *b1, const double *b2, \
                                     double *x1, double *x2, double *t1, double *t2, const IT *fc, int threads) { \
        int nb = S->fblocks;                                                                               \
        const int *fs = S->fs, *fm = S->fm, *fu = S->fu;                                                   \
        if (nb <= 1) {                                                                                     \
            for (int i = n - 1; i >= 0; i--) {                                                             \
                double s1 = b1[i], s2 = b2[i];                                                             \
                row2_lu_##SUF(S, fc, i, v1, v2, x1, x2, &s1, &s2);                                         \
                x1[i] = s1 * d1[i];                                                                        \
                x2[i] = s2 * d2[i];                                                                        \
            }                                                                                              \
            return;                                                                                        \
        }                                                                                                  \
        memcpy(t1, x1, sizeof(double) * (size_t)n);                                                        \
        memcpy(t2, x2, sizeof(double) * (size_t)n);                                                        \
        _Pragma("omp parallel for schedule(static) num_threads(threads)") for (int t = 0; t < nb; t++) {  \
            int lo = (int)((long)n * t / nb), hi = (int)((long)n * (t + 1) / nb);                          \
            for (int i = hi - 1; i >= lo; i--) {                                                           \
                double s1 = b1[i], s2 = b2[i];                                                             \
                row2_##SUF(fc, i, fs[i], fm[i], v1, v2, x1, x2, &s1, &s2); /* same block */                \
                for (int k = fu[i]; k < fs[i + 1]; k++) {                                                  \
                    int j = COL(k), in = j >= lo && j < hi;                                                \
                    s1 -= v1[k] * (in ? x1[j] : t1[j]);                                                    \
                    s2 -= v2[k] * (in ? x2[j] : t2[j]);                                                    \
                }                                                                                          \
                x1[i] = s1 * d1[i];                                                                        \
                x2[i] = s2 * d2[i];                                                                        \
            }                                                                                              \
        }                                                                                                  \
    }                                                                                                      \
    static void residual2_##SUF(const sph_smoother *S, int n, const float *v1, const float *v2,     \
                                      const double *d1, const double *d2, const double *b1, const double *b2, \
                                      const double *x1, const double *x2, double *r1, double *r2, const IT *fc, \
                                      int threads) {                                                     \
        _Pragma("omp parallel for schedule(static) num_threads(n < SPH_AMG_PAR_MIN ? 1 : threads)")           \
        for (int i = 0; i < n; i++) {                                                                      \
            double s1 = b1[i] - x1[i] / d1[i], s2 = b2[i] - x2[i] / d2[i];                                 \
            row2_lu_##SUF(S, fc, i, v1, v2, x1, x2, &s1, &s2);                                             \
            r1[i] = s1;                                                                                    \
            r2[i] = s2;                                                                                    \
        }                                                                                                  \
    }

FINE_SWEEPS2(16, int16_t, COL16)
FINE_SWEEPS2(32, int, COL32)

/* A level's values for the two systems (level 0: the second's are sph_amg_second's). */
sph_smoother_pair sph_smoother_pair_of(const sph_smoother *S, int l) {
    sph_smoother_pair q = {S->fval, S->fval, S->fdinv, S->fdinv};
    if (l == 0 && S->has2) {
        q.v2 = S->fval2;
        q.d2 = S->fdinv2;
    }
    return q;
}

void sph_smoother_forward2(const sph_smoother *S, sph_smoother_pair q, int n, const double *b1, const double *b2,
                           double *x1, double *x2, double *r1, double *r2, int threads) {
    if (S->f16) fine_forward2_16(S, n, q.v1, q.v2, q.d1, q.d2, b1, b2, x1, x2, r1, r2, S->fofs, threads);
    else fine_forward2_32(S, n, q.v1, q.v2, q.d1, q.d2, b1, b2, x1, x2, r1, r2, S->fcol, threads);
}

void sph_smoother_backward2(const sph_smoother *S, sph_smoother_pair q, int n, const double *b1, const double *b2,
                            double *x1, double *x2, double *t1, double *t2, int threads) {
    if (S->f16) fine_backward2_16(S, n, q.v1, q.v2, q.d1, q.d2, b1, b2, x1, x2, t1, t2, S->fofs, threads);
    else fine_backward2_32(S, n, q.v1, q.v2, q.d1, q.d2, b1, b2, x1, x2, t1, t2, S->fcol, threads);
}

void sph_smoother_residual2(const sph_smoother *S, sph_smoother_pair q, int n, const double *b1, const double *b2,
                            const double *x1, const double *x2, double *r1, double *r2, int threads) {
    if (S->f16) residual2_16(S, n, q.v1, q.v2, q.d1, q.d2, b1, b2, x1, x2, r1, r2, S->fofs, threads);
    else residual2_32(S, n, q.v1, q.v2, q.d1, q.d2, b1, b2, x1, x2, r1, r2, S->fcol, threads);
}

void sph_smoother_free(sph_smoother *S) {
    free(S->fs);
    free(S->fm);
    free(S->fu);
    free(S->fcol);
    free(S->fofs);
    free(S->fval);
    free(S->fdinv);
    free(S->fval2);
    free(S->fdinv2);
    memset(S, 0, sizeof *S);
}

