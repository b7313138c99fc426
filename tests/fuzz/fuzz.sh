#!/bin/sh
# fuzz.sh -- the steps of `make fuzz` and `make fuzz-regress`
# (tests/fuzz/fuzz.mk). Run from the repository root.
#
#   sh tests/fuzz/fuzz.sh probe CC OUT
#       exit 0 if CC builds a libFuzzer + ASan + UBSan program (in OUT)
#   sh tests/fuzz/fuzz.sh run OUT SECONDS [SEED]
#       fuzz every harness OUT/fuzz_* for SECONDS seconds, one process each,
#       on a work copy of its seed corpus (OUT/corpus/HARNESS; the checked-in
#       tests/fuzz/corpus/ is never written), then replay. With SEED, the
#       run is reproducible: libFuzzer's -seed=SEED, and at most the
#       harness's check_runs inputs (below) from its seed corpus alone, so
#       every machine tries the same inputs (a slow one stops at SECONDS
#       with a prefix of them): what make check runs
#   sh tests/fuzz/fuzz.sh replay OUT
#       run every harness once over its seed corpus, then every file of
#       tests/fuzz/crashers/ (HARNESS-description) through its harness;
#       fail if any input crashes or breaks an invariant
#
# Harness settings (max_len, dictionary, timeout, runs) are below, in one
# place.

set -u

fuzz_dir=tests/fuzz
harnesses="fuzz_scene_parse fuzz_scene_run fuzz_api"

# flags HARNESS: libFuzzer options of a harness (used to fuzz and replay)
flags() {
    case $1 in
    fuzz_scene_parse) echo "-max_len=4096 -timeout=10 -dict=$fuzz_dir/scene.dict" ;;
    fuzz_scene_run) echo "-max_len=8192 -timeout=30 -dict=$fuzz_dir/scene.dict" ;;
    fuzz_api) echo "-max_len=2048 -timeout=30" ;;
    *) echo "" ;;
    esac
}

probe() {
    cc=$1 out=$2
    command -v "$cc" >/dev/null 2>&1 || return 1
    mkdir -p "$out" || return 1
    printf '%s\n' '#include <stddef.h>' '#include <stdint.h>' \
        'int LLVMFuzzerTestOneInput(const uint8_t *d, size_t n)' \
        '{ (void)d; (void)n; return 0; }' >"$out/probe.c"
    "$cc" -fsanitize=fuzzer,address,undefined "$out/probe.c" \
        -o "$out/probe" >/dev/null 2>&1
}

# check_runs HARNESS: inputs of a reproducible run (about 30 s each here)
check_runs() {
    case $1 in
    fuzz_scene_parse) echo 400000 ;;
    fuzz_scene_run) echo 8000 ;;
    fuzz_api) echo 15000 ;;
    *) echo 10000 ;;
    esac
}

replay() {
    out=$1
    bad=0
    for h in $harnesses; do
        if [ ! -x "$out/$h" ]; then
            echo "fuzz: $out/$h is missing (make fuzz-build)" >&2
            return 2
        fi
        seeds=$fuzz_dir/corpus/$h
        [ -d "$seeds" ] || continue
        n=$(find "$seeds" -type f | wc -l)
        # shellcheck disable=SC2046
        if "$out/$h" $(flags "$h") -runs=0 "$seeds" >"$out/$h.replay.log" 2>&1; then
            echo "ok - $h: $n seed inputs"
        else
            echo "not ok - $h: a seed input fails (log: $out/$h.replay.log)"
            grep -E 'INVARIANT VIOLATED|while:|ERROR: |SUMMARY:|runtime error' \
                "$out/$h.replay.log" | head -n 8 | sed 's/^/    /'
            bad=1
        fi
    done
    found=0
    for f in "$fuzz_dir"/crashers/*; do
        [ -f "$f" ] || continue
        name=$(basename "$f")
        case $name in *.md | *.txt) continue ;; esac
        found=1
        h=${name%%-*}
        if [ ! -x "$out/$h" ]; then
            echo "not ok - crashers/$name: no harness '$h' (name files HARNESS-what)"
            bad=1
            continue
        fi
        log=$out/crashers/$name.log
        mkdir -p "$out/crashers"
        # shellcheck disable=SC2046
        if "$out/$h" $(flags "$h") "$f" >"$log" 2>&1; then
            echo "ok - crashers/$name (fixed: now a regression test)"
        else
            echo "not ok - crashers/$name still fails (log: $log)"
            grep -E 'INVARIANT VIOLATED|while:|ERROR: |SUMMARY:|runtime error|ALARM' \
                "$log" | head -n 6 | sed 's/^/    /'
            bad=1
        fi
    done
    [ $found = 1 ] || echo "fuzz: no crashers in $fuzz_dir/crashers/"
    return $bad
}

run() {
    out=$1 seconds=$2 seed=${3:-}
    failed=""
    for h in $harnesses; do
        work=$out/corpus/$h
        art=$out/artifacts/$h
        extra=""
        if [ -n "$seed" ]; then
            # the checked-in seeds only, whatever earlier runs added
            rm -rf "$work"
            extra="-seed=$seed -runs=$(check_runs "$h")"
        fi
        mkdir -p "$work" "$art" || return 2
        for f in "$fuzz_dir/corpus/$h"/*; do
            [ -f "$f" ] || continue
            [ -e "$work/$(basename "$f")" ] || cp "$f" "$work/"
        done
        if [ -n "$seed" ]; then
            echo "fuzz: $h, seed $seed, at most $(check_runs "$h") inputs or $seconds s (corpus $work, log $out/$h.log)"
        else
            echo "fuzz: $h for $seconds s (corpus $work, log $out/$h.log)"
        fi
        # shellcheck disable=SC2046,SC2086
        "$out/$h" $(flags "$h") $extra -max_total_time="$seconds" \
            -print_final_stats=1 -artifact_prefix="$art/" "$work" \
            >"$out/$h.log" 2>&1
        rc=$?
        grep -E '^#[0-9]+[[:space:]]+(INITED|DONE)' "$out/$h.log" | sed 's/^/    /'
        grep -E '^stat::(number_of_executed_units|peak_rss_mb|new_units_added)' \
            "$out/$h.log" | sed 's/^/    /'
        if [ $rc -ne 0 ]; then
            echo "fuzz: $h FAILED (exit $rc); the end of $out/$h.log:"
            grep -E 'INVARIANT VIOLATED|while:|ERROR: |SUMMARY:|runtime error|Test unit written|ALARM' \
                "$out/$h.log" | head -n 12 | sed 's/^/    /'
            echo "    keep the input as a regression test:"
            echo "    cp $art/<crash-file> $fuzz_dir/crashers/$h-<what-it-does>"
            failed="$failed $h"
        fi
    done
    replay "$out"
    replay_rc=$?
    if [ -n "$failed" ]; then
        echo "fuzz: new findings in:$failed"
        return 1
    fi
    return $replay_rc
}

case ${1:-} in
probe) probe "${2:-clang}" "${3:-build/fuzz}" ;;
run) run "${2:-build/fuzz}" "${3:-30}" "${4:-}" ;;
replay) replay "${2:-build/fuzz}" ;;
*)
    echo "usage: sh $0 probe CC OUT | run OUT SECONDS [SEED] | replay OUT" >&2
    exit 2
    ;;
esac
