/* Neighbour search: a cell grid of cell size = kernel support (3h), particles sorted by
 * cell with a stable counting sort (memory locality; every per-particle array is permuted
 * together), and compressed neighbour lists built once per step for the rows of the
 * pressure system (fluid particles and the wall particles near fluid). Each pair stores
 * grad_i W_ij and r_ij . grad_i W_ij / r^2, reused by every pass of the step. */
#include "internal.h"
#include "kernel.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

static int ensure_int(int **p, int *cap, int need) {
    if (need <= *cap) return 0;
    int c = need + need / 4 + 64;
    int *q = realloc(*p, sizeof(int) * (size_t)c);
    if (!q) return -1;
    *p = q;
    *cap = c;
    return 0;
}

static inline int cell_coord(double v, double o, double cell, int nc) {
    int c = (int)floor((v - o) / cell);
    return c < 0 ? 0 : (c >= nc ? nc - 1 : c);
}

/* Grid over the real particles' bounding box, grown by one cell on every side so that
 * ghosts (within one support of a mirror or periodic edge) fall inside. */
static int make_grid(sph_world *w) {
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (int i = 0; i < w->n; i++) {
        if (w->x[i] < x0) x0 = w->x[i];
        if (w->x[i] > x1) x1 = w->x[i];
        if (w->y[i] < y0) y0 = w->y[i];
        if (w->y[i] > y1) y1 = w->y[i];
    }
    if (!(isfinite(x0) && isfinite(x1) && isfinite(y0) && isfinite(y1)))
        return sph_world_fail(w, "non-finite particle position at step %ld (t = %g)", w->steps,
                              w->t);
    double cell = SPH_KERNEL_SUPPORT * w->h;
    w->cell = cell;
    w->gx0 = x0 - 1.5 * cell;
    w->gy0 = y0 - 1.5 * cell;
    double nx = floor((x1 - x0) / cell) + 4, ny = floor((y1 - y0) / cell) + 4;
    if (nx * ny > 64.0 * w->n + 4e6) {
        /* Find the particle farthest from the others' median to name it. */
        return sph_world_fail(w,
                              "the scene grew to %.3g x %.3g (from x = %g..%g, y = %g..%g) at "
                              "step %ld, t = %g: a particle has escaped",
                              x1 - x0, y1 - y0, x0, x1, y0, y1, w->steps, w->t);
    }
    w->ncx = (int)nx;
    w->ncy = (int)ny;
    int ncell = w->ncx * w->ncy;
    if (ncell + 1 > w->ncell_cap) {
        int cap = ncell + 1 + ncell / 4 + 64;
        int *cs = realloc(w->cell_start, sizeof(int) * (size_t)cap);
        if (cs) w->cell_start = cs;
        unsigned char *cf = realloc(w->cellflag, (size_t)cap);
        if (cf) w->cellflag = cf;
        if (!cs || !cf) return sph_world_fail(w, "out of memory (%d cells)", ncell);
        w->ncell_cap = cap;
    }
    return 0;
}

/* Permute every persistent per-particle array by perm (new i <- old perm[i]): one parallel
 * region (a region costs a team set-up), one array after the other through the scratch. */
static void permute(sph_world *w, const int *perm) {
    int n = w->n;
    double *dscratch = w->xs;
    /* a first guess's arrays only while it is in use (explicit viscosity: never): 0 skips */
#define GUESS(g) ((g).n == n ? (g).d : 0), ((g).n == n ? (g).d1 : 0)
    double *darr[] = {w->x,        w->y,        w->u,        w->v,        w->ax,        w->ay,
                      w->p,        w->rho,      w->m,        w->eta,      w->gd,        w->phi,
                      w->lamxx,    w->lamxy,    w->tau,      w->visc,
                      w->psens[0], w->psens[1], w->psens[2], w->psens[3], GUESS(w->gu), GUESS(w->gv),
                      GUESS(w->gp)};
#undef GUESS
    int *iscratch = w->iscratch;
    int *iarr[] = {w->kind, w->mat, w->id};
    int nd = (int)(sizeof darr / sizeof *darr), ni = (int)(sizeof iarr / sizeof *iarr);
#pragma omp parallel num_threads(w->threads)
    {
        for (int a = 0; a < nd; a++) {
            double *arr = darr[a];
            if (!arr) continue; /* the same for every thread: no barrier skipped unevenly */
#pragma omp for schedule(static)
            for (int i = 0; i < n; i++) dscratch[i] = arr[perm[i]];
#pragma omp for schedule(static)
            for (int i = 0; i < n; i++) arr[i] = dscratch[i];
        }
        for (int a = 0; a < ni; a++) {
            int *arr = iarr[a];
#pragma omp for schedule(static)
            for (int i = 0; i < n; i++) iscratch[i] = arr[perm[i]];
#pragma omp for schedule(static)
            for (int i = 0; i < n; i++) arr[i] = iscratch[i];
        }
    }
    unsigned char *c = (unsigned char *)w->iscratch;
    for (int i = 0; i < n; i++) c[i] = w->surf[perm[i]];
    memcpy(w->surf, c, (size_t)n);
}

int sph_neighbours_sort(sph_world *w) {
    w->nb_n = -1;
    if (make_grid(w)) return -1;
    int n = w->n, ncell = w->ncx * w->ncy;
    int *cs = w->cell_start;
    memset(cs, 0, sizeof(int) * (size_t)(ncell + 1));
#pragma omp parallel for schedule(static) num_threads(w->threads)
    for (int i = 0; i < n; i++)
        w->cell_of[i] = cell_coord(w->y[i], w->gy0, w->cell, w->ncy) * w->ncx +
                        cell_coord(w->x[i], w->gx0, w->cell, w->ncx);
    for (int i = 0; i < n; i++) cs[w->cell_of[i] + 1]++;
    for (int c = 0; c < ncell; c++) cs[c + 1] += cs[c];
    for (int i = 0; i < n; i++) w->perm[cs[w->cell_of[i]]++] = i;
    permute(w, w->perm);
    return 0;
}

/* Bin every particle, ghosts included, into the grid (stable: index order per cell). */
static int bin_all(sph_world *w) {
    int nt = w->n + w->ng, ncell = w->ncx * w->ncy;
    int *cs = w->cell_start;
    if (ensure_int(&w->cell_items, &w->cell_items_cap, nt)) return sph_world_fail(w, "out of memory");
    memset(cs, 0, sizeof(int) * (size_t)(ncell + 1));
#pragma omp parallel for schedule(static) num_threads(w->threads)
    for (int i = 0; i < nt; i++)
        w->cell_of[i] = cell_coord(w->y[i], w->gy0, w->cell, w->ncy) * w->ncx +
                        cell_coord(w->x[i], w->gx0, w->cell, w->ncx);
    for (int i = 0; i < nt; i++) cs[w->cell_of[i] + 1]++;
    for (int c = 0; c < ncell; c++) cs[c + 1] += cs[c];
    for (int i = 0; i < nt; i++) w->cell_items[cs[w->cell_of[i]]++] = i;
    for (int c = ncell; c > 0; c--) cs[c] = cs[c - 1];
    cs[0] = 0;
    return 0;
}

/* Where real particle i stood when this step's lists were built: its entry in the
 * cell-ordered copy of the positions (cx, cy), found in its cell's run of cell_items. */
void sph_neighbours_built_position(const sph_world *w, int i, double *x, double *y) {
    int c = w->cell_of[i];
    for (int k = w->cell_start[c]; k < w->cell_start[c + 1]; k++)
        if (w->cell_items[k] == i) {
            *x = w->cx[k];
            *y = w->cy[k];
            return;
        }
    *x = w->x[i]; /* not binned (no lists built yet): where it is */
    *y = w->y[i];
}

/* Rows: fluid particles, and wall particles in the 3 x 3 cells around any fluid particle
 * (real or ghost): a superset of the walls within the support of fluid. */
static void mark_rows(sph_world *w) {
    int n = w->n, nt = n + w->ng, ncx = w->ncx, ncy = w->ncy;
    int ncell = ncx * ncy;
    unsigned char *flag = w->cellflag;
    memset(flag, 0, (size_t)ncell);
    for (int i = 0; i < nt; i++)
        if (w->kind[i] == SPH_FLUID) flag[w->cell_of[i]] = 1;
    for (int i = 0; i < n; i++) {
        if (w->kind[i] == SPH_FLUID) {
            w->active[i] = 1;
            continue;
        }
        int c = w->cell_of[i], cx = c % ncx, cy = c / ncx, on = 0;
        for (int yy = cy - 1; yy <= cy + 1 && !on; yy++)
            for (int xx = cx - 1; xx <= cx + 1; xx++)
                if (xx >= 0 && yy >= 0 && xx < ncx && yy < ncy && flag[yy * ncx + xx]) {
                    on = 1;
                    break;
                }
        w->active[i] = (unsigned char)on;
    }
}

/* The candidates of particle i are the items of the 3 x 3 cells around its cell: three
 * runs of consecutive items (one per row of cells), [k0[r], k1[r]). */
static inline int candidate_runs(const sph_world *w, int i, int k0[3], int k1[3]) {
    int c = w->cell_of[i], cx = c % w->ncx, cy = c / w->ncx;
    int ya = cy > 0 ? cy - 1 : 0, yb = cy + 1 < w->ncy ? cy + 1 : cy;
    int xa = cx > 0 ? cx - 1 : 0, xb = cx + 1 < w->ncx ? cx + 1 : cx;
    int nr = 0;
    for (int yy = ya; yy <= yb; yy++, nr++) {
        k0[nr] = w->cell_start[yy * w->ncx + xa];
        k1[nr] = w->cell_start[yy * w->ncx + xb + 1];
    }
    return nr;
}

/* Per-thread candidate scratch: room for the largest 3 x 3 block of cells. */
static int reserve_candidates(sph_world *w) {
    int ncx = w->ncx, ncy = w->ncy, most = 0;
    for (int cy = 0; cy < ncy; cy++) {
        int ya = cy > 0 ? cy - 1 : 0, yb = cy + 1 < ncy ? cy + 1 : cy;
        for (int cx = 0; cx < ncx; cx++) {
            int xa = cx > 0 ? cx - 1 : 0, xb = cx + 1 < ncx ? cx + 1 : cx, m = 0;
            for (int yy = ya; yy <= yb; yy++)
                m += w->cell_start[yy * ncx + xb + 1] - w->cell_start[yy * ncx + xa];
            if (m > most) most = m;
        }
    }
    if (most <= w->cand_cap && w->threads <= w->cand_threads) return 0;
    int cap = most + most / 4 + 64, nt = w->threads;
    int *j = realloc(w->cand_j, sizeof(int) * 3 * (size_t)(cap + 1) * (size_t)nt);
    if (!j) return sph_world_fail(w, "out of memory (neighbour candidates)");
    w->cand_j = j;
    w->cand_cap = cap;
    w->cand_threads = nt;
    return 0;
}

/* The candidates' count of row i: particles within the support (i itself excluded). */
static SPH_CLONES int count_row(const sph_world *w, int i, double r2max) {
    const double *cx = w->cx, *cy = w->cy;
    double xi = w->x[i], yi = w->y[i], cd = 0.0;
    int k0[3], k1[3], nr = candidate_runs(w, i, k0, k1);
    for (int r = 0; r < nr; r++) {
        int a = k0[r], b = k1[r];
#pragma omp simd reduction(+ : cd)
        for (int k = a; k < b; k++) {
            double dx = xi - cx[k], dy = yi - cy[k];
            cd += dx * dx + dy * dy < r2max ? 1.0 : 0.0;
        }
    }
    return (int)cd - 1; /* i itself is among its candidates, at r = 0 */
}

/* Row i's list (see sph_neighbours_build): ki its place in the cell order; cls, kf_, kw_
 * the thread's scratch. */
static SPH_CLONES void fill_row(sph_world *w, int i, int ki, int *cls, int *kf_, int *kw_, double r2max, double kc,
                                double kv, double hinv) {
    const double *cx = w->cx, *cy = w->cy, *vol = w->vol;
    const unsigned char *cfl = w->cellfl;
    const int *items = w->cell_items;
    double xi = w->x[i], yi = w->y[i];
    int k0[3], k1[3], nr = candidate_runs(w, i, k0, k1);
    int nc = 0;
    for (int r = 0; r < nr; r++) {
        int a = k0[r], b = k1[r];
        int *cr = cls + nc - a;
#pragma omp simd
        for (int k = a; k < b; k++) {
            double dx = xi - cx[k], dy = yi - cy[k];
            cr[k] = dx * dx + dy * dy < r2max;
        }
        if (ki >= a && ki < b) cr[ki] = 0; /* i itself */
        nc += b - a;
    }
    /* compaction (branch-free: a kept candidate is not predictable) */
    int nf = 0, nw = 0, q0 = 0;
    for (int r = 0; r < nr; r++) {
        int a = k0[r], b = k1[r];
        const int *cr = cls + q0 - a;
        for (int k = a; k < b; k++) {
            int in = cr[k], fl = cfl[k];
            kf_[nf] = k;
            kw_[nw] = k;
            nf += in & fl;
            nw += in & !fl;
        }
        q0 += b - a;
    }
    for (int q = 0; q < nw; q++) kf_[nf + q] = kw_[q]; /* walls after the fluid */
    int s = w->nb_start[i];
    w->nb_mid[i] = s + nf;
    int m = nf + nw;
    int *nj = w->nb_j + s;
    double *ngx = w->nb_gx + s, *ngy = w->nb_gy + s, *nf_ = w->nb_f + s, *nw_ = w->nb_w + s;
    double divr = 0.0, mxx = 0.0, mxy = 0.0, myy = 0.0;
#pragma omp simd reduction(+ : divr, mxx, mxy, myy)
    for (int q = 0; q < m; q++) {
        int k = kf_[q];
        double dx = xi - cx[k], dy = yi - cy[k], r2 = dx * dx + dy * dy;
        double r = sqrt(r2), sq = r * hinv;
        double dw = kc * sph_kernel_dshape(sq);
        /* g = dW/dr / r, also F = r dW/dr / r^2 (finite at r = 0: dW/dr ~ r there; an own
         * image on a mirror plane sits at r = 0 and gets 0) */
        double g = r > 0.0 ? dw / r : 0.0;
        int j = items[k];
        nj[q] = j;
        ngx[q] = g * dx;
        ngy[q] = g * dy;
        nf_[q] = g;
        nw_[q] = kv * sph_kernel_shape(sq);
        double v = vol[j];
        divr -= v * r * dw;
        mxx -= v * g * dx * dx;
        mxy -= v * g * dx * dy;
        myy -= v * g * dy * dy;
    }
    w->divr[i] = divr;
    /* L = M^-1, M = sum_j V_j (x_j - x_i) (x) grad_i W_ij (= I in the bulk). Where the
     * support is too truncated for M to be trusted, L = I. */
    double det = mxx * myy - mxy * mxy;
    if (det > 0.25 && mxx > 0 && myy > 0) {
        w->lxx[i] = myy / det;
        w->lxy[i] = -mxy / det;
        w->lyy[i] = mxx / det;
    } else {
        w->lxx[i] = w->lyy[i] = 1.0;
        w->lxy[i] = 0.0;
    }
}

/* Neighbour lists of the rows (fluid and active walls). Positions are first copied in cell
 * order (cx, cy), so that the distance tests run over contiguous arrays (vectorised). A
 * count pass sizes the lists (no allocation once they are large enough); the fill pass
 * then, per row: (1) a vectorised loop classifies every candidate (0: out of the support
 * or i itself, 1: fluid neighbour, 2: wall); (2) a branch-free compaction writes the
 * candidate indices of the fluid neighbours to one list and of the walls to another (the
 * order met); (3) one loop over the neighbours, fluid first, computes the kernel gradient of
 * every pair from the cell-order positions.
 * Of ~137 candidates a particle (the 3 x 3 cells of the support's size) ~25 are kept, so
 * the tests are vectorised and only the kept ones are written. The fill pass's time is about
 * half the kernel loop (a square root and a division a pair); the count pass is ~13 % of the
 * build, about what a single pass into per-thread buffers would spend writing the 28 bytes
 * a pair twice. Half-size cells (5 x 5 minus the corners: ~80 candidates) would change the
 * order of the pairs, and so the round-off everywhere. */
int sph_neighbours_build(sph_world *w) {
    if (bin_all(w)) return -1;
    mark_rows(w);
    if (reserve_candidates(w)) return -1;
    int n = w->n, nt = n + w->ng, threads = w->threads;
    double h = w->h, r2max = SPH_KERNEL_SUPPORT * SPH_KERNEL_SUPPORT * h * h;
    int *cnt = w->nb_count;
    const int *items = w->cell_items;
    double *cx = w->cx, *cy = w->cy, *vol = w->vol;
    unsigned char *cfl = w->cellfl;

#pragma omp parallel for schedule(static) num_threads(threads)
    for (int k = 0; k < nt; k++) {
        int j = items[k];
        cx[k] = w->x[j];
        cy[k] = w->y[j];
        cfl[k] = w->kind[j] == SPH_FLUID;
        vol[k] = w->m[k] / w->rho[k];
    }

#pragma omp parallel for schedule(dynamic, 256) num_threads(threads)
    for (int i = 0; i < n; i++) cnt[i] = w->active[i] ? count_row(w, i, r2max) : 0;
    w->nb_start[0] = 0;
    for (int i = 0; i < n; i++) {
        if (cnt[i] < 0) /* not among its own candidates: a position the grid does not hold (NaN) */
            return sph_world_fail(w, "particle %d (id %d) at (%g, %g) is outside the cell grid at step %ld", i + 1,
                                  w->id[i], w->x[i], w->y[i], w->steps);
        w->nb_start[i + 1] = w->nb_start[i] + cnt[i];
    }
    long total = w->nb_start[n];
    if (total > w->nb_cap) {
        long cap = total + total / 4 + 1024;
        int *j = realloc(w->nb_j, sizeof(int) * (size_t)cap);
        if (j) w->nb_j = j;
        double *a = realloc(w->nb_gx, sizeof(double) * (size_t)cap);
        if (a) w->nb_gx = a;
        double *b = realloc(w->nb_gy, sizeof(double) * (size_t)cap);
        if (b) w->nb_gy = b;
        double *f = realloc(w->nb_f, sizeof(double) * (size_t)cap);
        if (f) w->nb_f = f;
        double *wv = realloc(w->nb_w, sizeof(double) * (size_t)cap);
        if (wv) w->nb_w = wv;
        if (!j || !a || !b || !f || !wv) return sph_world_fail(w, "out of memory (%ld neighbour pairs)", total);
        w->nb_cap = cap;
    }

    /* the counts are summed up: cnt takes each real particle's place in the cell order */
    int *kof = cnt;
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int k = 0; k < nt; k++)
        if (items[k] < n) kof[items[k]] = k;
    double kc = -5.0 * 7.0 / (478.0 * SPH_PI * h * h * h), hinv = 1.0 / h; /* as in sph_kernel_deriv */
    double kv = 7.0 / (478.0 * SPH_PI * h * h);                             /* as in sph_kernel_value */
    int cap = w->cand_cap;
#pragma omp parallel num_threads(threads)
    {
        int t = omp_get_thread_num();
        /* per thread: the candidates' classes, the fluid and the wall neighbours' candidate
         * indices (k: cell order) */
        int *cls = w->cand_j + (size_t)t * 3 * (cap + 1), *kf_ = cls + cap + 1, *kw_ = kf_ + cap + 1;
#pragma omp for schedule(dynamic, 256)
        for (int i = 0; i < n; i++) {
            if (!w->active[i]) {
                w->nb_mid[i] = w->nb_start[i];
                continue;
            }
            fill_row(w, i, kof[i], cls, kf_, kw_, r2max, kc, kv, hinv);
        }
    }
    w->nb_n = n;
    return 0;
}

int sph_neighbours_brute(const sph_world *w, int i, int *out, int cap) {
    double r2max = SPH_KERNEL_SUPPORT * SPH_KERNEL_SUPPORT * w->h * w->h;
    int c = 0;
    for (int j = 0; j < w->n + w->ng; j++) {
        double dx = w->x[i] - w->x[j], dy = w->y[i] - w->y[j];
        if (j != i && dx * dx + dy * dy < r2max) {
            if (c < cap) out[c] = j;
            c++;
        }
    }
    return c;
}
