#!/bin/sh
# bench.sh -- `make bench`: the cost of the op-count profiler.
# Builds the library four ways and times the same scenes with each, in one
# run, interleaved, several repetitions, medians; then callgrind instruction
# counts (repeatable) for the default and reference builds.
#   default   CAROM_ENABLE_PROFILE=0: the arithmetic layer, no counter
#   plain     the layer replaced by bare C operators (CR_ARITH_PLAIN)
#   detached  CAROM_ENABLE_PROFILE=1, no profile attached
#   counting  CAROM_ENABLE_PROFILE=1, counting into a profile
set -eu
cc="${CC:-cc}"
out="${BENCH_OUT:-build/bench}"
reps="${BENCH_REPS:-7}"
mkdir -p "$out"
cflags="-std=c99 -pedantic -Wall -Wextra -Werror -Wdouble-promotion -ffp-contract=off -O2"
variant() { # name flags
    make -s BUILD="$out/$1" lib CAROM_FLAGS="$2" >/dev/null
    # shellcheck disable=SC2086 # flag lists are words
    $cc $cflags -D_POSIX_C_SOURCE=200809L -Iinclude -Itools $2 tools/bench_profile.c \
        tools/scene.c "$out/$1/libcarom.a" -lm -o "$out/bench-$1"
}
variant default ""
variant plain "-DCR_ARITH_PLAIN"
variant prof "-DCAROM_ENABLE_PROFILE=1"

printf '%-26s %7s %10s %10s %10s %10s %9s %9s\n' scene steps default plain detached counting plain/def count/def
for spec in tools/scenes/default.scene:600 tools/scenes/gas.scene:300; do
    sc=${spec%:*} n=${spec#*:}
    d=$("$out/bench-default" "$sc" "$n" "$reps")
    p=$("$out/bench-plain" "$sc" "$n" "$reps")
    a=$("$out/bench-prof" "$sc" "$n" "$reps")
    c=$("$out/bench-prof" "$sc" "$n" "$reps" count)
    awk -v s="$(basename "$sc")" -v n="$n" -v d="$d" -v p="$p" -v a="$a" -v c="$c" 'BEGIN {
        printf "%-26s %7d %10.0f %10.0f %10.0f %10.0f %9.3f %9.3f\n", s, n, d, p, a, c, p / d, c / d }'
done
echo "(ns per step, median of $reps runs)"

if command -v valgrind >/dev/null 2>&1; then
    echo
    echo "callgrind instructions, tools/scenes/gas.scene, 60 steps:"
    for v in default plain; do
        valgrind --tool=callgrind --callgrind-out-file="$out/cg.$v" \
            "$out/bench-$v" tools/scenes/gas.scene 60 1 > /dev/null 2> "$out/cg.$v.log"
        printf '  %-8s %s\n' "$v" "$(grep -o 'refs: *[0-9,]*' "$out/cg.$v.log" | tr -d ' ,' | cut -d: -f2)"
    done
fi
