/* Replacing a file whole (atomic.h): write a temporary file next to the target, rename it
 * into place. rename within one directory replaces the target in one step on POSIX, so a
 * reader sees the old file or the new one, never a part. */
#include "atomic.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "message.h"

static void release(sph_atomic_file *af) {
    free(af->path);
    free(af->temp);
    af->fp = 0;
    af->path = af->temp = 0;
}

int sph_atomic_open(sph_atomic_file *af, const char *path, char *err, size_t errlen) {
    memset(af, 0, sizeof *af);
    if (!path || !*path)
        return sph_message_set(err, errlen, "no output file name");
    size_t len = strlen(path), cap = len + 64;
    af->path = malloc(len + 1);
    af->temp = malloc(cap);
    if (!af->path || !af->temp) {
        release(af);
        return sph_message_set(err, errlen, "cannot write '%s': out of memory", path);
    }
    memcpy(af->path, path, len + 1);
    /* A name no one else uses: the pid tells processes apart, the clock and the attempt
     * tell apart the calls of one process (threads, a leftover of a crashed run); O_EXCL
     * makes a clash an EEXIST and another try, never a shared file. 0666 as fopen would
     * create it (less the umask). */
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    int fd = -1, e = 0;
    for (int attempt = 0; attempt < 100 && fd < 0; attempt++) {
        snprintf(af->temp, cap, "%s.tmp.%ld.%lx", path, (long)getpid(),
                 ((unsigned long)ts.tv_nsec ^ ((unsigned long)ts.tv_sec << 20)) + (unsigned long)attempt * 7919u);
        fd = open(af->temp, O_WRONLY | O_CREAT | O_EXCL, 0666);
        e = errno;
        if (fd < 0 && e != EEXIST) break;
    }
    if (fd < 0) {
        release(af);
        return sph_message_set(err, errlen, "cannot open '%s' for writing: %s", path, strerror(e));
    }
    /* an existing target keeps its permissions, as when it was written in place */
    struct stat st;
    if (stat(path, &st) == 0 && S_ISREG(st.st_mode)) (void)fchmod(fd, st.st_mode & 07777);
    af->fp = fdopen(fd, "wb");
    if (!af->fp) {
        e = errno;
        close(fd);
        unlink(af->temp);
        release(af);
        return sph_message_set(err, errlen, "cannot open '%s' for writing: %s", path, strerror(e));
    }
    return 0;
}

int sph_atomic_commit(sph_atomic_file *af, char *err, size_t errlen) {
    int bad = ferror(af->fp), e = errno;
    if (fflush(af->fp) != 0 && !bad) bad = 1, e = errno;
    if (fclose(af->fp) != 0 && !bad) bad = 1, e = errno;
    af->fp = 0;
    if (bad) {
        int rc = sph_message_set(err, errlen, "cannot write '%s': %s", af->path, strerror(e ? e : EIO));
        unlink(af->temp);
        release(af);
        return rc;
    }
    if (rename(af->temp, af->path) != 0) {
        e = errno;
        int rc = sph_message_set(err, errlen, "cannot replace '%s': %s", af->path, strerror(e));
        unlink(af->temp);
        release(af);
        return rc;
    }
    release(af);
    return 0;
}

void sph_atomic_abort(sph_atomic_file *af) {
    if (af->fp) fclose(af->fp);
    if (af->temp) unlink(af->temp);
    release(af);
}
