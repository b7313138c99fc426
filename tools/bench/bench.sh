#!/bin/sh
# bench.sh -- `make bench` and `make bench-quick` (issue 12): carom's methods,
# Box2D 2.4.1 and Box2D v3 timed side by side, operation counts, the
# profiler's cost, callgrind hotspots; writes a markdown report and, for
# the full run, the figures docs/bench-gas.png and docs/bench-pile.png.
#
#   sh tools/bench/bench.sh --bench build/carom-bench --ops build/carom-bench-ops
#                           [--plain build/bench/carom-bench-plain]
#                           [--out docs/benchmarks.md] [--work build/bench]
#                           [--build TEXT] [--quick] [--no-callgrind]
#
# --bench    the timing build of tools/bench/bench.c (plain library, Box2D)
# --ops      the same driver linked with the profiling library
# --plain    the same driver with bare C arithmetic (CR_ARITH_PLAIN): with it
#            the profiler's cost is measured too
# --quick    10^2 and 10^3 bodies, 3 repetitions, no figures (about 1 min)
# --build    how carom was compiled, for the report
# Every number in the report comes from this run. The full run takes about
# 10 minutes on a 2-CPU machine (a run stops timing after 30 s, a settling
# run after 20 s). Needs python3; valgrind for the hotspots (skipped
# without it), gnuplot for the figures (skipped without it).
set -eu

bench=""
ops=""
plain=""
out=docs/benchmarks.md
work=build/bench
build="carom built by the Makefile"
quick=0
callgrind=1

usage() {
    awk 'NR == 1 { next } /^set -eu/ { exit } { sub(/^# ?/, ""); print }' "$0"
}
need_value() {
    [ $# -ge 2 ] || { echo "bench.sh: $1 needs a value (try --help)" >&2; exit 2; }
}
while [ $# -gt 0 ]; do
    case "$1" in
    --bench) need_value "$@"; bench="$2"; shift 2 ;;
    --ops) need_value "$@"; ops="$2"; shift 2 ;;
    --plain) need_value "$@"; plain="$2"; shift 2 ;;
    --out) need_value "$@"; out="$2"; shift 2 ;;
    --work) need_value "$@"; work="$2"; shift 2 ;;
    --build) need_value "$@"; build="$2"; shift 2 ;;
    --quick) quick=1; shift ;;
    --no-callgrind) callgrind=0; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "bench.sh: unknown argument '$1' (try --help)" >&2; exit 2 ;;
    esac
done
for exe in "$bench" "$ops"; do
    if [ -z "$exe" ] || [ ! -x "$exe" ]; then
        echo "bench.sh: '$exe' is not an executable: give --bench and --ops (make bench builds them)" >&2
        exit 2
    fi
done
if [ -n "$plain" ] && [ ! -x "$plain" ]; then
    echo "bench.sh: --plain '$plain' is not an executable" >&2
    exit 2
fi
command -v python3 >/dev/null 2>&1 || { echo "bench.sh: python3 is needed for the report" >&2; exit 2; }
here=$(dirname "$0")
mkdir -p "$work"
start=$(date +%s)

# 1. time per step, every engine, alternated; then the settled pile
if [ "$quick" = 1 ]; then
    echo "bench.sh: timing (quick: 10^2, 10^3 bodies)" >&2
    "$bench" --quick --settle 1000 > "$work/time.txt"
else
    echo "bench.sh: timing (10^2 to 10^5 bodies)" >&2
    "$bench" --budget 30 --settle 1000,10000 --settle-max 3600 --settle-budget 120 > "$work/time.txt"
fi

# 2. operation counts of the same steps (profiling build)
echo "bench.sh: operation counts" >&2
if [ "$quick" = 1 ]; then
    "$ops" --ops --quick > "$work/ops.txt"
else
    "$ops" --ops > "$work/ops.txt"
fi

# 3. the profiler's cost: the same runs with the library built four ways,
# alternated, CPU time per step (the ns_step of a --run record)
: > "$work/overhead.txt"
if [ -n "$plain" ]; then
    echo "bench.sh: the profiler's cost" >&2
    run_ns() { # exe args... -> ns per step
        "$@" | sed -n 's/.* ns_step=\([0-9.]*\) .*/\1/p'
    }
    median() {
        sort -g | awk '{ v[NR] = $1 } END { if (NR == 0) print "nan"; else if (NR % 2) print v[(NR + 1) / 2]; else print (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
    }
    for spec in "gas 1000 events 120" "pile 1000 discrete 60"; do
        # shellcheck disable=SC2086 # four words
        set -- $spec
        : > "$work/o.default"; : > "$work/o.plain"; : > "$work/o.detached"; : > "$work/o.counting"
        r=0
        while [ $r -lt 5 ]; do
            run_ns "$bench" --run "$1" "$2" "$3" --steps "$4" --warmup 1 >> "$work/o.default"
            run_ns "$plain" --run "$1" "$2" "$3" --steps "$4" --warmup 1 >> "$work/o.plain"
            run_ns "$ops" --run "$1" "$2" "$3" --steps "$4" --warmup 1 >> "$work/o.detached"
            run_ns "$ops" --run "$1" "$2" "$3" --steps "$4" --warmup 1 --count >> "$work/o.counting"
            r=$((r + 1))
        done
        echo "overhead scene=$1 n=$2 engine=$3 steps=$4 default=$(median < "$work/o.default") plain=$(median < "$work/o.plain") detached=$(median < "$work/o.detached") counting=$(median < "$work/o.counting")" >> "$work/overhead.txt"
    done
fi

# 4. callgrind: where the instructions of the timed steps go
: > "$work/hotspots.md"
if [ "$callgrind" = 1 ] && command -v valgrind >/dev/null 2>&1 && command -v callgrind_annotate >/dev/null 2>&1; then
    echo "bench.sh: callgrind" >&2
    cg() { # name args...
        name=$1
        shift
        valgrind --tool=callgrind --collect-atstart=no --toggle-collect=bench_timed_steps \
            --callgrind-out-file="$work/cg.$name.out" "$bench" --run "$@" \
            > "$work/cg.$name.txt" 2> "$work/cg.$name.log" ||
            { echo "bench.sh: callgrind $*: failed (see $work/cg.$name.log)" >&2; return 1; }
    }
    if [ "$quick" = 1 ]; then
        cg gas-events gas 1000 events --steps 20 --warmup 1
        cg pile-events pile 1000 events --steps 10 --warmup 1
        python3 "$here/hotspots.py" --top 10 \
            "gas of 10^3, method events, 20 steps=$work/cg.gas-events.out" \
            "pile of 10^3, method events, falling (steps 2 to 11)=$work/cg.pile-events.out" \
            > "$work/hotspots.md"
    else
        cg gas-events gas 10000 events --steps 10 --warmup 1
        cg gas-discrete gas 10000 discrete --steps 10 --warmup 1
        cg pile-events pile 1000 events --steps 15 --warmup 1
        cg pile-discrete pile 1000 discrete --steps 15 --warmup 1
        python3 "$here/hotspots.py" --top 12 \
            "gas of 10^4, method events, 10 steps=$work/cg.gas-events.out" \
            "gas of 10^4, method discrete, 10 steps=$work/cg.gas-discrete.out" \
            "pile of 10^3, method events, falling (steps 2 to 16)=$work/cg.pile-events.out" \
            "pile of 10^3, method discrete, falling (steps 2 to 16)=$work/cg.pile-discrete.out" \
            > "$work/hotspots.md"
    fi
else
    echo "bench.sh: no valgrind: no hotspots" >&2
fi

end=$(date +%s)
mkdir -p "$(dirname "$out")"
quickarg=""
[ "$quick" = 1 ] && quickarg="--quick"
# shellcheck disable=SC2086 # empty or one flag
python3 "$here/report.py" --time "$work/time.txt" --ops "$work/ops.txt" \
    --overhead "$work/overhead.txt" --hotspots "$work/hotspots.md" \
    --build "$build" --seconds "$((end - start))" $quickarg --out "$out"
echo "bench.sh: wrote $out ($((end - start)) s)" >&2

# 5. figures (full run only): time per step against bodies, log-log
if [ "$quick" = 0 ]; then
    sh "$here/plot.sh" "$work/time.txt" "$(dirname "$out")" "$work"
fi
