#!/bin/sh
# check-symbols.sh LIB.a [PROFILE_LIB.a] -- the core library may reference
# no allocator and no libm function but sqrtf: takes the symbols the
# archive's members need but no member defines, and fails on anything
# outside the allow-list; every symbol it defines is carom_* or cr_*. The
# default build must contain no op counter
# (profiling compiled out costs nothing); the profiling build must.
#
# The nm that reads the archive is chosen from its contents, not its name:
# readelf's machine field of the members (ARM: arm-none-eabi-nm), else
# whichever of nm and arm-none-eabi-nm lists its symbols.
set -eu
usage="usage: sh tools/check-symbols.sh LIB.a [PROFILE_LIB.a]"
if [ $# -ge 1 ] && { [ "$1" = "--help" ] || [ "$1" = "-h" ]; }; then
    echo "$usage"
    exit 0
fi
if [ $# -lt 1 ] || [ $# -gt 2 ]; then
    echo "$usage" >&2
    exit 2
fi
lib="$1"
[ -f "$lib" ] || { echo "check-symbols: no such archive: $lib" >&2; exit 2; }

# pick_nm ARCHIVE: print the nm command for the archive's machine
pick_nm() {
    machine=$(readelf -h "$1" 2>/dev/null | sed -n 's/^ *Machine: *//p' | sort -u | head -n 1)
    case "$machine" in
        *ARM*|*AArch64*)
            command -v arm-none-eabi-nm >/dev/null 2>&1 || {
                echo "check-symbols: $1 holds $machine code: needs arm-none-eabi-nm (Debian: binutils-arm-none-eabi)" >&2
                return 1; }
            echo arm-none-eabi-nm
            return 0 ;;
    esac
    for cand in nm arm-none-eabi-nm; do
        if command -v "$cand" >/dev/null 2>&1 && "$cand" "$1" >/dev/null 2>&1; then
            echo "$cand"
            return 0
        fi
    done
    echo "check-symbols: no nm here reads $1 (machine: ${machine:-unknown})" >&2
    return 1
}
nm=$(pick_nm "$lib") || exit 2
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
# Every symbol the archive defines for the linker is carom's: the public
# carom_* API or the internal cr_* functions one module calls in another
# (C has no module scope; the prefix keeps them out of the program's way).
foreign=$(grep -Ev '^(carom_|cr_|carom__)' "$tmp/defined" || true)
if [ -n "$foreign" ]; then
    echo "check-symbols: FAIL: $lib defines symbols outside carom_* and cr_*: $(printf "%s" "$foreign" | tr "\n" " ")" >&2
    exit 1
fi
echo "check-symbols: ok: $lib defines $(grep -c '^carom_' "$tmp/defined") carom_* and $(grep -c '^cr_' "$tmp/defined") internal cr_* symbols, nothing else"
if $nm "$lib" | grep -q 'carom__op_row'; then
    echo "check-symbols: FAIL: $lib contains the op counter (carom__op_row): the default build must not count" >&2
    exit 1
fi
echo "check-symbols: ok: $lib has no op counter (counting compiled out)"
if [ $# -ge 2 ]; then
    [ -f "$2" ] || { echo "check-symbols: no such archive: $2" >&2; exit 2; }
    nm=$(pick_nm "$2") || exit 2
    if ! $nm -g --defined-only "$2" | grep -q ' carom__op_row$'; then
        echo "check-symbols: FAIL: $2 lacks the op counter: profiling is not compiled in" >&2
        exit 1
    fi
    if $nm -u "$2" | grep -qE ' (malloc|calloc|realloc|free)$'; then
        echo "check-symbols: FAIL: $2 calls the allocator" >&2
        exit 1
    fi
    echo "check-symbols: ok: $2 defines the op counter and does not allocate"
fi
