#!/bin/sh
# calibrate.sh BUILD CLI SUITE_LIST OUT.cal -- fit `carom profile
# --calibration` to the instructions the Cortex-M4F executes.
#
# Runs two firmwares of the embedded suite on mps2-an386 under qemu with
# the insn_count plugin: the plain M4F firmware (BUILD/m4f/fw.elf: what a
# program runs) and the phase firmware (BUILD/m4f-phase/fw.elf: the
# profiling library, every phase switch marked, its per-phase operation
# counts printed). Adds `CLI profile --json` of each run's scene, method
# and steps, writes it all to BUILD/calibration.data, and runs
# BUILD/calibrate on it, which writes OUT.cal and prints, per run, the
# instructions against the cortex-m4f preset and the calibrated
# prediction.
set -eu
if [ $# -ne 4 ]; then
    echo "usage: calibrate.sh BUILD CLI SUITE_LIST OUT.cal" >&2
    exit 2
fi
build="$1"
cli="$2"
list="$3"
cal="$4"
qemu="${QEMU_ARM:-qemu-system-arm}"
plugin="$build/insn_count.so"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# addr ELF SYMBOL: the symbol's address, 0x...
addr() {
    a=$(arm-none-eabi-nm "$1" | awk -v s="$2" '$3 == s { print $1 }')
    [ -n "$a" ] || { echo "calibrate: no $2 in $1" >&2; exit 1; }
    echo "0x$a"
}

# run_fw NAME ELF PLUGIN-ARGS: run a firmware under qemu with the counter
run_fw() {
    if ! timeout 300 "$qemu" -machine mps2-an386 -nographic -monitor none \
            -semihosting-config enable=on,target=native -kernel "$2" \
            -plugin "$plugin,mark=$(addr "$2" platform_mark),out=$tmp/$1.marks$3" \
            < /dev/null > "$tmp/$1.out" 2>&1; then
        echo "calibrate: the $1 firmware failed under qemu:" >&2
        tail -n 5 "$tmp/$1.out" >&2
        exit 1
    fi
    grep -q '^done runs=.* failures=0$' "$tmp/$1.out" ||
        { echo "calibrate: the $1 firmware reported failures" >&2; grep '^error' "$tmp/$1.out" >&2; exit 1; }
}

elf="$build/m4f-phase/fw.elf"
phases=""
for k in 0 1 2 3 4 5 6 7; do
    phases="$phases${phases:+:}$(addr "$elf" "fw_phase_$k")"
done
prof=$(arm-none-eabi-nm -S "$elf" | awk '$4 == "cr_prof_phase" { print $1, $2 }')
[ -n "$prof" ] || { echo "calibrate: no cr_prof_phase in $elf" >&2; exit 1; }
# shellcheck disable=SC2086 # address and size
set -- $prof
prof_end=$(printf '0x%x' $((0x$1 + 0x$2)))
run_fw plain "$build/m4f/fw.elf" ""
run_fw phase "$elf" ",phase=$phases,meta=$(addr "$elf" __fwmeta_start):$(addr "$elf" __fwmeta_end),meta=0x$1:$prof_end"

grep '^result ' "$tmp/plain.out" > "$tmp/plain.results"
grep '^result ' "$tmp/phase.out" > "$tmp/phase.results"
cmp -s "$tmp/plain.results" "$tmp/phase.results" ||
    { echo "calibrate: the phase firmware's results differ from the plain one's" >&2; exit 1; }
grep '^insn-mark ' "$tmp/plain.marks" | awk '{ print $2 }' > "$tmp/plain.counts"
grep '^insn-buckets ' "$tmp/phase.marks" | cut -d' ' -f2- > "$tmp/phase.buckets"
runs=$(wc -l < "$tmp/plain.results")
[ "$(wc -l < "$tmp/plain.counts")" -eq $((2 * runs)) ] ||
    { echo "calibrate: the plain firmware's marks do not pair with its runs" >&2; exit 1; }
[ "$(wc -l < "$tmp/phase.buckets")" -eq $((2 * runs)) ] ||
    { echo "calibrate: the phase firmware's buckets do not pair with its runs" >&2; exit 1; }

data="$build/calibration.data"
echo "# NAME METHOD PLAIN B0..B7 META OPS0..OPS5 PROFILE-JSON (tools/embedded/calibrate.c)" > "$data"
i=0
while read -r _ name method steps _; do
    steps=${steps#steps=}
    i=$((i + 1))
    start=$(sed -n "$((2 * i - 1))p" "$tmp/plain.counts")
    end=$(sed -n "$((2 * i))p" "$tmp/plain.counts")
    b0=$(sed -n "$((2 * i - 1))p" "$tmp/phase.buckets")
    b1=$(sed -n "$((2 * i))p" "$tmp/phase.buckets")
    buckets=$(printf '%s\n%s\n' "$b0" "$b1" | awk 'NR == 1 { for (k = 1; k <= NF; k++) a[k] = $k }
        NR == 2 { for (k = 1; k <= NF; k++) printf "%s%d", (k > 1 ? " " : ""), $k - a[k] }')
    ops=$(awk -v n="$name" -v m="$method" '$1 == "ops" && $2 == n && $3 == m && $4 != "body_steps" {
            printf "%s%d", (c++ ? " " : ""), $5 + $6 + $7 + $8 + $9 + $10 }' "$tmp/phase.out")
    path=$(awk -v n="$name" '$1 == n { print $2 }' "$list")
    [ -n "$path" ] || { echo "calibrate: $name is not in $list" >&2; exit 1; }
    json=$("$cli" profile "$path" --no-progress --json --method "$method" --steps "$steps")
    echo "$name $method $((end - start)) $buckets $ops $json" >> "$data"
done < "$tmp/plain.results"
"$build/calibrate" "$data" -o "$cal"
