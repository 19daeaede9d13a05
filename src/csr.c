/* Compressed sparse rows (growth, product) and the small dense solve. */
#include "linalg.h"

#include <math.h>
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
    const int *st = a->start, *col = a->col; /* in locals: not reloaded after each store to y */
    const double *val = a->val;
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int i = 0; i < n; i++) {
        double s = 0.0;
        for (int k = st[i]; k < st[i + 1]; k++) s += val[k] * x[col[k]];
        y[i] = s;
    }
}

/* Small dense solve A x = b (Gaussian elimination with partial pivoting): A is n x n with
 * rows lda apart, x holds b on entry. Returns the number of zero pivots; their unknowns
 * come out 0 (the plates' system treats any as an error, the GMRES least squares takes
 * the solution in the space the others span). */
#define A_(r, c) a[(size_t)(r) * (size_t)lda + (size_t)(c)]
int sph_dense_solve(int n, double *a, int lda, double *x) {
    int zero = 0;
    for (int c = 0; c < n; c++) {
        int piv = c;
        for (int r = c + 1; r < n; r++)
            if (fabs(A_(r, c)) > fabs(A_(piv, c))) piv = r;
        if (A_(piv, c) == 0.0) {
            zero++;
            continue;
        }
        if (piv != c) {
            for (int k = 0; k < n; k++) {
                double t = A_(c, k);
                A_(c, k) = A_(piv, k);
                A_(piv, k) = t;
            }
            double t = x[c];
            x[c] = x[piv];
            x[piv] = t;
        }
        for (int r = c + 1; r < n; r++) {
            double f = A_(r, c) / A_(c, c);
            for (int k = c; k < n; k++) A_(r, k) -= f * A_(c, k);
            x[r] -= f * x[c];
        }
    }
    for (int r = n - 1; r >= 0; r--) {
        for (int k = r + 1; k < n; k++) x[r] -= A_(r, k) * x[k];
        x[r] = A_(r, r) != 0.0 ? x[r] / A_(r, r) : 0.0;
    }
    return zero;
}
#undef A_
