#!/bin/sh
# insn-profile.sh BUILD CLI SUITE_LIST [CALIBRATION] -- instructions
# executed by the steps of each suite run on the Cortex-M4F (mps2-an386
# under qemu, counted by the insn_count plugin between the firmware's two
# platform_mark calls), next to what `carom profile --weights cortex-m4f`
# predicts for the same scene, method and steps (total_cost, in the
# preset's cycles) and, given a calibration file, what `carom profile
# --calibration FILE` predicts (instructions) and its error.
#
# Needs a qemu-system-arm built with TCG plugin support (Debian's is) and
# BUILD/insn_count.so (tools/embedded/insn_count.c).
set -eu
build="$1"
cli="$2"
list="$3"
cal="${4:-}"
qemu="${QEMU_ARM:-qemu-system-arm}"
elf="$build/m4f/fw.elf"
plugin="$build/insn_count.so"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

mark=$(arm-none-eabi-nm "$elf" | awk '$3 == "platform_mark" { print $1 }')
[ -n "$mark" ] || { echo "insn-profile: no platform_mark in $elf" >&2; exit 1; }
if ! timeout 120 "$qemu" -machine mps2-an386 -nographic -monitor none \
        -semihosting-config enable=on,target=native -kernel "$elf" \
        -plugin "$plugin,mark=0x$mark,out=$tmp/marks" \
        < /dev/null > "$tmp/out" 2>&1; then
    echo "insn-profile: the firmware failed under qemu:" >&2
    tail -n 5 "$tmp/out" >&2
    exit 1
fi
grep '^result ' "$tmp/out" > "$tmp/results"
grep '^insn-mark ' "$tmp/marks" | awk '{ print $2 }' > "$tmp/counts"
runs=$(wc -l < "$tmp/results")
marks=$(wc -l < "$tmp/counts")
if [ "$marks" -ne $((2 * runs)) ]; then
    echo "insn-profile: $marks marks for $runs runs" >&2
    exit 1
fi

printf '%-8s %-8s %5s %6s %13s %11s %13s %9s' scene method steps bodies \
    instructions "insn/step" "m4f cost" "insn/cost"
[ -z "$cal" ] || printf ' %13s %7s' calibrated error
printf '\n'
total_cal=0
i=0
total_insn=0
total_cost=0
while read -r _ name method steps bodies _ impacts; do
    steps=${steps#steps=}
    bodies=${bodies#bodies=}
    impacts=${impacts#impacts=}
    i=$((i + 1))
    start=$(sed -n "$((2 * i - 1))p" "$tmp/counts")
    end=$(sed -n "$((2 * i))p" "$tmp/counts")
    insn=$((end - start))
    path=$(awk -v n="$name" '$1 == n { print $2 }' "$list")
    "$cli" profile "$path" --weights cortex-m4f --json --method "$method" \
        --steps "$steps" ${cal:+--calibration "$cal"} > "$tmp/json"
    cost=$(sed 's/.*"total_cost": *\([-0-9.eE+]*\).*/\1/' "$tmp/json")
    pimpacts=$(sed 's/.*"impacts": *\([0-9]*\).*/\1/' "$tmp/json")
    if [ "$pimpacts" != "$impacts" ]; then
        echo "insn-profile: warning: $name $method: the profiled run met $pimpacts impacts, the firmware $impacts (not the same run?)" >&2
    fi
    awk -v s="$name" -v m="$method" -v n="$steps" -v b="$bodies" -v i="$insn" -v c="$cost" \
        'BEGIN { printf "%-8s %-8s %5d %6d %13d %11.0f %13.0f %9.2f", s, m, n, b, i, i / n, c, (c > 0 ? i / c : 0) }'
    if [ -n "$cal" ]; then
        pred=$(sed 's/.*"calibrated":.*"total": *\([-0-9.eE+]*\).*/\1/' "$tmp/json")
        awk -v p="$pred" -v i="$insn" 'BEGIN { printf " %13.0f %+6.1f%%", p, 100 * (p / i - 1) }'
        total_cal=$(awk -v a="$total_cal" -v p="$pred" 'BEGIN { printf "%.0f", a + p }')
    fi
    printf '\n'
    total_insn=$((total_insn + insn))
    total_cost=$(awk -v a="$total_cost" -v c="$cost" 'BEGIN { printf "%.0f", a + c }')
done < "$tmp/results"
awk -v i="$total_insn" -v c="$total_cost" \
    'BEGIN { printf "%-8s %-8s %5s %6s %13d %11s %13.0f %9.2f", "all", "", "", "", i, "", c, (c > 0 ? i / c : 0) }'
[ -z "$cal" ] || awk -v p="$total_cal" -v i="$total_insn" \
    'BEGIN { printf " %13.0f %+6.1f%%", p, 100 * (p / i - 1) }'
printf '\n'
