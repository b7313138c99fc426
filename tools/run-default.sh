#!/bin/sh
# run-default.sh CAROM SCENE -- `make run`: step a scene and say what
# happened (impacts, final state). A run that stops early (carom exits 1,
# the state reached marked partial) is still shown, up to where it
# stopped, and the script then exits 1; a bad scene (exit 2) shows nothing
# but carom's message.
set -eu
carom="$1"
scene="$2"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# CSV to aligned columns (no dependency on column(1))
table() {
    awk -F, '{ for (i = 1; i <= NF; ++i) printf "  %-14s", $i; printf "\n" }'
}
rc=0
"$carom" run "$scene" --events "$tmp/events.csv" > "$tmp/final.csv" || rc=$?
if [ "$rc" -ne 0 ] && [ "$rc" -ne 1 ]; then
    exit "$rc"
fi
# a partial run's first line: "# partial: stopped at step N of M: ..."
grep '^#' "$tmp/final.csv" > "$tmp/partial" || true
grep -v '^#' "$tmp/final.csv" > "$tmp/state.csv" || true
bodies=$(($(wc -l < "$tmp/state.csv") - 1))
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
if [ -s "$tmp/partial" ]; then
    sed "s/^# //" "$tmp/partial"
    echo
    echo "state reached:"
else
    echo "final state:"
fi
table < "$tmp/state.csv"
echo
echo "floating-point work (carom profile, design note's cost table; docs/cost-model.md):"
if [ "$rc" -eq 0 ]; then
    "$carom" profile "$scene" | sed -n '/^phase/,$p'
else
    # the steps taken; the error is the one carom run gave above
    "$carom" profile "$scene" 2> /dev/null | sed -n '/^phase/,$p'
    echo "run-default.sh: $scene: the run stopped early (carom's message above); shown: what it did until then" >&2
fi
exit "$rc"
