/* Replacing a file whole: every writer (states, CSV, VTK, PNG pictures and animations)
 * writes a temporary file in the target's directory and renames it onto the target only
 * once all of it is written, so a failed write leaves the old file as it was. */
#ifndef SPH_ATOMIC_H
#define SPH_ATOMIC_H

#include <stddef.h>
#include <stdio.h>

typedef struct sph_atomic_file {
    FILE *fp;   /* the temporary file, open for writing (binary)               */
    char *path; /* the target                                                    */
    char *temp; /* the temporary file's name: path + ".tmp.<pid>.<n>"           */
} sph_atomic_file;

/* Create the temporary file for path (never an existing file: O_EXCL). 0, or -1 with a
 * message naming path in err (and nothing created). */
int sph_atomic_open(sph_atomic_file *af, const char *path, char *err, size_t errlen);
/* Flush and close the temporary file and rename it onto the path. 0, or -1 with a
 * message in err: the temporary file is removed and the path left as it was. Either way
 * af is released. */
int sph_atomic_commit(sph_atomic_file *af, char *err, size_t errlen);
/* Close and remove the temporary file, leave the path as it was, release af. */
void sph_atomic_abort(sph_atomic_file *af);

#endif
