/* Error messages into a caller's buffer: the one formatter the pictures layer shares. */
#include "message.h"

#include <stdarg.h>
#include <stdio.h>

int sph_message_set(char *err, size_t errlen, const char *fmt, ...) {
    va_list ap;
    if (err && errlen) {
        va_start(ap, fmt);
        vsnprintf(err, errlen, fmt, ap);
        va_end(ap);
    }
    return -1;
}
