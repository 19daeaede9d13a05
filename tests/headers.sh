#!/bin/sh
# The public headers as a C user sees them (issue 28): src/sph.h and src/sph_pictures.h,
# copied alone into an empty directory as `make install` puts them, must compile with only
# the C standard library (no cairo, Lua or OpenMP include path), pedantic C11 and no
# warnings, and must not pull in cairo's headers; and a program that includes sph.h alone
# links against libsph.a with no cairo and no Lua ("no Lua, no display") and runs a step.
# Usage: tests/headers.sh [BUILD_DIR]   (CC from the environment, default cc)
B=${1:-build}
CC=${CC:-cc}
top=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d /tmp/sph_headers_XXXXXX) || exit 1
trap 'rm -rf "$tmp"' EXIT
mkdir "$tmp/include"
cp "$top/src/sph.h" "$top/src/sph_pictures.h" "$tmp/include/"
flags="-std=c11 -Wall -Wextra -pedantic -Werror -I$tmp/include"
status=0
check() { # check NAME COMMAND...: "ok - NAME" when COMMAND succeeds
    name=$1; shift
    if "$@" >"$tmp/out" 2>&1; then echo "ok - $name"
    else echo "not ok - $name"; sed 's/^/#   /' "$tmp/out"; status=1; fi
}
for h in sph.h sph_pictures.h; do
    check "$h compiles alone with only the C library" \
        sh -c "echo '#include \"$h\"' | $CC $flags -fsyntax-only -x c -"
    # the preprocessed header names no cairo file (also where cairo.h is on the default path)
    check "$h includes no cairo header" \
        sh -c "echo '#include \"$h\"' | $CC $flags -E -x c - >'$tmp/pp.i' &&
               ! grep -qi cairo '$tmp/pp.i'"
done
check "sph.h and sph_pictures.h together, in either order" \
    sh -c "printf '#include \"sph_pictures.h\"\n#include \"sph.h\"\n#include \"sph_pictures.h\"\n' |
           $CC $flags -fsyntax-only -x c -"
cat >"$tmp/embed.c" <<'EOC'
#include "sph.h"
#include <stdio.h>
int main(void) {
    char err[256];
    sph_params p;
    sph_params_default(&p);
    p.dx = 0.1;
    p.threads = 1;
    sph_world *w = sph_world_new(&p, err, sizeof err);
    if (!w) { fprintf(stderr, "%s\n", err); return 1; }
    sph_material m = {SPH_NEWTONIAN, 1, 0, 0, 0, 0};
    const double fluid[4] = {0, 0, 1, 1}, wall[4] = {-0.5, -0.4, 1.5, 0};
    if (sph_world_fill(w, fluid, &m) <= 0 || sph_world_plate(w, wall, -1) < 0 ||
        sph_world_step(w, 0) < 0) {
        fprintf(stderr, "%s\n", sph_world_error(w));
        sph_world_free(w);
        return 1;
    }
    printf("%d %ld\n", sph_world_nfluid(w), sph_world_steps(w));
    sph_world_free(w);
    return 0;
}
EOC
if [ -f "$top/$B/libsph.a" ]; then
    check "a C program with sph.h alone links against libsph.a without cairo or Lua" \
        $CC $flags -fopenmp -o "$tmp/embed" "$tmp/embed.c" "$top/$B/libsph.a" -lm -fopenmp \
        $(case "$B" in *san*) echo -fsanitize=address,undefined;; esac)
    check "that program runs a step" sh -c "'$tmp/embed' | grep -qx '100 1'"
else
    echo "not ok - $B/libsph.a missing: build first (make)"; status=1
fi
exit $status
