#!/bin/sh
# check-switches.sh -- every switch of include/carom_config.h must build,
# and turning a capability off must make the library smaller (or, for
# CAROM_ENABLE_PROFILE, turning it on bigger). Prints the code size of
# each variant.
set -eu
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
size_of() {
    make -s -j"$(nproc 2>/dev/null || echo 2)" BUILD="$tmp/b" lib CAROM_FLAGS="$1" > "$tmp/log" 2>&1 || {
        echo "check-switches: FAIL: build with '$1'" >&2; cat "$tmp/log" >&2; exit 1; }
    # it must link, every object of it, into a program
    printf '#include "carom.h"\nint main(void) { return carom_world_step(0) == CAROM_OK; }\n' \
        > "$tmp/main.c"
    ${CC:-cc} -Iinclude $1 "$tmp/main.c" -Wl,--whole-archive "$tmp/b/libcarom.a" \
        -Wl,--no-whole-archive -lm -o "$tmp/main" > "$tmp/log" 2>&1 || {
        echo "check-switches: FAIL: link with '$1'" >&2; cat "$tmp/log" >&2; exit 1; }
    size -t "$tmp/b/libcarom.a" | tail -n 1 | awk '{print $1}'
    rm -rf "$tmp/b"
}
base=$(size_of "")
printf '%8s  %s\n' "$base" "defaults"
fail=0
for sw in POLYGONS ROTATION FRICTION FORCES EVENTS SLEEP KINEMATIC POLYGON_POLYGON GRID \
    DYNAMIC_POLYGONS FILTERING SENSORS QUERIES TOUCH_EVENTS STACKING STATUS_NAMES GROW ANGLES \
    BODY_EDITS DISCRETE CONTINUOUS; do
    n=$(size_of "-DCAROM_ENABLE_$sw=0")
    printf '%8s  CAROM_ENABLE_%s=0\n' "$n" "$sw"
    if [ "$n" -ge "$base" ]; then
        echo "check-switches: FAIL: CAROM_ENABLE_$sw=0 removed no code" >&2
        fail=1
    fi
done
# compensated sums change results, not capabilities: they must build; the
# size may go either way with the compiler's inlining
n=$(size_of "-DCAROM_ENABLE_COMPENSATED=0")
printf '%8s  CAROM_ENABLE_COMPENSATED=0\n' "$n"
# so does the soft push of deep overlaps between unlike bodies (off by
# default; make check-soft-deep tests it)
n=$(size_of "-DCAROM_SOFT_DEEP_CONTACTS=1")
printf '%8s  CAROM_SOFT_DEEP_CONTACTS=1\n' "$n"
# and every impact of the events methods at its instant (off by default)
n=$(size_of "-DCAROM_EXACT_PILE_IMPACTS=1")
printf '%8s  CAROM_EXACT_PILE_IMPACTS=1\n' "$n"
n=$(size_of "-DCAROM_ENABLE_PROFILE=1")
printf '%8s  CAROM_ENABLE_PROFILE=1\n' "$n"
[ "$n" -gt "$base" ] || { echo "check-switches: FAIL: profiling added no code" >&2; fail=1; }
all_off="-DCAROM_ENABLE_POLYGONS=0 -DCAROM_ENABLE_ROTATION=0 -DCAROM_ENABLE_FRICTION=0 -DCAROM_ENABLE_FORCES=0 -DCAROM_ENABLE_EVENTS=0 -DCAROM_ENABLE_SLEEP=0 -DCAROM_ENABLE_KINEMATIC=0 -DCAROM_ENABLE_COMPENSATED=0 -DCAROM_ENABLE_FILTERING=0 -DCAROM_ENABLE_SENSORS=0 -DCAROM_ENABLE_QUERIES=0 -DCAROM_ENABLE_TOUCH_EVENTS=0 -DCAROM_ENABLE_STACKING=0 -DCAROM_ENABLE_GRID=0 -DCAROM_ENABLE_STATUS_NAMES=0 -DCAROM_ENABLE_GROW=0 -DCAROM_ENABLE_ANGLES=0 -DCAROM_ENABLE_BODY_EDITS=0 -DCAROM_ENABLE_CONTINUOUS=0"
n=$(size_of "$all_off")
printf '%8s  all capabilities off (circles, no rotation, no friction, gravity only)\n' "$n"
exit $fail
