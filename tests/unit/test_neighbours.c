/* Neighbour lists against a brute-force search, on random and perturbed lattices, with
 * periodic edges and symmetry planes (ghosts included). Also the pressure matrix's
 * symmetry and the solver's residual on a manufactured problem, and momentum conservation
 * of the symmetric pair forces. */
#include "../../src/internal.h"
#include "unit.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* xorshift: a seeded generator of our own (no rand(), no global state) */
static double rnd(uint64_t *s) {
    *s ^= *s << 13;
    *s ^= *s >> 7;
    *s ^= *s << 17;
    return (double)(*s >> 11) / 9007199254740992.0;
}

static int cmp_int(const void *a, const void *b) { return *(const int *)a - *(const int *)b; }

static sph_world *make_world(int periodic, int sym, double jitter, uint64_t seed) {
    sph_params p;
    sph_params_default(&p);
    p.dx = 0.05;
    p.threads = 2;
    if (periodic) {
        p.periodic[0] = 1;
        p.period_lo[0] = 0.0;
        p.period_hi[0] = 1.0;
    }
    if (sym) {
        p.symmetry[1] = 1;
        p.sym_at[1] = 0.0;
    }
    char err[128];
    sph_world *w = sph_world_new(&p, err, sizeof err);
    sph_material m = {SPH_NEWTONIAN, 1.0, 0, 0, 0, 0};
    double r[4] = {0.0, 0.0, 1.0, 0.6};
    sph_world_fill(w, r, &m);
    double pr[4] = {0.0, 0.6, 1.0, 0.75};
    sph_world_plate(w, pr, 0);
    for (int i = 0; i < w->n; i++) {
        if (w->kind[i] != SPH_FLUID) continue;
        w->x[i] += jitter * p.dx * (rnd(&seed) - 0.5);
        w->y[i] += jitter * p.dx * (rnd(&seed) - 0.5);
        if (w->y[i] < 0) w->y[i] = -w->y[i];
        if (w->y[i] > 0.6) w->y[i] = 0.6 - 1e-3;
    }
    return w;
}

static void compare(sph_world *w, const char *name) {
    sph_boundary_wrap(w);
    int ok = !sph_neighbours_sort(w) && !sph_boundary_ghosts(w) && !sph_neighbours_build(w);
    CHECK(ok, "neighbour build succeeds", "%s", w->err);
    int bad = 0, rows = 0, ghosts = w->ng;
    int *brute = malloc(sizeof(int) * 4096), *list = malloc(sizeof(int) * 4096);
    for (int i = 0; i < w->n; i++) {
        if (!w->active[i]) continue;
        rows++;
        int nb = sph_neighbours_brute(w, i, brute, 4096);
        int nl = w->nb_start[i + 1] - w->nb_start[i];
        memcpy(list, w->nb_j + w->nb_start[i], sizeof(int) * (size_t)nl);
        qsort(brute, (size_t)nb, sizeof(int), cmp_int);
        qsort(list, (size_t)nl, sizeof(int), cmp_int);
        if (nb != nl || memcmp(brute, list, sizeof(int) * (size_t)nb)) bad++;
    }
    CHECK(bad == 0 && rows > 0, name, "%d of %d rows differ from brute force", bad, rows);
    (void)ghosts;
    free(brute);
    free(list);
}

/* The pressure system is symmetric, and PCG reaches its tolerance on it. */
static void check_pressure(sph_world *w) {
    uint64_t s = 99;
    for (int i = 0; i < w->n + w->ng; i++) {
        w->us[i] = rnd(&s) - 0.5;
        w->vs[i] = rnd(&s) - 0.5;
    }
    for (int i = 0; i < w->n; i++) w->surf[i] = w->kind[i] == SPH_FLUID && w->divr[i] < 1.5;
    for (int g = w->n; g < w->n + w->ng; g++) w->surf[g] = w->surf[w->src[g]];
    int rc = sph_pressure_solve(w, 1e-3);
    CHECK(rc == 0, "pressure solve converges on a random field", "%s", w->err);
    sph_csr *A = &w->A;
    double asym = 0.0, amax = 0.0;
    for (int r = 0; r < A->n; r++)
        for (int k = A->start[r]; k < A->start[r + 1]; k++) {
            int c = A->col[k];
            double v = 0.0, t = 0.0;
            for (int q = A->start[r]; q < A->start[r + 1]; q++)
                if (A->col[q] == c) v += A->val[q];
            for (int q = A->start[c]; q < A->start[c + 1]; q++)
                if (A->col[q] == r) t += A->val[q];
            if (fabs(v - t) > asym) asym = fabs(v - t);
            if (fabs(v) > amax) amax = fabs(v);
        }
    CHECK(asym <= 1e-12 * amax, "pressure matrix is symmetric", "max |A_ij - A_ji| = %g (max %g)", asym, amax);
    double *y = malloc(sizeof(double) * (size_t)A->n), rr = 0, bb = 0;
    sph_csr_matvec(A, w->sol, y, 1);
    for (int r = 0; r < A->n; r++) {
        rr += (w->b[r] - y[r]) * (w->b[r] - y[r]);
        bb += w->b[r] * w->b[r];
    }
    CHECK(sqrt(rr / bb) <= w->par.tol * 1.0001, "pressure residual below the tolerance", "%g", sqrt(rr / bb));
    free(y);
}

/* A world of parameters p holding the unit square of material m on the dx lattice. */
static sph_world *unit_block(const sph_params *p, const sph_material *m) {
    char err[128];
    sph_world *w = sph_world_new(p, err, sizeof err);
    double r[4] = {0, 0, 1, 1};
    sph_world_fill(w, r, m);
    return w;
}

/* a step's neighbour build: wrap, sort, ghosts, lists */
static void build_neighbours(sph_world *w) {
    sph_boundary_wrap(w);
    sph_neighbours_sort(w);
    sph_boundary_ghosts(w);
    sph_neighbours_build(w);
}

/* Symmetric pair forces: with no walls, pressure and viscous forces change no momentum. */
static void check_momentum(void) {
    sph_params p;
    sph_params_default(&p);
    p.dx = 0.05;
    p.threads = 2;
    p.periodic[0] = p.periodic[1] = 1;
    p.period_hi[0] = p.period_hi[1] = 1.0;
    sph_material m = {SPH_BINGHAM, 1.0, 1.0, 100.0, 0, 0};
    sph_world *w = unit_block(&p, &m);
    uint64_t s = 7;
    for (int i = 0; i < w->n; i++) {
        w->x[i] += 0.2 * p.dx * (rnd(&s) - 0.5);
        w->y[i] += 0.2 * p.dx * (rnd(&s) - 0.5);
        w->u[i] = rnd(&s) - 0.5;
        w->v[i] = rnd(&s) - 0.5;
        w->p[i] = 10 * rnd(&s);
        w->rho[i] = 1.0 + 0.01 * (rnd(&s) - 0.5);
    }
    build_neighbours(w);
    sph_viscous_rheology(w, 1e-3);
    double px0 = 0, py0 = 0, px1 = 0, py1 = 0, pref = 0;
    for (int i = 0; i < w->n; i++) {
        px0 += w->m[i] * w->u[i];
        py0 += w->m[i] * w->v[i];
        pref += w->m[i] * hypot(w->u[i], w->v[i]);
    }
    sph_viscous_explicit(w, 1e-3);
    for (int i = 0; i < w->n; i++) {
        px1 += w->m[i] * w->us[i];
        py1 += w->m[i] * w->vs[i];
    }
    CHECK(fabs(px1 - px0) < 1e-12 * pref && fabs(py1 - py0) < 1e-12 * pref,
          "viscous pair forces conserve momentum", "change (%g, %g) of %g", px1 - px0, py1 - py0, pref);
    sph_boundary_sync(w, w->p, 0, 0);
    px0 = px1, py0 = py1;
    sph_pressure_correct(w, 1e-3);
    px1 = py1 = 0;
    for (int i = 0; i < w->n; i++) {
        px1 += w->m[i] * w->u[i];
        py1 += w->m[i] * w->v[i];
    }
    CHECK(fabs(px1 - px0) < 1e-12 * pref && fabs(py1 - py0) < 1e-12 * pref,
          "pressure pair forces conserve momentum", "change (%g, %g) of %g", px1 - px0, py1 - py0, pref);
    sph_world_free(w);
}

/* the thin-film scheme's gradient: the renormalised difference form is exact for a linear
 * pressure, whatever the disorder and the pressure's level (the symmetric form is not:
 * its p_i sum_j V_j grad W_ij term scales with the level). A perturbed lattice, p = 1000 +
 * 3 x - 5 y: the velocity change of every particle away from the block's edges (where the
 * renormalisation may fall back to L = I) is -dt (3, -5) / rho. */
static void check_difference_gradient(void) {
    for (int form = 0; form < 2; form++) {
        sph_params p;
        sph_params_default(&p);
        p.dx = 0.05;
        p.threads = 2;
        p.thin_film = form;
        sph_material m = {SPH_NEWTONIAN, 1.0, 0, 0, 0, 0};
        sph_world *w = unit_block(&p, &m);
        uint64_t s = 99;
        for (int i = 0; i < w->n; i++) {
            w->x[i] += 0.3 * p.dx * (rnd(&s) - 0.5);
            w->y[i] += 0.3 * p.dx * (rnd(&s) - 0.5);
        }
        build_neighbours(w);
        for (int i = 0; i < w->n + w->ng; i++) {
            w->p[i] = 1000.0 + 3.0 * w->x[i] - 5.0 * w->y[i];
            w->us[i] = w->vs[i] = 0.0;
        }
        double dt = 1e-3, emax = 0.0;
        sph_pressure_correct(w, dt);
        for (int i = 0; i < w->n; i++) {
            if (w->x[i] < 0.2 || w->x[i] > 0.8 || w->y[i] < 0.2 || w->y[i] > 0.8) continue;
            double ex = w->u[i] - (-dt * 3.0), ey = w->v[i] - (dt * 5.0);
            emax = fmax(emax, hypot(ex, ey) / (dt * hypot(3.0, 5.0)));
        }
        if (form)
            CHECK(emax < 1e-9, "difference-form pressure gradient exact for a linear p on a perturbed lattice",
                  "max relative error %g", emax);
        else
            CHECK(emax > 1.0, "symmetric-form pressure gradient feels the pressure level (p = 1000 + linear)",
                  "max relative error %g", emax);
        sph_world_free(w);
    }
}

/* AMG-PCG on a manufactured problem: the 5-point Laplacian with Dirichlet edges. */
static void check_pcg(void) {
    int m = 60, n = m * m;
    sph_csr A;
    memset(&A, 0, sizeof A);
    sph_csr_reserve(&A, n, 5 * n);
    int e = 0;
    A.start[0] = 0;
    for (int j = 0; j < m; j++)
        for (int i = 0; i < m; i++) {
            int r = j * m + i;
            A.col[e] = r;
            A.val[e++] = 4.0;
            int nb[4][2] = {{i - 1, j}, {i + 1, j}, {i, j - 1}, {i, j + 1}};
            for (int q = 0; q < 4; q++)
                if (nb[q][0] >= 0 && nb[q][0] < m && nb[q][1] >= 0 && nb[q][1] < m) {
                    A.col[e] = nb[q][1] * m + nb[q][0];
                    A.val[e++] = -1.0;
                }
            A.diag[r] = 4.0;
            A.start[r + 1] = e;
        }
    double *xs = malloc(sizeof(double) * (size_t)n), *b = malloc(sizeof(double) * (size_t)n);
    double *x = calloc((size_t)n, sizeof(double));
    for (int r = 0; r < n; r++) xs[r] = sin(0.1 * r) + 0.3 * cos(0.037 * r * r);
    sph_csr_matvec(&A, xs, b, 2);
    sph_solver s;
    memset(&s, 0, sizeof s);
    sph_solver_reserve(&s, n);
    sph_solve_result none = sph_solver_pcg(&s, &A, b, x, 1e-10, 5000, 2);
    CHECK(!none.converged && none.iterations == 0, "PCG without a multigrid setup for the matrix fails at once",
          "converged %d after %d iterations", none.converged, none.iterations);
    CHECK(sph_solver_setup(&s, &A, 2) == 0, "multigrid setup of the manufactured problem", "rc != 0");
    sph_solve_result res = sph_solver_pcg(&s, &A, b, x, 1e-10, 5000, 2);
    double err = 0;
    for (int r = 0; r < n; r++) err = fmax(err, fabs(x[r] - xs[r]));
    CHECK(res.converged && res.residual <= 1e-10, "PCG reaches 1e-10 on a manufactured Poisson problem",
          "residual %g after %d iterations", res.residual, res.iterations);
    /* error <= cond(A) * residual: cond ~ (2m/pi)^2 ~ 1.5e3 */
    CHECK(err < 1e-6, "PCG solution matches the manufactured one", "max error %g", err);
    sph_solve_result again = sph_solver_pcg(&s, &A, b, x, 1e-10, 5000, 2);
    CHECK(again.iterations == 0, "PCG warm-started from the solution takes no iteration", "%d", again.iterations);
    for (int r = 0; r < n; r++) x[r] = 0.0;
    sph_solve_result capped = sph_solver_pcg(&s, &A, b, x, 1e-30, 3, 2);
    CHECK(!capped.converged && capped.iterations == 3, "PCG reports non-convergence at its iteration limit",
          "converged %d after %d", capped.converged, capped.iterations);
    free(xs);
    free(b);
    free(x);
    sph_csr_free(&A);
    sph_solver_free(&s);
}

int main(void) {
    check_difference_gradient();
    for (int c = 0; c < 4; c++) {
        int periodic = c & 1, sym = (c >> 1) & 1;
        for (int q = 0; q < 2; q++) {
            double jitter = q == 0 ? 0.0 : 0.9;
            sph_world *w = make_world(periodic, sym, jitter, 12345u + (uint64_t)c);
            char name[160];
            snprintf(name, sizeof name, "neighbours equal brute force (%s lattice%s%s)",
                     q == 0 ? "regular" : "perturbed", periodic ? ", periodic x" : "",
                     sym ? ", symmetry y = 0" : "");
            compare(w, name);
            if (c == 3 && q == 1) check_pressure(w);
            sph_world_free(w);
        }
    }
    /* random cloud */
    {
        sph_params p;
        sph_params_default(&p);
        p.dx = 0.05;
        char err[128];
        sph_world *w = sph_world_new(&p, err, sizeof err);
        sph_material m = {SPH_NEWTONIAN, 1.0, 0, 0, 0, 0};
        double r[4] = {0, 0, 1, 1};
        sph_world_fill(w, r, &m);
        uint64_t s = 4242;
        for (int i = 0; i < w->n; i++) {
            w->x[i] = 2.0 * rnd(&s);
            w->y[i] = rnd(&s);
        }
        compare(w, "neighbours equal brute force (random cloud)");
        sph_world_free(w);
    }
    check_momentum();
    check_pcg();
    UNIT_END();
}
