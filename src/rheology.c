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
