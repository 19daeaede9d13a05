/* Walls and plates: rigid rectangles filled with wall particles on the fluid's lattice,
 * fixed or moving along one axis under a velocity law or a load law; the forces the fluid
 * puts on them and the loaded plates' equation of motion. No-slip follows
 * Morris, Fox & Zhu (1997): a wall particle B seen from fluid particle a carries the
 * velocity u_B = u_w - (d_B / d_a)(u_a - u_w), so u_a - u_B = beta (u_a - u_w) with
 * beta = 1 + d_B / d_a. Morris clamps beta at 1.5; that clamp, which binds for every wall
 * row, makes the wall a half-slip one (an effective slip length of about 0.4 dx in the
 * squeeze, ten times the Couette start-up error). Here d_a is instead floored at dx / 2,
 * the lattice distance of the first fluid row, which keeps the extrapolation exact for
 * every wall row (beta up to 6 with three rows) and bounded when a particle comes close to
 * the wall. */
#include "internal.h"
#include "kernel.h"

#include <math.h>
#include <string.h>

int sph_plate_fill(sph_world *w, const double rect[4], int axis) {
    const sph_params *P = &w->par;
    double dx = w->dx;
    int k = w->nplates;
    if (k >= SPH_MAX_PLATES) return sph_world_fail(w, "too many plates (at most %d)", SPH_MAX_PLATES);
    int nx, ny;
    if (sph_world_lattice(w, rect, "plate", &nx, &ny)) return -1;
    if (sph_world_reserve(w, w->n + nx * ny)) return -1; /* all at once: no half-made plate */
    double wd = rect[2] - rect[0], ht = rect[3] - rect[1];
    double thick = wd < ht ? wd : ht, need = SPH_KERNEL_SUPPORT * w->h;
    if (thick < need * (1.0 - 1e-9))
        return sph_world_fail(w,
                              "plate rect {%g, %g, %g, %g} is %g thick: a plate must be at "
                              "least the kernel support 3h = %g thick",
                              rect[0], rect[1], rect[2], rect[3], thick, need);
    for (int a = 0; a < 2; a++) {
        if (P->symmetry[a] && axis == a && rect[a] < P->sym_at[a] && rect[a + 2] > P->sym_at[a])
            return sph_world_fail(w, "a plate that straddles the symmetry plane cannot move across it");
    }
    sph_plate *pl = &w->plates[k];
    pl->rect[0] = rect[0];
    pl->rect[1] = rect[1];
    pl->rect[2] = rect[2];
    pl->rect[3] = rect[3];
    pl->axis = axis;
    pl->mode = SPH_PLATE_FIXED;
    pl->vel = pl->vel_new = pl->load = pl->force = pl->force_visc = pl->impulse = 0.0;
    pl->slide[0] = pl->slide[1] = 0.0;
    pl->mass_set = 0;
    pl->face_side = 0;
    pl->doubled = 0;
    for (int a = 0; a < 2; a++)
        if (P->symmetry[a] && rect[a] < P->sym_at[a] && rect[a + 2] > P->sym_at[a]) pl->doubled = 1;
    int count = 0;
    for (int j = 0; j < ny; j++) {
        for (int i = 0; i < nx; i++) {
            double px = rect[0] + (i + 0.5) * dx, py = rect[1] + (j + 0.5) * dx;
            if ((P->symmetry[0] && px < P->sym_at[0]) || (P->symmetry[1] && py < P->sym_at[1]))
                continue;
            if ((P->periodic[0] && (px < P->period_lo[0] || px >= P->period_hi[0])) ||
                (P->periodic[1] && (py < P->period_lo[1] || py >= P->period_hi[1])))
                continue;
            int q = w->n;
            w->x[q] = px;
            w->y[q] = py;
            w->u[q] = w->v[q] = 0.0;
            w->kind[q] = k;
            w->mat[q] = -1;
            w->m[q] = w->mass0;
            w->rho[q] = P->rho0;
            w->id[q] = w->next_id++;
            w->n++;
            count++;
        }
    }
    pl->count = count;
    pl->mass = w->mass0 * count * sph_plate_whole(pl);
    w->nplates++;
    w->prepared = 0;
    return k;
}

/* Which side of the plate the fluid is on, along its axis, from the fluid's centroid. */
/* The axis along which a plate's position is measured: its own, or for a fixed plate the
 * direction across its thinner side. */
static int position_axis(const sph_plate *pl) {
    if (pl->axis >= 0) return pl->axis;
    return pl->rect[2] - pl->rect[0] < pl->rect[3] - pl->rect[1] ? 0 : 1;
}

static int face_side(const sph_world *w, const sph_plate *pl) {
    int a = position_axis(pl);
    double c = 0.0;
    int nf = 0;
    for (int i = 0; i < w->n; i++)
        if (w->kind[i] == SPH_FLUID) {
            c += a == 0 ? w->x[i] : w->y[i];
            nf++;
        }
    if (nf == 0) return 0;
    c /= nf;
    double mid = 0.5 * (pl->rect[a] + pl->rect[a + 2]);
    return c >= mid ? 1 : -1;
}

void sph_plate_prepare(sph_world *w) {
    for (int k = 0; k < w->nplates; k++) {
        sph_plate *pl = &w->plates[k];
        pl->face_side = face_side(w, pl);
    }
}

double sph_plate_position(const sph_world *w, int k) {
    const sph_plate *pl = &w->plates[k];
    int a = position_axis(pl);
    int side = pl->face_side ? pl->face_side : face_side(w, pl);
    return side > 0 ? pl->rect[a + 2] : pl->rect[a];
}

/* The velocity wall particle b carries in the no-slip extrapolation: the plate's rigid
 * velocity along its axis plus its surface (slide) velocity, with b's mirror signs. */
void sph_plate_wall_velocity(const sph_world *w, int b, double *vx, double *vy) {
    const sph_plate *pl = &w->plates[w->kind[b]];
    *vx = pl->slide[0] * w->gsx[b];
    *vy = pl->slide[1] * w->gsy[b];
    if (pl->axis == 0) *vx += pl->vel * w->gsx[b];
    else if (pl->axis == 1) *vy += pl->vel * w->gsy[b];
}

/* The plate's rigid velocity alone, without the slide: what the pressure source and the
 * continuity see. A slide is tangential to the face, so on a flat face its divergence
 * vanishes by symmetry, but where a sliding lid meets a fixed wall the kernel sums see a
 * velocity jump along the face: with the slide in the source the cavity's corner particles
 * are driven into the corners and the flow under the lid runs backwards. */
void sph_plate_rigid_velocity(const sph_world *w, int b, double *vx, double *vy) {
    const sph_plate *pl = &w->plates[w->kind[b]];
    *vx = *vy = 0.0;
    if (pl->axis == 0) *vx = pl->vel * w->gsx[b];
    else if (pl->axis == 1) *vy = pl->vel * w->gsy[b];
}

/* The axis of the normal of the face of wall particle b's plate nearest to fluid particle a:
 * the axis along which a lies farther out of the rectangle, or, for a particle that has
 * come into it, the face it is least deep behind. A periodic axis has no face (a plate
 * sliding across it has moved its rectangle's ends, not made faces there). */
static int face_axis(const sph_world *w, int a, int b) {
    if (w->par.periodic[0]) return 1;
    if (w->par.periodic[1]) return 0;
    const double *R = w->plates[w->kind[b]].rect;
    double xa = w->x[a], ya = w->y[a];
    double ox = fmax(fmax(R[0] - xa, xa - R[2]), 0.0), oy = fmax(fmax(R[1] - ya, ya - R[3]), 0.0);
    if (ox > 0.0 || oy > 0.0) return oy >= ox;
    return fmin(ya - R[1], R[3] - ya) <= fmin(xa - R[0], R[2] - xa);
}

/* The distances of fluid particle a and wall particle b from b's plate face nearest to a. */
static int wall_distances(const sph_world *w, int a, int b, double *da_out, double *db_out) {
    const sph_plate *pl = &w->plates[w->kind[b]];
    const double *R = pl->rect;
    double xa = w->x[a], ya = w->y[a], xb = w->x[b], yb = w->y[b];
    /* The plate face nearest to a, taken from the rectangle (images included: a ghost
     * wall particle is compared with its plate's rectangle through the same distances
     * along the face normal, which mirrors and periodic shifts leave unchanged). */
    double ox = fmax(fmax(R[0] - xa, xa - R[2]), 0.0);
    double oy = fmax(fmax(R[1] - ya, ya - R[3]), 0.0);
    double da, db;
    int axis = oy >= ox;
    if (axis) {
        double face = ya > 0.5 * (R[1] + R[3]) ? R[3] : R[1];
        da = fabs(ya - face);
        db = fabs(yb - face);
    } else {
        double face = xa > 0.5 * (R[0] + R[2]) ? R[2] : R[0];
        da = fabs(xa - face);
        db = fabs(xb - face);
    }
    *da_out = da;
    *db_out = db;
    return axis;
}

double sph_plate_noslip(const sph_world *w, int a, int b, int *normal) {
    double da, db, floor_a = 0.5 * w->dx;
    wall_distances(w, a, b, &da, &db);
    *normal = face_axis(w, a, b);
    return 1.0 + db / (da > floor_a ? da : floor_a);
}

void sph_plate_move(sph_world *w, int k, double dpos) {
    sph_plate *pl = &w->plates[k];
    if (pl->axis < 0 || dpos == 0.0) return;
    pl->rect[pl->axis] += dpos;
    pl->rect[pl->axis + 2] += dpos;
    double *c = pl->axis == 0 ? w->x : w->y;
    for (int i = 0; i < w->n; i++)
        if (w->kind[i] == k) c[i] += dpos;
}

/* Contact of free-surface particles with the plates. A free-surface particle is held at
 * p = 0, and the walls next to free-surface particles alone are no pressure unknowns
 * (pressure.c, mark_unknowns), so nothing in the pressure keeps it off a wall: a drop or a
 * sheet of spray that reaches a plate would go through it. Such a particle is kept at least
 * CONTACT_MIN dx off the plate's rectangle, on the side it came from, and its velocity
 * relative to the plate loses the component into the plate (an inelastic contact). Particles
 * off the free surface are left to the pressure: one that ends a step inside a plate stops
 * the run (sph_plate_check_escape). In the stability suite's cases no fluid particle comes
 * closer than about 0.2 dx to a face, so at 0.1 dx the contact touches none of them.
 * w->st.wall_contacts counts the contacts. */
#define CONTACT_MIN 0.1

static void closest_on_rect(const double *R, double x, double y, double *cx, double *cy) {
    *cx = x < R[0] ? R[0] : x > R[2] ? R[2] : x;
    *cy = y < R[1] ? R[1] : y > R[3] ? R[3] : y;
}

void sph_plate_contact(sph_world *w) {
    double dmin = CONTACT_MIN * w->dx;
    int contacts = 0;
    for (int i = 0; i < w->n; i++) {
        if (w->kind[i] != SPH_FLUID || !w->surf[i]) continue;
        for (int k = 0; k < w->nplates; k++) {
            const sph_plate *pl = &w->plates[k];
            const double *R = pl->rect, *R0 = pl->rect0;
            double cx, cy;
            closest_on_rect(R, w->x[i], w->y[i], &cx, &cy);
            double ex = w->x[i] - cx, ey = w->y[i] - cy, d = hypot(ex, ey);
            if (d >= dmin) continue;
            if (d == 0.0) { /* inside: the side it came from, in the plate's frame */
                double ox, oy;
                sph_neighbours_built_position(w, i, &ox, &oy);
                ox += R[0] - R0[0];
                oy += R[1] - R0[1];
                closest_on_rect(R, ox, oy, &cx, &cy);
                ex = ox - cx;
                ey = oy - cy;
                d = hypot(ex, ey);
                if (d == 0.0) continue; /* it started the step inside: an escape */
                ex /= d;
                ey /= d;
                double depth = (w->x[i] - cx) * ex + (w->y[i] - cy) * ey; /* <= 0 */
                w->x[i] += (dmin - depth) * ex;
                w->y[i] += (dmin - depth) * ey;
            } else {
                ex /= d;
                ey /= d;
                w->x[i] = cx + dmin * ex;
                w->y[i] = cy + dmin * ey;
            }
            double pu = pl->slide[0] + (pl->axis == 0 ? pl->vel : 0.0);
            double pv = pl->slide[1] + (pl->axis == 1 ? pl->vel : 0.0);
            double vn = (w->u[i] - pu) * ex + (w->v[i] - pv) * ey;
            if (vn < 0.0) {
                w->u[i] -= vn * ex;
                w->v[i] -= vn * ey;
            }
            contacts++;
        }
    }
    w->st.wall_contacts += contacts;
}

int sph_plate_check_escape(sph_world *w) {
    for (int i = 0; i < w->n; i++) {
        if (w->kind[i] != SPH_FLUID) continue;
        for (int k = 0; k < w->nplates; k++) {
            const double *R = w->plates[k].rect;
            if (w->x[i] > R[0] && w->x[i] < R[2] && w->y[i] > R[1] && w->y[i] < R[3])
                return sph_world_fail(w,
                                      "fluid particle %d at (%.6g, %.6g) went through plate %d "
                                      "{%.6g, %.6g, %.6g, %.6g} at step %ld, t = %.6g",
                                      w->id[i], w->x[i], w->y[i], k + 1, R[0], R[1], R[2], R[3],
                                      w->steps, w->t);
        }
    }
    return 0;
}

/* Fluid pressure force on every plate along its axis, for a pressure field p (ghosts
 * synced): F = sum_{a fluid, B in plate} m_a m_B (p_a / rho_a^2 + p_B / rho_B^2) grad_a W. */
void sph_plate_pressure_force(const sph_world *w, const double *p, double *out) {
    int n = w->n, np = w->nplates;
    double f[SPH_MAX_PLATES] = {0};
#pragma omp parallel for schedule(static) num_threads(w->threads) reduction(+ : f[:SPH_MAX_PLATES])
    for (int i = 0; i < n; i++) {
        if (w->kind[i] != SPH_FLUID) continue;
        double pi = p[i] / (w->rho[i] * w->rho[i]);
        for (int k = w->nb_mid[i]; k < w->nb_start[i + 1]; k++) { /* walls */
            int j = w->nb_j[k], pk = w->kind[j];
            if (w->plates[pk].axis < 0) continue;
            double c = w->m[i] * w->m[j] * (pi + p[j] / (w->rho[j] * w->rho[j]));
            f[pk] += w->plates[pk].axis == 0 ? c * w->nb_gx[k] * w->gsx[j] : c * w->nb_gy[k] * w->gsy[j];
        }
    }
    for (int k = 0; k < np; k++) out[k] = f[k] * sph_plate_whole(&w->plates[k]);
}

/* The loaded plates' equations of motion M (V - V^n) / dt = F_load + F_visc + F_p(V), with
 * the fluid's pressure force linear in the velocities, F_p = F0 + sum_q V_q Fk[q] (the
 * pressure solve's sensitivities): a small dense system, stable whatever the plate's mass
 * against the fluid's added mass. x: V^{n+1} of each loaded plate. */
int sph_plate_loaded_velocities(sph_world *w, double dt, int K, const int *loaded, const double *F0,
                                double (*Fk)[SPH_MAX_PLATES], double *x) {
    double a[SPH_MAX_LOADED][SPH_MAX_LOADED];
    for (int r = 0; r < K; r++) {
        sph_plate *pl = &w->plates[loaded[r]];
        for (int c = 0; c < K; c++) a[r][c] = -Fk[c][loaded[r]];
        a[r][r] += pl->mass / dt;
        x[r] = pl->mass * pl->vel / dt + pl->load + pl->force_visc + F0[loaded[r]];
    }
    if (sph_dense_solve(K, &a[0][0], SPH_MAX_LOADED, x))
        return sph_world_fail(w, "singular plate system at step %ld (t = %g)", w->steps, w->t);
    for (int q = 0; q < K; q++) w->plates[loaded[q]].vel_new = x[q]; /* V^{n+1} */
    return 0;
}

/* Whole-sample viscous force of each plate from the simulated part's sums f. */
void sph_plate_set_viscous_forces(sph_world *w, const double *f) {
    for (int k = 0; k < w->nplates; k++) w->plates[k].force_visc = f[k] * sph_plate_whole(&w->plates[k]);
}

/* plate accessors (whole-sample values) */
static int plate_ok(sph_world *w, int k) {
    if (k < 0 || k >= w->nplates) return sph_world_fail(w, "no plate %d", k + 1);
    return 0;
}

int sph_plate_set_velocity(sph_world *w, int k, double v) {
    if (plate_ok(w, k)) return -1;
    if (w->plates[k].axis < 0) return sph_world_fail(w, "plate %d is fixed (no axis): it cannot move", k + 1);
    if (!isfinite(v)) return sph_world_fail(w, "plate %d: velocity %g is not finite", k + 1, v);
    w->plates[k].mode = SPH_PLATE_VELOCITY;
    w->plates[k].vel = v;
    return 0;
}

int sph_plate_set_load(sph_world *w, int k, double f) {
    if (plate_ok(w, k)) return -1;
    if (w->plates[k].axis < 0) return sph_world_fail(w, "plate %d is fixed (no axis): it cannot move", k + 1);
    if (!isfinite(f)) return sph_world_fail(w, "plate %d: load %g is not finite", k + 1, f);
    sph_plate *pl = &w->plates[k];
    pl->mode = SPH_PLATE_LOAD;
    pl->load = f;
    return 0;
}

int sph_plate_set_mass(sph_world *w, int k, double m) {
    if (plate_ok(w, k)) return -1;
    if (!(m > 0 && isfinite(m))) return sph_world_fail(w, "plate %d: mass must be a positive number", k + 1);
    w->plates[k].mass = m;
    w->plates[k].mass_set = 1;
    return 0;
}

int sph_plate_set_slide(sph_world *w, int k, double sx, double sy) {
    if (plate_ok(w, k)) return -1;
    if (!isfinite(sx) || !isfinite(sy))
        return sph_world_fail(w, "plate %d: slide velocity (%g, %g) is not finite", k + 1, sx, sy);
    w->plates[k].slide[0] = sx;
    w->plates[k].slide[1] = sy;
    return 0;
}

void sph_plate_slide(const sph_world *w, int k, double slide[2]) {
    slide[0] = w->plates[k].slide[0];
    slide[1] = w->plates[k].slide[1];
}

sph_plate_mode sph_plate_mode_of(const sph_world *w, int k) { return w->plates[k].mode; }
int sph_plate_axis(const sph_world *w, int k) { return w->plates[k].axis; }
double sph_plate_velocity(const sph_world *w, int k) { return w->plates[k].vel; }
double sph_plate_load(const sph_world *w, int k) {
    return w->plates[k].mode == SPH_PLATE_LOAD ? w->plates[k].load : 0.0;
}
double sph_plate_force(const sph_world *w, int k) { return w->plates[k].force; }
double sph_plate_impulse(const sph_world *w, int k) { return w->plates[k].impulse; }
double sph_plate_mass(const sph_world *w, int k) { return w->plates[k].mass; }
void sph_plate_rect(const sph_world *w, int k, double rect[4]) {
    memcpy(rect, w->plates[k].rect, sizeof(double) * 4);
}
