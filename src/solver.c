/* Sparse linear algebra: a CSR matrix and preconditioned conjugate gradients, the
 * preconditioner Jacobi or the algebraic multigrid V-cycle of amg.c.
 * The solver has a contract (SPlisHSPlasH style): tolerance and iteration limit in,
 * iterations, residual and convergence out; it never fails silently. */
#include "internal.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>

int sph_grow(void **p, size_t elem, int count) {
    void *q = realloc(*p, elem * (size_t)(count > 0 ? count : 1));
    if (!q) return -1;
    *p = q;
    return 0;
}

int sph_csr_reserve(sph_csr *a, int n, int nnz) {
    if (n + 1 > a->cap) {
        int cap = n + 1 + n / 4;
        if (sph_grow((void **)&a->start, sizeof(int), cap) || sph_grow((void **)&a->diag, sizeof(double), cap))
            return -1;
        a->cap = cap;
    }
    if (nnz > a->nnz) {
        int cap = nnz + nnz / 4;
        if (sph_grow((void **)&a->col, sizeof(int), cap) || sph_grow((void **)&a->val, sizeof(double), cap))
            return -1;
        a->nnz = cap;
    }
    a->n = n;
    return 0;
}

void sph_csr_free(sph_csr *a) {
    free(a->start);
    free(a->col);
    free(a->val);
    free(a->diag);
    a->start = a->col = 0;
    a->val = a->diag = 0;
    a->n = a->nnz = a->cap = 0;
}

void sph_csr_matvec(const sph_csr *a, const double *x, double *y, int threads) {
    int n = a->n;
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int i = 0; i < n; i++) {
        double s = 0.0;
        for (int k = a->start[i]; k < a->start[i + 1]; k++) s += a->val[k] * x[a->col[k]];
        y[i] = s;
    }
}

int sph_solver_reserve(sph_solver *s, int n) {
    if (n <= s->cap) return 0;
    int cap = n + n / 4 + 16;
    if (sph_grow((void **)&s->r, sizeof(double), cap) || sph_grow((void **)&s->z, sizeof(double), cap) ||
        sph_grow((void **)&s->q, sizeof(double), cap) || sph_grow((void **)&s->d, sizeof(double), cap))
        return -1;
    s->cap = cap;
    return 0;
}

void sph_solver_free(sph_solver *s) {
    free(s->r);
    free(s->z);
    free(s->q);
    free(s->d);
    s->r = s->z = s->q = s->d = 0;
    s->cap = 0;
    sph_amg_free(&s->amg);
    s->amg_for = 0;
}

int sph_solver_setup(sph_solver *s, const sph_csr *a, sph_linear_solver kind, int threads) {
    s->amg_for = 0;
    if (kind != SPH_SOLVER_AMG || a->n == 0) return 0;
    double t0 = omp_get_wtime();
    int rc = sph_amg_setup(&s->amg, a, threads);
    s->setup_time += omp_get_wtime() - t0;
    if (rc) return -1;
    s->amg_for = a;
    return 0;
}

int sph_solver_refresh(sph_solver *s, const sph_csr *a, int threads) {
    if (s->amg_for != a || s->amg.levels == 0) return 0;
    double t0 = omp_get_wtime();
    int rc = sph_amg_refresh(&s->amg, a, threads);
    s->setup_time += omp_get_wtime() - t0;
    if (rc) s->amg_for = 0; /* out of memory: Jacobi from here on */
    return rc;
}

static double dot(const double *a, const double *b, int n, int threads) {
    double s = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : s) num_threads(threads)
    for (int i = 0; i < n; i++) s += a[i] * b[i];
    return s;
}

/* z = M^-1 r */
static void precondition(sph_solver *s, const sph_csr *a, const double *r, double *z, int amg, int threads) {
    int n = a->n;
    if (amg) {
        sph_amg_apply(&s->amg, a, r, z, threads);
        return;
    }
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int i = 0; i < n; i++) z[i] = r[i] / a->diag[i];
}

sph_solve_result sph_solver_pcg(sph_solver *s, const sph_csr *a, const double *b, double *x,
                                double tol, int max_iter, int threads) {
    sph_solve_result res = {0, 0.0, 1};
    int n = a->n;
    if (n == 0) return res;
    double t0 = omp_get_wtime();
    s->solves++;
    int amg = s->amg_for == a && s->amg.levels > 0 && s->amg.fine_n == n;
    double *r = s->r, *z = s->z, *q = s->q, *d = s->d;
    double bnorm = sqrt(dot(b, b, n, threads));
    if (bnorm == 0.0) {
        for (int i = 0; i < n; i++) x[i] = 0.0;
        return res;
    }
    sph_csr_matvec(a, x, q, threads);
    for (int i = 0; i < n; i++) r[i] = b[i] - q[i];
    precondition(s, a, r, z, amg, threads);
    for (int i = 0; i < n; i++) d[i] = z[i];
    double rz = dot(r, z, n, threads);
    double rnorm = sqrt(dot(r, r, n, threads));
    int it = 0;
    while (rnorm > tol * bnorm && it < max_iter) {
        sph_csr_matvec(a, d, q, threads);
        double dq = dot(d, q, n, threads);
        if (!(dq > 0.0)) break; /* not SPD, or breakdown: reported as not converged */
        double alpha = rz / dq;
        double rr = 0.0, rz1 = 0.0;
        if (amg) {
#pragma omp parallel for schedule(static) reduction(+ : rr) num_threads(threads)
            for (int i = 0; i < n; i++) {
                x[i] += alpha * d[i];
                r[i] -= alpha * q[i];
                rr += r[i] * r[i];
            }
            it++;
            if (!(sqrt(rr) > tol * bnorm)) {
                rnorm = sqrt(rr);
                break;
            }
            precondition(s, a, r, z, amg, threads);
            rz1 = dot(r, z, n, threads);
        } else { /* Jacobi: one fused pass */
#pragma omp parallel for schedule(static) reduction(+ : rr, rz1) num_threads(threads)
            for (int i = 0; i < n; i++) {
                x[i] += alpha * d[i];
                r[i] -= alpha * q[i];
                z[i] = r[i] / a->diag[i];
                rr += r[i] * r[i];
                rz1 += r[i] * z[i];
            }
            it++;
        }
        rnorm = sqrt(rr);
        if (!(rz1 > 0.0)) break; /* preconditioner not positive definite: not converged */
        double beta = rz1 / rz;
        rz = rz1;
#pragma omp parallel for schedule(static) num_threads(threads)
        for (int i = 0; i < n; i++) d[i] = z[i] + beta * d[i];
    }
    res.iterations = it;
    res.residual = rnorm / bnorm;
    res.converged = isfinite(rnorm) && rnorm <= tol * bnorm;
    s->solve_time += omp_get_wtime() - t0;
    return res;
}
