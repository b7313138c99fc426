#!/bin/sh
# check-symbols.sh LIB.a [PROFILE_LIB.a] -- the core library may reference
# no allocator and no libm function but sqrtf: takes the symbols the
# archive's members need but no member defines, and fails on anything
# outside the allow-list. The default build must contain no op counter
# (profiling compiled out costs nothing); the profiling build must.
set -eu
lib="$1"
[ -f "$lib" ] || { echo "check-symbols: no such archive: $lib" >&2; exit 2; }
nm="nm"
case "$lib" in *m4f*|*arm*) nm=arm-none-eabi-nm ;; esac
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
$nm -g --defined-only "$lib" | awk 'NF == 3 {print $3}' | sort -u > "$tmp/defined"
$nm -u "$lib" | awk '$1 == "U" {print $2}' | sort -u > "$tmp/needed"
undef=$(comm -23 "$tmp/needed" "$tmp/defined")
# memcpy/memset may be emitted by the compiler for struct copies; strcmp
# looks up method names; __aeabi_* are the ARM compiler runtime's helpers
# (integer <-> float conversions, memory), not libm.
allowed='^(sqrtf|memcpy|memset|memmove|strcmp|__aeabi_[a-z0-9_]+)$'
alloc=$(printf '%s\n' "$undef" | grep -E '^(malloc|calloc|realloc|free|aligned_alloc|posix_memalign|reallocarray)$' || true)
if [ -n "$alloc" ]; then
    echo "check-symbols: FAIL: $lib calls the allocator: $(printf "%s" "$alloc" | tr "\n" " ")" >&2
    exit 1
fi
bad=$(printf '%s\n' "$undef" | grep -Ev "$allowed" | grep -v '^$' || true)
if [ -n "$bad" ]; then
    echo "check-symbols: FAIL: $lib needs symbols outside the allow-list: $(printf "%s" "$bad" | tr "\n" " ")" >&2
    exit 1
fi
echo "check-symbols: ok: $lib needs only: $(printf "%s" "$undef" | tr "\n" " ")"
if $nm "$lib" | grep -q 'carom__op_row'; then
    echo "check-symbols: FAIL: $lib contains the op counter (carom__op_row): the default build must not count" >&2
    exit 1
fi
echo "check-symbols: ok: $lib has no op counter (counting compiled out)"
if [ $# -ge 2 ]; then
    if ! nm -g --defined-only "$2" | grep -q ' carom__op_row$'; then
        echo "check-symbols: FAIL: $2 lacks the op counter: profiling is not compiled in" >&2
        exit 1
    fi
    if nm -u "$2" | grep -qE ' (malloc|calloc|realloc|free)$'; then
        echo "check-symbols: FAIL: $2 calls the allocator" >&2
        exit 1
    fi
    echo "check-symbols: ok: $2 defines the op counter and does not allocate"
fi
