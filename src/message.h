/* Error messages into a caller's buffer (the pictures layer's convention). */
#ifndef SPH_MESSAGE_H
#define SPH_MESSAGE_H

#include <stddef.h>

/* Format into err (when err and errlen are set) and return -1. */
int sph_message_set(char *err, size_t errlen, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

#endif
