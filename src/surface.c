/* Free-surface detection: which fluid particles hold the traction-free surface
 * condition (the pressure's Dirichlet rows, viscous.c's surface stress). */
#include "internal.h"

#include <math.h>

/* Surface flags: position divergence below the threshold (about 2 inside, 1 on a
 * straight free surface), with hysteresis: a surface particle leaves the surface only once
 * its divergence is 0.1 above the threshold, so a particle hovering at the threshold does
 * not switch its Dirichlet condition on and off from step to step (each switch jolts the
 * plate force). surface = 0 turns both tests off (a closed domain).
 * The divergence misses some edge particles that have a wall in their support (the contact
 * line, where the sample meets a plate: divergences 1.6-2.0). So a particle not in the bulk
 * (div r < 1.85; to enter, 1.84) is also on the surface when nothing lies in front of it (Marrone et al.
 * 2010, simplified): no particle, fluid, wall or image, within a radius (SURFACE_CONE_FLUID
 * and the others below) inside the 30-degree cone around its outward normal
 * n = -sum_j V_j grad_i W_ij / |...|. The normal leans away from the wall, so a wider cone
 * (45 degrees) sees the edge's own neighbours next to a plate and misses the particle.
 * The bulk bound has a hysteresis of its own, 0.01: a stretched film's interior particle
 * can sit at div r 1.848 for hundreds of steps with an empty cone, and round-off (an -O1
 * build against -O2) then decides whether it is taken for surface. */
/* The cone's normal must mean something: |sum_j V_j grad_i W_ij| h at least
 * SURFACE_NORMAL_MIN. Inside a sample stretched by the squeeze the particles stand in
 * columns (rows 0.65 dx apart, columns 1.55 dx), div r drops to 1.82-1.85 and the kernel
 * sum's gradient nearly vanishes (|n| h 0.001-0.014): the normal is noise, and a cone along
 * a row finds the next column beyond the radius, so particles inside the sample would be
 * taken for free surface. On the outlines of the stability suite's cases |n| h is at least
 * 0.04, and at 0.03 they miss no edge particle and flag none inside. With the thin-film
 * options some flags inside a stretched film remain (particles whose nearest neighbour in
 * the cone is 1.5-2 dx away, |n| h 0.03-0.12). */
#define SURFACE_NORMAL_MIN 0.03
#define BULK_HYSTERESIS 0.01
/* The cone's radius: 2 dx for fluid particles (and images), 1.75 dx for them next to a wall
 * (a wall within 2 dx), 1.7 dx for wall particles, and a fluid particle of div r < 1
 * (spray: a droplet thrown off, few neighbours) does not close the cone. The radii are
 * clear of the 1.6 dx opening that the stability suite's surface check
 * (lua/sph/stability.lua) takes for a true surface (a plate as its wall row within 1.5 dx),
 * so round-off does not decide the particles that stand between the two; a vacancy inside
 * the sample is closed by particles 1.8 dx off, inside the fluid radius (Marrone et al.'s
 * scan reaches 2h and more along the normal). Walls at 1.5 dx, or spray counted, miss an edge particle with a spray particle
 * 1.6 dx in front of it; 2 dx next to a wall too flags contact-line particles whose density
 * error then shrinks dt (a quarter more steps on the headline squeeze). */
#define SURFACE_CONE_FLUID 2.0
#define SURFACE_CONE_FLUID_WALL 1.75
#define SURFACE_CONE_WALL 1.7
#define SURFACE_SPRAY_DIVR 1.0

static int cone_empty(const sph_world *w, int i) {
    double nx = 0.0, ny = 0.0;
    for (int k = w->nb_start[i]; k < w->nb_start[i + 1]; k++) {
        int j = w->nb_j[k]; /* w->vol: V_j from this step's neighbour build */
        nx -= w->vol[j] * w->nb_gx[k];
        ny -= w->vol[j] * w->nb_gy[k];
    }
    double nn = hypot(nx, ny);
    if (!(nn * w->h >= SURFACE_NORMAL_MIN)) return 0;
    nx /= nn;
    ny /= nn;
    /* one pass: a wall within 2 dx (it sets the fluid radius), the nearest wall and the
     * nearest fluid particle (spray left out) within 30 degrees of n */
    double d2 = w->dx * w->dx, fluid2 = INFINITY, wall2 = INFINITY;
    int nearwall = 0;
    for (int k = w->nb_start[i]; k < w->nb_start[i + 1]; k++) {
        int j = w->nb_j[k], fl = w->kind[j] == SPH_FLUID;
        double dx = w->x[j] - w->x[i], dy = w->y[j] - w->y[i], r2 = dx * dx + dy * dy;
        if (!fl && r2 < 4.0 * d2) nearwall = 1;
        double along = dx * nx + dy * ny;
        if (!(along > 0.0 && 4.0 * along * along > 3.0 * r2)) continue; /* within 30 degrees of n */
        if (!fl) wall2 = fmin(wall2, r2);
        else if (w->divr[w->src[j]] >= SURFACE_SPRAY_DIVR) fluid2 = fmin(fluid2, r2);
    }
    double rf = nearwall ? SURFACE_CONE_FLUID_WALL : SURFACE_CONE_FLUID;
    return fluid2 >= rf * rf * d2 && wall2 >= SURFACE_CONE_WALL * SURFACE_CONE_WALL * d2;
}

void sph_surface_mark(sph_world *w) {
    int ns = 0, n = w->n;
    double on = w->par.surface_div, off = on + 0.1, bulk = 1.85;
#pragma omp parallel for schedule(static) num_threads(w->threads) reduction(+ : ns)
    for (int i = 0; i < n; i++) {
        double lim = w->surf[i] ? off : on;
        unsigned char s = 0;
        if (w->kind[i] == SPH_FLUID && on > 0)
            s = w->divr[i] < lim || (w->divr[i] < (w->surf[i] ? bulk : bulk - BULK_HYSTERESIS) && cone_empty(w, i));
        w->surf[i] = s;
        ns += s;
    }
    for (int g = w->n; g < w->n + w->ng; g++) w->surf[g] = w->surf[w->src[g]];
    w->st.surface = ns;
}
