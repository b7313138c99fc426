#!/bin/sh
# header-example.sh HEADER OUT.c -- extract the minimal program from the
# opening comment of include/carom.h (the lines after "A minimal program",
# each starting " *     ") into a compilable C file with a main().
set -eu
[ $# -eq 2 ] || { echo "usage: header-example.sh HEADER OUT.c" >&2; exit 2; }
{
    printf '#include <stdio.h>\n#include "carom.h"\nint main(void)\n{\n'
    awk '/A minimal program/ { on = 1; next }
         on && /^ \*\// { exit }
         on && /^ \*     / { sub(/^ \*     /, "    "); print }' "$1"
    printf '    return 0;\n}\n'
} > "$2"
grep -q carom_world_init "$2" || { echo "header-example.sh: no example found in $1" >&2; exit 1; }
