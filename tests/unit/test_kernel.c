/* Kernel invariants: normalisation, partition of unity and gradient moments on a lattice,
 * derivative against a finite difference, compact support. */
#include "../../src/kernel.h"
#include "unit.h"

int main(void) {
    double h = 0.7;
    /* compact support and sign */
    double out = 3.0 * h * (1 + 1e-12);
    CHECK(sph_kernel_value(out, h) == 0.0 && sph_kernel_value(3.5 * h, h) == 0.0, "W = 0 for r >= 3h", "W(3h+) = %g", sph_kernel_value(out, h));
    CHECK(sph_kernel_deriv(out, h) == 0.0 && sph_kernel_deriv(4.0 * h, h) == 0.0, "dW = 0 for r >= 3h", "dW(3h+) = %g", sph_kernel_deriv(out, h));
    CHECK(fabs(sph_kernel_value(3.0 * h, h)) < 1e-60, "W vanishes at the support's edge", "W(3h) = %g", sph_kernel_value(3.0 * h, h));
    int pos = 1, dec = 1;
    for (int k = 0; k < 300; k++) {
        double r = k * 0.01 * h;
        pos &= sph_kernel_value(r, h) > 0;
        dec &= sph_kernel_deriv(r, h) <= 0;
    }
    CHECK(pos && dec, "W > 0 and dW <= 0 inside the support", "pos %d dec %d", pos, dec);
    CHECK_CLOSE(sph_kernel_deriv(0.0, h), 0.0, 1e-12, "dW(0) = 0 (smooth peak)");

    /* normalisation: integral of W over the plane by the midpoint rule, 2 pi int W r dr */
    double s = 0.0, dr = 1e-4 * h;
    for (double r = 0.5 * dr; r < 3 * h; r += dr) s += 2 * SPH_PI * r * sph_kernel_value(r, h) * dr;
    CHECK_CLOSE(s, 1.0, 1e-7, "integral of W over the plane is 1");

    /* derivative against a central finite difference */
    double worst = 0.0;
    for (int k = 1; k < 30; k++) {
        double r = k * 0.1 * h, e = 1e-6 * h;
        double fd = (sph_kernel_value(r + e, h) - sph_kernel_value(r - e, h)) / (2 * e);
        double d = fabs(fd - sph_kernel_deriv(r, h)) / (fabs(sph_kernel_deriv(0.5 * h, h)));
        if (d > worst) worst = d;
    }
    CHECK(worst < 1e-7, "dW/dr matches a finite difference", "worst relative difference %g", worst);

    /* on a square lattice (h = dx is the default): partition of unity and the first moment
     * sum_j V (x_j - x_i) d W / d x_i = 1 (the SPH gradient of x) */
    for (int q = 0; q < 3; q++) {
        double ratio = q == 0 ? 1.0 : q == 1 ? 1.2 : 1.5; /* h / dx */
        double dx = h / ratio, V = dx * dx, sum = 0, gx = 0, gy = 0, mxx = 0, mxy = 0, divr = 0;
        for (int i = -10; i <= 10; i++)
            for (int j = -10; j <= 10; j++) {
                double x = i * dx, y = j * dx, r = sqrt(x * x + y * y);
                sum += V * sph_kernel_value(r, h);
                if (r == 0) continue;
                double d = sph_kernel_deriv(r, h);
                /* grad_i W_ij with r_ij = x_i - x_j = -(x, y) */
                double wx = d * (-x) / r, wy = d * (-y) / r;
                gx += V * wx;
                gy += V * wy;
                mxx += V * x * wx;
                mxy += V * x * wy;
                divr -= V * r * d;
            }
        char name[128];
        /* measured lattice errors (|sum W V - 1|, |moment - 1|, |div r - 2|):
         * h = dx: 2.6e-4, 8.0e-4, 1.6e-3; h = 1.2 dx: 5.6e-5, 6.2e-4, 1.2e-3;
         * h = 1.5 dx: 1.6e-4, 1.6e-4, 3.1e-4. Tolerances: twice these. */
        double tol_s = ratio == 1.0 ? 5.2e-4 : ratio == 1.2 ? 1.2e-4 : 3.2e-4;
        double tol_m = ratio == 1.0 ? 1.6e-3 : ratio == 1.2 ? 1.3e-3 : 3.2e-4;
        double tol_d = ratio == 1.0 ? 3.2e-3 : ratio == 1.2 ? 2.5e-3 : 6.2e-4;
        snprintf(name, sizeof name, "partition of unity on a lattice, h = %.1f dx", ratio);
        CHECK_CLOSE(sum, 1.0, tol_s, name);
        snprintf(name, sizeof name, "gradient sums vanish on a lattice, h = %.1f dx", ratio);
        CHECK(fabs(gx) < 1e-12 && fabs(gy) < 1e-12, name, "(%g, %g)", gx, gy);
        snprintf(name, sizeof name, "first moment sum V (x_j - x_i) dW/dx_i = 1, h = %.1f dx", ratio);
        CHECK_CLOSE(mxx, 1.0, tol_m, name);
        CHECK_CLOSE(mxy, 0.0, 1e-12, "first moment off-diagonal vanishes");
        snprintf(name, sizeof name, "position divergence is 2 in the bulk, h = %.1f dx", ratio);
        CHECK_CLOSE(divr, 2.0, tol_d, name);
    }
    UNIT_END();
}
