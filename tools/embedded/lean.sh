#!/bin/sh
# lean.sh -- the checks of `make lean` (mk/lean.mk).
#
#   lean.sh --scene FILE --dir DIR --cli CLI --lean-cli LEAN_CLI
#           --lib LIB.a --lean-lib LEAN_LIB.a
#           [--m4f-lib LIB.a --lean-m4f-lib LEAN_LIB.a]
#       prints text, data and bss of the lean library against the default
#       one (x86-64, and Cortex-M4F when given), then runs FILE through
#       both CLIs and fails unless the final state, the --events list and
#       the --trace of every step are byte-identical; then runs the lean
#       CLI's `profile` and prints its op count beside the default's.
#   lean.sh --switches CAROM_CONFIG_H --header CAROM_LEAN_H
#       fails unless the header defines every CAROM_ENABLE_* switch of the
#       configuration header.
#   lean.sh --help
set -eu

usage() {
    sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//'
}

die() {
    echo "lean.sh: $*" >&2
    exit 1
}

scene='' dir='' cli='' lean_cli='' lib='' lean_lib='' m4f_lib='' lean_m4f_lib=''
switches='' header=''
while [ $# -gt 0 ]; do
    case "$1" in
        --help|-h) usage; exit 0 ;;
        --scene|--dir|--cli|--lean-cli|--lib|--lean-lib|--m4f-lib|--lean-m4f-lib|--switches|--header)
            [ $# -ge 2 ] || { echo "lean.sh: $1 needs a value" >&2; exit 2; }
            v=$2
            case "$1" in
                --scene) scene=$v ;;
                --dir) dir=$v ;;
                --cli) cli=$v ;;
                --lean-cli) lean_cli=$v ;;
                --lib) lib=$v ;;
                --lean-lib) lean_lib=$v ;;
                --m4f-lib) m4f_lib=$v ;;
                --lean-m4f-lib) lean_m4f_lib=$v ;;
                --switches) switches=$v ;;
                --header) header=$v ;;
            esac
            shift 2 ;;
        *) echo "lean.sh: unknown argument '$1' (try --help)" >&2; exit 2 ;;
    esac
done

# ---- every switch covered -----------------------------------------------------

if [ -n "$switches" ]; then
    [ -f "$switches" ] || die "no such file: $switches"
    [ -f "$header" ] || die "no such header: $header"
    missing=
    sed -n 's/^#ifndef \(CAROM_ENABLE_[A-Z0-9_]*\).*/\1/p' "$switches" > "$header.switches"
    while read -r sw; do
        grep -q "^#define $sw " "$header" || missing="$missing $sw"
    done < "$header.switches"
    rm -f "$header.switches"
    [ -z "$missing" ] || die "$header does not set:$missing (teach 'carom lean' these switches)"
    echo "lean: $header sets every switch of $switches"
    exit 0
fi

for v in scene dir cli lean_cli lib lean_lib; do
    eval "x=\$$v"
    [ -n "$x" ] || { echo "lean.sh: missing --$(echo "$v" | tr _ -) (try --help)" >&2; exit 2; }
done
[ -f "$scene" ] || die "no such scene: $scene"

# ---- sizes --------------------------------------------------------------------

# size_row LABEL SIZE-TOOL DEFAULT.a LEAN.a
size_row() {
    "$2" -t "$3" | tail -n 1 > "$dir/size.default"
    "$2" -t "$4" | tail -n 1 > "$dir/size.lean"
    read -r dt dd db _ < "$dir/size.default"
    read -r lt ld lb _ < "$dir/size.lean"
    awk -v l="$1" -v dt="$dt" -v dd="$dd" -v db="$db" -v lt="$lt" -v ld="$ld" -v lb="$lb" \
        'BEGIN { printf "%-22s %8d %8d %6d %6d %6d %6d %7.2f\n", l, dt, lt, dd, ld, db, lb, lt / dt }'
    rm -f "$dir/size.default" "$dir/size.lean"
}

echo "lean: $scene: library size, lean against default (size -t; text includes rodata)"
printf '%-22s %8s %8s %6s %6s %6s %6s %7s\n' library "text" "lean" data lean bss lean "text x"
size_row "x86-64 libcarom.a" size "$lib" "$lean_lib"
if [ -n "$m4f_lib" ] && [ -n "$lean_m4f_lib" ]; then
    size_row "Cortex-M4F libcarom.a" arm-none-eabi-size "$m4f_lib" "$lean_m4f_lib"
fi

# ---- same results ---------------------------------------------------------------

check="$dir/check"
mkdir -p "$check"
for which in default lean; do
    if [ "$which" = default ]; then c=$cli; else c=$lean_cli; fi
    "$c" run "$scene" --no-progress --events "$check/$which.events" \
        --trace "$check/$which.trace" > "$check/$which.state" 2> "$check/$which.err" ||
        { cat "$check/$which.err" >&2; die "$which CLI failed on $scene"; }
done
for part in state events trace; do
    if ! cmp -s "$check/default.$part" "$check/lean.$part"; then
        echo "lean: FAIL: the lean build's $part differs from the default build's on $scene:" >&2
        diff "$check/default.$part" "$check/lean.$part" | head -n 6 >&2
        echo "lean: (kept in $check/; the header is $dir/carom_lean.h)" >&2
        exit 1
    fi
done
# the measured run is the lean build's own: no warning; one step more is
# beyond it, and the lean CLI says so
if grep -q "goes beyond" "$check/lean.err"; then
    cat "$check/lean.err" >&2
    die "the lean CLI warned on the run it was measured on"
fi
steps=$(sed -n 's/^#define CAROM_LEAN_STEPS \([0-9]*\)L.*/\1/p' "$dir/carom_lean.h")
[ -n "$steps" ] || die "no CAROM_LEAN_STEPS in $dir/carom_lean.h"
"$lean_cli" run "$scene" --no-progress --steps $((steps + 1)) > /dev/null 2> "$check/beyond.err" || true
grep -q "goes beyond" "$check/beyond.err" ||
    die "the lean CLI did not warn on a run of $((steps + 1)) steps, one past the $steps measured"
rows=$(($(wc -l < "$check/default.trace") - 1))
events=$(($(wc -l < "$check/default.events") - 1))
echo "lean: ok: final state, $events events and $rows trace rows byte-identical to the default build"
"$lean_cli" profile "$scene" --no-progress --json > "$check/lean.profile" ||
    die "the lean CLI's profile failed on $scene"
"$cli" profile "$scene" --no-progress --json > "$check/default.profile" ||
    die "the default CLI's profile failed on $scene"
cost() { sed 's/.*"total_cost": *\([-0-9.eE+]*\).*/\1/' "$1"; }
awk -v d="$(cost "$check/default.profile")" -v l="$(cost "$check/lean.profile")" \
    'BEGIN { printf "lean: profile works: seed cost %.0f (default build %.0f, x %.3f)\n", l, d, (d > 0 ? l / d : 0) }'
rm -f "$check/default.trace" "$check/lean.trace"
