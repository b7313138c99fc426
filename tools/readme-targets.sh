#!/bin/sh
# readme-targets.sh -- rewrite the "Make targets" table of README.md from
# `make help` (the README lists what make help lists; make docs-check
# fails when they differ). Run from the repository root:
#   sh tools/readme-targets.sh [--check]
# --check: exit 1 if the table would change, without writing.
set -eu
[ -f README.md ] || { echo "readme-targets.sh: run from the repository root" >&2; exit 2; }
help=$(mktemp)
new=$(mktemp)
trap 'rm -f "$help" "$new"' EXIT
make -s --no-print-directory help > "$help"
awk -v helpfile="$help" '
    function table(   line, t, d) {
        print "| target | what it does |"
        print "| --- | --- |"
        while ((getline line < helpfile) > 0) {
            if (line !~ /^  make /) continue
            sub(/^  /, "", line)
            t = line; sub(/  .*/, "", t)
            d = line; sub(/^make [^ ]+ +/, "", d)
            if (d == line) d = ""
            gsub(/\$\(BUILD\)/, "build", d)
            print "| `" t "` | " d " |"
        }
    }
    /^## Make targets/ { inmake = 1 }
    inmake && /^\| target \| what it does \|/ { table(); skipping = 1; next }
    skipping && /^\|/ { next }
    skipping { skipping = 0; inmake = 0 }
    { print }
' README.md > "$new"
if [ "${1:-}" = --check ]; then
    cmp -s README.md "$new" || { echo "readme-targets.sh: README.md's targets table differs from make help" >&2; exit 1; }
    exit 0
fi
cp "$new" README.md
