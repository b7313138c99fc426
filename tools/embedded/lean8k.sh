#!/bin/sh
# lean8k.sh DIR BYTES NAME... -- run DIR/NAME/fw.elf (a lean Cortex-M0
# firmware with a world buffer of BYTES) on QEMU's micro:bit, and compare
# its result line with DIR/NAME/host (the same scene and method on the
# default x86-64 build). Prints, per scene, the world the lean capacities
# need on the M0, the step's peak stack and the verdict.
set -eu
if [ $# -lt 3 ]; then
    echo "usage: lean8k.sh DIR BYTES NAME..." >&2
    exit 2
fi
dir="$1"
bytes="$2"
shift 2
qemu="${QEMU_ARM:-qemu-system-arm}"
status=0
for n in "$@"; do
    out="$dir/$n/qemu.out"
    rc=0
    timeout 50 "$qemu" -machine microbit -nographic -monitor none \
        -semihosting-config enable=on,target=native -kernel "$dir/$n/fw.elf" \
        < /dev/null > "$out" 2>&1 || rc=$?
    "$dir/$n/host" > "$dir/$n/host.out"
    want=$(grep '^result ' "$dir/$n/host.out" || true)
    got=$(grep '^result ' "$out" || true)
    world=$(awk '$1 == "world" { sub("bytes=", "", $3); print $3 }' "$out")
    peak=$(awk '$1 == "stack" { sub("step_peak=", "", $4); print $4 }' "$out")
    switches=$(grep -c '^#define CAROM_ENABLE_[A-Z_]* 1 ' "$dir/$n/carom_lean.h" || true)
    if [ "$rc" = 0 ] && [ -n "$want" ] && [ "$want" = "$got" ]; then
        echo "embedded-lean8k: ok: $n on the micro:bit (Cortex-M0): world ${world:-?} of $bytes bytes, step stack ${peak:-?} B, $switches switches on; result equals x86-64's"
    else
        echo "embedded-lean8k: FAIL: $n on the micro:bit (qemu exit $rc):" >&2
        grep -E '^(world|result|error|FAULT|stack)' "$out" | sed 's/^/    firmware: /' >&2 || true
        echo "    x86-64:   $want" >&2
        status=1
    fi
done
exit $status
