/* Quintic spline kernel (Morris, Fox & Zhu 1997), 2D, support 3h.
 * W(s) = 7/(478 pi h^2) [ (3-s)^5 - 6 (2-s)^5 + 15 (1-s)^5 ], each term only where its
 * bracket is positive. Written branch-light: each (k - s)_+ is a max, so the compiler can
 * vectorise loops over pairs. */
#ifndef SPH_KERNEL_H
#define SPH_KERNEL_H

#include <math.h>

#define SPH_PI 3.14159265358979323846

#define SPH_KERNEL_SUPPORT 3.0 /* in units of h */

static inline double sph_kernel_pos5(double a) {
    a = a > 0.0 ? a : 0.0;
    double a2 = a * a;
    return a2 * a2 * a;
}

static inline double sph_kernel_pos4(double a) {
    a = a > 0.0 ? a : 0.0;
    double a2 = a * a;
    return a2 * a2;
}

/* The bracket of W at s = r / h (W = 7/(478 pi h^2) sph_kernel_shape(s)), and the one of
 * dW/dr (dW/dr = -5 * 7/(478 pi h^3) sph_kernel_dshape(s)): the hot loops (neighbours.c,
 * shifting.c) take these with their constants hoisted. */
static inline double sph_kernel_shape(double s) {
    return sph_kernel_pos5(3.0 - s) - 6.0 * sph_kernel_pos5(2.0 - s) + 15.0 * sph_kernel_pos5(1.0 - s);
}

static inline double sph_kernel_dshape(double s) {
    return sph_kernel_pos4(3.0 - s) - 6.0 * sph_kernel_pos4(2.0 - s) + 15.0 * sph_kernel_pos4(1.0 - s);
}

/* W(r, h) */
static inline double sph_kernel_value(double r, double h) {
    double c = 7.0 / (478.0 * SPH_PI * h * h);
    return c * sph_kernel_shape(r / h);
}

/* dW/dr (<= 0) */
static inline double sph_kernel_deriv(double r, double h) {
    double c = -5.0 * 7.0 / (478.0 * SPH_PI * h * h * h);
    return c * sph_kernel_dshape(r / h);
}

#endif
