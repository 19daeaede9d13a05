#!/bin/sh
# make install and make uninstall as a user runs them (issue 29), into a temporary prefix
# (no root, a few seconds): the files land where they should (libsph.so with its soname,
# sph.pc, the Lua module in the standard 5.4 layout); a C program builds with
# `pkg-config --cflags --libs sph` against libsph.so and with the static flags against
# libsph.a, and runs a step, and so does the installed examples/squeeze.c built with the
# command its comment gives; a stock lua5.4 with LUA_CPATH / LUA_PATH into the prefix
# requires "sph" and "sph.params" from it and runs a step; the installed host, with the
# prefix copied elsewhere and the original moved away, takes its helpers from the copy
# (package.path names no folder of the build tree) and runs a short squeeze and an
# installed example; make uninstall leaves no file in the prefix; the same with DESTDIR.
# Usage: tests/install.sh [BUILD_DIR]   (CC from the environment, default cc)
B=${1:-build}
CC=${CC:-cc}
top=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d /tmp/sph_install_XXXXXX) || exit 1
trap 'rm -rf "$tmp"' EXIT
prefix=$tmp/prefix
# make check's build: install that one, and link the test programs with the sanitizers
san=; make_san=
case "$B" in *san*) san="-fsanitize=address,undefined"; make_san="SANITIZE=1 OPT=-O1";; esac
# run from make test: a make of our own, not a job of the parent's jobserver
unset MAKEFLAGS MFLAGS MAKELEVEL
unset SPH_LUA_DIR
export OMP_WAIT_POLICY=passive
export PKG_CONFIG_PATH="$prefix/lib/pkgconfig"
version=$(sed -n 's/.*define SPH_VERSION "\(.*\)".*/\1/p' "$top/src/sph.h")
soname=libsph.so.${version%%.*}
status=0
check() { # check NAME COMMAND...: "ok - NAME" when COMMAND succeeds
    name=$1; shift
    if "$@" >"$tmp/out" 2>&1; then echo "ok - $name"
    else echo "not ok - $name"; sed 's/^/#   /' "$tmp/out" | tail -n 30; status=1; fi
}
mk() { make -s -C "$top" $make_san CC="$CC" "$@"; }

check "make install PREFIX=$prefix" mk install PREFIX="$prefix"

files="bin/sph include/sph.h include/sph_pictures.h lib/libsph.a lib/libsph.so lib/$soname
       lib/libsph.so.$version lib/pkgconfig/sph.pc lib/lua/5.4/sph.so share/lua/5.4/sph/params.lua
       share/lua/5.4/sph/squeeze.lua share/sph/scripts/squeeze.lua share/sph/examples/README.md
       share/sph/examples/squeeze_velocity.lua share/sph/examples/squeeze.c share/doc/sph/README.md
       share/doc/sph/docs/api.md"
installed() { # every file of $files under the prefix; names the missing ones
    m=0
    for f in $files; do [ -e "$prefix/$f" ] || { echo "missing: $f"; m=1; }; done
    return $m
}
check "the headers, libraries, pkg-config file, Lua module and helpers, host, scripts, examples and docs are installed" installed
check "libsph.so and $soname link to libsph.so.$version, whose soname is $soname" \
    sh -c "[ \"\$(readlink '$prefix/lib/libsph.so')\" = libsph.so.$version ] &&
           [ \"\$(readlink '$prefix/lib/$soname')\" = libsph.so.$version ] &&
           readelf -d '$prefix/lib/libsph.so.$version' | grep -q 'SONAME.*\\[$soname\\]'"
check "pkg-config knows sph $version" sh -c "[ \"\$(pkg-config --modversion sph)\" = '$version' ]"

# the README's C program (with one thread on a shared machine)
cat >"$tmp/prog.c" <<'EOC'
#include <sph.h>
#include <stdio.h>
int main(void) {
    sph_params p; sph_params_default(&p); p.dx = 0.1; p.threads = 1;
    sph_world *w = sph_world_new(&p, NULL, 0);
    sph_material water = {SPH_NEWTONIAN, 1, 0, 0, 0, 0};
    sph_world_fill(w, (double[4]){0, 0, 1, 1}, &water);            /* 100 particles */
    sph_world_plate(w, (double[4]){-0.5, -0.4, 1.5, 0}, -1);       /* a fixed plate under them */
    sph_world_step(w, 0);
    printf("%d particles, %ld step, t = %g\n", sph_world_nfluid(w), sph_world_steps(w), sph_world_time(w));
    sph_world_free(w);
}
EOC
cflags="-std=c11 -Wall -Wextra -Werror $san"
check "a C program builds with \`pkg-config --cflags --libs sph\` (libsph.so)" \
    sh -c "$CC $cflags -o '$tmp/prog' '$tmp/prog.c' \$(pkg-config --cflags --libs sph) &&
           readelf -d '$tmp/prog' | grep -q 'NEEDED.*\\[$soname\\]'"
check "it runs a step against the installed libsph.so" \
    sh -c "LD_LIBRARY_PATH='$prefix/lib' '$tmp/prog' | grep -q '^100 particles, 1 step'"
# static: libsph.a, then what it needs from `pkg-config --libs --static sph` (cairo, libm,
# OpenMP); --as-needed drops the -lsph that the archive has already resolved
check "it builds with the static flags against libsph.a (pkg-config --libs --static sph)" \
    sh -c "$CC $cflags -o '$tmp/prog_static' '$tmp/prog.c' \$(pkg-config --cflags sph) -Wl,--as-needed \
           -Wl,-Bstatic -lsph -Wl,-Bdynamic \$(pkg-config --libs --static sph) &&
           ! readelf -d '$tmp/prog_static' | grep -q 'NEEDED.*libsph'"
check "and runs a step without libsph.so" sh -c "'$tmp/prog_static' | grep -q '^100 particles, 1 step'"

# the installed C example, built with the command its comment gives (with $CC)
example_c() {
    mkdir -p "$tmp/exc" && cp "$prefix/share/sph/examples/squeeze.c" "$tmp/exc/" || return 1
    cmd=$(sed -n 's/^ \*   cc /'"$CC $san"' /p' "$tmp/exc/squeeze.c")
    echo "$cmd"
    [ -n "$cmd" ] && (cd "$tmp/exc" && eval "$cmd") &&
        LD_LIBRARY_PATH="$prefix/lib" "$tmp/exc/squeeze" steps=2 threads=1 out="$tmp/exc/out" &&
        [ -s "$tmp/exc/out/series.csv" ] && [ -s "$tmp/exc/out/yield.png" ]
}
check "the installed examples/squeeze.c builds with the command in its comment and runs" example_c
# it draws a picture: cairo comes from sph.pc's Requires.private with --static
example_c_static() {
    $CC $san -std=c11 -O2 -o "$tmp/exc/squeeze_static" "$tmp/exc/squeeze.c" $(pkg-config --cflags sph) \
        -Wl,--as-needed -Wl,-Bstatic -lsph -Wl,-Bdynamic $(pkg-config --libs --static sph) &&
        ! readelf -d "$tmp/exc/squeeze_static" | grep -q 'NEEDED.*libsph' &&
        "$tmp/exc/squeeze_static" steps=2 threads=1 out="$tmp/exc/out_static" && [ -s "$tmp/exc/out_static/yield.png" ]
}
check "and with the static flags against libsph.a (cairo from Requires.private), and runs" example_c_static

# a stock lua5.4 with the standard 5.4 layout under the prefix (and nothing else) on its paths
stock_lua() {
    pre="env $SPH_LUA_PRELOAD" # a sanitizer build's module needs their runtime first (tests/run.sh)
    $pre LUA_CPATH="$prefix/lib/lua/5.4/?.so" LUA_PATH="$prefix/share/lua/5.4/?.lua" lua5.4 -e '
        local sph = require "sph"
        local params = require "sph.params"
        local w = sph.world{ dx = 0.1, threads = 1 }
        w:fill{ rect = { 0, 0, 1, 1 }, material = sph.newtonian{ mu = 1 } }
        w:plate{ rect = { -0.5, -0.4, 1.5, 0 } }
        w:step()
        print(package.searchpath("sph", package.cpath))
        print(package.searchpath("sph.params", package.path))
        print(w:stats().fluid, w.steps, params.parse("x", { { "n", "integer", 3 } }, "n=4").n)' >"$tmp/lua.out" || return 1
    cat "$tmp/lua.out"
    [ "$(sed -n 1p "$tmp/lua.out")" = "$prefix/lib/lua/5.4/sph.so" ] &&
        [ "$(sed -n 2p "$tmp/lua.out")" = "$prefix/share/lua/5.4/sph/params.lua" ] &&
        [ "$(sed -n 3p "$tmp/lua.out" | tr -s ' \t' ' ')" = "100 1 4" ]
}
if command -v lua5.4 >/dev/null 2>&1; then
    check "lua5.4 requires sph and sph.params from the prefix and runs a step" stock_lua
else
    echo "# lua5.4 not installed: the stock-Lua check is skipped"
fi

# the installed host, moved: the prefix copied elsewhere and the original removed
cat >"$tmp/where.lua" <<'EOL'
print(package.searchpath("sph.params", package.path))
print(package.path)
EOL
where_ok() { # where_ok HOST DIR: the host takes the helpers from DIR, and names no other sph folder
    "$1" "$tmp/where.lua" >"$tmp/where" 2>&1 && [ "$(sed -n 1p "$tmp/where")" = "$2/sph/params.lua" ] &&
        ! sed -n 2p "$tmp/where" | tr ';' '\n' | grep -v "^$2/" | grep -q "^$top/"
}
check "the installed host takes its Lua helpers from PREFIX/share/lua/5.4" where_ok "$prefix/bin/sph" "$prefix/share/lua/5.4"
cp -R "$prefix" "$tmp/moved" && mv "$prefix" "$tmp/away"
check "moved elsewhere, it takes them from its new prefix (never the build tree's lua/)" \
    where_ok "$tmp/moved/bin/sph" "$tmp/moved/share/lua/5.4"
check "and runs the installed squeeze script (t_end=0.01 dx=0.05)" \
    sh -c "'$tmp/moved/bin/sph' '$tmp/moved/share/sph/scripts/squeeze.lua' t_end=0.01 dx=0.05 threads=1 out='$tmp/sq' &&
           grep -q . '$tmp/sq/series.csv'"
check "and an installed example that uses the helpers (cavity.lua, steps=2)" \
    sh -c "'$tmp/moved/bin/sph' '$tmp/moved/share/sph/examples/cavity.lua' steps=2 threads=1 out='$tmp/cav' &&
           [ -s '$tmp/cav/profiles.csv' ]"
check "SPH_LUA_DIR still comes first" sh -c "SPH_LUA_DIR='$top/lua' '$tmp/moved/bin/sph' '$tmp/where.lua' | grep -qx '$top/lua/sph/params.lua'"
check "the build tree's host takes the build tree's lua/" where_ok "$top/$B/sph" "$top/lua"
rm -rf "$tmp/moved"; mv "$tmp/away" "$prefix"

check "make uninstall PREFIX=$prefix" mk uninstall PREFIX="$prefix"
check "leaves no file in the prefix, nor sph's folders" \
    sh -c "[ -z \"\$(find '$prefix' ! -type d)\" ] && [ ! -e '$prefix/share/sph' ] &&
           [ ! -e '$prefix/share/doc/sph' ] && [ ! -e '$prefix/share/lua/5.4/sph' ]"

# DESTDIR: staged under it, for PREFIX (the pkg-config file names PREFIX, not the stage)
stage=$tmp/stage
check "make install DESTDIR=... PREFIX=/opt/sph stages the files under DESTDIR/opt/sph" \
    sh -c "make -s -C '$top' $make_san CC='$CC' install DESTDIR='$stage' PREFIX=/opt/sph &&
           [ -x '$stage/opt/sph/bin/sph' ] && grep -qx 'prefix=/opt/sph' '$stage/opt/sph/lib/pkgconfig/sph.pc' &&
           [ -z \"\$(find '$stage' ! -type d ! -path '$stage/opt/sph/*')\" ]"
check "make uninstall DESTDIR=... PREFIX=/opt/sph removes them" \
    sh -c "make -s -C '$top' $make_san CC='$CC' uninstall DESTDIR='$stage' PREFIX=/opt/sph &&
           [ -z \"\$(find '$stage' ! -type d)\" ]"
exit $status
