#!/bin/sh
# random_run.sh -- run a directory of stress scenes (random_scenes.py) through
# carom's events and discrete methods and check each with build/stress_check.
#
# usage: sh tools/stress/random_run.sh DIR [--carom PATH] [--jobs N]
#
# Prints one line per run, "SCENE METHOD PASS|FAIL|ERR ...", then a count
# per family, method and result. Runs with a trace only when the scene's
# criterion needs one. Exit status: 0 every run passed, 1 one did not,
# 2 bad usage or missing tools.
set -eu
carom=build/carom
checker=build/stress_check
jobs=2
dir=
while [ $# -gt 0 ]; do
    case "$1" in
    --carom) carom=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    -h|--help) sed -n '2,11p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "random_run.sh: unknown option '$1' (try --help)" >&2; exit 2 ;;
    *) dir=$1; shift ;;
    esac
done
[ -n "$dir" ] && [ -d "$dir" ] || { echo "random_run.sh: no scene directory given (try --help)" >&2; exit 2; }
[ -x "$carom" ] && [ -x "$checker" ] || { echo "random_run.sh: build $carom and $checker first (make all)" >&2; exit 2; }
export carom checker
out=$(ls "$dir"/*.scene | xargs -P "$jobs" -I{} sh -c '
    f=$1
    tr=$("$checker" --info "$f" | awk "\$1 == \"trace\" { print \$2 }")
    for m in events discrete; do
        o=${f%.scene}.$m
        set -- "$f"
        if [ "$tr" = 1 ]; then set -- "$f" --trace "$o.trace"; fi
        if "$carom" run "$@" --method $m > "$o.final" 2> "$o.err"; then
            if [ "$tr" = 1 ]; then r=$("$checker" "$f" "$o.final" "$o.trace" 2>&1 | head -n 1)
            else r=$("$checker" "$f" "$o.final" 2>&1 | head -n 1); fi
        else
            r="ERR $(head -n 1 "$o.err")"
        fi
        echo "$(basename "$f" .scene) $m $r"
        rm -f "$o.trace" "$o.final" "$o.err"
    done' sh {})
echo "$out"
echo "$out" | awk '{ split($1, a, "-"); n[a[1] " " $2 " " $3]++ }
    END { for (k in n) print "count " k, n[k] }' | sort
echo "$out" | awk '$3 != "PASS" { bad = 1 } END { exit bad }'
