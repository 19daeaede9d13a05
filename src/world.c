/* The world: all state of one simulation (particles, materials, plates, solver scratch,
 * statistics, the last error), and the time step that ties the passes together. */
#include "internal.h"
#include "kernel.h"

#include <limits.h>
#include <math.h>
#include <omp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

void sph_params_default(sph_params *p) {
    memset(p, 0, sizeof *p);
    p->dx = 0.0;
    p->rho0 = 1.0;
    p->viscosity = SPH_VISC_IMPLICIT;
    /* the relative residual of every solve, the pressure's and the implicit viscous
     * step's: the suite's figures (squeeze forces, the FE comparisons) are measured at it */
    p->tol = 1e-6;
    p->surface_div = 1.5;
    p->density_tol = 0.005;
    p->thin_film = 0;
    p->shifting = SPH_SHIFTING_AUTO;
}

int sph_world_fail(sph_world *w, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(w->err, sizeof w->err, fmt, ap);
    va_end(ap);
    return -1;
}

const char *sph_world_error(const sph_world *w) { return w->err; }
const sph_params *sph_world_params(const sph_world *w) { return &w->par; }
double sph_world_h(const sph_world *w) { return w->h; }

static const char *check_params(const sph_params *p) {
    static const char *const bad[] = {
        "dx must be a positive number", "rho must be a positive number", "periodic range must have lo < hi",
        "an axis cannot be both periodic and a symmetry plane", "tol must be in (0, 1)", "gravity must be finite",
        "shifting must be >= 0 or auto (-1)", "density_tol must be in [0, 1)", "thin_film must be 0 or 1",
        "threads must be 1..256 (0: all cores)", "dt_max must be a number >= 0 (0: no bound)",
        "surface must be a number >= 0 (0: no free surface)",
        "h must be 0 (dx) or between dx and 2 dx: the kernel's support 3 h must hold the lattice's neighbours",
        "cfl must be 0 (0.25) or in (0, 1]"};
    _Static_assert(SPH_MAX_THREADS == 256, "the threads message names the bound");
    if (!(p->dx > 0 && isfinite(p->dx))) return bad[0];
    if (!(p->rho0 > 0 && isfinite(p->rho0))) return bad[1];
    for (int a = 0; a < 2; a++) {
        if (p->periodic[a] && !(p->period_lo[a] < p->period_hi[a])) return bad[2];
        if (p->periodic[a] && p->symmetry[a]) return bad[3];
    }
    if (!(p->tol > 0 && p->tol < 1)) return bad[4];
    if (!isfinite(p->gravity[0]) || !isfinite(p->gravity[1])) return bad[5];
    if (!(p->shifting >= 0 || p->shifting == SPH_SHIFTING_AUTO)) return bad[6];
    if (!(p->density_tol >= 0 && p->density_tol < 1)) return bad[7];
    if (p->thin_film != 0 && p->thin_film != 1) return bad[8];
    if (!(p->threads >= 0 && p->threads <= SPH_MAX_THREADS)) return bad[9];
    if (!(p->dt_max >= 0 && isfinite(p->dt_max))) return bad[10];
    if (!(p->surface_div >= 0 && isfinite(p->surface_div))) return bad[11];
    if (!(p->h == 0 || (p->h >= p->dx && p->h <= 2 * p->dx))) return bad[12];
    if (!(p->cfl == 0 || (p->cfl > 0 && p->cfl <= 1))) return bad[13];
    return 0;
}

sph_world *sph_world_new(const sph_params *p, char *err, size_t errlen) {
    const char *bad = check_params(p);
    if (bad) {
        if (err) snprintf(err, errlen, "%s", bad);
        return 0;
    }
    /* The step squares and cubes the lengths (mass rho dx^2, kernel gradients 1 / h^3, the
     * Laplacian's 1 / h^4): outside these bounds they underflow to 0 or overflow. */
    if (!(p->dx >= SPH_MIN_LENGTH && p->dx <= SPH_MAX_LENGTH)) {
        if (err)
            snprintf(err, errlen, "dx = %g is out of range: it must be in [%g, %g]", p->dx, SPH_MIN_LENGTH,
                     SPH_MAX_LENGTH);
        return 0;
    }
    if (!isnormal(p->rho0 * p->dx * p->dx) || !isfinite(p->rho0 * p->dx * p->dx)) {
        if (err)
            snprintf(err, errlen, "the particle mass rho dx^2 = %g * %g^2 is not a normal positive number", p->rho0,
                     p->dx);
        return 0;
    }
    sph_world *w = calloc(1, sizeof *w);
    if (!w) {
        if (err) snprintf(err, errlen, "out of memory");
        return 0;
    }
    w->par = *p;
    w->pin = -1;
    w->cluster_step = -1;
    w->st.shifting_since = -1.0;
    w->dx = p->dx;
    /* h = dx by default: the quintic kernel reaches 3 dx, the support every figure of the
     * suite and of docs/validation.md was measured with (docs/method.md, "Kernel and
     * neighbours"). */
    w->h = p->h > 0 ? p->h : p->dx;
    w->mass0 = p->rho0 * p->dx * p->dx;
    /* 0: OMP_NUM_THREADS where it is set (the OpenMP convention: tests/run.sh sets it to 1
     * while it runs two test programs at once), else every core */
    const char *omp = getenv("OMP_NUM_THREADS");
    w->threads = p->threads > 0 ? p->threads : omp && *omp ? omp_get_max_threads() : omp_get_num_procs();
    if (w->threads > SPH_MAX_THREADS) w->threads = SPH_MAX_THREADS; /* a machine of more cores */
    if (w->par.dt_min <= 0) w->par.dt_min = 1e-12 * w->h;
    if (w->par.cfl <= 0) w->par.cfl = SPH_CFL;
    return w;
}

/* Every per-particle array (slots for real particles and ghosts): grown together by
 * sph_world_reserve, freed together. */
#define PARTICLE_DOUBLES(w)                                                                 \
    {&w->x,   &w->y,   &w->u,   &w->v,   &w->us,  &w->vs,  &w->ax,       &w->ay,       \
     &w->p,   &w->rho, &w->m,   &w->eta, &w->gd,  &w->divr, &w->visc, &w->lamxx, &w->lamxy, &w->tau, &w->sxx, &w->sxy, &w->xs, &w->ys, &w->lxx,       \
     &w->lxy, &w->lyy, &w->gux, &w->guy, &w->gvx, &w->gvy, &w->phi, &w->ps, &w->psens[0], &w->psens[1], \
     &w->psens[2], &w->psens[3], &w->dp, &w->vol, &w->sa, &w->sb, &w->cx, &w->cy, &w->ru, &w->rv, &w->dcx, &w->dcy, \
     &w->gu.d, &w->gu.d1, &w->gv.d, &w->gv.d1, &w->gp.d, &w->gp.d1}
#define PARTICLE_INTS(w)                                                                    \
    {&w->kind, &w->mat, &w->id, &w->src, &w->row, &w->perm, &w->iscratch, &w->cell_of,     \
     &w->nb_count, &w->nb_mid}

void sph_world_free(sph_world *w) {
    if (!w) return;
    double **d[] = PARTICLE_DOUBLES(w);
    for (size_t k = 0; k < sizeof d / sizeof *d; k++) free(*d[k]);
    int **ip[] = PARTICLE_INTS(w);
    for (size_t k = 0; k < sizeof ip / sizeof *ip; k++) free(*ip[k]);
    double **o[] = {&w->nb_gx, &w->nb_gy, &w->nb_f, &w->nb_w, &w->b, &w->sol, &w->bk[0], &w->bk[1], &w->bk[2],
                    &w->bk[3], &w->solk[0], &w->solk[1], &w->solk[2], &w->solk[3], &w->vb, &w->vsol, &w->vval, &w->vdiag, &w->vrhs};
    for (size_t k = 0; k < sizeof o / sizeof *o; k++) free(*o[k]);
    int **oi[] = {&w->cell_start, &w->cell_items, &w->nb_start, &w->nb_j, &w->row_of, &w->vrow_of};
    for (size_t k = 0; k < sizeof oi / sizeof *oi; k++) free(*oi[k]);
    free(w->cand_j);
    free(w->gm);
    free(w->gsx);
    free(w->gsy);
    free(w->surf);
    free(w->active);
    free(w->cellfl);
    free(w->cellflag);
    sph_csr_free(&w->A);
    sph_csr_free(&w->V);
    sph_solver_free(&w->solver);
    free(w);
}

/* Room for `need` particles (real and ghosts) in every per-particle array. */
int sph_world_reserve(sph_world *w, int need) {
    if (need <= w->cap) return 0;
    /* the growth margin in long long: need + need / 2 overflows int from 1.4e9 on */
    if (need < 0) return sph_world_fail(w, "cannot hold %d particles", need);
    long long want = (long long)need + need / 2 + 256;
    int cap = want > INT_MAX ? INT_MAX : (int)want;
    double **d[] = PARTICLE_DOUBLES(w);
    for (size_t k = 0; k < sizeof d / sizeof *d; k++) {
        double *q = realloc(*d[k], sizeof(double) * (size_t)cap);
        if (!q) return sph_world_fail(w, "out of memory (%d particles)", need);
        memset(q + w->cap, 0, sizeof(double) * (size_t)(cap - w->cap));
        *d[k] = q;
    }
    int **ip[] = PARTICLE_INTS(w);
    for (size_t k = 0; k < sizeof ip / sizeof *ip; k++) {
        int *q = realloc(*ip[k], sizeof(int) * (size_t)cap);
        if (!q) return sph_world_fail(w, "out of memory (%d particles)", need);
        memset(q + w->cap, 0, sizeof(int) * (size_t)(cap - w->cap));
        *ip[k] = q;
    }
    int *ns = realloc(w->nb_start, sizeof(int) * (size_t)(cap + 1));
    if (!ns) return sph_world_fail(w, "out of memory (%d particles)", need);
    w->nb_start = ns;
    unsigned char **c[] = {&w->surf, &w->active, &w->cellfl};
    for (size_t k = 0; k < 3; k++) {
        unsigned char *q = realloc(*c[k], (size_t)cap);
        if (!q) return sph_world_fail(w, "out of memory (%d particles)", need);
        memset(q + w->cap, 0, (size_t)(cap - w->cap));
        *c[k] = q;
    }
    signed char **s[] = {&w->gsx, &w->gsy};
    for (size_t k = 0; k < 2; k++) {
        signed char *q = realloc(*s[k], (size_t)cap);
        if (!q) return sph_world_fail(w, "out of memory (%d particles)", need);
        memset(q + w->cap, 1, (size_t)(cap - w->cap));
        *s[k] = q;
    }
    w->cap = cap;
    return 0;
}

int sph_world_lattice(sph_world *w, const double rect[4], const char *what, int *nx, int *ny) {
    if (!isfinite(rect[0]) || !isfinite(rect[1]) || !isfinite(rect[2]) || !isfinite(rect[3]))
        return sph_world_fail(w, "%s rect {%g, %g, %g, %g} must be finite", what, rect[0], rect[1], rect[2],
                              rect[3]);
    if (!(rect[2] > rect[0] && rect[3] > rect[1]))
        return sph_world_fail(w, "%s rect {%g, %g, %g, %g} must have x0 < x1 and y0 < y1", what, rect[0],
                              rect[1], rect[2], rect[3]);
    /* counted in doubles: a wide rect at a small dx is far beyond int (and converting such
     * a double to int is undefined); the width of a finite rect may still overflow to inf */
    double fx = floor((rect[2] - rect[0]) / w->dx + 0.5), fy = floor((rect[3] - rect[1]) / w->dx + 0.5);
    if (!(fx >= 1 && fy >= 1))
        return sph_world_fail(w, "%s rect {%g, %g, %g, %g} holds no lattice point at dx = %g", what, rect[0],
                              rect[1], rect[2], rect[3], w->dx);
    if (!(fx * fy <= (double)(SPH_MAX_PARTICLES - w->n)))
        return sph_world_fail(w,
                              "%s rect {%g, %g, %g, %g} at dx = %g asks for %.4g particles: with the %d "
                              "already there more than the %d a world holds",
                              what, rect[0], rect[1], rect[2], rect[3], w->dx, fx * fy, w->n, SPH_MAX_PARTICLES);
    *nx = (int)fx;
    *ny = (int)fy;
    return 0;
}

/* Lattice point (i, j) of a fluid rect: 0 when it is filled, 1 when it lies outside the
 * simulated domain (behind a symmetry plane, outside a periodic range), 2 + k when it lies
 * inside plate k. */
static int fluid_point(const sph_world *w, const double rect[4], int i, int j, double *px, double *py) {
    const sph_params *P = &w->par;
    double x = rect[0] + (i + 0.5) * w->dx, y = rect[1] + (j + 0.5) * w->dx;
    *px = x;
    *py = y;
    if ((P->symmetry[0] && x < P->sym_at[0]) || (P->symmetry[1] && y < P->sym_at[1])) return 1;
    if ((P->periodic[0] && (x < P->period_lo[0] || x >= P->period_hi[0])) ||
        (P->periodic[1] && (y < P->period_lo[1] || y >= P->period_hi[1])))
        return 1;
    for (int k = 0; k < w->nplates; k++) {
        const double *R = w->plates[k].rect;
        if (x > R[0] && x < R[2] && y > R[1] && y < R[3]) return 2 + k;
    }
    return 0;
}

/* All or nothing: the points are counted (and every check made) first, room for all of
 * them reserved at once, and only then the world changed, so a failure (out of memory, a
 * plate in the way) leaves it as it was. */
int sph_world_fill(sph_world *w, const double rect[4], const sph_material *mat) {
    const char *bad = sph_rheology_check(mat);
    if (bad) return sph_world_fail(w, "material: %s", bad);
    int nx, ny;
    if (sph_world_lattice(w, rect, "fill", &nx, &ny)) return -1;
    int mi = -1;
    for (int k = 0; k < w->nmats; k++)
        if (!memcmp(&w->mats[k], mat, sizeof *mat)) mi = k;
    if (mi < 0 && w->nmats == SPH_MAX_MATERIALS)
        return sph_world_fail(w, "too many materials (at most %d)", SPH_MAX_MATERIALS);
    int count = 0, overlap = 0, plate = -1;
    double px, py;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            int at = fluid_point(w, rect, i, j, &px, &py);
            if (at == 0) count++;
            if (at >= 2) {
                overlap++;
                if (plate < 0) plate = at - 2;
            }
        }
    /* a fluid cannot fill a plate: those points would be lost without a word */
    if (overlap)
        return sph_world_fail(w, "fill rect {%g, %g, %g, %g} overlaps plate %d: %d of its lattice points at dx = %g "
                                 "lie inside a plate", rect[0], rect[1], rect[2], rect[3], plate + 1, overlap, w->dx);
    if (count == 0)
        return sph_world_fail(w, "fill rect {%g, %g, %g, %g} has no lattice point inside the simulated domain "
                                 "(behind the symmetry plane or outside the periodic range)",
                              rect[0], rect[1], rect[2], rect[3]);
    if (sph_world_reserve(w, w->n + count)) return -1;
    if (mi < 0) {
        w->mats[w->nmats] = *mat;
        mi = w->nmats++;
    }
    const sph_params *P = &w->par;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            if (fluid_point(w, rect, i, j, &px, &py)) continue;
            int q = w->n++;
            w->x[q] = px;
            w->y[q] = py;
            w->u[q] = w->v[q] = 0.0;
            w->kind[q] = SPH_FLUID;
            w->mat[q] = mi;
            w->m[q] = w->mass0;
            w->rho[q] = P->rho0;
            w->eta[q] = w->visc[q] = sph_rheology_eta(mat, 0.0);
            w->lamxx[q] = w->lamxy[q] = w->tau[q] = 0.0;
            w->id[q] = w->next_id++;
        }
    w->nfluid += count;
    w->prepared = 0;
    return count;
}

int sph_world_plate(sph_world *w, const double rect[4], int axis) {
    int nx, ny;
    if (sph_world_lattice(w, rect, "plate", &nx, &ny)) return -1;
    if (axis < -1 || axis > 1) return sph_world_fail(w, "axis must be -1, 0 or 1");
    /* fluid already inside the new plate would start through it */
    for (int i = 0; i < w->n; i++)
        if (w->kind[i] == SPH_FLUID && w->x[i] > rect[0] && w->x[i] < rect[2] && w->y[i] > rect[1] &&
            w->y[i] < rect[3])
            return sph_world_fail(w, "plate rect {%g, %g, %g, %g} overlaps fluid at (%g, %g)",
                                  rect[0], rect[1], rect[2], rect[3], w->x[i], w->y[i]);
    return sph_plate_fill(w, rect, axis);
}

int sph_world_nplates(const sph_world *w) { return w->nplates; }
double sph_world_time(const sph_world *w) { return w->t; }
double sph_world_dt(const sph_world *w) { return w->dt; }
long sph_world_steps(const sph_world *w) { return w->steps; }
int sph_world_nfluid(const sph_world *w) { return w->nfluid; }

static int check_finite(sph_world *w) {
    int n = w->n, first = n; /* the first bad particle, found in parallel */
#pragma omp parallel for schedule(static) num_threads(w->threads) reduction(min : first)
    for (int i = 0; i < n; i++) {
        if (w->kind[i] != SPH_FLUID) continue;
        if (!isfinite(w->x[i]) || !isfinite(w->y[i]) || !isfinite(w->u[i]) || !isfinite(w->v[i]) ||
            !isfinite(w->p[i]) || !(w->rho[i] > 0.0))
            first = i < first ? i : first;
    }
    if (first < n) {
        int i = first;
        return sph_world_fail(w,
                              "%s at fluid particle %d at step %ld (t = %g): "
                              "x = (%g, %g), u = (%g, %g), p = %g, rho = %g",
                              isfinite(w->rho[i]) && w->rho[i] <= 0.0 ? "non-positive density" : "NaN or infinity",
                              w->id[i], w->steps, w->t, w->x[i], w->y[i], w->u[i], w->v[i], w->p[i],
                              w->rho[i]);
    }
    for (int k = 0; k < w->nplates; k++)
        if (!isfinite(w->plates[k].vel) || !isfinite(w->plates[k].force))
            return sph_world_fail(w, "plate %d: non-finite velocity or force at step %ld (t = %g)",
                                  k + 1, w->steps, w->t);
    return 0;
}

/* Without shifting, a sample that stretches (the squeeze's extension) turns its lattice
 * into columns whose particles close in on each other, and the run fails later, far from the
 * cause (docs/limitations.md, "A squeeze needs shifting"); shifting from the start costs a
 * channel its accuracy (rows that slide past each other meander). Every 8th step of an
 * unshifted run looks for the closest fluid pair (the largest W_ij of the neighbour build).
 * With shifting = SPH_SHIFTING_AUTO a pair closer than 0.7 dx turns shifting on at
 * AUTO_SHIFT_A for the rest of the run (par.shifting, so a saved state carries it): a
 * flow that keeps the lattice (Couette, Poiseuille, the square at t = 0+) never gets there;
 * DESIGN.md's squeeze at dx = 1/40 does at t = 0.2 and its cavity at t = 0.18, both of which
 * fail without. With shifting = 0 a pair closer than dx / 2 is kept for a failure's message. */
#define AUTO_SHIFT_GAP 0.7
#define AUTO_SHIFT_A 20.0 /* the squeeze scripts' coefficient (method.md, "Particle shifting") */
static void watch_clustering(sph_world *w) {
    int autom = w->par.shifting == SPH_SHIFTING_AUTO;
    if (w->par.shifting > 0 || w->cluster_step >= 0 || w->steps % 8) return;
    double wh = sph_kernel_value((autom ? AUTO_SHIFT_GAP : 0.5) * w->dx, w->h), wmax = 0.0;
    int n = w->n;
#pragma omp parallel for schedule(static) num_threads(w->threads) reduction(max : wmax)
    for (int i = 0; i < n; i++) {
        if (w->kind[i] != SPH_FLUID) continue;
        for (int k = w->nb_start[i]; k < w->nb_mid[i]; k++)
            if (w->nb_w[k] > wmax) wmax = w->nb_w[k];
    }
    if (wmax > wh && autom) {
        w->par.shifting = AUTO_SHIFT_A;
        w->st.shifting_since = w->t;
    } else if (wmax > wh) {
        w->cluster_step = w->steps;
        w->cluster_t = w->t;
    }
}

/* Appends the clustering hint to the message of a step that failed (advance, or a time step
 * below the minimum); returns -1. */
static int with_hint(sph_world *w) {
    if (w->par.shifting > 0 || w->cluster_step < 0) return -1;
    size_t len = strlen(w->err);
    snprintf(w->err + len, sizeof w->err - len,
             "; shifting is off and fluid particles came within dx / 2 of each other from step %ld (t = %g) on: "
             "a flow that stretches the particle lattice (a squeeze, a cavity) needs particle shifting, "
             "sph.world{shifting = 20}, or the default, \"auto\" (docs/limitations.md)",
             w->cluster_step, w->cluster_t);
    return -1;
}

static void prepare(sph_world *w) {
    if (w->prepared) return;
    sph_plate_prepare(w);
    w->prepared = 1;
}

double sph_world_next_dt(sph_world *w) {
    prepare(w);
    return sph_timestep_compute(w);
}

static const char *const PHASE_NAMES[] = {"sort",     "neighbours",        "rheology",
                                          "viscous_assembly", "viscous_solve", "pressure_assembly",
                                          "pressure_solve", "correction", "shifting", "other", 0};

const char *const *sph_phase_names(void) { return PHASE_NAMES; }

void sph_lap(sph_world *w, int phase) {
    double now = omp_get_wtime();
    w->phase_time[phase] += now - w->lap;
    w->lap = now;
}


/* A dt the caller gives may be at most this many times the viscous time rho h^2 / max eta
 * of the fluid: beyond it no flow is resolved (and w:step(1e300) would take t to 2e300). */
#define SPH_DT_SPAN 1e6

int sph_world_step(sph_world *w, double dt) { return sph_world_step_given(w, dt, dt > 0); }

/* given: dt is the caller's, so it is held to SPH_DT_SPAN; a run's adaptive steps
 * (run.c), spread to land on an output time, are the engine's own and are not: at rest a
 * regularised Bingham law's viscosity tau0 m (8e5 at Bn = 1000, M = 800) makes the viscous
 * time far shorter than any step the flow needs. */
static int advance(sph_world *w, double dt, double t0);

int sph_world_step_given(sph_world *w, double dt, int given) {
    double t0 = omp_get_wtime();
    w->lap = t0;
    prepare(w);
    if (w->nfluid == 0) return sph_world_fail(w, "the world has no fluid: call fill first");
    /* a step that failed on a NaN leaves it in the particles; stepping on from there would
     * run the neighbour build off its arrays (a particle not among its own candidates) */
    if (check_finite(w)) {
        char why[sizeof w->err];
        memcpy(why, w->err, sizeof why);
        return sph_world_fail(w, "cannot step: %.900s (left by a failed step: load a saved state or build the world "
                                 "again)", why);
    }
    if (!isfinite(dt))
        return sph_world_fail(w, "dt must be a finite positive number (or <= 0: adaptive), got %g at step %ld (t = %g)",
                              dt, w->steps, w->t);
    if (dt > 0 && given) {
        double etamax = 0.0;
        for (int i = 0; i < w->n; i++)
            if (w->kind[i] == SPH_FLUID && w->visc[i] > etamax) etamax = w->visc[i];
        double bound = SPH_DT_SPAN * w->par.rho0 * w->h * w->h / etamax;
        if (etamax > 0 && dt > bound)
            return sph_world_fail(w,
                                  "dt = %g exceeds the bound %g (%g times the viscous time rho h^2 / max eta) "
                                  "at step %ld (t = %g)",
                                  dt, bound, SPH_DT_SPAN, w->steps, w->t);
    }
    if (!(dt > 0)) dt = sph_timestep_compute(w);
    if (!isfinite(dt) || dt < w->par.dt_min) {
        char why[512];
        sph_timestep_explain(w, why, sizeof why);
        sph_world_fail(w, "time step %g below the minimum %g at step %ld (t = %g): %s", dt, w->par.dt_min, w->steps,
                       w->t, why);
        return with_hint(w);
    }
    return advance(w, dt, t0) ? with_hint(w) : 0;
}

/* One step of length dt, the arguments checked (sph_world_step_given); t0: the wall clock
 * at the step's start. -1 with w->err set on a failure of the physics (a solver, a NaN, a
 * particle through a plate). */
static int advance(sph_world *w, double dt, double t0) {
    /* plates: the velocity each holds during this step */
    double vold[SPH_MAX_PLATES];
    for (int k = 0; k < w->nplates; k++) {
        sph_plate *pl = &w->plates[k];
        if (pl->mode == SPH_PLATE_FIXED) pl->vel = 0.0;
        vold[k] = pl->vel;
    }

    sph_lap(w, SPH_PHASE_OTHER);
    sph_boundary_wrap(w);
    if (sph_neighbours_sort(w) || sph_boundary_ghosts(w)) return -1;
    sph_lap(w, SPH_PHASE_SORT);
    if (sph_neighbours_build(w)) return -1;
    watch_clustering(w);
    sph_surface_mark(w);
    for (int k = 0; k < w->nplates; k++) memcpy(w->plates[k].rect0, w->plates[k].rect, sizeof w->plates[k].rect);
    sph_lap(w, SPH_PHASE_NEIGHBOURS);
    sph_viscous_rheology(w, dt);
    sph_lap(w, SPH_PHASE_RHEOLOGY);
    /* the solver's clocks, split between the viscous and the pressure solves */
    double su0 = w->solver.setup_time, so0 = w->solver.solve_time;
    long ns0 = w->solver.solves;
    if (w->par.viscosity == SPH_VISC_IMPLICIT) {
        if (sph_viscous_implicit(w, dt)) return -1;
    } else {
        sph_viscous_explicit(w, dt);
    }
    sph_lap(w, SPH_PHASE_VISC_ASSEMBLY); /* the plates' viscous forces */
    double su1 = w->solver.setup_time, so1 = w->solver.solve_time;
    w->st.visc_setup_time += su1 - su0;
    w->st.visc_solve_time += so1 - so0;
    long ns1 = w->solver.solves;
    w->st.visc_solves += ns1 - ns0;
    if (sph_pressure_solve(w, dt)) return -1;
    for (int k = 0; k < w->nplates; k++)
        if (w->plates[k].mode == SPH_PLATE_LOAD) w->plates[k].vel = w->plates[k].vel_new;
    sph_lap(w, SPH_PHASE_OTHER); /* plate pressure forces, loaded plates' velocities */
    sph_pressure_correct(w, dt);
    if (sph_density_correct(w, dt)) return -1;
    sph_lap(w, SPH_PHASE_CORRECTION);
    w->st.pressure_setup_time += w->solver.setup_time - su1;
    w->st.pressure_solve_time += w->solver.solve_time - so1;
    w->st.pressure_solves += w->solver.solves - ns1;
    if (w->par.shifting > 0) sph_shifting_apply(w, dt);
    sph_lap(w, SPH_PHASE_SHIFTING);
    for (int k = 0; k < w->nplates; k++) { /* the plates move; each sums the force it held (sph_plate_impulse) */
        sph_plate_move(w, k, 0.5 * dt * (vold[k] + w->plates[k].vel));
        w->plates[k].impulse += w->plates[k].force * dt;
    }

    w->t += dt;
    w->dt = dt;
    w->dt_prev = dt;
    w->steps++;
    w->st.visc_iterations_total += w->st.visc_iterations;
    if (w->st.max_density_error > w->st.peak_density_error)
        w->st.peak_density_error = w->st.max_density_error;
    sph_plate_contact(w);
    int bad = check_finite(w) || sph_plate_check_escape(w);
    sph_lap(w, SPH_PHASE_OTHER);
    w->wall_time += w->lap - t0;
    return bad ? -1 : 0;
}

void sph_world_stats(const sph_world *w, sph_stats *s) {
    *s = w->st;
    s->correction_share = w->st.motion_sq > 0.0 ? sqrt(w->st.correction_sq / w->st.motion_sq) : 0.0;
    s->fluid = w->nfluid;
    s->particles = w->n;
    s->wall = w->n - w->nfluid;
    s->ghosts = w->ng;
    double ke = 0, area = 0, umax = 0, etamax = 0;
    int yielded = 0;
    for (int i = 0; i < w->n; i++) {
        if (w->kind[i] != SPH_FLUID) continue;
        double s2 = w->u[i] * w->u[i] + w->v[i] * w->v[i];
        ke += 0.5 * w->m[i] * s2;
        area += w->m[i] / w->rho[i];
        if (s2 > umax) umax = s2;
        if (w->eta[i] > etamax) etamax = w->eta[i];
        yielded += sph_particle_yielded(w, i);
    }
    s->kinetic_energy = ke;
    s->area = area;
    s->max_speed = sqrt(umax);
    s->max_eta = etamax;
    s->yielded = yielded;
    long pairs = w->n > 0 && w->nb_n == w->n ? w->nb_start[w->n] : 0; /* no list yet: 0 */
    int rows = 0;
    for (int i = 0; i < w->n; i++) rows += w->active[i];
    s->neighbours_mean = rows ? (double)pairs / rows : 0.0;
    s->wall_time = w->wall_time;
    memcpy(s->phase_time, w->phase_time, sizeof s->phase_time);
    s->steps = w->steps;
}

static const char *const FIELD_NAMES[] = {"x",     "y",        "u",      "v",       "p",
                                          "rho",   "eta",      "gammadot", "stress", "yielded",
                                          "speed", "surface",  "material", "id",    "rho_sum", "divr", 0};

const char *const *sph_world_field_names(void) { return FIELD_NAMES; }

/* Kernel-summation density sum_j m_j W_ij (self, walls and images included) at the current
 * positions, over the neighbour list of the last step (the caller checks that it was built
 * for these particles): a check on the continuity density, meaningful where the support is
 * full (away from the free surface). */
static double density_sum(const sph_world *w, int i) {
    double s = w->m[i] * sph_kernel_value(0.0, w->h);
    for (int k = w->nb_start[i]; k < w->nb_start[i + 1]; k++) {
        int j = w->nb_j[k];
        s += w->m[j] * sph_kernel_value(hypot(w->x[i] - w->x[j], w->y[i] - w->y[j]), w->h);
    }
    return s;
}

int sph_world_field(const sph_world *w, const char *name, double *out) {
    int f = -1;
    for (int k = 0; FIELD_NAMES[k]; k++)
        if (!strcmp(name, FIELD_NAMES[k])) f = k;
    if (f < 0) return -1;
    if (f == 14 && w->n > 0 && w->nb_n != w->n) return -2; /* rho_sum: no list for these particles */
    int c = 0;
    for (int i = 0; i < w->n; i++) {
        if (w->kind[i] != SPH_FLUID) continue;
        double v = 0;
        switch (f) {
        case 0: v = w->x[i]; break;
        case 1: v = w->y[i]; break;
        case 2: v = w->u[i]; break;
        case 3: v = w->v[i]; break;
        case 4: v = w->p[i]; break;
        case 5: v = w->rho[i]; break;
        case 6: v = w->eta[i]; break;
        case 7: v = w->gd[i]; break;
        case 8: v = sph_particle_stress(w, i); break;
        case 9: v = sph_particle_yielded(w, i); break;
        case 10: v = hypot(w->u[i], w->v[i]); break;
        case 11: v = w->surf[i]; break;
        case 12: v = w->mat[i] + 1; break;
        case 13: v = w->id[i] + 1; break;
        case 14: v = density_sum(w, i); break;
        case 15: v = w->divr[i]; break;
        }
        out[c++] = v;
    }
    return c;
}

int sph_world_set_velocity(sph_world *w, const double *u, const double *v) {
    int c = 0;
    for (int i = 0; i < w->n; i++) {
        if (w->kind[i] != SPH_FLUID) continue;
        if ((u && !isfinite(u[c])) || (v && !isfinite(v[c])))
            return sph_world_fail(w, "velocity of fluid particle %d is not finite", c + 1);
        c++;
    }
    c = 0;
    for (int i = 0; i < w->n; i++) {
        if (w->kind[i] != SPH_FLUID) continue;
        if (u) w->u[i] = u[c];
        if (v) w->v[i] = v[c];
        c++;
    }
    return 0;
}
