#!/bin/bash
# The one test runner: the public headers (tests/headers.sh, with $CC), make install
# (tests/install.sh), C unit tests (build/tests/test_*) and Lua tests (tests/lua/*.lua, run
# by the sph host). Every check prints "ok - ..." or "not ok - ..."; a program that exits
# non-zero without a "not ok" line counts as one failure. Ends with the summary line.
# The unit and Lua tests run SPH_TEST_JOBS at a time (default: the cores, at most 4): most
# worlds in them are single-threaded, so one at a time left a core idle. Their reports are
# printed in the order of the list, whatever order they end in.
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
jobs_max=${SPH_TEST_JOBS:-$(nproc 2>/dev/null || echo 1)}
[ "$jobs_max" -gt 4 ] && jobs_max=4
[ "$jobs_max" -ge 1 ] 2>/dev/null || jobs_max=1
# a world's default thread count (threads = 0) follows OMP_NUM_THREADS: one each while two
# programs run at once (two-thread worlds on a shared core wait at every parallel loop:
# test_stability took over 16 minutes instead of 2.5)
[ "$jobs_max" -gt 1 ] && export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
start_all=$(date +%s)
# run NAME CMD...: runs the test, leaves its report in $work/NAME.report and its counts in
# $work/NAME.counts
run() {
    name=$1; shift
    out="$work/$name.out"
    t0=$(date +%s)
    "$@" >"$out" 2>&1
    rc=$?
    secs=$(( $(date +%s) - t0 ))
    p=$(grep -c '^ok - ' "$out"); f=$(grep -c '^not ok - ' "$out")
    if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
        f=1; echo "not ok - $name: exited with status $rc" >>"$out"
    fi
    {
        grep -E '^(not ok - )' "$out"
        if [ "$f" -ne 0 ] || [ "$rc" -ne 0 ]; then tail -n 20 "$out" | grep -v '^ok - '; fi
        printf '%-40s %4d passed, %d failed  %4d s\n' "$name" "$p" "$f" "$secs"
    } >"$work/$name.report"
    echo "$p $f" >"$work/$name.counts"
}
names=()
# the public headers need only the C library; libsph.a links without cairo or Lua
run headers.sh sh "$top/tests/headers.sh" "$B"; names+=(headers.sh)
# make install / uninstall into a temporary prefix, used as a C library, a Lua module, a host
run install.sh sh "$top/tests/install.sh" "$B"; names+=(install.sh)
cat "$work/headers.sh.report" "$work/install.sh.report"
# the longest first, so that the last to start are short ones
list=()
for t in test_stability test_squeeze_validation test_square test_squeeze; do
    [ -f "$top/tests/lua/$t.lua" ] && list+=("lua:$top/tests/lua/$t.lua")
done
for t in "$top/$B"/tests/test_*; do
    [ -x "$t" ] && list+=("c:$t")
done
for t in "$top"/tests/lua/*.lua; do
    case " ${list[*]} " in *" lua:$t "*) continue ;; esac
    [ -f "$t" ] && list+=("lua:$t")
done
running=0
for item in "${list[@]}"; do
    kind=${item%%:*}; path=${item#*:}; name=$(basename "$path")
    names+=("$name")
    if [ "$kind" = c ]; then
        run "$name" "$path" &
    else
        run "$name" "$top/$B/sph" "$path" &
    fi
    running=$((running + 1))
    if [ "$running" -ge "$jobs_max" ]; then
        wait -n
        running=$((running - 1))
    fi
done
wait
pass=0; fail=0
for name in "${names[@]}"; do
    case "$name" in headers.sh|install.sh) ;; *) cat "$work/$name.report" ;; esac
    if [ -f "$work/$name.counts" ]; then
        read -r p f <"$work/$name.counts"
    else
        p=0; f=1; echo "not ok - $name: no report"
    fi
    pass=$((pass + p)); fail=$((fail + f))
done
echo "# $(( $(date +%s) - start_all )) s in all ($jobs_max at a time)"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
