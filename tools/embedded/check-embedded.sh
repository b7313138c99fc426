#!/bin/sh
# check-embedded.sh [--expect-mismatch] BUILD TARGET:BOARD:SCOPE ...
#
# Runs BUILD/TARGET/fw.elf under qemu-system-arm -machine BOARD (all
# targets at once) and compares every "result" line it prints (scene,
# method, steps, bodies, FNV-1a hash of every body's state bits, impact
# count) with the x86-64 build's (BUILD/suite_host; SCOPE "small": the
# reduced suite, --small). Fails on any difference, a missing line, a
# firmware error or fault, or a run over the time limit. Prints per target
# the peak stack of carom_world_step (painted-stack measurement).
#
# --expect-mismatch: the negative test; succeeds only if the firmware ran
# to the end and at least one hash differs from the x86-64 build's.
set -eu
expect_mismatch=0
if [ "${1:-}" = "--expect-mismatch" ]; then
    expect_mismatch=1
    shift
fi
build="$1"
shift
qemu="${QEMU_ARM:-qemu-system-arm}"
limit="${EMB_TIME_LIMIT:-50}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

"$build/suite_host" > "$tmp/host-full.txt"
"$build/suite_host" --small > "$tmp/host-small.txt"

# Every firmware at once (each is one single-threaded qemu).
for spec in "$@"; do
    t=${spec%%:*}
    rest=${spec#*:}
    board=${rest%%:*}
    (
        rc=0
        timeout "$limit" "$qemu" -machine "$board" -nographic -monitor none \
            -semihosting-config enable=on,target=native \
            -kernel "$build/$t/fw.elf" < /dev/null > "$tmp/$t.out" 2>&1 || rc=$?
        echo "$rc" > "$tmp/$t.rc"
    ) &
done
wait

status=0
for spec in "$@"; do
    t=${spec%%:*}
    rest=${spec#*:}
    board=${rest%%:*}
    scope=${rest#*:}
    rc=$(cat "$tmp/$t.rc")
    out="$tmp/$t.out"
    cp "$out" "$build/$t/qemu.out"
    grep '^result ' "$tmp/host-$scope.txt" > "$tmp/$t.want" || true
    grep '^result ' "$out" > "$tmp/$t.got" || true
    want=$(wc -l < "$tmp/$t.want")
    differ=$(diff "$tmp/$t.want" "$tmp/$t.got" | grep -c '^>' || true)
    peak=$(awk '$1 == "stack" && $4 ~ /^step_peak=/ { sub("step_peak=", "", $4);
                if ($4 + 0 > best) { best = $4 + 0; where = $2 " " $3 } }
                END { if (best) print best " B (" where ")"; else print "?" }' "$out")
    world=$(awk '$1 == "world" { sub("bytes=", "", $3); if ($3 + 0 > best) { best = $3 + 0; where = $2 } }
                 END { if (best) print best " B (" where ")"; else print "?" }' "$out")
    ran_to_end=0
    if [ "$rc" = 0 ] && grep -q '^done runs=.* failures=0$' "$out"; then
        ran_to_end=1
    fi
    if [ "$expect_mismatch" = 1 ]; then
        got=$(wc -l < "$tmp/$t.got")
        if grep -q '^done runs=' "$out" && [ "$differ" -gt 0 ]; then
            echo "check-embedded-negative: ok: $t on $board: $differ of $want results differ from x86-64's, as they must ($((want - got)) more not produced)"
            diff "$tmp/$t.want" "$tmp/$t.got" | sed -n 's/^/    /p' | head -n 8
            grep '^error' "$out" | sed 's/^/    firmware: /' || true
        else
            echo "check-embedded-negative: FAIL: $t on $board: the build meant to differ gave the x86-64 results (or did not run: qemu exit $rc)" >&2
            sed 's/^/    /' "$out" | tail -n 5 >&2
            status=1
        fi
        continue
    fi
    if [ "$rc" = 124 ]; then
        echo "check-embedded: FAIL: $t on $board: over the ${limit} s limit" >&2
        status=1
    elif [ "$ran_to_end" != 1 ]; then
        echo "check-embedded: FAIL: $t on $board: the firmware failed (qemu exit $rc):" >&2
        grep -E '^(error|FAULT|stack .*overflow|done)' "$out" | sed 's/^/    /' >&2 || true
        tail -n 3 "$out" | sed 's/^/    /' >&2
        status=1
    fi
    if [ "$want" -eq 0 ]; then
        echo "check-embedded: FAIL: the x86-64 suite printed no result" >&2
        status=1
    elif ! cmp -s "$tmp/$t.want" "$tmp/$t.got"; then
        echo "check-embedded: FAIL: $t on $board differs from x86-64 (< x86-64, > $t):" >&2
        diff "$tmp/$t.want" "$tmp/$t.got" | sed 's/^/    /' >&2 || true
        status=1
    else
        echo "check-embedded: ok: $t on $board: $want of $want results equal x86-64's; step stack peak $peak; largest world $world"
    fi
done
exit $status
