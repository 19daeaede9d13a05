/* Constitutive laws eta(gammadot) (PHYSICS.md): Newtonian, and the Papanastasiou (1987)
 * regularisations of Bingham and Herschel-Bulkley. The regularised yield term
 * tau0 (1 - exp(-m g)) / g is evaluated as tau0 * (-expm1(-m g)) / g, with its limit
 * tau0 * m at g = 0 so that a material at rest has a finite viscosity and no NaN. */
#include "sph.h"

#include <math.h>

static double papanastasiou(double tau0, double m, double g) {
    double mg = m * g;
    if (mg < 1e-8) return tau0 * m * (1.0 - 0.5 * mg); /* series: exact to O(mg^2) */
    return tau0 * (-expm1(-mg)) / g;
}

double sph_rheology_eta(const sph_material *mat, double g) {
    switch (mat->model) {
    case SPH_BINGHAM:
        return mat->mu + papanastasiou(mat->tau0, mat->m, g);
    case SPH_HERSCHEL_BULKLEY: {
        /* K g^(n-1) diverges at g = 0 when n < 1: the power-law part is evaluated at no
         * less than 1/m, the shear rate at which the Papanastasiou term itself levels
         * off, so eta(0) = K m^(1-n) + tau0 m stays finite. */
        double gmin = mat->n < 1.0 ? 1.0 / mat->m : 0.0;
        double gg = g > gmin ? g : gmin;
        return mat->K * pow(gg, mat->n - 1.0) + papanastasiou(mat->tau0, mat->m, g);
    }
    case SPH_NEWTONIAN:
    default:
        return mat->mu;
    }
}

const char *sph_rheology_check(const sph_material *mat) {
    switch (mat->model) {
    case SPH_NEWTONIAN:
        if (!(mat->mu > 0 && isfinite(mat->mu))) return "mu must be a positive number";
        return 0;
    case SPH_BINGHAM:
        if (!(mat->mu > 0 && isfinite(mat->mu))) return "mu must be a positive number";
        if (!(mat->tau0 >= 0 && isfinite(mat->tau0))) return "tau0 must be a number >= 0";
        if (!(mat->m > 0 && isfinite(mat->m))) return "m must be a positive number";
        return 0;
    case SPH_HERSCHEL_BULKLEY:
        if (!(mat->K > 0 && isfinite(mat->K))) return "K must be a positive number";
        if (!(mat->n > 0 && isfinite(mat->n))) return "n must be a positive number";
        if (!(mat->tau0 >= 0 && isfinite(mat->tau0))) return "tau0 must be a number >= 0";
        if (!(mat->m > 0 && isfinite(mat->m))) return "m must be a positive number";
        return 0;
    }
    return "unknown model";
}

/* The stress magnitude of the law at shear rate g, tau(g) = eta(g) g, and its slope. */
double sph_rheology_stress(const sph_material *mat, double g, double *slope) {
    double ds = 0.0, t = 0.0;
    double yt = 0.0, yd = 0.0; /* the Papanastasiou term tau0 (1 - exp(-m g)) */
    if (mat->model != SPH_NEWTONIAN) {
        double em = expm1(-mat->m * g); /* e - 1 */
        yt = -mat->tau0 * em;
        yd = mat->tau0 * mat->m * (em + 1.0);
    }
    switch (mat->model) {
    case SPH_BINGHAM:
        t = mat->mu * g + yt;
        ds = mat->mu + yd;
        break;
    case SPH_HERSCHEL_BULKLEY: {
        double gmin = mat->n < 1.0 ? 1.0 / mat->m : 0.0;
        if (g > gmin) {
            t = mat->K * pow(g, mat->n) + yt;
            ds = mat->n * mat->K * pow(g, mat->n - 1.0) + yd;
        } else {
            double k = mat->K * pow(gmin, mat->n - 1.0);
            t = k * g + yt;
            ds = k + yd;
        }
        break;
    }
    case SPH_NEWTONIAN:
    default:
        t = mat->mu * g;
        ds = mat->mu;
    }
    if (slope) *slope = ds;
    return t;
}

/* The shear rate g >= 0 with tau(g) + r g = q (q >= 0, r > 0): tau is increasing, so the
 * root is unique and lies in [q / (r + eta(0)), q / r] (tau(g) <= eta(0) g for these laws
 * but Herschel-Bulkley with n > 1, where the bracket's low end is 0). Newton's method kept
 * inside the bracket (bisection when a step leaves it). */
double sph_rheology_prox(const sph_material *mat, double q, double r, double hint) {
    if (!(q > 0.0)) return 0.0;
    double lo = 0.0, hi = q / r;
    double g = q / (r + sph_rheology_eta(mat, 0.0));
    if (mat->model == SPH_BINGHAM && q > mat->tau0) g = fmax(g, (q - mat->tau0) / (mat->mu + r));
    if (hint > g && hint < hi) g = hint; /* the last step's rate: usually a few 1e-3 off */
    for (int it = 0; it < 60; it++) {
        double ds, f = sph_rheology_stress(mat, g, &ds) + r * g - q;
        if (f < 0) lo = g;
        else hi = g;
        double gn = g - f / (ds + r);
        if (!(gn > lo && gn < hi)) gn = 0.5 * (lo + hi);
        if (fabs(gn - g) <= 1e-12 * g || hi - lo <= 1e-15 * hi) return gn;
        g = gn;
    }
    return g;
}
