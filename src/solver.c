/* Conjugate gradients preconditioned by the algebraic multigrid cycle of amg.c, for one
 * system or two of the same structure, and the solves' first guesses.
 * The solver has a contract (SPlisHSPlasH style): tolerance and iteration limit in,
 * iterations, residual and convergence out; it never fails silently. */
#include "linalg.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>

void sph_guess_weights(const sph_guess *g, int n, double dt, double *a, double *b) {
    *a = *b = 0.0;
    if (g->n != n || !(g->dt > 0)) return;
    *a = dt / g->dt;
    if (g->n1 == n && g->dt1 > 0) {
        *a *= 2.0;
        *b = dt / g->dt1;
    }
}

double *sph_guess_keep(sph_guess *g, int n, double dt) {
    double *t = g->d1;
    g->d1 = g->d;
    g->d = t;
    g->dt1 = g->dt;
    g->n1 = g->n;
    g->dt = dt;
    g->n = n;
    return g->d;
}

int sph_solver_reserve(sph_solver *s, int n) {
    if (n <= s->cap) return 0;
    int cap = n + n / 4 + 16;
    if (sph_grow((void **)&s->r, sizeof(double), cap) || sph_grow((void **)&s->z, sizeof(double), cap) ||
        sph_grow((void **)&s->q, sizeof(double), cap) || sph_grow((void **)&s->d, sizeof(double), cap) ||
        sph_grow((void **)&s->r2, sizeof(double), cap) || sph_grow((void **)&s->z2, sizeof(double), cap) ||
        sph_grow((void **)&s->q2, sizeof(double), cap) || sph_grow((void **)&s->d2, sizeof(double), cap) ||
        sph_grow((void **)&s->x2, sizeof(double), cap))
        return -1;
    s->cap = cap;
    return 0;
}

void sph_solver_free(sph_solver *s) {
    free(s->r);
    free(s->z);
    free(s->q);
    free(s->d);
    free(s->r2);
    free(s->z2);
    free(s->q2);
    free(s->d2);
    free(s->x2);
    s->r = s->z = s->q = s->d = 0;
    s->r2 = s->z2 = s->q2 = s->d2 = s->x2 = 0;
    s->cap = 0;
    sph_amg_free(&s->amg);
    sph_amg_free(&s->amg2);
    s->amg.built_for = s->amg2.built_for = 0;
    s->amg_for = 0;
    s->cur = 0;
}

/* The hierarchy slot for matrix a: the one built for it, else a free one, else the first. */
static sph_amg *slot_for(sph_solver *s, const sph_csr *a) {
    if (s->amg.built_for == a) return &s->amg;
    if (s->amg2.built_for == a) return &s->amg2;
    if (!s->amg.built_for) return &s->amg;
    if (!s->amg2.built_for) return &s->amg2;
    return &s->amg;
}

/* Reuse across steps (sph_solver_setup_reuse, the pressure system; sph_solver_setup_pair
 * with row_of and id, the viscous pair). The particles move a fraction of dx a step, so the
 * hierarchy of an earlier step (its aggregates, prolongation and coarse operators; the
 * prolongation's rows follow their particles by id) stays a good preconditioner: about one
 * iteration a solve more, for most of a setup's time saved. The finest level's smoother
 * always takes the current values (the viscous pair's: both components'): the viscous values
 * follow the apparent viscosity, which changes by large factors from one step to the next
 * where the material yields, and with the last step's smoother the viscous solves take four
 * times the iterations. A hierarchy is rebuilt when it is REUSE_MAX_AGE steps old, when the
 * first solve after the last reuse took more than REUSE_SLACK iterations above the first
 * solve after the last setup, or when the row count changed by more than REUSE_MAX_CHANGE of
 * it. Redoing only the numeric part of a setup (the aggregates kept) would save little: the
 * Galerkin products and the smoothers' copies are most of it, and the fine matrix's pattern
 * changes every step (the neighbour lists). */
#define REUSE_MAX_AGE 20
#define REUSE_SLACK 1
#define REUSE_MAX_CHANGE 0.05

static int setup(sph_solver *s, const sph_csr *a, const sph_csr *a2, int threads, const int *row_of,
                 const int *id) {
    s->amg_for = 0;
    s->cur = 0;
    if (a->n == 0) return 0;
    double t0 = omp_get_wtime();
    sph_amg *g = slot_for(s, a);
    g->wcycle_from = 0; /* the default cycle (sph_solver_vcycle changes it until the next setup) */
    /* one set of setup scratch for both hierarchies: this one takes it */
    sph_amg_swap_scratch(g, g == &s->amg ? &s->amg2 : &s->amg);
    int rc = 1;
    if (row_of && g->built_for == a && g->levels > 1 && g->age < REUSE_MAX_AGE && g->it_fresh >= 0 &&
        g->it_recent <= g->it_fresh + REUSE_SLACK && fabs((double)(a->n - g->fine_n)) <= REUSE_MAX_CHANGE * g->fine_n) {
        rc = sph_amg_reuse(g, a, a2, row_of, id, threads);
        if (rc == 0) {
            g->age++;
            s->reuses++;
        }
    }
    if (rc) {
        g->built_for = 0;
        rc = a2 ? sph_amg_setup_pair(g, a, a2, threads) : sph_amg_setup(g, a, threads);
        if (!rc && row_of) rc = sph_amg_set_ids(g, a->n, row_of, id);
        if (!rc && !row_of) {
            free(g->rid);
            g->rid = 0;
            g->ridcap = 0;
        }
        g->age = 0;
        g->it_fresh = -1;
    }
    s->setup_time += omp_get_wtime() - t0;
    if (rc) return -1;
    g->built_for = a;
    s->cur = g;
    s->amg_for = a;
    s->first_pending = 1;
    return 0;
}

int sph_solver_setup(sph_solver *s, const sph_csr *a, int threads) { return setup(s, a, 0, threads, 0, 0); }

int sph_solver_setup_reuse(sph_solver *s, const sph_csr *a, int threads, const int *row_of, const int *id) {
    return setup(s, a, 0, threads, row_of, id);
}

/* The viscous u and v systems: one setup for both, the finest smoother's two copies made
 * in one pass (amg.c, sph_amg_setup_pair), a third faster than sph_solver_second after the
 * setup. */
int sph_solver_setup_pair(sph_solver *s, const sph_csr *a, const sph_csr *a2, int threads, const int *row_of,
                          const int *id) {
    return setup(s, a, a2, threads, row_of, id);
}

/* The viscous systems take a V-cycle. Their diagonal (rho / dt, scaled by mass) dominates,
 * and the W-cycle's second visits of the coarse levels buy nothing there: the V-cycle takes
 * the same iterations in 7 % less time. The pressure systems keep the W-cycle: with the
 * V-cycle they take about 30 % more iterations and 14 % more time. */
void sph_solver_vcycle(sph_solver *s, const sph_csr *a) {
    if (s->amg_for == a && s->cur) s->cur->wcycle_from = SPH_AMG_MAX_LEVELS;
}

int sph_solver_refresh(sph_solver *s, const sph_csr *a, int threads) {
    if (s->amg_for != a || !s->cur || s->cur->levels == 0) return 0;
    double t0 = omp_get_wtime();
    int rc = sph_amg_refresh(s->cur, a, threads);
    s->setup_time += omp_get_wtime() - t0;
    if (rc) s->amg_for = 0; /* out of memory: no hierarchy (the solves on a fail) */
    return rc;
}

static double dot(const double *a, const double *b, int n, int threads) {
    double s = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : s) num_threads(threads)
    for (int i = 0; i < n; i++) s += a[i] * b[i];
    return s;
}

/* y = a x and x . y in one pass (CG's product and its dot product d . q: the same sums
 * as sph_csr_matvec and dot, in the same order). The arrays are in locals, so they are not
 * reloaded after each store to y (8 % off a CG iteration). */
static double matvec_dot(const sph_csr *a, const double *x, double *y, int threads) {
    int n = a->n;
    const int *st = a->start, *col = a->col;
    const double *val = a->val;
    double s = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : s) num_threads(threads)
    for (int i = 0; i < n; i++) {
        double t = 0.0;
        for (int k = st[i]; k < st[i + 1]; k++) t += val[k] * x[col[k]];
        y[i] = t;
        s += x[i] * t;
    }
    return s;
}

int sph_solver_second(sph_solver *s, const sph_csr *a, const sph_csr *a2, int threads) {
    if (s->amg_for != a || !s->cur || s->cur->levels == 0) return 0;
    double t0 = omp_get_wtime();
    int rc = sph_amg_second(s->cur, a2, threads);
    s->setup_time += omp_get_wtime() - t0;
    return rc;
}

/* Conjugate gradients preconditioned by the multigrid cycle, for one system or two side by
 * side (the viscous u and v): the products and the cycle take both systems in one pass
 * while both iterate, one alone once the other has stopped, so each system's iterates are
 * those it has solved alone.
 * The cycle's sweeps are bound by the instructions per nonzero more than by memory: the
 * two systems in one loop share the column loads and the loop, and their two chains of
 * additions overlap, which takes about a fifth off the pair's solve time. */
typedef struct pcg_state {
    const sph_csr *a;
    const double *b;
    double *x, *r, *z, *q, *d;
    double bnorm, rnorm, rz, rz1, alpha;
    int it, on; /* on: still iterating */
    sph_solve_result res;
} pcg_state;

/* y1 = a1 x1, y2 = a2 x2 for two matrices of the same structure, and the dot products
 * x1 . y1, x2 . y2 (as matvec_dot) */
static void matvec_pair_dot(const sph_csr *a1, const sph_csr *a2, const double *x1, const double *x2, double *y1,
                            double *y2, double dots[2], int threads) {
    int n = a1->n;
    const int *st = a1->start, *col = a1->col;
    const double *v1 = a1->val, *v2 = a2->val;
    double d1 = 0.0, d2 = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : d1, d2) num_threads(threads)
    for (int i = 0; i < n; i++) {
        double s1 = 0.0, s2 = 0.0;
        for (int k = st[i]; k < st[i + 1]; k++) {
            int j = col[k];
            s1 += v1[k] * x1[j];
            s2 += v2[k] * x2[j];
        }
        y1[i] = s1;
        y2[i] = s2;
        d1 += x1[i] * s1;
        d2 += x2[i] * s2;
    }
    dots[0] = d1;
    dots[1] = d2;
}

/* CG on k = 1 or 2 systems of the structure of a1 (a2, b2, x2 unused when k = 1). */
static void pcg_run(sph_solver *s, int k, const sph_csr *a1, const sph_csr *a2, const double *b1, const double *b2,
                    double *x1, double *x2, double tol, int max_iter, int threads, sph_solve_result *res) {
    int n = a1->n;
    double t0 = omp_get_wtime();
    pcg_state P[2] = {{a1, b1, x1, s->r, s->z, s->q, s->d, 0, 0, 0, 0, 0, 0, 0, {0, 0.0, 1}},
                      {k == 2 ? a2 : a1, b2, x2, s->r2, s->z2, s->q2, s->d2, 0, 0, 0, 0, 0, 0, 0, {0, 0.0, 1}}};
    for (int c = 0; c < k; c++) {
        pcg_state *p = &P[c];
        s->solves++;
        p->bnorm = sqrt(dot(p->b, p->b, n, threads));
        if (p->bnorm == 0.0) {
            for (int i = 0; i < n; i++) p->x[i] = 0.0;
            if (k == 1) { /* nothing to solve; not the hierarchy's first solve either */
                res[0] = (sph_solve_result){0, 0.0, 1};
                return;
            }
            continue;
        }
        sph_csr_matvec(p->a, p->x, p->q, threads);
        for (int i = 0; i < n; i++) p->r[i] = p->b[i] - p->q[i];
    }
    /* the first preconditioning */
    int need0 = P[0].bnorm != 0.0, need1 = P[1].bnorm != 0.0;
    if (need0 && need1) sph_amg_apply2(s->cur, a1, a2, P[0].r, P[1].r, P[0].z, P[1].z, threads);
    else if (need0) sph_amg_apply(s->cur, a1, P[0].r, P[0].z, threads);
    else if (need1) sph_amg_apply_second(s->cur, a2, P[1].r, P[1].z, threads);
    for (int c = 0; c < k; c++) {
        pcg_state *p = &P[c];
        if (p->bnorm == 0.0) continue;
        for (int i = 0; i < n; i++) p->d[i] = p->z[i];
        p->rz = dot(p->r, p->z, n, threads);
        p->rnorm = sqrt(dot(p->r, p->r, n, threads));
        p->on = p->rnorm > tol * p->bnorm && p->it < max_iter;
    }
    while (P[0].on || P[1].on) {
        double dqs[2] = {0.0, 0.0};
        if (P[0].on && P[1].on) matvec_pair_dot(a1, a2, P[0].d, P[1].d, P[0].q, P[1].q, dqs, threads);
        else if (P[0].on) dqs[0] = matvec_dot(a1, P[0].d, P[0].q, threads);
        else dqs[1] = matvec_dot(a2, P[1].d, P[1].q, threads);
        int pre[2] = {0, 0};
        for (int c = 0; c < 2; c++) {
            pcg_state *p = &P[c];
            if (!p->on) continue;
            double *x = p->x, *r = p->r, *q = p->q, *d = p->d;
            double dq = dqs[c];
            if (!(dq > 0.0)) { /* not SPD, or breakdown: reported as not converged */
                p->on = 0;
                continue;
            }
            double alpha = p->rz / dq, rr = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : rr) num_threads(threads)
            for (int i = 0; i < n; i++) {
                x[i] += alpha * d[i];
                r[i] -= alpha * q[i];
                rr += r[i] * r[i];
            }
            p->it++;
            if (!(sqrt(rr) > tol * p->bnorm)) {
                p->rnorm = sqrt(rr);
                p->on = 0;
                continue;
            }
            p->rnorm = sqrt(rr);
            pre[c] = 1;
        }
        if (pre[0] && pre[1]) sph_amg_apply2(s->cur, a1, a2, P[0].r, P[1].r, P[0].z, P[1].z, threads);
        else if (pre[0]) sph_amg_apply(s->cur, a1, P[0].r, P[0].z, threads);
        else if (pre[1]) sph_amg_apply_second(s->cur, a2, P[1].r, P[1].z, threads);
        for (int c = 0; c < 2; c++) {
            pcg_state *p = &P[c];
            if (!pre[c]) continue;
            double *z = p->z, *d = p->d;
            double rz1 = dot(p->r, z, n, threads);
            if (!(rz1 > 0.0)) { /* preconditioner not positive definite: not converged */
                p->on = 0;
                continue;
            }
            double beta = rz1 / p->rz;
            p->rz = rz1;
#pragma omp parallel for schedule(static) num_threads(threads)
            for (int i = 0; i < n; i++) d[i] = z[i] + beta * d[i];
            p->on = p->rnorm > tol * p->bnorm && p->it < max_iter;
        }
    }
    for (int c = 0; c < k; c++) {
        pcg_state *p = &P[c];
        if (p->bnorm == 0.0) {
            res[c] = (sph_solve_result){0, 0.0, 1};
            continue;
        }
        res[c].iterations = p->it;
        res[c].residual = p->rnorm / p->bnorm;
        res[c].converged = isfinite(p->rnorm) && p->rnorm <= tol * p->bnorm;
    }
    if (s->first_pending) {
        s->first_pending = 0;
        s->cur->it_recent = P[0].it;
        if (s->cur->it_fresh < 0) s->cur->it_fresh = P[0].it;
    }
    s->solve_time += omp_get_wtime() - t0;
}

sph_solve_result sph_solver_pcg(sph_solver *s, const sph_csr *a, const double *b, double *x,
                                double tol, int max_iter, int threads) {
    sph_solve_result res = {0, 0.0, 1};
    int n = a->n;
    if (n == 0) return res;
    if (!(s->amg_for == a && s->cur && s->cur->levels > 0 && s->cur->fine_n == n))
        return (sph_solve_result){0, 1.0, 0}; /* no hierarchy for a */
    pcg_run(s, 1, a, 0, b, 0, x, 0, tol, max_iter, threads, &res);
    return res;
}

void sph_solver_pcg2(sph_solver *s, const sph_csr *a1, const sph_csr *a2, const double *b1, const double *b2,
                     double *x1, double *x2, double tol, int max_iter, int threads, sph_solve_result res[2]) {
    int n = a1->n;
    int amg = s->amg_for == a1 && s->cur && s->cur->levels > 0 && s->cur->fine_n == n;
    if (!amg || a2->n != n || a2->start != a1->start || a2->col != a1->col) { /* no hierarchy for the pair */
        res[0] = res[1] = (sph_solve_result){0, 1.0, 0};
        return;
    }
    pcg_run(s, 2, a1, a2, b1, b2, x1, x2, tol, max_iter, threads, res);
}
