/* Saving and loading a world's state (w:save, sph.load): the parameters, materials,
 * plates, clock and statistics (with the density correction's fallback wait), and every
 * real particle's persistent fields, in the particles' current order. The file is for the
 * same build (raw structs, checked by a header of sizes): a restart on this machine, not an
 * exchange format. Ghosts, neighbour
 * lists and solver hierarchies are rebuilt by the next step, so a continued run agrees
 * with the uninterrupted one to the solvers' tolerances, not to the last bit (the pressure
 * multigrid hierarchy is reused for up to 20 steps in a run and rebuilt after a load). */
#include "internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define STATE_MAGIC "SPHSTAT5" /* 2: the density fallback's wait, 3: the later passes' wait, 4: the
                                  * last later pass stalled, 5: the last first pass's form (density.c) */

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
#define STATE_DOUBLES(w) {w->x, w->y, w->u, w->v, w->ax, w->ay, w->p, w->rho, w->m, w->phi, w->eta, w->gd}
#define STATE_INTS(w) {w->kind, w->mat, w->id}

int sph_world_save(sph_world *w, const char *file) {
    FILE *f = fopen(file, "wb");
    if (!f) return sph_world_fail(w, "cannot open '%s' for writing", file);
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
    long wait[6] = {w->fallback_after, w->fallback_wait, w->passes_after, w->passes_wait, w->later_stalled,
                    w->first_difference};
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
    if (fclose(f) != 0) ok = 0;
    if (!ok) return sph_world_fail(w, "writing '%s' failed", file);
    return 0;
}

sph_world *sph_world_load(const char *file, char *err, size_t errlen) {
    FILE *f = fopen(file, "rb");
    if (!f) {
        snprintf(err, errlen, "cannot open '%s'", file);
        return 0;
    }
    state_header h, want;
    header(&want);
    sph_params par;
    if (fread(&h, sizeof h, 1, f) != 1 || memcmp(&h, &want, sizeof h) != 0) {
        snprintf(err, errlen, "'%s' is not a state saved by this build of sph (w:save)", file);
        fclose(f);
        return 0;
    }
    if (fread(&par, sizeof par, 1, f) != 1) {
        snprintf(err, errlen, "'%s' is truncated", file);
        fclose(f);
        return 0;
    }
    sph_world *w = sph_world_new(&par, err, errlen);
    if (!w) {
        fclose(f);
        return 0;
    }
    w->par = par; /* as saved (sph_world_new fills in h and dt_min the same way) */
    int ints[3];
    double dbl[4];
    int ok = fread(&w->nmats, sizeof w->nmats, 1, f) == 1;
    ok = ok && fread(w->mats, sizeof w->mats[0], SPH_MAX_MATERIALS, f) == SPH_MAX_MATERIALS;
    ok = ok && fread(&w->nplates, sizeof w->nplates, 1, f) == 1;
    ok = ok && fread(w->plates, sizeof w->plates[0], SPH_MAX_PLATES, f) == SPH_MAX_PLATES;
    ok = ok && fread(ints, sizeof ints, 1, f) == 1 && fread(dbl, sizeof dbl, 1, f) == 1;
    ok = ok && fread(&w->steps, sizeof w->steps, 1, f) == 1;
    long wait[6];
    ok = ok && fread(wait, sizeof wait, 1, f) == 1 && wait[1] >= 0 && wait[1] <= 1L << 20 && wait[3] >= 0 &&
         wait[3] <= 1L << 20 && (wait[4] == 0 || wait[4] == 1) && (wait[5] == 0 || wait[5] == 1);
    if (ok) {
        w->fallback_after = wait[0];
        w->fallback_wait = (int)wait[1];
        w->passes_after = wait[2];
        w->passes_wait = (int)wait[3];
        w->later_stalled = (int)wait[4];
        w->first_difference = (int)wait[5];
    }
    ok = ok && fread(&w->st, sizeof w->st, 1, f) == 1;
    ok = ok && fread(w->phase_time, sizeof w->phase_time, 1, f) == 1;
    ok = ok && ints[0] >= 0 && ints[1] >= 0 && ints[1] <= ints[0] && w->nmats >= 0 &&
         w->nmats <= SPH_MAX_MATERIALS && w->nplates >= 0 && w->nplates <= SPH_MAX_PLATES;
    if (ok && ints[0] > 0 && sph_world_reserve(w, ints[0])) ok = 0;
    if (ok) {
        w->n = ints[0];
        w->nfluid = ints[1];
        w->next_id = ints[2];
        w->t = dbl[0];
        w->dt = dbl[1];
        w->dt_prev = dbl[2];
        w->wall_time = dbl[3];
        size_t n = (size_t)w->n;
        double *d[] = STATE_DOUBLES(w);
        for (size_t k = 0; k < sizeof d / sizeof *d; k++) ok = ok && fread(d[k], sizeof(double), n, f) == n;
        for (int k = 0; k < SPH_MAX_LOADED; k++) ok = ok && fread(w->psens[k], sizeof(double), n, f) == n;
        int *iv[] = STATE_INTS(w);
        for (size_t k = 0; k < sizeof iv / sizeof *iv; k++) ok = ok && fread(iv[k], sizeof(int), n, f) == n;
        ok = ok && fread(w->surf, 1, n, f) == n;
        for (size_t i = 0; ok && i < n; i++) /* kinds and fluid materials in range */
            ok = w->kind[i] == SPH_FLUID ? w->mat[i] >= 0 && w->mat[i] < w->nmats
                                         : w->kind[i] >= 0 && w->kind[i] < w->nplates;
    }
    fclose(f);
    if (!ok) {
        snprintf(err, errlen, "'%s' is truncated or damaged", file);
        sph_world_free(w);
        return 0;
    }
    w->prepared = 0;
    return w;
}
