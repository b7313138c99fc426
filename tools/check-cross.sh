#!/bin/sh
# check-cross.sh -- the core must build for a Cortex-M4F with the project's
# strict flags (short enums, hard float), call nothing but sqrtf (and the
# compiler's memcpy/memset), and report its code size. Skips, saying so,
# when arm-none-eabi-gcc is not installed.
set -eu
cc=arm-none-eabi-gcc
if ! command -v "$cc" >/dev/null 2>&1; then
    echo "check-cross: skipped: $cc not installed"
    exit 0
fi
out="${1:-build/m4f}"
mkdir -p "$out"
flags="-mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard -std=c99 -pedantic -Wall -Wextra -Werror -Wdouble-promotion -ffp-contract=off -O2 -Iinclude"
rm -f "$out"/*.o "$out/libcarom.a"
for f in src/*.c; do
    # shellcheck disable=SC2086 # flags are words
    $cc $flags -c "$f" -o "$out/$(basename "$f" .c).o"
done
arm-none-eabi-ar rcs "$out/libcarom.a" "$out"/*.o
sh tools/check-symbols.sh "$out/libcarom.a" >/dev/null
echo "check-cross: ok: Cortex-M4F build, $(arm-none-eabi-size -t "$out/libcarom.a" | tail -n 1 | awk '{print $1}') bytes of code"
