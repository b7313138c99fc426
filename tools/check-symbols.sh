#!/bin/sh
# check-symbols.sh LIB.a -- the core library may reference no allocator and
# no libm function but sqrtf. Takes the symbols the archive's members need
# but no member defines, and fails on anything outside the allow-list.
set -eu
lib="$1"
[ -f "$lib" ] || { echo "check-symbols: no such archive: $lib" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
nm -g --defined-only "$lib" | awk 'NF == 3 {print $3}' | sort -u > "$tmp/defined"
nm -u "$lib" | awk '$1 == "U" {print $2}' | sort -u > "$tmp/needed"
undef=$(comm -23 "$tmp/needed" "$tmp/defined")
# memcpy/memset may be emitted by the compiler for struct copies; strcmp
# looks up method names.
allowed='^(sqrtf|memcpy|memset|memmove|strcmp)$'
alloc=$(printf '%s\n' "$undef" | grep -E '^(malloc|calloc|realloc|free|aligned_alloc|posix_memalign|reallocarray)$' || true)
if [ -n "$alloc" ]; then
    echo "check-symbols: FAIL: $lib calls the allocator: $(echo $alloc)" >&2
    exit 1
fi
bad=$(printf '%s\n' "$undef" | grep -Ev "$allowed" | grep -v '^$' || true)
if [ -n "$bad" ]; then
    echo "check-symbols: FAIL: $lib needs symbols outside the allow-list: $(echo $bad)" >&2
    exit 1
fi
echo "check-symbols: ok: $lib needs only: $(echo $undef)"
