/* sph: incompressible SPH for viscoplastic flows (2D, plane strain).
 *
 * The engine's public C API. It does not depend on Lua: another C program can embed it.
 * Units are whatever the caller uses consistently (the scripts use H = U = mu = 1).
 * Every call that can fail returns a status (0 = ok, -1 = error) or a count (-1 = error)
 * and leaves a message in sph_world_error(). Nothing here aborts or prints.
 */
#ifndef SPH_H
#define SPH_H

/* Only the C library: the pictures layer (render, plot, animate; needs cairo to link) has
   its own header, sph_pictures.h. */
#include <stddef.h>

#define SPH_VERSION "0.1.0"

typedef struct sph_world sph_world;

/* Constitutive laws eta(gammadot); see rheology.c. */
typedef enum { SPH_NEWTONIAN = 0, SPH_BINGHAM = 1, SPH_HERSCHEL_BULKLEY = 2 } sph_model;

typedef struct sph_material {
    sph_model model;
    double mu;   /* Newtonian / plastic viscosity [Pa s]            */
    double tau0; /* yield stress [Pa] (Bingham, Herschel-Bulkley)   */
    double m;    /* Papanastasiou stress-growth exponent [s]        */
    double K;    /* consistency [Pa s^n] (Herschel-Bulkley)         */
    double n;    /* flow index (Herschel-Bulkley)                   */
} sph_material;

/* Apparent viscosity and its value at gammadot = 0 (finite: tau0 * m). */
double sph_rheology_eta(const sph_material *mat, double gammadot);
/* The law's stress magnitude tau(g) = eta(g) g (and d tau / d g into slope, if given), and
 * the shear rate g with tau(g) + r g = q (the augmented-Lagrangian step, viscous.c). */
double sph_rheology_stress(const sph_material *mat, double gammadot, double *slope);
double sph_rheology_prox(const sph_material *mat, double q, double r, double hint);
/* A message naming the bad field, or NULL when the material is valid. */
const char *sph_rheology_check(const sph_material *mat);

typedef enum { SPH_VISC_EXPLICIT = 0, SPH_VISC_IMPLICIT = 1 } sph_viscosity;

/* The options a user chooses for a physical or a practical reason (sph.world{...},
 * docs/api.md); the scheme's numerical constants live in the file that uses them. */
/* sph_params.shifting = SPH_SHIFTING_AUTO: no shifting while the particle lattice holds,
 * shifting with A = 20 from the step a fluid pair is found closer than 0.7 dx. */
#define SPH_SHIFTING_AUTO (-1.0)

typedef struct sph_params {
    double dx;             /* initial particle spacing (> 0)                       */
    double h;              /* smoothing length, the kernel's support is 3 h: 0 (the
                              default) is dx; else in [dx, 2 dx] (sph_world_h)       */
    double cfl;            /* dt <= cfl h / max speed: 0 (the default) is 0.25;
                              else in (0, 1]; sph_world_params gives the value used  */
    double rho0;           /* reference density                                    */
    double gravity[2];     /* body force per unit mass                             */
    sph_viscosity viscosity;
    double shifting;       /* particle-shifting coefficient A, 0 = off; SPH_SHIFTING_AUTO
                              (the default): off until the lattice clusters, then
                              20 (world.c, watch_clustering)                        */
    double dt_max;         /* upper bound on dt, >= 0 (0: none)                    */
    double dt_min;         /* a step below this is an error (0: 1e-12 * h)         */
    int periodic[2];       /* periodic in x / y                                    */
    double period_lo[2], period_hi[2];
    int symmetry[2];       /* mirror plane x = sym_at[0] / y = sym_at[1]           */
    double sym_at[2];
    int threads;           /* 0: OMP_NUM_THREADS if set, else all cores; at most
                              SPH_MAX_THREADS (see "Threads")                      */
    double tol;            /* relative residual of every solve, the pressure's and
                              the implicit viscous step's; default 1e-6
                              (docs/performance.md: what looser costs)               */
    double surface_div;    /* free surface where div r < this, >= 0 (2D: 2 full) */
    double density_tol;    /* dt shrinks while the max density error exceeds this
                              (0: no control); default 0.005                        */
    int thin_film;         /* 1: the thin-film scheme, for films a/h >= 5 of 16 rows
                              or fewer, where the free surface's traction is a share
                              h^2 / (2 a^2) of the force: the projection's gradient in
                              the renormalised difference form with p = 0 at the free
                              surface, and the density correction as GMRES over its
                              passes (pressure.c, density.c). 0 (default): the
                              symmetric gradient, the traction-free surface          */
} sph_params;

void sph_params_default(sph_params *p);

/* Threads. A world runs threads OpenMP threads (sph_params.threads; 0, the default:
 * OMP_NUM_THREADS where the environment sets it, else one per core the machine has, at
 * most SPH_MAX_THREADS; sph.world{threads = n}). At a barrier
 * they spin briefly, then sleep: the sph host sets GOMP_SPINCOUNT=10000 when the
 * environment sets neither it nor OMP_WAIT_POLICY (main.c; it executes itself again for
 * it, as libgomp reads them only when it is loaded). libgomp's own long spin took a busy
 * machine's cores from the work, sleeping at once (passive) pays a wake-up at each of a
 * step's many short loops (the headline squeeze on two threads: 0.9 s bounded, 5.6 s
 * passive). A program embedding libsph (or lua loading sph.so) chooses for itself: set
 * GOMP_SPINCOUNT (or OMP_WAIT_POLICY) in its environment before it starts (a setenv in
 * main is too late), or give threads = 1 on a shared machine. Either variable set in the
 * host's environment is kept.
 *
 * OpenMP threads a world may ask for. A fixed bound, not a multiple of this machine's
 * cores, so a state saved on a large machine still loads on a small one; far beyond it
 * (threads = 100000) the OpenMP runtime overflowed its stack and crashed. */
#define SPH_MAX_THREADS 256

/* dx must lie in [SPH_MIN_LENGTH, SPH_MAX_LENGTH] (powers of it up to the fourth stay
 * normal doubles), and the particle mass rho dx^2 must be a normal number. */
#define SPH_MIN_LENGTH 1e-30
#define SPH_MAX_LENGTH 1e30

/* A new empty world; NULL with a message in err on bad parameters. */
sph_world *sph_world_new(const sph_params *p, char *err, size_t errlen);
void sph_world_free(sph_world *w);
/* The state (parameters, materials, plates, clock, statistics, particles, and the solves'
 * first guesses and multigrid hierarchies) to a file, and a new world from one (state.c):
 * a restart on the same build, which continues the run bit for bit on the same thread
 * count; 0 / NULL with a message (a file of another state version is named as such). */
int sph_world_save(sph_world *w, const char *file);
sph_world *sph_world_load(const char *file, char *err, size_t errlen);
const char *sph_world_error(const sph_world *w);
const sph_params *sph_world_params(const sph_world *w);
/* The smoothing length h: the spacing dx. The kernel reaches 3h, so plates must be at
 * least 3h thick. */
double sph_world_h(const sph_world *w);

/* Real particles (fluid and walls) a world holds at most: fills, plates and sph.load
 * beyond it fail up front with the count asked for (2e8 is about 60 GB of arrays). */
#define SPH_MAX_PARTICLES 200000000

/* Fill rect {x0, y0, x1, y1} with fluid on the dx lattice (points at (i + 1/2) dx from
 * the lower-left corner); returns the number of particles added or -1. All or nothing: on
 * an error the world is unchanged. It is an error when the rect holds no lattice point,
 * when none of its points lies in the simulated domain, or when any lies inside a plate. */
int sph_world_fill(sph_world *w, const double rect[4], const sph_material *mat);

/* Plates: rigid walls of particles filling rect (at least 3h thick). axis: -1 fixed,
 * 0 moves along x, 1 along y. Returns the plate index or -1. */
int sph_world_plate(sph_world *w, const double rect[4], int axis);
int sph_world_nplates(const sph_world *w);

typedef enum { SPH_PLATE_FIXED = 0, SPH_PLATE_VELOCITY = 1, SPH_PLATE_LOAD = 2 } sph_plate_mode;
int sph_plate_set_velocity(sph_world *w, int plate, double v);
int sph_plate_set_load(sph_world *w, int plate, double force);
int sph_plate_set_mass(sph_world *w, int plate, double mass);
/* Surface velocity (sx, sy): the wall particles carry it in the no-slip extrapolation and
 * the pressure source but stay in place (a lid that slides along itself, a belt), on top
 * of the plate's own velocity along its axis. Any plate, fixed or not; 0 by default. */
int sph_plate_set_slide(sph_world *w, int plate, double sx, double sy);
void sph_plate_slide(const sph_world *w, int plate, double slide[2]);
sph_plate_mode sph_plate_mode_of(const sph_world *w, int plate);
int sph_plate_axis(const sph_world *w, int plate);
/* Coordinate along the axis of the face that touches the fluid. */
double sph_plate_position(const sph_world *w, int plate);
double sph_plate_velocity(const sph_world *w, int plate);
/* The load applied along the axis (the whole sample's) in SPH_PLATE_LOAD mode; 0 in the
 * other modes. */
double sph_plate_load(const sph_world *w, int plate);
/* Fluid force on the plate along its axis (the whole sample's, with a symmetry plane). */
double sph_plate_force(const sph_world *w, int plate);
/* The sum of that force times dt over every step taken (the whole sample's impulse). Its
 * change between two times over their difference is the force's mean between them: a load
 * cell's reading. The force of one step can jump (to a few times the mean, for that step
 * only) when a particle at the plate's edge joins or leaves the free surface; the mean over
 * a few tens of steps hardly feels it (docs/limitations.md). */
double sph_plate_impulse(const sph_world *w, int plate);
double sph_plate_mass(const sph_world *w, int plate);
/* Current rectangle of a plate (it moves). */
void sph_plate_rect(const sph_world *w, int plate, double rect[4]);

/* Time stepping. sph_world_next_dt: the adaptive dt the next step would take.
 * sph_world_step(w, dt): one step of the given dt (<= 0: adaptive). */
double sph_world_next_dt(sph_world *w);
int sph_world_step(sph_world *w, double dt);
/* Steps until the time is t_end and lands on it exactly (sph_world_time(w) == t_end).
 * Each step is dt (<= 0: the adaptive sph_world_next_dt), and the interval left is spread
 * evenly over the steps it needs rather than the last step cut short (a much shorter step
 * shows in the plate force; run.c). before_step, when not NULL, runs before every step
 * (a plate law is set there); a nonzero return stops the run before that step. Returns 0
 * at t_end (no step when the time is already there or past it, within 1e-9 t_end), 1 when
 * before_step stopped it, -1 with a message in sph_world_error() (a failed step's, or a
 * t_end or dt that is not finite). */
typedef int (*sph_step_hook)(sph_world *w, void *ctx);
int sph_world_run_until(sph_world *w, double t_end, double dt, sph_step_hook before_step, void *ctx);
double sph_world_time(const sph_world *w);
double sph_world_dt(const sph_world *w);
long sph_world_steps(const sph_world *w);

enum {
    SPH_PHASE_SORT,
    SPH_PHASE_NEIGHBOURS,
    SPH_PHASE_RHEOLOGY,
    SPH_PHASE_VISC_ASSEMBLY,
    SPH_PHASE_VISC_SOLVE,
    SPH_PHASE_PRESSURE_ASSEMBLY,
    SPH_PHASE_PRESSURE_SOLVE,
    SPH_PHASE_CORRECTION,
    SPH_PHASE_SHIFTING,
    SPH_PHASE_OTHER,
    SPH_PHASES
};

typedef struct sph_stats {
    int particles;            /* fluid + wall (real, not ghosts)          */
    int fluid;
    int wall;
    int ghosts;
    int surface;              /* fluid particles held at p = 0            */
    int unknowns;             /* rows of the pressure system             */
    int solver_iterations;    /* last pressure solve                      */
    double solver_residual;   /* relative residual reached               */
    long solver_iterations_total;
    int visc_iterations;      /* last implicit viscous solve (0: explicit) */
    double visc_residual;
    long visc_iterations_total;
    double max_density_error; /* max |rho/rho0 - 1| over interior fluid, last step */
    double peak_density_error; /* the largest max_density_error of any step so far */
    double correction_share;  /* the share of the fluid particles' motion made by the density
                                 correction over the run so far: sqrt(sum |d_c|^2 / dt over
                                 sum |d_u + d_c|^2 / dt), over fluid particles and steps
                                 (each step weighted by its length), d_u the velocity's
                                 move dt (u^n + u^{n+1}) / 2, d_c the correction's
                                 (sph_world_stats derives it from the two sums below) */
    double correction_sq, motion_sq; /* the two sums behind correction_share */
    double shifting_since;    /* with shifting = SPH_SHIFTING_AUTO: the time its shifting
                                 started (-1: not, or shifting set by the caller) */
    double density_alpha;     /* smallest step length of the last step's density passes (1: full) */
    int density_passes;       /* density-correction passes in the last step */
    long density_fallbacks;   /* steps whose passes stalled above the density limit (0.8 %)
                                 and took a GMRES correction after them (density.c) */
    long density_descents;    /* steepest-descent moves so far (density.c)   */
    long density_switches;    /* first density passes so far that moved along the
                                 difference form's direction (density.c)             */
    long density_probes;      /* later density passes tried first on a loose solve
                                 (after one that moved nothing; density.c) so far    */
    long density_probes_ended; /* of those, the ones whose direction could not lower
                                 the error: the pass ended without its full solve    */
    int floating_walls;       /* active walls the fluid does not reach, left out of
                                 the last pressure system (pressure.c)            */
    long wall_contacts;       /* fluid particles held 0.1 dx off a plate so far
                                 (plates.c, sph_plate_contact)                     */
    double kinetic_energy;    /* sum 1/2 m |u|^2 over fluid               */
    double area;              /* sum m / rho over fluid                   */
    double max_speed;
    double max_eta;
    int yielded;              /* fluid particles with |tau| > tau0        */
    double neighbours_mean;
    double wall_time;         /* seconds spent in sph_world_step so far   */
    /* Wall time of each phase of the step, seconds since the world was made (their sum is
     * wall_time); names and order from sph_phase_names(). */
    double phase_time[SPH_PHASES];
    long steps;               /* steps taken (the phases' divisor)        */
    /* seconds spent so far in the linear solver: preconditioner setup and CG iterations,
     * for the implicit viscous solves and for the pressure ones (pressure, loaded-plate
     * sensitivities, density correction) */
    double visc_setup_time, visc_solve_time, pressure_setup_time, pressure_solve_time;
    long visc_solves, pressure_solves; /* solves so far (each u or v component counts) */
} sph_stats;

/* The phases of sph_world_step timed in sph_stats.phase_time, NULL-terminated:
 * sort (periodic wrap, sort by cell, ghosts), neighbours (binning, neighbour list, kernel
 * gradients, renormalisation, surface flags), rheology, viscous_assembly (implicit matrix
 * and right-hand side, or the explicit sweep; plate viscous forces), viscous_solve,
 * pressure_assembly, pressure_solve (the pressure, plate-sensitivity and density-correction
 * solves), correction (projection, continuity, density-correction displacements), shifting,
 * other (time-step bookkeeping, plate forces and motion, checks). */
const char *const *sph_phase_names(void);

void sph_world_stats(const sph_world *w, sph_stats *s);

/* Per-fluid-particle fields (in the engine's current order). Names: x y u v p rho eta
 * gammadot stress yielded speed surface material id rho_sum (kernel-summation density)
 * divr (position divergence, about 2 in the bulk). Returns the count written into out
 * (which must hold sph_world_nfluid values) or -1 for an unknown name. */
int sph_world_nfluid(const sph_world *w);
int sph_world_field(const sph_world *w, const char *name, double *out);
/* Every field name, NULL-terminated. */
const char *const *sph_world_field_names(void);
/* Set the velocity of every fluid particle, in the order of sph_world_field (u or v may be
 * 0 to keep that component): initial conditions such as the Taylor-Green vortex. */
int sph_world_set_velocity(sph_world *w, const double *u, const double *v);

/* Output. 0 or -1 with a message. Every file is written whole or not at all (a temporary
 * file renamed into place). All of them hold every particle, fluid and wall, with the
 * names of sph_world_field: id, kind (0 fluid, k the walls of plate k), u, v, p, rho, eta,
 * gammadot, stress, yielded, surface, material (0 for walls); the VTK files add the vector
 * velocity = (u, v, 0) and give x, y as the points.
 * CSV: a header line and one row per particle: id,kind,x,y,u,v,... in that order.
 * Legacy VTK: ASCII polydata of vertices. */
int sph_world_write_csv(sph_world *w, const char *file);
int sph_world_write_vtk(sph_world *w, const char *file);

/* VTK XML unstructured grid (.vtu) of vertex cells, binary little-endian data. */
typedef struct sph_vtu_options {
    int appended; /* 0: inline base64 data (format="binary"); 1: raw appended data     */
    int header64; /* 1: header_type UInt64 (the default); 0: UInt32                    */
    int mirror;   /* 1: also the mirror images across the symmetry planes (positions
                     reflected, the velocity component normal to the plane negated, ids
                     offset by the world's id count, so distinct); default 1 when the
                     world has a symmetry plane */
} sph_vtu_options;
void sph_vtu_defaults(const sph_world *w, sph_vtu_options *o);
/* o NULL: the defaults. */
int sph_world_write_vtu(sph_world *w, const char *file, const sph_vtu_options *o);
/* A ParaView collection (.pvd): n data files with their times, one animation. File
 * names as given (relative ones are read relative to the .pvd's folder). 0, or -1 with a
 * message in err. */
int sph_write_pvd(const char *file, size_t n, const double *t, const char *const *files, char *err,
                  size_t errlen);

#endif
