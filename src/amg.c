/* Algebraic multigrid preconditioner: smoothed aggregation (Vanek, Mandel & Brezina 1996)
 * for the engine's symmetric M-matrix-like systems (the pressure Poisson matrix and the
 * implicit viscous matrix, rows scaled by particle mass).
 *
 * Setup, level by level until at most coarse_max rows are left:
 *   - strength of connection: j is a strong neighbour of i when |a_ij| >= theta sqrt(a_ii a_jj)
 *     (the matrices are symmetric, so the graph is too);
 *   - aggregates: (1) every node whose strong neighbours are all free starts an aggregate
 *     with them; (2) a node left over joins the aggregate of its strongest neighbour from
 *     step 1; (3) what is still free starts aggregates with its free strong neighbours.
 *     Nodes without strong neighbours (a row dominated by its diagonal: a Dirichlet-like
 *     row, or the viscous matrix at a small dt) stay out: the smoother solves them;
 *   - tentative prolongation T: piecewise constant on the aggregates (the constant is the
 *     near null space of both operators); smoothed P = (I - omega D_F^-1 A_F) T with the
 *     filtered matrix A_F (weak connections lumped into the diagonal, which keeps P's
 *     stencil as narrow as the strong graph) and omega = 2/3 = 4/3 / 2 (the spectral radius
 *     of D_F^-1 A_F is at most 2: A_F is diagonally dominant);
 *   - R = P^T, Galerkin coarse operator R A P (two sparse products);
 *   - the coarsest operator is factored by dense Cholesky.
 * Cycle: `sweeps` forward Gauss-Seidel sweeps before the coarse correction and as many
 * backward sweeps after it, so the preconditioner is symmetric positive definite and CG can
 * use it. The finest level visits the next one once, every coarser level twice (a W-cycle
 * below the finest level: the coarse levels hold a sixth of the nonzeros, so it costs about
 * 20 % more than a V-cycle per iteration, and on the pressure matrix it takes a fifth fewer
 * iterations). With several threads the sweeps are hybrid: Gauss-Seidel inside each
 * thread's block of rows, Jacobi (the values from before the sweep) across blocks; the
 * blocks are the same in both directions, so the cycle stays symmetric. */
/* Code placement: the hot loops on 64-byte boundaries. The sweeps' speed depends on where
 * their loops fall: the same source at another place in the binary runs the pressure-type
 * solves up to 12 % slower. GCC only (clang ignores the pragma); the same flags in the
 * Makefile would do it for every file. */
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC optimize("align-loops=64", "align-functions=64")
#endif
#include "linalg.h"
#include "sph.h"

#include <math.h>
#include <omp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define AMG_OMEGA (2.0 / 3.0)

static int grow_vectors(sph_amg_level *L, int n) {
    if (n <= L->vcap) return 0;
    int cap = n + n / 4 + 16;
    if (sph_grow((void **)&L->x, sizeof(double), cap) || sph_grow((void **)&L->b, sizeof(double), cap) ||
        sph_grow((void **)&L->r, sizeof(double), cap) || sph_grow((void **)&L->t, sizeof(double), cap) ||
        sph_grow((void **)&L->x2, sizeof(double), cap) || sph_grow((void **)&L->b2, sizeof(double), cap) ||
        sph_grow((void **)&L->r2, sizeof(double), cap) || sph_grow((void **)&L->t2, sizeof(double), cap))
        return -1;
    L->vcap = cap;
    return 0;
}

static int grow_ints(sph_amg *g, int n) {
    if (n <= g->icap) return 0;
    int cap = n + n / 4 + 16;
    if (sph_grow((void **)&g->agg, sizeof(int), cap) || sph_grow((void **)&g->mark, sizeof(int), cap) ||
        sph_grow((void **)&g->sstart, sizeof(int), cap + 1))
        return -1;
    g->icap = cap;
    return 0;
}

/* c = a with duplicate columns summed and the diagonal (a->diag) filled in. */
static int merge_copy(sph_amg *g, const sph_csr *a, sph_csr *c) {
    int n = a->n;
    if (grow_ints(g, n) || sph_csr_reserve(c, n, a->start[n] > 0 ? a->start[n] : 1)) return -1;
    int *pos = g->mark;
    for (int i = 0; i < n; i++) pos[i] = -1;
    int e = 0;
    c->start[0] = 0;
    for (int i = 0; i < n; i++) {
        int row0 = e;
        for (int k = a->start[i]; k < a->start[i + 1]; k++) {
            int j = a->col[k];
            if (pos[j] >= row0) {
                c->val[pos[j]] += a->val[k];
            } else {
                pos[j] = e;
                c->col[e] = j;
                c->val[e] = a->val[k];
                e++;
            }
        }
        c->diag[i] = pos[i] >= row0 ? c->val[pos[i]] : 0.0;
        c->start[i + 1] = e;
    }
    return 0;
}

/* t = transpose of a (a: n x m); cur: scratch of m ints. */
static int transpose(const sph_csr *a, int m, sph_csr *t, int *cur) {
    int n = a->n, nnz = a->start[n];
    if (sph_csr_reserve(t, m, nnz > 0 ? nnz : 1)) return -1;
    for (int j = 0; j <= m; j++) t->start[j] = 0;
    for (int k = 0; k < nnz; k++) t->start[a->col[k] + 1]++;
    for (int j = 0; j < m; j++) t->start[j + 1] += t->start[j];
    if (m > 0) memcpy(cur, t->start, sizeof(int) * (size_t)m);
    for (int i = 0; i < n; i++)
        for (int k = a->start[i]; k < a->start[i + 1]; k++) {
            int e = cur[a->col[k]]++;
            t->col[e] = i;
            t->val[e] = a->val[k];
        }
    for (int j = 0; j < m; j++) t->diag[j] = 0.0;
    return 0;
}

/* c = a b (a: n x k, b: k x m; Gustavson's row-by-row product, duplicate-free result).
 * One pass: each thread appends its block of rows to its own buffer (grown as needed),
 * then the blocks are copied into c. A first pass to count each row's entries would cost
 * ~30 % of the product's time, and the fine level's A P is the largest part of a setup
 * (about a third at 10^5 rows). */
static int spgemm(sph_amg *g, const sph_csr *a, const sph_csr *b, int m, sph_csr *c, int threads) {
    int n = a->n;
    if (n < SPH_AMG_PAR_MIN) threads = 1;
    if (threads > SPH_AMG_MAX_THREADS) threads = SPH_AMG_MAX_THREADS;
    long need = (long)(m > 0 ? m : 1) * threads;
    if (need > g->pcap) {
        long cap = need + need / 4 + 16;
        int *q = realloc(g->pmark, sizeof(int) * (size_t)cap);
        if (!q) return -1;
        g->pmark = q;
        double *v = realloc(g->pacc, sizeof(double) * (size_t)cap);
        if (!v) return -1;
        g->pacc = v;
        g->pcap = cap;
    }
    if (sph_csr_reserve(c, n, 1)) return -1;
    int *marks = g->pmark;
    double *accs = g->pacc;
    int fail = 0, nt = threads;
    long used[SPH_AMG_MAX_THREADS] = {0};
    /* rows: entries per row go to c->start[i + 1] */
#pragma omp parallel num_threads(nt) reduction(| : fail)
    {
        int tid = omp_get_thread_num(), T = omp_get_num_threads();
        int lo = (int)((long)n * tid / T), hi = (int)((long)n * (tid + 1) / T);
        int *mk = marks + (size_t)tid * (size_t)m;
        double *acc = accs + (size_t)tid * (size_t)m;
        for (int j = 0; j < m; j++) mk[j] = -1;
        long e = 0;
        for (int i = lo; i < hi && !fail; i++) {
            long bound = 0; /* the row's entries are at most the sum of b's rows it reads */
            for (int ka = a->start[i]; ka < a->start[i + 1]; ka++) bound += b->start[a->col[ka] + 1] - b->start[a->col[ka]];
            if (e + bound > g->tcap[tid]) {
                long cap = (e + bound) + (e + bound) / 2 + 1024;
                int *q = realloc(g->tcol[tid], sizeof(int) * (size_t)cap);
                double *v = q ? realloc(g->tval[tid], sizeof(double) * (size_t)cap) : 0;
                if (q) g->tcol[tid] = q;
                if (v) {
                    g->tval[tid] = v;
                    g->tcap[tid] = cap;
                } else {
                    fail = 1;
                    break;
                }
            }
            int *col = g->tcol[tid];
            double *val = g->tval[tid];
            long e0 = e;
            for (int ka = a->start[i]; ka < a->start[i + 1]; ka++) {
                int r = a->col[ka];
                double av = a->val[ka];
                for (int kb = b->start[r]; kb < b->start[r + 1]; kb++) {
                    int j = b->col[kb];
                    if (mk[j] != i) {
                        mk[j] = i;
                        acc[j] = 0.0;
                        col[e++] = j;
                    }
                    acc[j] += av * b->val[kb];
                }
            }
            double d = 0.0, off = 0.0;
            for (long k = e0; k < e; k++) {
                val[k] = acc[col[k]];
                if (col[k] == i) d = val[k];
                else off += fabs(val[k]);
            }
            /* the smoother's diagonal: a coarse unknown that holds a whole cluster with
             * no Dirichlet neighbour (a drop thrown off a Re = 1000 squeeze) has a zero
             * (or round-off) entry, its cluster's constant being in the null space; it
             * is smoothed with the off-diagonal sum instead (1 when that is zero too) */
            if (!(d > 1e-10 * off) || !(d > 0.0)) d = off > 0.0 ? off : 1.0;
            c->diag[i] = d;
            c->start[i + 1] = (int)(e - e0);
        }
        used[tid] = e;
        if (tid == 0) nt = T;
    }
    if (fail) return -1;
    c->start[0] = 0;
    for (int i = 0; i < n; i++) c->start[i + 1] += c->start[i];
    if (sph_csr_reserve(c, n, c->start[n] > 0 ? c->start[n] : 1)) return -1;
#pragma omp parallel for schedule(static) num_threads(nt)
    for (int t = 0; t < nt; t++) {
        int lo = (int)((long)n * t / nt);
        if (used[t] == 0) continue;
        memcpy(c->col + c->start[lo], g->tcol[t], sizeof(int) * (size_t)used[t]);
        memcpy(c->val + c->start[lo], g->tval[t], sizeof(double) * (size_t)used[t]);
    }
    return 0;
}

/* Strong graph of a (merged, diag filled) into g->sstart / g->sj. */
static int strength(sph_amg *g, const sph_csr *a, double theta) {
    int n = a->n;
    long need = a->start[n];
    if (need > g->sjcap) {
        long cap = need + need / 4 + 16;
        int *q = realloc(g->sj, sizeof(int) * (size_t)cap);
        if (!q) return -1;
        g->sj = q;
        g->sjcap = cap;
    }
    int e = 0;
    double t2 = theta * theta;
    g->sstart[0] = 0;
    for (int i = 0; i < n; i++) { /* squared: no square root per entry */
        double di = t2 * fabs(a->diag[i]);
        for (int k = a->start[i]; k < a->start[i + 1]; k++) {
            int j = a->col[k];
            double v = a->val[k];
            g->sj[e] = j;
            e += j != i && v * v >= di * fabs(a->diag[j]); /* branch-free: strong or not is data */
        }
        g->sstart[i + 1] = e;
    }
    return 0;
}

/* Aggregates of the strong graph: g->agg[i] in [0, nc) or -1 (isolated). Returns nc. */
static int aggregate(sph_amg *g, const sph_csr *a, int n) {
    int *agg = g->agg, *first = g->mark, *ss = g->sstart, *sj = g->sj;
    int nc = 0;
    for (int i = 0; i < n; i++) agg[i] = -1;
    /* 1: a node whose strong neighbours are all free starts an aggregate with them */
    for (int i = 0; i < n; i++) {
        if (agg[i] >= 0 || ss[i] == ss[i + 1]) continue;
        int free_all = 1;
        for (int k = ss[i]; k < ss[i + 1] && free_all; k++) free_all = agg[sj[k]] < 0;
        if (!free_all) continue;
        agg[i] = nc;
        for (int k = ss[i]; k < ss[i + 1]; k++) agg[sj[k]] = nc;
        nc++;
    }
    /* 2: a free node joins the step-1 aggregate it is most strongly connected to */
    for (int i = 0; i < n; i++) first[i] = agg[i];
    for (int i = 0; i < n; i++) {
        if (agg[i] >= 0 || ss[i] == ss[i + 1]) continue;
        double best = 0.0;
        int to = -1;
        for (int k = a->start[i]; k < a->start[i + 1]; k++) {
            int j = a->col[k];
            if (j == i || first[j] < 0) continue;
            double s = fabs(a->val[k]);
            if (s > best) {
                best = s;
                to = first[j];
            }
        }
        /* only through a strong connection */
        if (to >= 0) {
            int strong = 0;
            for (int k = ss[i]; k < ss[i + 1] && !strong; k++) strong = first[sj[k]] == to;
            if (strong) agg[i] = to;
        }
    }
    /* 3: what is still free starts aggregates with its free strong neighbours */
    for (int i = 0; i < n; i++) {
        if (agg[i] >= 0 || ss[i] == ss[i + 1]) continue;
        agg[i] = nc;
        for (int k = ss[i]; k < ss[i + 1]; k++)
            if (agg[sj[k]] < 0) agg[sj[k]] = nc;
        nc++;
    }
    return nc;
}

/* P = (I - omega D_F^-1 A_F) T for the aggregates in g->agg (nc columns). The viscous
 * systems take the smoothed P too: the unsmoothed T (one entry a row) makes their setup
 * cheaper, but the solves' extra iterations cost as much. */
static int prolongation(sph_amg *g, const sph_csr *a, sph_csr *P, int nc) {
    int n = a->n, *agg = g->agg, *ss = g->sstart, *sj = g->sj;
    /* each row: its own aggregate plus its strong neighbours' (at most 1 + strong count) */
    if (sph_csr_reserve(P, n, ss[n] + n)) return -1;
    int *pos = g->mark; /* nc <= n entries; the aggregation's use of it is over */
    for (int c = 0; c < nc; c++) pos[c] = -1;
    int e = 0;
    P->start[0] = 0;
    for (int i = 0; i < n; i++) {
        int e0 = e;
        P->diag[i] = 0.0;
        if (agg[i] >= 0) {
            /* filtered diagonal: a_ii plus the weak off-diagonals */
            double dF = a->diag[i];
            int ks = ss[i];
            for (int k = a->start[i]; k < a->start[i + 1]; k++) {
                int j = a->col[k];
                if (j == i) continue;
                if (ks < ss[i + 1] && sj[ks] == j) {
                    ks++;
                } else {
                    dF += a->val[k];
                }
            }
            if (!(dF > 0.0)) dF = a->diag[i];
            pos[agg[i]] = e;
            P->col[e] = agg[i];
            P->val[e] = 1.0 - AMG_OMEGA;
            e++;
            ks = ss[i];
            for (int k = a->start[i]; k < a->start[i + 1]; k++) {
                int j = a->col[k];
                if (j == i || ks >= ss[i + 1] || sj[ks] != j) continue;
                ks++;
                int c = agg[j];
                if (c < 0) continue;
                double v = -AMG_OMEGA * a->val[k] / dF;
                if (pos[c] >= e0) {
                    P->val[pos[c]] += v;
                } else {
                    pos[c] = e;
                    P->col[e] = c;
                    P->val[e] = v;
                    e++;
                }
            }
        }
        P->start[i + 1] = e;
    }
    return 0;
}

/* In-place dense Cholesky of the n x n matrix c (row-major, lower triangle used). A pivot
 * that falls to round-off of its diagonal entry (a singular coarse operator: a cluster of
 * particles with no free-surface neighbour, as the drops a Re = 1000 squeeze throws off,
 * whose pressure is defined up to a constant) is replaced by that diagonal entry: the
 * factor is then of a nearby positive definite matrix, still a valid preconditioner (a
 * zero diagonal entry, a cluster whose whole operator is zero, takes 1). Only a non-finite
 * entry is an error. */
static int cholesky(double *c, int n) {
    for (int j = 0; j < n; j++) {
        double d = c[(size_t)j * n + j], ajj = d;
        if (!isfinite(ajj)) return -1;
        if (!(ajj > 0.0)) ajj = 1.0; /* a zero-operator cluster (see spgemm's diagonal) */
        for (int k = 0; k < j; k++) d -= c[(size_t)j * n + k] * c[(size_t)j * n + k];
        if (!(d > 1e-10 * ajj)) d = ajj;
        d = sqrt(d);
        c[(size_t)j * n + j] = d;
        for (int i = j + 1; i < n; i++) {
            double s = c[(size_t)i * n + j];
            for (int k = 0; k < j; k++) s -= c[(size_t)i * n + k] * c[(size_t)j * n + k];
            c[(size_t)i * n + j] = s / d;
        }
    }
    return 0;
}

static void cholesky_solve(const double *c, int n, const double *b, double *x) {
    for (int i = 0; i < n; i++) {
        double s = b[i];
        for (int k = 0; k < i; k++) s -= c[(size_t)i * n + k] * x[k];
        x[i] = s / c[(size_t)i * n + i];
    }
    for (int i = n - 1; i >= 0; i--) {
        double s = x[i];
        for (int k = i + 1; k < n; k++) s -= c[(size_t)k * n + i] * x[k];
        x[i] = s / c[(size_t)i * n + i];
    }
}

int sph_amg_second(sph_amg *g, const sph_csr *a2, int threads) {
    sph_smoother *S = &g->lev[0].S;
    if (g->levels < 2 || S->n != a2->n) return 0;
    return sph_smoother_second(S, a2, threads);
}

/* The coarsest level l's dense Cholesky factor when it is small enough (see setup_impl),
 * else none (Gauss-Seidel sweeps); -1 out of memory or not positive definite. */
static int coarse_factor(sph_amg *g, int l, int coarse_max) {
    const sph_csr *c = &g->lev[l].A;
    g->chol_n = 0;
    if (c->n > 0 && (c->n <= coarse_max || (l > 0 && c->n <= 4 * coarse_max))) {
        int n = c->n;
        if ((long)n * n > g->chol_cap) {
            double *q = realloc(g->chol, sizeof(double) * (size_t)n * (size_t)n);
            if (!q) return -1;
            g->chol = q;
            g->chol_cap = (long)n * n;
        }
        memset(g->chol, 0, sizeof(double) * (size_t)n * (size_t)n);
        for (int i = 0; i < n; i++)
            for (int k = c->start[i]; k < c->start[i + 1]; k++) g->chol[(size_t)i * n + c->col[k]] += c->val[k];
        if (cholesky(g->chol, n)) {
            g->chol_n = 0;
            return -1;
        }
        g->chol_n = n;
    }
    return 0;
}

static int setup_impl(sph_amg *g, const sph_csr *a, const sph_csr *a2, int threads) {
    double theta = g->theta > 0 ? g->theta : 0.08;
    int coarse_max = g->coarse_max > 0 ? g->coarse_max : 100;
    g->levels = 0;
    g->fine_n = a->n;
    if (merge_copy(g, a, &g->lev[0].A) || grow_vectors(&g->lev[0], a->n)) return -1;
    g->nnz_total = g->lev[0].A.start[a->n];
    int l = 0;
    for (; l < SPH_AMG_MAX_LEVELS - 1; l++) {
        sph_amg_level *L = &g->lev[l], *C = &g->lev[l + 1];
        int n = L->A.n;
        if (n <= coarse_max) break;
        if (grow_ints(g, n) || strength(g, &L->A, theta)) return -1;
        int nc = aggregate(g, &L->A, n);
        if (nc == 0 || nc > 0.85 * n) break; /* no coarse space, or coarsening stalled */
        if (prolongation(g, &L->A, &L->P, nc) || transpose(&L->P, nc, &L->R, g->mark) ||
            spgemm(g, &L->A, &L->P, nc, &g->AP, threads) || spgemm(g, &L->R, &g->AP, nc, &C->A, threads) ||
            grow_vectors(C, nc))
            return -1;
        g->nnz_total += C->A.start[nc];
    }
    g->levels = l + 1;
    for (int q = 0; q < l; q++) /* the smoothers' copies (not the coarsest: solved directly) */
        if (sph_smoother_build(&g->lev[q].S, q ? &g->lev[q].A : a, q ? 0 : a2, threads)) {
            g->levels = 0;
            return -1;
        }
    /* coarsest: dense Cholesky when small enough, else Gauss-Seidel sweeps. Up to
     * 4 coarse_max rows only below the finest level: a whole system of a few hundred rows
     * (nothing coarsened: a small scene, or a viscous matrix whose diagonal dominates) would
     * be factored densely at every setup, n^3 / 3 flops, which makes small runs several
     * times slower. */
    if (coarse_factor(g, l, coarse_max)) {
        g->levels = 0;
        return -1;
    }
    return 0;
}

int sph_amg_setup(sph_amg *g, const sph_csr *a, int threads) { return setup_impl(g, a, 0, threads); }

/* sph_amg_setup, then sph_amg_second with a2, the finest smoother's two copies made in one
 * pass (the columns and the split into L and U done once for both: a third faster than two
 * passes, the same copies bit for bit). */
int sph_amg_setup_pair(sph_amg *g, const sph_csr *a, const sph_csr *a2, int threads) {
    return setup_impl(g, a, a2, threads);
}

/* One Gauss-Seidel sweep on a x = b (forward or backward); hybrid across threads. */
static void gs_sweep(const sph_csr *a, const double *b, double *x, double *tmp, int backward, int threads) {
    int n = a->n;
    if (n < SPH_AMG_PAR_MIN) threads = 1;
    if (threads <= 1) {
        for (int s = 0; s < n; s++) {
            int i = backward ? n - 1 - s : s;
            double r = b[i];
            for (int k = a->start[i]; k < a->start[i + 1]; k++) {
                int j = a->col[k];
                if (j != i) r -= a->val[k] * x[j];
            }
            x[i] = r / a->diag[i];
        }
        return;
    }
    memcpy(tmp, x, sizeof(double) * (size_t)n);
#pragma omp parallel num_threads(threads)
    {
        int t = omp_get_thread_num(), nt = omp_get_num_threads();
        int lo = (int)((long)n * t / nt), hi = (int)((long)n * (t + 1) / nt);
        for (int s = lo; s < hi; s++) {
            int i = backward ? hi - 1 - (s - lo) : s;
            double r = b[i];
            for (int k = a->start[i]; k < a->start[i + 1]; k++) {
                int j = a->col[k];
                if (j == i) continue;
                r -= a->val[k] * (j >= lo && j < hi ? x[j] : tmp[j]);
            }
            x[i] = r / a->diag[i];
        }
    }
}

static void matvec(const sph_csr *a, const double *x, double *y, int threads) {
    sph_csr_matvec(a, x, y, a->n < SPH_AMG_PAR_MIN ? 1 : threads);
}

/* x += P e, the coarse correction: the product (the sums of sph_csr_matvec) and the update
 * in one pass, on the threads (the same figures bit for bit as a product and an update). */
static void prolong_add(const sph_csr *p, const double *e, double *x, int threads) {
    int n = p->n;
    const int *st = p->start, *col = p->col;
    const double *val = p->val;
#pragma omp parallel for schedule(static) num_threads(n < SPH_AMG_PAR_MIN ? 1 : threads)
    for (int i = 0; i < n; i++) {
        double s = 0.0;
        for (int k = st[i]; k < st[i + 1]; k++) s += val[k] * e[col[k]];
        x[i] += s;
    }
}

static void vcycle(sph_amg *g, int l, const sph_csr *a, const double *b, double *x, int threads) {
    sph_amg_level *L = &g->lev[l];
    int n = a->n, sweeps = g->sweeps > 0 ? g->sweeps : 1;
    if (l == g->levels - 1) {
        if (g->chol_n) {
            cholesky_solve(g->chol, g->chol_n, b, x);
        } else {
            for (int i = 0; i < n; i++) x[i] = 0.0;
            for (int s = 0; s < 4; s++) {
                gs_sweep(a, b, x, L->t, 0, threads);
                gs_sweep(a, b, x, L->t, 1, threads);
            }
        }
        return;
    }
    sph_amg_level *C = &g->lev[l + 1];
    int visits = l >= (g->wcycle_from > 0 ? g->wcycle_from : 1) ? 2 : 1;
    if (sweeps == 1 && L->S.n == n) { /* through the smoother's copy */
        sph_smoother_forward(&L->S, n, b, x, L->r, threads);
        for (int v = 0; v < visits; v++) {
            if (v > 0) sph_smoother_residual(&L->S, n, b, x, L->r, threads);
            matvec(&L->R, L->r, C->b, threads);
            vcycle(g, l + 1, &C->A, C->b, C->x, threads);
            prolong_add(&L->P, C->x, x, threads);
        }
        sph_smoother_backward(&L->S, n, b, x, L->t, threads);
        return;
    }
    for (int i = 0; i < n; i++) x[i] = 0.0;
    for (int s = 0; s < sweeps; s++) gs_sweep(a, b, x, L->t, 0, threads);
    for (int v = 0; v < visits; v++) {
        matvec(a, x, L->r, threads);
        for (int i = 0; i < n; i++) L->r[i] = b[i] - L->r[i];
        matvec(&L->R, L->r, C->b, threads);
        vcycle(g, l + 1, &C->A, C->b, C->x, threads);
        prolong_add(&L->P, C->x, x, threads);
    }
    for (int s = 0; s < sweeps; s++) gs_sweep(a, b, x, L->t, 1, threads);
}

/* row i of a times x1 and x2: s1, s2 (sums from 0 in the row's order) */
static inline void csr_row2(const int *st, const int *col, const double *val, int i, const double *x1,
                            const double *x2, double *s1, double *s2) {
    double a1 = 0.0, a2 = 0.0;
    for (int k = st[i]; k < st[i + 1]; k++) {
        int j = col[k];
        double v = val[k];
        a1 += v * x1[j];
        a2 += v * x2[j];
    }
    *s1 = a1;
    *s2 = a2;
}

/* y1 = a x1, y2 = a x2 (one matrix, two vectors: R and P) */
static void matvec2(const sph_csr *a, const double *x1, const double *x2, double *y1, double *y2, int threads) {
    int n = a->n;
    const int *st = a->start, *col = a->col;
    const double *val = a->val;
#pragma omp parallel for schedule(static) num_threads(n < SPH_AMG_PAR_MIN ? 1 : threads)
    for (int i = 0; i < n; i++) csr_row2(st, col, val, i, x1, x2, &y1[i], &y2[i]);
}

/* x1 += P e1, x2 += P e2 (prolong_add for two vectors, the sums of matvec2) */
static void prolong_add2(const sph_csr *p, const double *e1, const double *e2, double *x1, double *x2, int threads) {
    int n = p->n;
    const int *st = p->start, *col = p->col;
    const double *val = p->val;
#pragma omp parallel for schedule(static) num_threads(n < SPH_AMG_PAR_MIN ? 1 : threads)
    for (int i = 0; i < n; i++) {
        double s1, s2;
        csr_row2(st, col, val, i, e1, e2, &s1, &s2);
        x1[i] += s1;
        x2[i] += s2;
    }
}

/* The second system alone: the finest level's smoother takes its values for the cycle. */
static void vcycle_second(sph_amg *g, int l, const sph_csr *a2, const double *b, double *x, int threads) {
    sph_smoother *S = &g->lev[0].S;
    int swap = l == 0 && S->has2;
    if (swap) {
        float *v = S->fval;
        double *d = S->fdinv;
        S->fval = S->fval2;
        S->fdinv = S->fdinv2;
        vcycle(g, l, a2, b, x, threads);
        S->fval = v;
        S->fdinv = d;
        return;
    }
    vcycle(g, l, a2, b, x, threads);
}

/* vcycle on two right-hand sides: the same steps, the structure of each level read once */
static void vcycle2(sph_amg *g, int l, const sph_csr *a1, const sph_csr *a2, const double *b1, const double *b2,
                    double *x1, double *x2, int threads) {
    sph_amg_level *L = &g->lev[l];
    int n = a1->n, sweeps = g->sweeps > 0 ? g->sweeps : 1;
    if (l == g->levels - 1 || sweeps != 1 || L->S.n != n) { /* the coarsest, or no split copy: in turn */
        vcycle(g, l, a1, b1, x1, threads);
        vcycle_second(g, l, a2, b2, x2, threads);
        return;
    }
    sph_amg_level *C = &g->lev[l + 1];
    int visits = l >= (g->wcycle_from > 0 ? g->wcycle_from : 1) ? 2 : 1;
    sph_smoother_pair q = sph_smoother_pair_of(&L->S, l);
    sph_smoother_forward2(&L->S, q, n, b1, b2, x1, x2, L->r, L->r2, threads);
    for (int v = 0; v < visits; v++) {
        if (v > 0) sph_smoother_residual2(&L->S, q, n, b1, b2, x1, x2, L->r, L->r2, threads);
        matvec2(&L->R, L->r, L->r2, C->b, C->b2, threads);
        vcycle2(g, l + 1, &C->A, &C->A, C->b, C->b2, C->x, C->x2, threads);
        prolong_add2(&L->P, C->x, C->x2, x1, x2, threads);
    }
    sph_smoother_backward2(&L->S, q, n, b1, b2, x1, x2, L->t, L->t2, threads);
}

int sph_amg_set_ids(sph_amg *g, int n, const int *row_of, const int *id) {
    if (n > g->ridcap) {
        int cap = n + n / 4 + 16;
        if (sph_grow((void **)&g->rid, sizeof(int), cap)) return -1;
        g->ridcap = cap;
    }
    for (int r = 0; r < n; r++) g->rid[r] = id[row_of[r]];
    return 0;
}

int sph_amg_reuse(sph_amg *g, const sph_csr *a, const sph_csr *a2, const int *row_of, const int *id, int threads) {
    if (g->levels < 2 || !g->rid) return 1;
    int n_old = g->fine_n, n = a->n, nc = g->lev[1].A.n, maxid = -1;
    for (int r = 0; r < n_old; r++)
        if (g->rid[r] > maxid) maxid = g->rid[r];
    if (maxid + 1 > g->idmapcap) {
        int cap = maxid + 1 + (maxid + 1) / 4 + 16;
        if (sph_grow((void **)&g->idmap, sizeof(int), cap)) return -1;
        for (int q = g->idmapcap; q < cap; q++) g->idmap[q] = -1;
        g->idmapcap = cap;
    }
    int *map = g->idmap;
    for (int r = 0; r < n_old; r++) map[g->rid[r]] = r;
    /* the new prolongation (into the scratch g->AP, then swapped in): row r is the old row
     * of its particle, or empty */
    sph_amg_level *L = &g->lev[0];
    sph_csr *P = &g->AP;
    int fail = sph_csr_reserve(P, n, 1);
    if (!fail) {
        P->start[0] = 0;
        for (int r = 0; r < n; r++) {
            int q = id[row_of[r]], o = q <= maxid ? map[q] : -1;
            P->start[r + 1] = P->start[r] + (o >= 0 ? L->P.start[o + 1] - L->P.start[o] : 0);
        }
        fail = sph_csr_reserve(P, n, P->start[n] > 0 ? P->start[n] : 1);
    }
    if (!fail) {
        for (int r = 0; r < n; r++) {
            int q = id[row_of[r]], o = q <= maxid ? map[q] : -1;
            P->diag[r] = 0.0;
            if (o < 0) continue;
            int e = P->start[r];
            for (int k = L->P.start[o]; k < L->P.start[o + 1]; k++, e++) {
                P->col[e] = L->P.col[k];
                P->val[e] = L->P.val[k];
            }
        }
    }
    for (int r = 0; r < n_old; r++) map[g->rid[r]] = -1;
    if (fail) {
        g->levels = 0;
        return -1;
    }
    sph_csr t = L->P;
    L->P = *P;
    *P = t;
    if (grow_ints(g, n > nc ? n : nc) || transpose(&L->P, nc, &L->R, g->mark) || grow_vectors(L, n) ||
        sph_amg_set_ids(g, n, row_of, id)) {
        g->levels = 0;
        return -1;
    }
    g->fine_n = n;
    if (sph_smoother_build(&g->lev[0].S, a, a2, threads)) {
        g->levels = 0;
        return -1;
    }
    return 0;
}

#define SWAP(T, x, y) \
    do {               \
        T t_ = (x);    \
        (x) = (y);     \
        (y) = t_;      \
    } while (0)

void sph_amg_swap_scratch(sph_amg *a, sph_amg *b) {
    SWAP(sph_csr, a->lev[0].A, b->lev[0].A);
    SWAP(sph_csr, a->AP, b->AP);
    SWAP(int *, a->agg, b->agg);
    SWAP(int *, a->mark, b->mark);
    SWAP(int *, a->sstart, b->sstart);
    SWAP(int *, a->sj, b->sj);
    SWAP(int, a->icap, b->icap);
    SWAP(long, a->sjcap, b->sjcap);
    SWAP(int *, a->pmark, b->pmark);
    SWAP(double *, a->pacc, b->pacc);
    SWAP(long, a->pcap, b->pcap);
    for (int t = 0; t < SPH_AMG_MAX_THREADS; t++) {
        SWAP(int *, a->tcol[t], b->tcol[t]);
        SWAP(double *, a->tval[t], b->tval[t]);
        SWAP(long, a->tcap[t], b->tcap[t]);
    }
}

int sph_amg_refresh(sph_amg *g, const sph_csr *a, int threads) {
    if (g->levels < 2 || a->n != g->fine_n) return 0;
    return sph_smoother_build(&g->lev[0].S, a, 0, threads);
}

void sph_amg_apply(sph_amg *g, const sph_csr *a, const double *r, double *z, int threads) {
    vcycle(g, 0, a, r, z, threads);
}

void sph_amg_apply2(sph_amg *g, const sph_csr *a1, const sph_csr *a2, const double *r1, const double *r2,
                    double *z1, double *z2, int threads) {
    vcycle2(g, 0, a1, a2, r1, r2, z1, z2, threads);
}

void sph_amg_apply_second(sph_amg *g, const sph_csr *a2, const double *r, double *z, int threads) {
    vcycle_second(g, 0, a2, r, z, threads);
}

void sph_amg_free(sph_amg *g) {
    for (int l = 0; l < SPH_AMG_MAX_LEVELS; l++) {
        sph_amg_level *L = &g->lev[l];
        sph_csr_free(&L->A);
        sph_csr_free(&L->P);
        sph_csr_free(&L->R);
        free(L->x);
        free(L->b);
        free(L->r);
        free(L->t);
        free(L->x2);
        free(L->b2);
        free(L->r2);
        free(L->t2);
        sph_smoother_free(&L->S);
        L->x = L->b = L->r = L->t = 0;
        L->x2 = L->b2 = L->r2 = L->t2 = 0;
        L->vcap = 0;
    }
    free(g->rid);
    free(g->idmap);
    g->rid = g->idmap = 0;
    g->ridcap = g->idmapcap = 0;
    free(g->chol);
    free(g->agg);
    free(g->mark);
    free(g->sstart);
    free(g->sj);
    sph_csr_free(&g->AP);
    for (int t = 0; t < SPH_AMG_MAX_THREADS; t++) {
        free(g->tcol[t]);
        free(g->tval[t]);
        g->tcol[t] = 0;
        g->tval[t] = 0;
        g->tcap[t] = 0;
    }
    free(g->pmark);
    free(g->pacc);
    g->pmark = 0;
    g->pacc = 0;
    g->pcap = 0;
    g->chol = 0;
    g->chol_cap = 0;
    g->chol_n = 0;
    g->agg = g->mark = g->sstart = g->sj = 0;
    g->icap = 0;
    g->sjcap = 0;
    g->levels = 0;
}

/* Saving a hierarchy with a world's state (state.c): what the cycle and the next reuse
 * read. The levels' sizes, each prolongation P (the finest level's too: its rows follow
 * the particles by id), the coarse operators (with their smoothers' diagonals), the ids of
 * the fine rows and the reuse counters. Rebuilt on reading: the restrictions R = P^T, the
 * coarse smoothers' copies (for `threads`, as at the setup) and the coarsest factor, the
 * same bit for bit; the finest smoother's copy is made by the next setup or reuse, which
 * always rebuilds it. A hierarchy of fewer than two levels is saved as none: the next
 * setup builds afresh either way. */
static int write_csr(const sph_csr *a, int n, int with_diag, FILE *f) {
    int nnz = a->start[n];
    int ok = fwrite(&nnz, sizeof nnz, 1, f) == 1 && fwrite(a->start, sizeof(int), (size_t)n + 1, f) == (size_t)n + 1 &&
             fwrite(a->col, sizeof(int), (size_t)nnz, f) == (size_t)nnz &&
             fwrite(a->val, sizeof(double), (size_t)nnz, f) == (size_t)nnz;
    if (ok && with_diag) ok = fwrite(a->diag, sizeof(double), (size_t)n, f) == (size_t)n;
    return ok ? 0 : -1;
}

int sph_amg_write(const sph_amg *g, FILE *f) {
    int levels = g->levels >= 2 ? g->levels : 0;
    int hd[6] = {levels, levels ? g->fine_n : 0, g->age, g->it_fresh, g->it_recent, levels && g->rid ? 1 : 0};
    if (fwrite(hd, sizeof hd, 1, f) != 1 || fwrite(&g->nnz_total, sizeof g->nnz_total, 1, f) != 1) return -1;
    if (!levels) return 0;
    int sizes[SPH_AMG_MAX_LEVELS];
    sizes[0] = g->fine_n;
    for (int l = 1; l < levels; l++) sizes[l] = g->lev[l].A.n;
    if (fwrite(sizes, sizeof(int), (size_t)levels, f) != (size_t)levels) return -1;
    for (int l = 0; l + 1 < levels; l++)
        if (write_csr(&g->lev[l].P, sizes[l], 0, f)) return -1;
    for (int l = 1; l < levels; l++)
        if (write_csr(&g->lev[l].A, sizes[l], 1, f)) return -1;
    if (hd[5] && fwrite(g->rid, sizeof(int), (size_t)g->fine_n, f) != (size_t)g->fine_n) return -1;
    return 0;
}

#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
static int amg_bad(char *why, size_t len, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, len, fmt, ap);
    va_end(ap);
    return -1;
}

/* an n x m CSR as write_csr wrote it, checked (structure, columns, finite values); 1: the
 * file ended */
static int read_csr(sph_csr *a, int n, int m, int with_diag, FILE *f, const char *what, char *why, size_t len) {
    int nnz;
    if (fread(&nnz, sizeof nnz, 1, f) != 1) return 1;
    if (nnz < 0 || (m > 0 && (double)nnz > (double)n * m) || (m == 0 && nnz != 0))
        return amg_bad(why, len, "%s: %d entries for %d x %d", what, nnz, n, m);
    if (sph_csr_reserve(a, n, nnz > 0 ? nnz : 1)) return amg_bad(why, len, "%s: out of memory", what);
    if (fread(a->start, sizeof(int), (size_t)n + 1, f) != (size_t)n + 1 ||
        fread(a->col, sizeof(int), (size_t)nnz, f) != (size_t)nnz ||
        fread(a->val, sizeof(double), (size_t)nnz, f) != (size_t)nnz)
        return 1;
    if (with_diag && fread(a->diag, sizeof(double), (size_t)n, f) != (size_t)n) return 1;
    if (!with_diag)
        for (int i = 0; i < n; i++) a->diag[i] = 0.0;
    if (a->start[0] != 0 || a->start[n] != nnz) return amg_bad(why, len, "%s: row starts do not span %d entries", what, nnz);
    for (int i = 0; i < n; i++) {
        if (a->start[i + 1] < a->start[i]) return amg_bad(why, len, "%s: row %d starts before row %d", what, i + 2, i + 1);
        if (with_diag && !isfinite(a->diag[i])) return amg_bad(why, len, "%s: diagonal %d is not finite", what, i + 1);
    }
    for (int k = 0; k < nnz; k++) {
        if (a->col[k] < 0 || a->col[k] >= m) return amg_bad(why, len, "%s: column %d not in [0, %d)", what, a->col[k], m);
        if (!isfinite(a->val[k])) return amg_bad(why, len, "%s: value %d is not finite", what, k + 1);
    }
    return 0;
}

int sph_amg_read(sph_amg *g, FILE *f, int next_id, int threads, char *why, size_t len) {
    int hd[6];
    long nnz_total;
    g->levels = 0;
    if (fread(hd, sizeof hd, 1, f) != 1 || fread(&nnz_total, sizeof nnz_total, 1, f) != 1) return 1;
    int levels = hd[0], fine_n = hd[1];
    if (!(levels == 0 || (levels >= 2 && levels <= SPH_AMG_MAX_LEVELS)))
        return amg_bad(why, len, "%d levels", levels);
    if (hd[2] < 0 || hd[3] < -1 || hd[4] < 0 || (hd[5] != 0 && hd[5] != 1))
        return amg_bad(why, len, "reuse counters {%d, %d, %d, %d} out of range", hd[2], hd[3], hd[4], hd[5]);
    g->age = hd[2];
    g->it_fresh = hd[3];
    g->it_recent = hd[4];
    g->nnz_total = nnz_total;
    g->fine_n = fine_n;
    if (!levels) return 0;
    int sizes[SPH_AMG_MAX_LEVELS];
    if (fread(sizes, sizeof(int), (size_t)levels, f) != (size_t)levels) return 1;
    if (fine_n < 1 || fine_n > SPH_MAX_PARTICLES || sizes[0] != fine_n)
        return amg_bad(why, len, "%d fine rows", fine_n);
    for (int l = 1; l < levels; l++)
        if (sizes[l] < 1 || sizes[l] > sizes[l - 1]) return amg_bad(why, len, "level %d: %d rows", l + 1, sizes[l]);
    char what[64];
    int rc;
    for (int l = 0; l + 1 < levels; l++) {
        snprintf(what, sizeof what, "level %d's prolongation", l + 1);
        g->lev[l].P.n = 0;
        if ((rc = read_csr(&g->lev[l].P, sizes[l], sizes[l + 1], 0, f, what, why, len))) return rc;
    }
    for (int l = 1; l < levels; l++) {
        snprintf(what, sizeof what, "level %d's operator", l + 1);
        if ((rc = read_csr(&g->lev[l].A, sizes[l], sizes[l], 1, f, what, why, len))) return rc;
    }
    if (hd[5]) {
        if (fine_n > g->ridcap) {
            int cap = fine_n + fine_n / 4 + 16;
            if (sph_grow((void **)&g->rid, sizeof(int), cap)) return amg_bad(why, len, "out of memory");
            g->ridcap = cap;
        }
        if (fread(g->rid, sizeof(int), (size_t)fine_n, f) != (size_t)fine_n) return 1;
        for (int r = 0; r < fine_n; r++)
            if (g->rid[r] < 0 || g->rid[r] >= next_id)
                return amg_bad(why, len, "fine row %d: id %d not in [0, %d)", r + 1, g->rid[r], next_id);
    } else {
        free(g->rid);
        g->rid = 0;
        g->ridcap = 0;
    }
    int coarse_max = g->coarse_max > 0 ? g->coarse_max : 100;
    for (int l = 0; l < levels; l++)
        if (grow_vectors(&g->lev[l], sizes[l])) return amg_bad(why, len, "out of memory");
    for (int l = 0; l + 1 < levels; l++)
        if (grow_ints(g, sizes[l]) || transpose(&g->lev[l].P, sizes[l + 1], &g->lev[l].R, g->mark))
            return amg_bad(why, len, "out of memory");
    for (int l = 1; l + 1 < levels; l++)
        if (sph_smoother_build(&g->lev[l].S, &g->lev[l].A, 0, threads)) return amg_bad(why, len, "out of memory");
    g->lev[0].S.n = 0; /* made by the next setup or reuse */
    if (coarse_factor(g, levels - 1, coarse_max))
        return amg_bad(why, len, "the coarsest operator (%d rows) is not positive definite", sizes[levels - 1]);
    g->levels = levels;
    return 0;
}
