/* Minimal unit-test harness: each check prints "ok - name" or "not ok - name: why";
   tests/run.sh counts the lines and prints the one summary line. */
#ifndef SPH_UNIT_H
#define SPH_UNIT_H
#include <math.h>
#include <stdio.h>

static int unit_fail_count;

#define CHECK(cond, name, ...)                                              \
    do {                                                                    \
        if (cond) {                                                         \
            printf("ok - %s\n", name);                                      \
        } else {                                                            \
            unit_fail_count++;                                              \
            printf("not ok - %s: ", name);                                  \
            printf(__VA_ARGS__);                                            \
            printf(" (%s:%d)\n", __FILE__, __LINE__);                       \
        }                                                                   \
        fflush(stdout);                                                     \
    } while (0)

/* |a - b| <= tol, printing both values when it fails */
#define CHECK_CLOSE(a, b, tol, name)                                        \
    do {                                                                    \
        double ua_ = (a), ub_ = (b), ut_ = (tol);                           \
        CHECK(fabs(ua_ - ub_) <= ut_, name, "%.12g vs %.12g (|diff| %.3g > %.3g)", \
              ua_, ub_, fabs(ua_ - ub_), ut_);                              \
    } while (0)

#define UNIT_END() return unit_fail_count ? 1 : 0

#endif
