/* Exported forms of the inline kernel, for tests and embedders. */
#include "kernel.h"

double sph_kernel_w(double r, double h);
double sph_kernel_dw(double r, double h);

double sph_kernel_w(double r, double h) { return sph_kernel_value(r, h); }
double sph_kernel_dw(double r, double h) { return sph_kernel_deriv(r, h); }
