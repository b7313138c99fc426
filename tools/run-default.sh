#!/bin/sh
# run-default.sh CAROM SCENE -- `make run`: step a scene and say what
# happened (impacts, final state).
set -eu
carom="$1"
scene="$2"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# CSV to aligned columns (no dependency on column(1))
table() {
    awk -F, '{ for (i = 1; i <= NF; ++i) printf "  %-14s", $i; printf "\n" }'
}
"$carom" run "$scene" --events "$tmp/events.csv" > "$tmp/final.csv"
bodies=$(($(wc -l < "$tmp/final.csv") - 1))
impacts=$(($(wc -l < "$tmp/events.csv") - 1))
echo "scene:   $scene"
grep -E '^world' "$scene" | sed 's/^/         /'
echo "bodies:  $bodies"
echo "impacts: $impacts (approach faster than the rest speed)"
if [ "$impacts" -gt 0 ]; then
    echo
    echo "first impacts:"
    head -n 9 "$tmp/events.csv" | table
fi
echo
echo "final state:"
table < "$tmp/final.csv"
echo
echo "floating-point work (carom profile, design note's cost table; docs/cost-model.md):"
"$carom" profile "$scene" | sed -n '/^phase/,$p'
