#!/bin/sh
# Benchmarks (not tests: they print timings and never fail on them), run by `make bench`:
#   - the headline Bingham squeeze (scripts/bench_squeeze.lua) at dx = 1/40 and 1/80 with
#     1 and 2 threads: median over BENCH_RUNS runs (default 3) of steps/s and microseconds
#     per particle-step, pressure-solver iterations per step;
#   - the renderer (tests/bench/bench_render.c): 100 000 particles to PNG, median of 5;
#   - the scaling of the step (scripts/bench_scaling.lua): the paper's squeeze (Bn = 5,
#     M = 800, Re = 1, V = -1) from 10^3 particles up to BENCH_MAX_N (default 120000; the
#     10^6 row is opt-in, BENCH_MAX_N=1000000: several minutes a run), steps 21-80 at a
#     fixed dt = dx/40 after 20 adaptive steps (BENCH_DT=adaptive: the engine's own step),
#     1 and 2 threads: ns per particle-step, solver iterations per step and the share of
#     each phase of the step; writes out/bench/scaling.csv and scaling.png.
#   - speed against error (scripts/bench_validation.lua): every validation case (modules
#     sph.flows and sph.squeeze_validation) at each of its resolutions, BENCH_RUNS repeats,
#     median wall time; the table goes to out/bench/validation.txt and validation.csv, the
#     plot to out/bench/error_vs_time.png. Much the longest part (minutes: the finest
#     resolutions); `only=WORD[,WORD]` runs the cases whose name contains a word,
#     `only=none` skips them, `quick=1` takes the quick resolutions:
#       make bench only=Newtonian        sh scripts/bench.sh build only=Bingham quick=1
# Prints the tables and writes them to out/bench/bench.txt. About 20 s on an idle 2-core
# machine for the first two, a few minutes for the scaling up to 1.2e5 particles;
# threads = 2 slows down many times over when another program holds a core (every
# step has hundreds of OpenMP fork/joins, several per pressure-solver iteration), so the
# CPU time other programs took during the bench is recorded with the figures.
#   sh scripts/bench.sh [BUILD_DIR] [only=...] [quick=1]       BENCH_RUNS=5 sh scripts/bench.sh
set -eu
B=${1:-build}
[ $# -gt 0 ] && shift
only=${only:-}
quick=${quick:-}
for a in "$@"; do
    case $a in
        only=*) only=${a#only=} ;;
        quick=*) quick=${a#quick=} ;;
        *) echo "bench.sh: unknown argument '$a' (only=..., quick=1 expected)" >&2; exit 2 ;;
    esac
done
top=$(cd "$(dirname "$0")/.." && pwd)
cd "$top"
runs=${BENCH_RUNS:-3}
max_n=${BENCH_MAX_N:-120000}
case $max_n in
    '' | *[!0-9]* | 0) echo "bench.sh: BENCH_MAX_N must be a positive integer, got '$max_n'" >&2; exit 2 ;;
esac
case $runs in
    '' | *[!0-9]* | 0) echo "bench.sh: BENCH_RUNS must be a positive integer, got '$runs'" >&2; exit 2 ;;
esac
case $B in
    build-san) mk="SANITIZE=1 OPT=-O1" ;;
    *) mk="" ;;
esac
# build first, unless `make bench` has (a nested make would lose the parent's jobserver)
if [ -z "${MAKELEVEL:-}" ]; then
    # shellcheck disable=SC2086 # $mk is a list of make variables
    make -s $mk all "$B/bench_render"
fi

out=out/bench
mkdir -p "$out"
txt=$out/bench.txt
tmp=$(mktemp)
trap 'rm -f "$tmp" "$tmp.t" "$tmp.c" "$tmp.p"' EXIT

# How busy the machine was: CPU time used by the whole machine during the bench (from
# /proc/stat) minus the bench's own (the shell's `times` for its children), over the wall time.
busy() { awk '/^cpu / { print ($2 + $3 + $4 + $7 + $8) / '"$(getconf CLK_TCK 2>/dev/null || echo 100)"' }' /proc/stat; }
uptime_s() { cut -d' ' -f1 /proc/uptime; }
own_cpu() { # children's user + system seconds, from the second line of `times` (0m1.23s 0m0.04s);
    # `times` in this shell, not in a $(...) subshell, which has no children of its own
    times >"$tmp.t"
    awk 'NR == 2 { s = 0; for (i = 1; i <= 2; i++) { split($i, a, /[ms]/); s += 60 * a[1] + a[2] }; print s }' "$tmp.t" >"$tmp.c"
    read -r own <"$tmp.c"
}
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo 2>/dev/null | head -n 1)
rev=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
if [ -n "$(git status --porcelain --untracked-files=no 2>/dev/null)" ]; then rev="$rev+changes"; fi
load0=$(cut -d' ' -f1-3 /proc/loadavg)
busy0=$(busy); up0=$(uptime_s); own_cpu; own0=$own
# each section is printed and kept for the file; a failing program stops the bench
# (a pipe into tee would hide its exit status from set -e)
section() {
    "$@" >"$tmp.p"
    cat "$tmp.p"
    cat "$tmp.p" >>"$tmp"
}
header() {
    echo "sph bench  $(date '+%Y-%m-%d %H:%M')  commit $rev  $B"
    echo "machine: ${cpu:-unknown CPU}, $(nproc 2>/dev/null || echo '?') cores"
    echo
    echo "Bingham squeeze, Re = 10, Bn = 0.5, M = 100, V = -1 (scripts/bench_squeeze.lua):"
    echo "median of $runs runs, after 20 untimed steps; particles = fluid + wall"
}
section header
section "$B/sph" scripts/bench_squeeze.lua runs="$runs"
section printf '\nrenderer, 100 000 particles (tests/bench/bench_render.c):\n'
section "$B/bench_render" "$out"
dt_rule=${BENCH_DT:-0.025}
dt_label="$dt_rule dx"
[ "$dt_rule" = adaptive ] && dt_label=adaptive
section printf '\nscaling of the step: squeeze Bn = 5, M = 800, Re = 1, V = -1, steps 21-80, after 20 adaptive steps, dt = %s (scripts/bench_scaling.lua):\n' "$dt_label"
section "$B/sph" scripts/bench_scaling.lua max_n="$max_n" out="$out" dt="$dt_rule"
# the validation cases, printed row by row as they finish (minutes) and written by the
# driver to out/bench/validation.txt; a failed run (an engine error) is printed as FAILED
# and the driver exits 1 once its table, CSV and plot are written: the bench goes on and
# fails at the end
vstatus=0
if [ "$only" != none ]; then
    section printf '\nspeed against error, validation cases (scripts/bench_validation.lua), threads = 1:\n'
    set -- runs="$runs" out="$out"
    [ -n "$only" ] && set -- "$@" only="$only"
    [ -n "$quick" ] && set -- "$@" quick="$quick"
    rm -f "$out/validation.txt"
    "$B/sph" scripts/bench_validation.lua "$@" || vstatus=$?
    if [ -f "$out/validation.txt" ]; then cat "$out/validation.txt" >>"$tmp"; fi
fi
busy1=$(busy); up1=$(uptime_s); own_cpu; own1=$own
others=$(awk -v b0="$busy0" -v b1="$busy1" -v o0="$own0" -v o1="$own1" -v u0="$up0" -v u1="$up1" \
    'BEGIN { x = ((b1 - b0) - (o1 - o0)) / (u1 - u0); printf "%.2f", x < 0 ? 0 : x }')
footer() {
    echo
    echo "other programs used $others cores on average during the bench (load average at start: $load0)"
    if awk -v x="$others" 'BEGIN { exit !(x > 0.1) }'; then
        echo "note: the machine was busy: timings are disturbed, threads = 2 most (see the spread column)"
    fi
}
section footer
cat "$tmp" >"$txt"
echo "wrote $txt"
if [ "$vstatus" -ne 0 ]; then
    echo "bench.sh: validation runs FAILED (status $vstatus): see the table above" >&2
    exit "$vstatus"
fi
