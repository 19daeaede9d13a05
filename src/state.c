/* Saving and loading a world's state (w:save, sph.load): the parameters, materials,
 * plates, clock and statistics (with the density correction's fallback wait), every
 * real particle's persistent fields, in the particles' current order, and what the solves
 * carry from one step to the next: their first guesses (the last two solves' changes) and
 * the multigrid hierarchies kept for reuse with their counters (amg.c, "Saving a
 * hierarchy"). The file is for the same build (raw structs, checked by a header of
 * sizes): a restart on this machine, not an exchange format. Ghosts and neighbour lists
 * are rebuilt by the next step; a continued run is the uninterrupted one bit for bit (on
 * the same thread count), which is why the solves' state is saved: without it a continued
 * run differs (by up to 5e-5 in a loaded plate's force). */
#include "internal.h"
#include "atomic.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define STATE_MAGIC "SPHSTAT;" /* the format's version: a file of another is refused */

typedef struct {
    char magic[8];
    unsigned sizes[5]; /* sph_params, sph_material, sph_plate, sph_stats, SPH_MAX_LOADED */
} state_header;

static void header(state_header *h) {
    memset(h, 0, sizeof *h);
    memcpy(h->magic, STATE_MAGIC, 8);
    h->sizes[0] = (unsigned)sizeof(sph_params);
    h->sizes[1] = (unsigned)sizeof(sph_material);
    h->sizes[2] = (unsigned)sizeof(sph_plate);
    h->sizes[3] = (unsigned)sizeof(sph_stats);
    h->sizes[4] = SPH_MAX_LOADED;
}

/* the per-particle doubles and ints that carry over from one step to the next */
#define STATE_DOUBLES(w) {w->x, w->y, w->u, w->v, w->ax, w->ay, w->p, w->rho, w->m, w->phi, w->eta, w->gd, w->lamxx, w->lamxy, w->tau}
#define STATE_INTS(w) {w->kind, w->mat, w->id}

/* The solves' state between steps (since SPHSTAT6): whether the plates' faces are set
 * (sph_plate_prepare), the three first guesses (their changes per particle, as permuted
 * with the particles), the reuse count and the two hierarchies with the matrix each was
 * built for (0 none, 1 the pressure matrix, 2 the viscous one). */
static const sph_guess *guess_of(const sph_world *w, int k) { return k == 0 ? &w->gu : k == 1 ? &w->gv : &w->gp; }

static int matrix_tag(const sph_world *w, const void *m) { return m == &w->A ? 1 : m == &w->V ? 2 : 0; }

static int save_solver(sph_world *w, FILE *f) {
    size_t n = (size_t)w->n;
    int ok = fwrite(&w->prepared, sizeof w->prepared, 1, f) == 1;
    for (int k = 0; k < 3; k++) {
        const sph_guess *g = guess_of(w, k);
        double dts[2] = {g->dt, g->dt1};
        int ns[2] = {g->n, g->n1};
        ok = ok && fwrite(dts, sizeof dts, 1, f) == 1 && fwrite(ns, sizeof ns, 1, f) == 1;
        if (n > 0) ok = ok && fwrite(g->d, sizeof(double), n, f) == n && fwrite(g->d1, sizeof(double), n, f) == n;
    }
    const sph_solver *s = &w->solver;
    int tags[2] = {matrix_tag(w, s->amg.built_for), matrix_tag(w, s->amg2.built_for)};
    ok = ok && fwrite(&s->reuses, sizeof s->reuses, 1, f) == 1 && fwrite(tags, sizeof tags, 1, f) == 1;
    ok = ok && sph_amg_write(&s->amg, f) == 0 && sph_amg_write(&s->amg2, f) == 0;
    return ok ? 0 : -1;
}

int sph_world_save(sph_world *w, const char *file) {
    sph_atomic_file af; /* a failed save leaves an earlier state at that path as it was */
    char why[512];
    if (sph_atomic_open(&af, file, why, sizeof why)) return sph_world_fail(w, "%s", why);
    FILE *f = af.fp;
    errno = 0;
    state_header h;
    header(&h);
    int ok = fwrite(&h, sizeof h, 1, f) == 1;
    ok = ok && fwrite(&w->par, sizeof w->par, 1, f) == 1;
    ok = ok && fwrite(&w->nmats, sizeof w->nmats, 1, f) == 1;
    ok = ok && fwrite(w->mats, sizeof w->mats[0], SPH_MAX_MATERIALS, f) == SPH_MAX_MATERIALS;
    ok = ok && fwrite(&w->nplates, sizeof w->nplates, 1, f) == 1;
    ok = ok && fwrite(w->plates, sizeof w->plates[0], SPH_MAX_PLATES, f) == SPH_MAX_PLATES;
    int ints[3] = {w->n, w->nfluid, w->next_id};
    double dbl[4] = {w->t, w->dt, w->dt_prev, w->wall_time};
    ok = ok && fwrite(ints, sizeof ints, 1, f) == 1 && fwrite(dbl, sizeof dbl, 1, f) == 1;
    ok = ok && fwrite(&w->steps, sizeof w->steps, 1, f) == 1;
    long wait[4] = {w->fallback_after, w->fallback_wait, w->later_stalled, w->first_difference};
    ok = ok && fwrite(wait, sizeof wait, 1, f) == 1;
    ok = ok && fwrite(&w->st, sizeof w->st, 1, f) == 1;
    ok = ok && fwrite(w->phase_time, sizeof w->phase_time, 1, f) == 1;
    size_t n = (size_t)w->n;
    if (n > 0) {
        double *d[] = STATE_DOUBLES(w);
        for (size_t k = 0; k < sizeof d / sizeof *d; k++) ok = ok && fwrite(d[k], sizeof(double), n, f) == n;
        for (int k = 0; k < SPH_MAX_LOADED; k++) ok = ok && fwrite(w->psens[k], sizeof(double), n, f) == n;
        int *iv[] = STATE_INTS(w);
        for (size_t k = 0; k < sizeof iv / sizeof *iv; k++) ok = ok && fwrite(iv[k], sizeof(int), n, f) == n;
        ok = ok && fwrite(w->surf, 1, n, f) == n;
    }
    ok = ok && save_solver(w, f) == 0;
    if (!ok) {
        int e = errno;
        sph_atomic_abort(&af);
        return sph_world_fail(w, "cannot write '%s': %s", file, strerror(e ? e : EIO));
    }
    if (sph_atomic_commit(&af, why, sizeof why)) return sph_world_fail(w, "%s", why);
    return 0;
}

/* sph_world_load reads through this: the first failure (short read or a bad value) is
 * kept in err and every later step is skipped, so the loader reads as a straight line. */
typedef struct {
    FILE *f;
    const char *file;
    char *err;
    size_t errlen;
    int bad;
} reader;

static int rd(reader *r, void *p, size_t size, size_t count, const char *what) {
    if (r->bad) return 0;
    if (fread(p, size, count, r->f) != count) {
        snprintf(r->err, r->errlen, "'%s' is truncated (reading %s)", r->file, what);
        r->bad = 1;
    }
    return !r->bad;
}

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static int damaged(reader *r, const char *fmt, ...) {
    if (r->bad) return -1;
    int k = snprintf(r->err, r->errlen, "'%s' is damaged: ", r->file);
    va_list ap;
    va_start(ap, fmt);
    if (k >= 0 && (size_t)k < r->errlen) vsnprintf(r->err + k, r->errlen - (size_t)k, fmt, ap);
    va_end(ap);
    r->bad = 1;
    return -1;
}

static int finite_nonneg(double v) { return isfinite(v) && v >= 0; }

/* A saved plate as the step needs it: everything is read as saved, so each field that
 * indexes, divides or moves something is checked. */
static int check_plate(reader *r, int k, const sph_plate *pl) {
    for (int q = 0; q < 4; q++)
        if (!isfinite(pl->rect[q]) || !isfinite(pl->rect0[q]))
            return damaged(r, "plate %d: rect[%d] = %g is not finite", k + 1, q + 1,
                           isfinite(pl->rect[q]) ? pl->rect0[q] : pl->rect[q]);
    if (!(pl->rect[2] > pl->rect[0] && pl->rect[3] > pl->rect[1]))
        return damaged(r, "plate %d: rect {%g, %g, %g, %g} is inverted", k + 1, pl->rect[0], pl->rect[1],
                       pl->rect[2], pl->rect[3]);
    if (pl->axis < -1 || pl->axis > 1) return damaged(r, "plate %d: axis %d is not -1, 0 or 1", k + 1, pl->axis);
    if (pl->mode != SPH_PLATE_FIXED && pl->mode != SPH_PLATE_VELOCITY && pl->mode != SPH_PLATE_LOAD)
        return damaged(r, "plate %d: mode %d is not fixed (0), velocity (1) or load (2)", k + 1, (int)pl->mode);
    if (pl->mode != SPH_PLATE_FIXED && pl->axis < 0)
        return damaged(r, "plate %d: mode %d on a fixed plate (axis -1)", k + 1, (int)pl->mode);
    if (!(pl->mass > 0 && isfinite(pl->mass)))
        return damaged(r, "plate %d: mass %g is not a positive finite number", k + 1, pl->mass);
    const double v[] = {pl->vel, pl->vel_new, pl->load, pl->force, pl->force_visc, pl->slide[0], pl->slide[1],
                        pl->impulse};
    static const char *const names[] = {"velocity", "new velocity", "load", "force", "viscous force", "slide x",
                                        "slide y", "impulse"};
    for (int q = 0; q < 8; q++)
        if (!isfinite(v[q])) return damaged(r, "plate %d: %s %g is not finite", k + 1, names[q], v[q]);
    if (pl->count < 0 || (pl->doubled != 0 && pl->doubled != 1) || (pl->mass_set != 0 && pl->mass_set != 1) ||
        pl->face_side < -1 || pl->face_side > 1)
        return damaged(r, "plate %d: count %d, doubled %d, mass_set %d or face_side %d out of range", k + 1,
                       pl->count, pl->doubled, pl->mass_set, pl->face_side);
    return 0;
}

/* The particles as read: kinds and materials index arrays, the doubles enter every sum
 * (make_grid's min / max scan skips a NaN, so it must not get that far). */
static int check_particles(reader *r, sph_world *w) {
    static const char *const dn[] = {"x",   "y",   "u",   "v",        "ax",   "ay",   "p",
                                     "rho", "m",   "phi", "eta", "gammadot", "stress xx", "stress xy"};
    double *d[] = STATE_DOUBLES(w);
    int fluid = 0;
    for (int i = 0; i < w->n && !r->bad; i++) {
        int kind = w->kind[i];
        if (kind == SPH_FLUID) {
            fluid++;
            if (w->mat[i] < 0 || w->mat[i] >= w->nmats)
                return damaged(r, "particle %d: material %d, the world has %d", i + 1, w->mat[i] + 1, w->nmats);
        } else if (kind < 0 || kind >= w->nplates) {
            return damaged(r, "particle %d: kind %d is neither fluid (-1) nor a plate of the %d", i + 1, kind,
                           w->nplates);
        }
        if (w->id[i] < 0 || w->id[i] >= w->next_id)
            return damaged(r, "particle %d: id %d not in [0, %d)", i + 1, w->id[i], w->next_id);
        for (size_t k = 0; k < sizeof d / sizeof *d; k++)
            if (!isfinite(d[k][i])) return damaged(r, "particle %d: %s = %g is not finite", i + 1, dn[k], d[k][i]);
        for (int k = 0; k < SPH_MAX_LOADED; k++)
            if (!isfinite(w->psens[k][i]))
                return damaged(r, "particle %d: load sensitivity %d = %g is not finite", i + 1, k + 1, w->psens[k][i]);
        if (!(w->rho[i] > 0) || !(w->m[i] > 0))
            return damaged(r, "particle %d: rho = %g and m = %g must be positive", i + 1, w->rho[i], w->m[i]);
        if (w->surf[i] > 1) return damaged(r, "particle %d: surface flag %d is not 0 or 1", i + 1, w->surf[i]);
    }
    if (!r->bad && fluid != w->nfluid)
        return damaged(r, "the fluid count %d disagrees with the %d fluid particles", w->nfluid, fluid);
    return r->bad ? -1 : 0;
}

/* The solves' state as save_solver wrote it, checked. */
static int load_solver(reader *r, sph_world *w) {
    size_t n = (size_t)w->n;
    int prepared;
    if (rd(r, &prepared, sizeof prepared, 1, "the plates' preparation") && prepared != 0 && prepared != 1)
        return damaged(r, "plate preparation flag %d is not 0 or 1", prepared);
    static const char *const gn[] = {"viscous u", "viscous v", "pressure"};
    for (int k = 0; k < 3 && !r->bad; k++) {
        sph_guess *g = (sph_guess *)guess_of(w, k);
        double dts[2];
        int ns[2];
        rd(r, dts, sizeof dts, 1, "the first guesses");
        rd(r, ns, sizeof ns, 1, "the first guesses");
        if (n > 0) {
            rd(r, g->d, sizeof(double), n, "the first guesses");
            rd(r, g->d1, sizeof(double), n, "the first guesses");
        }
        if (r->bad) break;
        if (!finite_nonneg(dts[0]) || !finite_nonneg(dts[1]) || ns[0] < 0 || ns[0] > SPH_MAX_PARTICLES || ns[1] < 0 ||
            ns[1] > SPH_MAX_PARTICLES)
            return damaged(r, "%s first guess: dt %g, %g or counts %d, %d out of range", gn[k], dts[0], dts[1], ns[0],
                           ns[1]);
        for (size_t i = 0; i < n; i++)
            if (!isfinite(g->d[i]) || !isfinite(g->d1[i]))
                return damaged(r, "%s first guess: particle %zu's change is not finite", gn[k], i + 1);
        g->dt = dts[0];
        g->dt1 = dts[1];
        g->n = ns[0];
        g->n1 = ns[1];
    }
    sph_solver *s = &w->solver;
    int tags[2];
    if (rd(r, &s->reuses, sizeof s->reuses, 1, "the solver's reuse count") && s->reuses < 0)
        return damaged(r, "solver reuse count %ld is negative", s->reuses);
    if (rd(r, tags, sizeof tags, 1, "the hierarchies' matrices") &&
        (tags[0] < 0 || tags[0] > 2 || tags[1] < 0 || tags[1] > 2 || (tags[0] && tags[0] == tags[1])))
        return damaged(r, "hierarchy matrices {%d, %d} out of range", tags[0], tags[1]);
    sph_amg *gs[2] = {&s->amg, &s->amg2};
    for (int k = 0; k < 2 && !r->bad; k++) {
        char why[256] = "";
        int rc = sph_amg_read(gs[k], r->f, w->next_id, w->threads, why, sizeof why);
        if (rc > 0) {
            snprintf(r->err, r->errlen, "'%s' is truncated (reading multigrid hierarchy %d)", r->file, k + 1);
            r->bad = 1;
            return -1;
        }
        if (rc < 0) return damaged(r, "multigrid hierarchy %d: %s", k + 1, why);
        gs[k]->built_for = tags[k] == 1 ? (const void *)&w->A : tags[k] == 2 ? (const void *)&w->V : 0;
    }
    if (!r->bad) w->prepared = prepared;
    return r->bad ? -1 : 0;
}

sph_world *sph_world_load(const char *file, char *err, size_t errlen) {
    reader r = {fopen(file, "rb"), file, err, errlen, 0};
    if (!r.f) {
        snprintf(err, errlen, "cannot open '%s'", file);
        return 0;
    }
    state_header h, want;
    header(&want);
    sph_params par;
    int got = fread(&h, sizeof h, 1, r.f) == 1;
    if (got && memcmp(h.magic, "SPHSTAT", 7) == 0 && memcmp(h.magic, want.magic, 8) != 0) {
        snprintf(err, errlen,
                 "'%s' was written by %s sph (%.8s; this build reads %.8s): load it with the build that saved it",
                 file, h.magic[7] < want.magic[7] ? "an older" : "a newer", h.magic, want.magic);
        fclose(r.f);
        return 0;
    }
    if (!got || memcmp(&h, &want, sizeof h) != 0) {
        snprintf(err, errlen, "'%s' is not a state saved by this build of sph (w:save)", file);
        fclose(r.f);
        return 0;
    }
    if (!rd(&r, &par, sizeof par, 1, "the parameters")) {
        fclose(r.f);
        return 0;
    }
    if (par.threads < 0 || par.threads > SPH_MAX_THREADS) { /* named with its value, unlike check_params */
        damaged(&r, "parameters: threads = %d: must be 1..%d (0: all cores)", par.threads, SPH_MAX_THREADS);
        fclose(r.f);
        return 0;
    }
    char why[256];
    sph_world *w = sph_world_new(&par, why, sizeof why); /* checks every parameter */
    if (!w) {
        damaged(&r, "parameters: %s", why);
        fclose(r.f);
        return 0;
    }
    w->par = par; /* as saved (sph_world_new fills in dt_min the same way) */
    if (!(finite_nonneg(par.dt_min) && finite_nonneg(par.dt_max)))
        damaged(&r, "parameters: dt_min %g and dt_max %g must be finite and >= 0", par.dt_min, par.dt_max);
    if (rd(&r, &w->nmats, sizeof w->nmats, 1, "the material count") && (w->nmats < 0 || w->nmats > SPH_MAX_MATERIALS))
        damaged(&r, "material count %d not in [0, %d]", w->nmats, SPH_MAX_MATERIALS);
    rd(&r, w->mats, sizeof w->mats[0], SPH_MAX_MATERIALS, "the materials");
    for (int k = 0; k < w->nmats && !r.bad; k++) {
        const sph_material *m = &w->mats[k];
        if (m->model != SPH_NEWTONIAN && m->model != SPH_BINGHAM && m->model != SPH_HERSCHEL_BULKLEY)
            damaged(&r, "material %d: model %d is not newtonian (0), bingham (1) or herschel_bulkley (2)", k + 1,
                    (int)m->model);
        else if (sph_rheology_check(m))
            damaged(&r, "material %d: %s", k + 1, sph_rheology_check(m));
    }
    if (rd(&r, &w->nplates, sizeof w->nplates, 1, "the plate count") && (w->nplates < 0 || w->nplates > SPH_MAX_PLATES))
        damaged(&r, "plate count %d not in [0, %d]", w->nplates, SPH_MAX_PLATES);
    rd(&r, w->plates, sizeof w->plates[0], SPH_MAX_PLATES, "the plates");
    for (int k = 0; k < w->nplates && !r.bad; k++) check_plate(&r, k, &w->plates[k]);
    int ints[3];
    double dbl[4];
    if (rd(&r, ints, sizeof ints, 1, "the particle counts")) {
        if (ints[0] < 0 || ints[0] > SPH_MAX_PARTICLES)
            damaged(&r, "particle count %d not in [0, %d]", ints[0], SPH_MAX_PARTICLES);
        else if (ints[1] < 0 || ints[1] > ints[0])
            damaged(&r, "fluid count %d not in [0, %d] (the particle count)", ints[1], ints[0]);
        else if (ints[2] < ints[0])
            damaged(&r, "next particle id %d below the particle count %d", ints[2], ints[0]);
    }
    if (rd(&r, dbl, sizeof dbl, 1, "the clock")) {
        static const char *const names[] = {"t", "dt", "the previous dt", "wall_time"};
        for (int q = 0; q < 4; q++)
            if (!finite_nonneg(dbl[q])) {
                damaged(&r, "%s = %g must be finite and >= 0", names[q], dbl[q]);
                break;
            }
    }
    if (rd(&r, &w->steps, sizeof w->steps, 1, "the step count") && w->steps < 0)
        damaged(&r, "step count %ld is negative", w->steps);
    long wait[4];
    if (rd(&r, wait, sizeof wait, 1, "the density correction's waits") &&
        !(wait[1] >= 0 && wait[1] <= 1L << 20 && (wait[2] == 0 || wait[2] == 1) && (wait[3] == 0 || wait[3] == 1)))
        damaged(&r, "density correction waits {%ld, %ld, %ld, %ld} out of range", wait[0], wait[1], wait[2], wait[3]);
    if (!r.bad) {
        w->fallback_after = wait[0];
        w->fallback_wait = (int)wait[1];
        w->later_stalled = (int)wait[2];
        w->first_difference = (int)wait[3];
    }
    rd(&r, &w->st, sizeof w->st, 1, "the statistics");
    rd(&r, w->phase_time, sizeof w->phase_time, 1, "the phase times");
    if (!r.bad && ints[0] > 0 && sph_world_reserve(w, ints[0])) {
        snprintf(err, errlen, "'%s': %s", file, sph_world_error(w));
        r.bad = 1;
    }
    if (!r.bad) {
        w->n = ints[0];
        w->nfluid = ints[1];
        w->next_id = ints[2];
        w->t = dbl[0];
        w->dt = dbl[1];
        w->dt_prev = dbl[2];
        w->wall_time = dbl[3];
        size_t n = (size_t)w->n;
        double *d[] = STATE_DOUBLES(w);
        for (size_t k = 0; k < sizeof d / sizeof *d; k++) rd(&r, d[k], sizeof(double), n, "the particles' doubles");
        for (int k = 0; k < SPH_MAX_LOADED; k++) rd(&r, w->psens[k], sizeof(double), n, "the load sensitivities");
        int *iv[] = STATE_INTS(w);
        for (size_t k = 0; k < sizeof iv / sizeof *iv; k++) rd(&r, iv[k], sizeof(int), n, "the particles' ints");
        rd(&r, w->surf, 1, n, "the surface flags");
        if (!r.bad) check_particles(&r, w);
    }
    if (!r.bad) load_solver(&r, w);
    if (!r.bad && fgetc(r.f) != EOF) damaged(&r, "data after the end of the state");
    fclose(r.f);
    if (r.bad) {
        sph_world_free(w);
        return 0;
    }
    return w;
}
