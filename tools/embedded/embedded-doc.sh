#!/bin/sh
# embedded-doc.sh OUT.md -- regenerate docs/embedded.md: every number in it
# is measured here, by `make embedded-doc` (tools/embedded/embedded.mk),
# which builds what this script runs first.
#
# Environment (set by the make rule): BUILD (the build directory), CLI
# (build/carom), CC, HOST_FLAGS (the library's host flags), ARM_CC,
# M4F_FLAGS, M0_FLAGS (the library's Cortex-M flags), M4F_CPU (the M4F
# CPU flags alone, for linking), QEMU_ARM.
#
# It runs: check-embedded.sh (hashes, stack) and its negative test;
# calibrate.sh (the profile calibration, rewriting
# tools/embedded/cortex-m4f.cal) and insn-profile.sh; lean8k.sh; the
# sizes firmware and suite_host --sizes; and builds the library for
# Cortex-M4F and x86-64 in every configuration of the footprint table
# (default, all switches off, each switch off alone, lean for each scene of
# tools/scenes/), under $BUILD/embedded/doc/.
set -eu
if [ $# -ne 1 ] || [ "$1" = "--help" ]; then
    echo "usage: BUILD=... CLI=... CC=... HOST_FLAGS=... ARM_CC=... M4F_FLAGS=... M0_FLAGS=... M4F_CPU=... sh embedded-doc.sh OUT.md" >&2
    [ $# -eq 1 ] && exit 0
    exit 2
fi
out="$1"
: "${BUILD:?}" "${CLI:?}" "${CC:?}" "${HOST_FLAGS:?}" "${ARM_CC:?}" "${M4F_FLAGS:?}" "${M0_FLAGS:?}"
: "${M4F_CPU:?}"
qemu="${QEMU_ARM:-qemu-system-arm}"
emb="$BUILD/embedded"
work="$emb/doc"
rm -rf "$work"
mkdir -p "$work"
jobs=$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 2)
doc="$work/embedded.md"

say() { echo "embedded-doc: $*" >&2; }

# ---- measurements ------------------------------------------------------------------

say "check-embedded (hashes, stack) and its negative test"
QEMU_ARM="$qemu" sh tools/embedded/check-embedded.sh "$emb" m4f:mps2-an386:full \
    m3:mps2-an385:full m0:microbit:small m0-mps2:mps2-an385:full > "$work/check.txt"
QEMU_ARM="$qemu" sh tools/embedded/check-embedded.sh --expect-mismatch "$emb" \
    m4f-fma:mps2-an386:full > "$work/negative.txt"
say "calibration (qemu instruction counts)"
QEMU_ARM="$qemu" sh tools/embedded/calibrate.sh "$emb" "$CLI" tools/embedded/suite.list \
    tools/embedded/cortex-m4f.cal > "$work/calibrate.txt"
say "8 KB of world on the micro:bit"
QEMU_ARM="$qemu" sh tools/embedded/lean8k.sh "$emb/lean8k" 8192 bounce stack > "$work/lean8k.txt" 2>&1 ||
    true
say "what worlds cost in memory"
"$emb/suite_host" --sizes > "$work/sizes-x86-64.txt"
timeout 30 "$qemu" -machine microbit -nographic -monitor none \
    -semihosting-config enable=on,target=native -kernel "$emb/m0-sizes/fw.elf" \
    < /dev/null > "$work/sizes-m0.txt" 2>&1

# ---- the library in every configuration of the footprint table ---------------------

# switches of include/carom_config.h (CAROM_ENABLE_PROFILE aside)
sed -n 's/^#ifndef CAROM_ENABLE_\([A-Z0-9_]*\).*/\1/p' include/carom_config.h |
    grep -v '^PROFILE$' > "$work/switches"
# (all off keeps one method: the discrete one)
all_off=""
while read -r sw; do
    [ "$sw" = DISCRETE ] || all_off="$all_off -DCAROM_ENABLE_$sw=0"
done < "$work/switches"

# build_cfg NAME FLAGS: libcarom.a for the M4F and for x86-64, then
# "NAME m4f-text data bss x86-text" into $work/NAME.size
build_cfg() {
    d="$work/cfg/$1"
    mkdir -p "$d/m4f" "$d/host"
    for f in src/*.c; do
        b=$(basename "$f" .c)
        # shellcheck disable=SC2086 # flag lists are words
        "$ARM_CC" $M4F_FLAGS -Iinclude $2 -c "$f" -o "$d/m4f/$b.o" 2>> "$d/log" || return 1
        # shellcheck disable=SC2086
        "$CC" $HOST_FLAGS -Iinclude $2 -c "$f" -o "$d/host/$b.o" 2>> "$d/log" || return 1
    done
    arm-none-eabi-ar rcs "$d/m4f.a" "$d"/m4f/*.o
    ar rcs "$d/host.a" "$d"/host/*.o
    m=$(arm-none-eabi-size -t "$d/m4f.a" | tail -n 1 | awk '{ print $1, $2, $3 }')
    h=$(size -t "$d/host.a" | tail -n 1 | awk '{ print $1 }')
    echo "$1 $m $h" > "$work/$1.size"
    # a program that steps a world must link against it
    # shellcheck disable=SC2086
    if ! { "$ARM_CC" $M4F_FLAGS -Iinclude $2 -c "$work/prog.c" -o "$d/prog.o" 2>> "$d/log" &&
           "$ARM_CC" $M4F_CPU --specs=nosys.specs --specs=nano.specs "$d/prog.o" "$d/m4f.a" \
               -lm -o "$d/prog.elf" 2> "$d/link.log"; }; then
        sed -n 's/.*undefined reference to .\([A-Za-z0-9_]*\).*/\1/p' "$d/link.log" | sort -u |
            paste -s -d ' ' - > "$work/$1.nolink"
    fi
}
cat > "$work/prog.c" <<'EOS'
#include "carom.h"
static unsigned char mem[1 << 16];
int main(void)
{
    carom_world_def wd = carom_default_world_def();
    carom_body_def b = carom_default_body_def();
    carom_world *w;
    int i;
    wd.max_bodies = 4;
    if (carom_world_init(&w, &wd, mem, sizeof mem) != CAROM_OK ||
        carom_world_add_body(w, &b, 0) != CAROM_OK)
        return 1;
    for (i = 0; i < 10; ++i)
        carom_world_step(w);
    return 0;
}
EOS

# the configurations, one per line: NAME FLAGS...
{
    echo "default"
    echo "all-off $all_off"
    while read -r sw; do echo "no-$sw -DCAROM_ENABLE_$sw=0"; done < "$work/switches"
    echo "profile -DCAROM_ENABLE_PROFILE=1"
    for s in tools/scenes/*.scene; do
        n=$(basename "$s" .scene)
        if "$CLI" lean "$s" > "$work/lean-$n.h" 2> "$work/lean-$n.err"; then
            echo "lean-$n -include $work/lean-$n.h"
        fi
    done
    # a circles-only frictionless scene with the discrete method
    if "$CLI" lean tools/scenes/cradle.scene --method discrete > "$work/lean-cradle-discrete.h" \
            2> "$work/lean-cradle-discrete.err"; then
        echo "lean-cradle-discrete -include $work/lean-cradle-discrete.h"
    fi
} > "$work/configs"
say "building $(wc -l < "$work/configs") configurations for Cortex-M4F and x86-64"
running=0
while read -r name flags; do
    ( build_cfg "$name" "$flags" || { say "configuration $name does not build:"; head -n 5 "$work/cfg/$name/log" >&2; } ) &
    running=$((running + 1))
    if [ "$running" -ge "$jobs" ]; then
        wait
        running=0
    fi
done < "$work/configs"
wait

read -r _ def_m4f _ _ def_host < "$work/default.size"
# row NAME LABEL: a table row of the footprint
row() {
    if [ -f "$work/$1.size" ]; then
        read -r _ m d b h < "$work/$1.size"
        note=""
        [ ! -f "$work/$1.nolink" ] || note=" (a program does not link: undefined $(cat "$work/$1.nolink"))"
        awk -v l="$2$note" -v m="$m" -v d="$d" -v b="$b" -v h="$h" -v dm="$def_m4f" -v dh="$def_host" \
            'BEGIN { printf "| %s | %d | %d | %d | %.2f | %d | %.2f |\n", l, m, d, b, m / dm, h, h / dh }'
    else
        echo "| $2 | (does not build) | | | | | |"
    fi
}

# ---- nm: what remains in the lean builds of the two size targets ---------------------

# fn_table LIB: the 25 largest functions and objects of an M4F archive
fn_table() {
    arm-none-eabi-nm -S -t d --size-sort "$1" | awk 'NF == 4 && $3 ~ /[tTrRdD]/ { print $2 + 0, $4 }' |
        sort -rn | head -n 25 | awk '{ printf "| `%s` | %d |\n", $2, $1 }'
}
# fn_sum LIB "NAME ...": bytes of the named symbols in an M4F archive
fn_sum() {
    arm-none-eabi-nm -S -t d "$1" | awk -v names="$2" '
        BEGIN { n = split(names, a, " "); for (i = 1; i <= n; i++) want[a[i]] = 1 }
        NF == 4 { s = $4; sub(/\..*/, "", s); if (s in want) t += $2 }
        END { print t + 0 }'
}
# fn_sum, or "inline" where the functions have no symbol of their own
# (inlined into their callers, whose bytes hold them)
fn_sum_or_inline() {
    n=$(fn_sum "$1" "$2")
    if [ "$n" -eq 0 ]; then echo "inline"; else echo "$n"; fi
}
default_lib="$work/cfg/default/m4f.a"
cradle_lib="$work/cfg/lean-cradle/m4f.a"
gas_lib="$work/cfg/lean-gas/m4f.a"
stacking="cr_solver_levels cr_solver_prime cr_solver_unload cr_solver_shock cr_one_sided cr_push_up cr_support_of cr_correct_shock"
quartic="cr_first_root4 cr_poly4"
toi_pp="cr_toi_vertices_edges"
wake="cr_island_wake_touched cr_island_wake"
profile_api="carom_op_weights_preset cr_presets carom_op_name carom_phase_name cr_op_names cr_phase_names carom_profile_cost carom_profile_reset"
block="cr_lcp2"
trig="carom_rot_from_angle carom_rot_angle"
continuous="cr_continuous_statics cr_continuous_escapes cr_escape_check cr_may_be_fast cr_escape_static cr_box_holds cr_box_merge cr_drift_still cr_is_wall cr_sweep_static cr_turn_between cr_path_turn cr_meet_static cr_fly_off cr_flight_meets cr_went_through cr_overlap_across cr_out_far_side cr_centre_through cr_centre_through_local cr_way_at cr_way_through_turning cr_local_outside cr_reach_along"
edits="carom_world_remove_body carom_body_set_velocity carom_body_set_angular_velocity carom_body_set_transform carom_body_apply_impulse carom_body_apply_angular_impulse carom_body_apply_force carom_body_apply_torque carom_body_set_restitution carom_body_set_friction carom_body_set_filter carom_body_set_force cr_wake_neighbours cr_forget_body"
# code_list "NAME ...": `NAME`, `NAME` ... for the document
code_list() { echo "$1" | awk '{ for (i = 1; i <= NF; i++) printf "%s`%s`", (i > 1 ? ", " : ""), $i }'; }
status_o() { arm-none-eabi-size "$1" | awk '$6 == "status.o" { print $1 }'; }

# flt_eval "FLAGS": FLT_EVAL_METHOD of the ARM compiler with those flags
flt_eval() {
    # shellcheck disable=SC2086 # a flag list
    echo | "$ARM_CC" $1 -dM -E - 2>/dev/null | sed -n 's/^#define __FLT_EVAL_METHOD__ //p'
}

# buffer TARGET: the world buffer the firmware reported
buffer() { sed -n 's/^world .* buffer=\([0-9]*\).*/\1/p' "$emb/$1/qemu.out" | head -n 1; }

# ---- the document ---------------------------------------------------------------------

# CAROM_COMMIT may name the source when this is not a git checkout
if [ -n "${CAROM_COMMIT:-}" ]; then
    commit=$CAROM_COMMIT
    dirty=""
else
    commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
    dirty=""
    git diff --quiet HEAD -- src include 2>/dev/null || dirty=" with uncommitted changes to src/ or include/"
fi
{
cat <<EOF
# carom on microcontrollers

Generated by \`make embedded-doc\` (tools/embedded/embedded-doc.sh); every
number below is measured by that run. Machine: $(uname -m), $(grep -c ^processor /proc/cpuinfo 2>/dev/null || echo "?") CPUs
($(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo 2>/dev/null | head -n 1)). Build: carom $commit$dirty;
$("$CC" --version | head -n 1); $("$ARM_CC" --version | head -n 1);
$("$qemu" --version | head -n 1).

## Targets tested

\`make check-embedded\` (part of \`make check\` when qemu-system-arm and
arm-none-eabi-gcc are installed) runs the scene suite of
tools/embedded/suite.list with the events and the discrete method on
emulated boards and fails unless every final-state hash (FNV-1a of the
bits of every body's position, rotation, velocity, angular velocity and
centre) and impact count equals the x86-64 build's.

| firmware | QEMU board | core | float ABI | world buffer, bytes | suite |
| --- | --- | --- | --- | --- | --- |
| m4f | mps2-an386 | Cortex-M4F | hard (\`-mfpu=fpv4-sp-d16 -mfloat-abi=hard\`) | $(buffer m4f) | all |
| m3 | mps2-an385 | Cortex-M3 | soft (libgcc \`__aeabi_f*\`) | $(buffer m3) | all |
| m0 | microbit (nRF51822, 16 KB RAM) | Cortex-M0 | soft | $(buffer m0) | reduced (\`small\`) |
| m0-mps2 | mps2-an385 | the Cortex-M0 build (ARMv6-M code) | soft | $(buffer m0-mps2) | all |

This run:

\`\`\`
$(cat "$work/check.txt")
\`\`\`

The check fails when it should: the M4F build with \`-ffp-contract=fast\`
(GCC then fuses multiply-adds into VFMA) must differ
(\`make check-embedded-negative\`):

\`\`\`
$(cat "$work/negative.txt")
\`\`\`

## Determinism: what it rests on

carom gives the same bits on every target that:

- computes in IEEE 754 single precision with round-to-nearest-even, every
  operation rounded to float: \`FLT_EVAL_METHOD\` 0. Here:
  x86-64 \`$(echo | "$CC" -dM -E - | sed -n 's/^#define __FLT_EVAL_METHOD__ //p')\`,
  Cortex-M4F \`$(flt_eval "$M4F_FLAGS")\`,
  Cortex-M0 (soft float) \`$(flt_eval "$M0_FLAGS")\`,
  i386 with the x87 (\`cc -m32\`)
  \`$(echo | "$CC" -m32 -dM -E - 2>/dev/null | sed -n 's/^#define __FLT_EVAL_METHOD__ //p')\`
  (excess precision: different bits), i386 with \`-msse2 -mfpmath=sse\`
  \`$(echo | "$CC" -m32 -msse2 -mfpmath=sse -dM -E - 2>/dev/null | sed -n 's/^#define __FLT_EVAL_METHOD__ //p')\`;
- contracts nothing: \`-ffp-contract=off\` (no fused multiply-add; the
  negative test above shows what FMA does), and no \`-ffast-math\`, no
  \`-Ofast\`, no \`-funsafe-math-optimizations\`, no \`-freciprocal-math\`
  (they reorder and approximate);
- has a correctly rounded \`sqrtf\` (IEEE 754 requires it; glibc's x86-64
  and newlib's are; a hardware VSQRT is; an approximation is not): it is
  the only libm function carom calls (\`make check-symbols\`);
- keeps denormals (no flush-to-zero mode set by the program).

carom computes no trigonometry through libm (its own, from + - * / and
sqrt), and its arithmetic goes through one layer (src/arith.h), so these
are all the assumptions.

## Footprint per configuration

\`size -t\` of libcarom.a (text includes read-only data), built with the
project's flags (\`-O2\`; Cortex-M4F: \`$M4F_FLAGS\`). "all off" turns
every capability switch of include/carom_config.h off ($(grep -v '^DISCRETE$' "$work/switches" | paste -s -d ' '); DISCRETE stays on, one method must be left); "no X"
turns X alone off; "lean NAME" uses the header \`carom lean
tools/scenes/NAME.scene\` prints (its scene's switches; see \`make lean\`).

| configuration | M4F text | data | bss | x default | x86-64 text | x default |
| --- | --- | --- | --- | --- | --- | --- |
EOF
row default "default"
row all-off "all off"
while read -r sw; do row "no-$sw" "no $sw"; done < "$work/switches"
row profile "profiling on (CAROM_ENABLE_PROFILE=1)"
for s in tools/scenes/*.scene; do
    n=$(basename "$s" .scene)
    if [ -f "$work/lean-$n.h" ]; then
        row "lean-$n" "lean $n ($(grep -c '^#define CAROM_ENABLE_[A-Z_]* 1 ' "$work/lean-$n.h") switches on)"
    else
        echo "| lean $n | (carom lean failed: $(head -n 1 "$work/lean-$n.err")) | | | | | |"
    fi
done
row lean-cradle-discrete "lean cradle with --method discrete"
cat <<EOF

### The size targets

A circles-only frictionless scene's lean library should be at most half
the default text, a gas in a box of static walls at most 0.8 of it. With
today's switches (M4F):

EOF
for t in cradle:0.5 cradle-discrete:0.5 gas:0.8; do
    n=${t%%:*}
    if [ -f "$work/lean-$n.size" ]; then
        read -r _ m _ _ _ < "$work/lean-$n.size"
        awk -v n="$n" -v m="$m" -v d="$def_m4f" -v t="${t#*:}" \
            'BEGIN { printf "- lean %s: %d of %d bytes, %.2f of the default: target %.1f %s\n", n, m, d, m / d, t, (m / d <= t + 0 ? "met" : "missed") }'
    fi
done
cat <<EOF

What is left of the lean cradle build (circles only, no
rotation, no friction, zero gravity, events method), largest first:

| symbol | bytes (M4F) |
| --- | --- |
$(fn_table "$cradle_lib")

Finer switches, with the bytes of the symbols each removes (or would
remove) from these two lean builds (nm of the M4F archives above; inlined
helpers are counted in their callers, so these are lower bounds). The
first rows exist, and the lean builds above already leave out what they
can (their bytes are those of the default build, where the code is still
in); the rows after them are proposals:

| switch | what it removes | when \`carom lean\` turns it off | default | cradle | gas |
| --- | --- | --- | --- | --- | --- |
| \`CAROM_ENABLE_STACKING\` | support order, cold-start priming, the warm start's unloading and shock propagation ($(code_list "$stacking")) | gravity 0 (they do nothing then) | $(fn_sum "$default_lib" "$stacking") | - | - |
| \`CAROM_ENABLE_STATUS_NAMES\` | the text of \`carom_status_string\` (one generic string left) | always, unless the program prints statuses | - | - | - |
| \`CAROM_ENABLE_GRID\` | the broadphase grid (every pair of boxes is tested instead) | up to 64 bodies | - | - | - |
| \`CAROM_ENABLE_BODY_EDITS\` | removing bodies and the \`carom_body_set_*\` / \`carom_body_apply_*\` calls ($(code_list "$edits"), stubs left) | always, unless the program calls them | $(fn_sum "$default_lib" "$edits") | - | - |
| \`CAROM_ENABLE_CONTINUOUS\` | the step's continuous guard against static and kinematic bodies ($(code_list "$continuous")) | no body went into or through a static or kinematic body in the run | $(fn_sum "$default_lib" "$continuous") | - | - |
| \`CAROM_ENABLE_ANGLES\` | the angle helpers ($(code_list "$trig")), with \`CAROM_ENABLE_CONTINUOUS\` off too the arctangent (\`cr_rot_angle\`), and with rotation off carom's sine and cosine (\`cr_rot_from_angle\`) | rotation off and every body at angle 0 | $(fn_sum "$default_lib" "$trig cr_rot_from_angle") | - | - |
| (circles only) the two-point block solve | \`cr_lcp2\` and its callers' block branches: compiled only when a contact can have two points (polygons) | with \`CAROM_ENABLE_POLYGONS\` | $(fn_sum_or_inline "$default_lib" "$block") | - | - |
| (not possible) the quartic time of impact without gravity and forces | $(code_list "$quartic") | never: a solved contact's impulse is spread over its substep as an acceleration (\`cr_solver_set_drifts\`), so bodies touching others accelerate even then | $(fn_sum "$default_lib" "$quartic") | $(fn_sum "$cradle_lib" "$quartic") | $(fn_sum "$gas_lib" "$quartic") |
| (a fix) polygon-polygon TOI under \`CAROM_ENABLE_POLYGON_POLYGON\` | \`cr_toi_vertices_edges\` | with POLYGON_POLYGON | $(fn_sum "$default_lib" "$toi_pp") | $(fn_sum "$cradle_lib" "$toi_pp") | $(fn_sum "$gas_lib" "$toi_pp") |
| (a fix) waking under \`CAROM_ENABLE_SLEEP\` | \`cr_island_wake_touched\`, \`cr_island_wake\` | with SLEEP | $(fn_sum "$default_lib" "$wake") | $(fn_sum "$cradle_lib" "$wake") | $(fn_sum "$gas_lib" "$wake") |
| weights and names only with \`CAROM_ENABLE_PROFILE\` | $(code_list "$profile_api") | always in a lean build | $(fn_sum "$default_lib" "$profile_api") | $(fn_sum "$cradle_lib" "$profile_api") | $(fn_sum "$gas_lib" "$profile_api") |
| statics only as boxes (\`CAROM_ENABLE_GENERAL_POLYGONS\`) | the convexity and self-intersection checks and the polygon mass of \`cr_body_build\` (inlined: $(fn_sum "$gas_lib" cr_body_build) bytes in gas, $(fn_sum "$cradle_lib" cr_body_build) without polygons) | every polygon a box, none dynamic | - | - | ~$(($(fn_sum "$gas_lib" cr_body_build) - $(fn_sum "$cradle_lib" cr_body_build))) |

## Stack

Peak stack of \`carom_world_step\`, measured by painting the stack before a
run's steps and finding the lowest word changed after them (everything the
step calls included: libgcc, \`sqrtf\`):

| firmware | deepest step, bytes | scene and method |
| --- | --- | --- |
EOF
for t in m4f m3 m0 m0-mps2; do
    awk -v t="$t" '$1 == "stack" && $4 ~ /^step_peak=/ { sub("step_peak=", "", $4);
        if ($4 + 0 > best) { best = $4 + 0; where = $2 " " $3 } }
        END { printf "| %s | %d | %s |\n", t, best, where }' "$emb/$t/qemu.out"
done
cat <<EOF

## RAM: what a world needs

\`carom_world_buffer_size()\` of worlds that differ in one capacity
(tools/embedded/sizes.c; on the Cortex-M0 the sizes firmware prints them
under QEMU's micro:bit). The per-body cost includes the simultaneous-impact
rows, sized per body up to CAROM_IMPACT_ISLAND_MAX_BODIES bodies, which is
why it drops above that.

| | x86-64 (64-bit) | Cortex-M0 (32-bit) |
| --- | --- | --- |
EOF
for k in world_1_body_all_capacities_1 per_body_below_256 per_body_above_256 per_pair \
         per_contact per_event per_impact default_world_6_bodies default_world_16_bodies \
         default_world_256_bodies default_world_4096_bodies; do
    a=$(awk -v k="$k" '$1 == "size" && $2 == k { print $3 }' "$work/sizes-x86-64.txt")
    b=$(awk -v k="$k" '$1 == "size" && $2 == k { print $3 }' "$work/sizes-m0.txt")
    label=$(echo "$k" | tr _ ' ')
    case "$k" in
        default_world_*)
            nb=$(echo "$k" | sed 's/default_world_\([0-9]*\)_bodies/\1/')
            awk -v l="$label" -v a="$a" -v b="$b" -v n="$nb" \
                'BEGIN { printf "| %s (default capacities) | %d (%d per body) | %d (%d per body) |\n", l, a, a / n, b, b / n }' ;;
        *) echo "| $label, bytes | $a | $b |" ;;
    esac
done
cat <<EOF

A unit of pair capacity is a candidate pair, its heap entry and its touch
entries (and a copy for the sort when the contacts are too few to lend
theirs); a contact is its constraint, its solve-order slot and its
warm-start record; an event is a \`carom_event\`. Impacts per step
(\`max_impacts\`) cost nothing: it is a budget, not an array. A program
with a heap can start smaller and let the world grow
(\`carom_world_def.grow\`, docs/robustness.md): a step short of pairs or
contacts then takes a pool twice as large and is taken again. The
target of at most 500 bytes per body at default capacities is
$(awk '$2 ~ /^default_world_/ { n = $2; gsub(/[^0-9]/, "", n); if ($3 / n > 500) bad = 1 }
       END { print (bad ? "not met" : "met") }' "$work/sizes-m0.txt").

Why it is not met: the default capacities must hold a dense pile (a
pile of N bodies must not fail at them), and a pile needs more than that
at exactly the capacities it uses. Equal circles packed hexagonally touch
6 others each (3 contacts a body), and \`docs/benchmarks.md\` (Memory per
body) measures about 3.1 to 3.5 candidate pairs and 1.4 to 1.9 contacts
a body on the falling pile of 10^2 to 10^4 bodies, 1,170 to 1,640 bytes a
body at exactly those capacities; the per-body records alone (the body
and its step backup, shape, bounding box, grid entry, solver and drift
state) are about 600 bytes. Box2D v3 holds the same 10^4 pile in about
4.5 KB a body, Box2D 2.4.1 in about 2.1 KB. Reaching 500 needs records of
less than half their size (a shared shape store, compact contact points),
not a smaller default.

### 8 KB of world on an M0

\`make embedded-lean8k\`: the bounce scene and the 5-box stack, each built
with the switches and capacities of its \`carom lean\` header, run on the
micro:bit's Cortex-M0 with a world buffer of 8192 bytes; the result must
equal the default x86-64 build's:

\`\`\`
$(cat "$work/lean8k.txt")
\`\`\`

## Porting to another MCU

1. Compile src/*.c with the project's flags: \`-std=c99 -O2
   -ffp-contract=off\` and your CPU flags; nothing else in src/ needs a
   port (no OS, no allocation, no libm function but \`sqrtf\`). A hardware
   FPU must be single precision IEEE 754 (FPv4-SP, FPv5); without one, the
   compiler's soft-float library (libgcc \`__aeabi_f*\`) gives the same
   bits.
2. Provide \`sqrtf\` correctly rounded, \`memcpy\`, \`memset\`, \`memmove\`
   and \`strcmp\` (newlib-nano has them; \`make check-symbols\` lists what
   the archive needs and picks arm-none-eabi-nm for ARM archives).
3. Check \`FLT_EVAL_METHOD\` is 0 and no option turns on contraction or
   fast math.
4. Size the world: \`carom lean SCENE\` prints the switches and capacities
   for a scene and \`CAROM_LEAN_WORLD_BYTES\`; call
   \`carom_world_buffer_size()\` on the target for the exact figure.
   Budget the step's stack from the table above, plus your own frames.
5. Prove it: add the board to tools/embedded/embedded.mk (a linker script
   with its FLASH and RAM, the CPU flags) and run \`make check-embedded\`:
   the hashes must equal x86-64's.

## Instruction counts and the profiler's prediction

\`make embedded-calibrate\` counts, with a QEMU TCG plugin
(tools/embedded/insn_count.c), the instructions each suite run's steps
execute on the M4F, in the plain firmware and in a phase firmware whose
library has the op counters and marks every profiler phase. The cortex-m4f
preset of \`carom profile\` (unchanged, the design note's unit) prices only
float operations, in FPv4 cycles; loads, stores, integer work and branches
are most of what runs. The calibration (tools/embedded/cortex-m4f.cal,
used by \`carom profile --calibration FILE\`) predicts instructions per
phase: instructions per float operation of that phase, plus overheads per
step, per body-step, per awake body-step and per contact-step, fitted by
non-negative least squares to the per-phase counts (the counters' own
instructions taken out in proportion to the operations). The op counts
themselves are unchanged and exact. "LOSO": the prediction when the run's
scene was left out of the fit. QEMU counts instructions, not cycles: on a
real Cortex-M4 cycles are at least as many (loads take 2, VDIV and VSQRT
14).

\`\`\`
$(cat "$work/calibrate.txt")
\`\`\`

The calibration:

\`\`\`
$(grep -v '^#' tools/embedded/cortex-m4f.cal)
\`\`\`
EOF
} > "$doc"
cp "$doc" "$out"
say "wrote $out"
