/* Constitutive laws: limits of the Papanastasiou regularisation. */
#include "../../src/sph.h"
#include "unit.h"

int main(void) {
    sph_material newt = {SPH_NEWTONIAN, 2.0, 0, 0, 0, 0};
    sph_material bing = {SPH_BINGHAM, 1.0, 5.0, 800.0, 0, 0};
    sph_material hb = {SPH_HERSCHEL_BULKLEY, 0, 2.0, 300.0, 1.5, 0.5};
    CHECK_CLOSE(sph_rheology_eta(&newt, 0.0), 2.0, 0, "Newtonian eta = mu at rest");
    CHECK_CLOSE(sph_rheology_eta(&newt, 1e3), 2.0, 0, "Newtonian eta = mu at any rate");
    /* gammadot = 0: finite, the limit mu + tau0 m */
    double e0 = sph_rheology_eta(&bing, 0.0);
    CHECK(isfinite(e0), "Bingham eta finite at zero shear rate", "%g", e0);
    CHECK_CLOSE(e0, 1.0 + 5.0 * 800.0, 1e-9, "Bingham eta(0) = mu + tau0 m");
    /* continuity across the series / expm1 switch */
    double a = sph_rheology_eta(&bing, 0.99e-8 / 800), b = sph_rheology_eta(&bing, 1.01e-8 / 800);
    CHECK(fabs(a - b) < 1e-9 * a, "Bingham eta continuous at the series switch", "%.17g vs %.17g", a, b);
    int mono = 1;
    for (int k = 0; k < 200; k++) {
        double g1 = pow(10, -8 + 0.05 * k), g2 = pow(10, -8 + 0.05 * (k + 1));
        mono &= sph_rheology_eta(&bing, g2) <= sph_rheology_eta(&bing, g1);
    }
    CHECK(mono, "Bingham eta decreases with shear rate", "not monotone");
    /* tau0 -> 0 is Newtonian */
    sph_material b0 = {SPH_BINGHAM, 1.0, 1e-12, 800.0, 0, 0};
    CHECK_CLOSE(sph_rheology_eta(&b0, 3.0), 1.0, 1e-12, "Bingham with tau0 -> 0 is Newtonian");
    /* large m approaches the ideal Bingham stress tau = tau0 + mu gammadot */
    double g = 0.1;
    double tau = sph_rheology_eta(&bing, g) * g;
    CHECK_CLOSE(tau, 5.0 + 1.0 * g, 1e-12, "large m: stress tends to tau0 + mu gammadot");
    sph_material bm = {SPH_BINGHAM, 1.0, 5.0, 1e6, 0, 0};
    CHECK_CLOSE(sph_rheology_eta(&bm, 1e-3) * 1e-3, 5.0 + 1e-3, 1e-9, "m = 1e6: ideal Bingham at gammadot = 1e-3");
    /* Herschel-Bulkley: finite at rest, power law at high rate */
    double h0 = sph_rheology_eta(&hb, 0.0);
    CHECK(isfinite(h0) && h0 > 0, "Herschel-Bulkley eta finite at zero shear rate", "%g", h0);
    CHECK_CLOSE(sph_rheology_eta(&hb, 100.0), 1.5 * pow(100.0, -0.5) + 2.0 / 100.0, 1e-12,
                "Herschel-Bulkley: K g^(n-1) + tau0 / g at high rate");
    sph_material hb1 = {SPH_HERSCHEL_BULKLEY, 0, 0.0, 300.0, 1.5, 1.0};
    CHECK_CLOSE(sph_rheology_eta(&hb1, 7.0), 1.5, 1e-12, "Herschel-Bulkley with n = 1, tau0 = 0 is Newtonian");
    /* validation */
    sph_material bad = {SPH_BINGHAM, 1.0, -1.0, 800.0, 0, 0};
    CHECK(sph_rheology_check(&bad) != 0, "negative tau0 is rejected", "accepted");
    CHECK(sph_rheology_check(&bing) == 0, "valid Bingham accepted", "%s", sph_rheology_check(&bing));
    UNIT_END();
}
