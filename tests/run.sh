#!/bin/sh
# The one test runner: the public headers (tests/headers.sh, with $CC), make install
# (tests/install.sh), C unit tests
# (build/tests/test_*) and Lua tests (tests/lua/*.lua, run by the sph host). Every check prints "ok - ..." or "not ok - ..."; a program that
# exits non-zero without a "not ok" line counts as one failure. Ends with the summary line.
B=${1:-build}
# OpenMP threads spin briefly, then sleep, while they wait (as the host sets it, src/main.c):
# libgomp's long default spin on a busy CI machine made test_cavity spend 78 % of its time
# in libgomp, and sleeping at once pays a wake-up at every parallel loop.
export GOMP_SPINCOUNT=${GOMP_SPINCOUNT:-10000}
# A stock lua5.4 loading a sanitizer build's module needs the sanitizer runtime loaded
# first: the tests that run one prefix its command with this (empty for a normal build).
case "$B" in
    *san*) SPH_LUA_PRELOAD="LD_PRELOAD=$(${CC:-cc} -print-file-name=libasan.so) ASAN_OPTIONS=detect_leaks=0" ;;
    *) SPH_LUA_PRELOAD= ;;
esac
export SPH_LUA_PRELOAD
top=$(cd "$(dirname "$0")/.." && pwd)
pass=0; fail=0
start_all=$(date +%s)
run() {
    name=$1; shift
    out=$(mktemp)
    t0=$(date +%s)
    "$@" >"$out" 2>&1
    rc=$?
    secs=$(( $(date +%s) - t0 ))
    p=$(grep -c '^ok - ' "$out"); f=$(grep -c '^not ok - ' "$out")
    if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
        f=1; echo "not ok - $name: exited with status $rc" >>"$out"
    fi
    grep -E '^(not ok - )' "$out"
    if [ "$f" -ne 0 ] || [ "$rc" -ne 0 ]; then tail -n 20 "$out" | grep -v '^ok - '; fi
    printf '%-40s %4d passed, %d failed  %4d s\n' "$name" "$p" "$f" "$secs"
    pass=$((pass + p)); fail=$((fail + f))
    rm -f "$out"
}
# the public headers need only the C library; libsph.a links without cairo or Lua
run headers.sh sh "$top/tests/headers.sh" "$B"
# make install / uninstall into a temporary prefix, used as a C library, a Lua module, a host
run install.sh sh "$top/tests/install.sh" "$B"
for t in "$top/$B"/tests/test_*; do
    [ -x "$t" ] || continue
    run "$(basename "$t")" "$t"
done
for t in "$top"/tests/lua/*.lua; do
    [ -f "$t" ] || continue
    run "$(basename "$t")" "$top/$B/sph" "$t"
done
echo "# $(( $(date +%s) - start_all )) s in all"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
