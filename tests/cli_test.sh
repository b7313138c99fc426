#!/bin/sh
# cli_test.sh -- end-to-end tests of the carom command-line tool.
#
# usage: sh tests/cli_test.sh build/carom
#
# Prints one "ok - ..." / "not ok - ..." line per check, then
# "N passed, M failed"; exits non-zero if any check failed.

set -u

if [ $# -ne 1 ]; then
    echo "usage: sh tests/cli_test.sh PATH-TO-CAROM" >&2
    exit 2
fi
cli=$1
case $cli in
    /*) ;;
    *) cli=$(pwd)/$cli ;;
esac
if [ ! -x "$cli" ]; then
    echo "cli_test.sh: '$cli' is not an executable" >&2
    exit 2
fi

root=$(cd "$(dirname "$0")/.." && pwd)
default_scene=$root/tools/scenes/default.scene

tmp=$(mktemp -d "${TMPDIR:-/tmp}/carom_cli_test.XXXXXX") || exit 2
trap 'rm -rf "$tmp"' EXIT
trap 'exit 2' HUP INT TERM

passed=0
failed=0

ok() {
    passed=$((passed + 1))
    echo "ok - $1"
}

not_ok() {
    failed=$((failed + 1))
    echo "not ok - $1"
    if [ $# -gt 1 ]; then
        echo "#   $2"
    fi
}

# check DESCRIPTION COMMAND...: ok if the command succeeds.
check() {
    desc=$1
    shift
    if "$@"; then
        ok "$desc"
    else
        not_ok "$desc"
    fi
}

# verdict STATUS DESCRIPTION: ok if STATUS is 0 (for awk programs, which
# are run directly so that shellcheck knows them for awk).
verdict() {
    if [ "$1" -eq 0 ]; then
        ok "$2"
    else
        not_ok "$2"
    fi
}

# run ARGS...: run the CLI; stdout to $tmp/out, stderr to $tmp/err, status
# to $rc.
run() {
    "$cli" "$@" >"$tmp/out" 2>"$tmp/err"
    rc=$?
}

# expect_rc WANT DESCRIPTION: compare the last run's status.
expect_rc() {
    if [ "$rc" -eq "$1" ]; then
        ok "$2 (exit $1)"
    else
        not_ok "$2 (exit $1)" "got exit $rc; stderr: $(head -n 3 "$tmp/err")"
    fi
}

# stderr_has TEXT DESCRIPTION: the last run's stderr contains TEXT.
stderr_has() {
    if grep -F -q -e "$1" "$tmp/err"; then
        ok "$2"
    else
        not_ok "$2" "stderr lacks '$1': $(head -n 3 "$tmp/err")"
    fi
}

# Count the bodies of a scene: lines whose first word is "body".
body_count() {
    awk '{ sub(/#.*/, "") } $1 == "body" { n++ } END { print n + 0 }' "$1"
}

nbodies=$(body_count "$default_scene")

# ---- usage ----------------------------------------------------------------

run --help
expect_rc 0 "--help"
check "--help prints usage" grep -q usage "$tmp/out"

run -h
expect_rc 0 "-h"

run run --help
expect_rc 0 "run --help"

run
expect_rc 2 "no arguments"
check "no arguments prints usage on stderr" grep -q usage "$tmp/err"

run frobnicate
expect_rc 2 "unknown command"
check "unknown command: message on stderr" test -s "$tmp/err"
stderr_has frobnicate "unknown command: stderr names the command"

run run "$default_scene" --frobnicate
expect_rc 2 "unknown option"
check "unknown option: message on stderr" test -s "$tmp/err"
stderr_has --frobnicate "unknown option: stderr names the option"

run run
expect_rc 2 "run without a scene"

run run "$default_scene" "$default_scene"
expect_rc 2 "two scenes"

run run "$default_scene" --steps
expect_rc 2 "--steps without a value"

# ---- run ---------------------------------------------------------------------

run run "$default_scene"
expect_rc 0 "run default.scene"
check "run: first line is the CSV header" \
    test "$(head -n 1 "$tmp/out")" = "body,x,y,angle,vx,vy,omega"
check "run: one row per body ($nbodies)" \
    test "$(wc -l <"$tmp/out")" -eq $((nbodies + 1))
awk -F, -v n="$nbodies" '
    NR == 1 { next }
    NF != 7 || $1 != NR - 2 { bad = 1 }
    { for (i = 2; i <= 7; i++) if ($i !~ /^-?[0-9.]+(e[-+][0-9]+)?$/) bad = 1 }
    END { exit bad || NR != n + 1 }' "$tmp/out"
verdict $? "run: rows are body 0..$((nbodies - 1)) with 7 finite fields"
check "run: nothing on stderr" test ! -s "$tmp/err"

run run "$default_scene" --steps 0
expect_rc 0 "--steps 0"
awk -F, '$1 == "0" { found = 1; if ($2 + 0 != 0 || $3 + 0 != -0.5) bad = 1 }
         END { exit bad || !found }' "$tmp/out"
verdict $? "--steps 0: body 0 at its initial position 0,-0.5"
# every body at the position= of its line (default 0,0), to float rounding:
# the library stores the centre of mass and gives the origin back from it
awk '
    BEGIN { n = 0 }
    FNR == NR { sub(/#.*/, "") }
    FNR == NR && $1 == "body" {
        p = "0,0"
        for (i = 3; i <= NF; i++) if ($i ~ /^position=/) p = substr($i, 10)
        split(p, xy, ","); want_x[n] = xy[1] + 0; want_y[n] = xy[2] + 0; n++
        next
    }
    FNR == NR { next }
    FNR > 1 { split($0, f, ","); rows++
              dx = f[2] - want_x[f[1]]; dy = f[3] - want_y[f[1]]
              if (dx * dx + dy * dy > 1e-10) bad = 1 }
    END { exit bad || rows != n }' "$default_scene" "$tmp/out"
verdict $? "--steps 0: every body at the position= of its scene line"
cp "$tmp/out" "$tmp/initial.csv"

# ---- --trace -----------------------------------------------------------------

run run "$default_scene" --steps 5 --trace "$tmp/trace.csv"
expect_rc 0 "--trace with --steps 5"
cp "$tmp/out" "$tmp/final5.csv"
check "--trace: header" \
    test "$(head -n 1 "$tmp/trace.csv")" = "step,t,body,x,y,angle,vx,vy,omega"
check "--trace: (5+1)*$nbodies rows, step 0 included" \
    test "$(($(wc -l <"$tmp/trace.csv") - 1))" -eq $((6 * nbodies))
awk -F, -v n="$nbodies" '
    NR == 1 { next }
    { k = NR - 2; if ($1 != int(k / n) || $3 != k % n || NF != 9) bad = 1 }
    END { exit bad }' "$tmp/trace.csv"
verdict $? "--trace: steps 0..5, each with bodies 0..$((nbodies - 1)) in order"
check "--trace: step 0 rows equal the --steps 0 output" \
    test "$(awk -F, 'NR > 1 && $1 == 0' "$tmp/trace.csv" | cut -d, -f3-)" = \
         "$(tail -n +2 "$tmp/initial.csv")"
check "--trace: step 5 rows equal the final output" \
    test "$(awk -F, 'NR > 1 && $1 == 5' "$tmp/trace.csv" | cut -d, -f3-)" = \
         "$(tail -n +2 "$tmp/final5.csv")"

# ---- --events ----------------------------------------------------------------

run run "$default_scene" --events "$tmp/events.csv"
expect_rc 0 "--events on default.scene"
check "--events: header" \
    test "$(head -n 1 "$tmp/events.csv")" = \
         "t,body_a,body_b,nx,ny,impulse,approach_speed"
check "--events: default.scene has impacts" \
    test "$(wc -l <"$tmp/events.csv")" -ge 2
awk -F, 'NR > 1 && !($7 + 0 >= 0) { bad = 1 } END { exit bad }' \
    "$tmp/events.csv"
verdict $? "--events: every approach_speed >= 0"
awk -F, 'NR > 2 && $1 + 0 < prev { bad = 1 } NR > 1 { prev = $1 + 0 }
         END { exit bad }' "$tmp/events.csv"
verdict $? "--events: times non-decreasing"
awk -F, 'NR > 1 && (NF != 7 || !($2 + 0 < $3 + 0) || !($6 + 0 >= 0)) { bad = 1 }
         END { exit bad }' "$tmp/events.csv"
verdict $? "--events: body_a < body_b, impulse >= 0, 7 fields"

cat >"$tmp/ball.scene" <<'EOF'
carom-scene 1
# a ball dropped on a static box
world gravity=0,-10 dt=0.016666667 steps=120
body box static half-extents=5,0.5 position=0,-0.5 restitution=0.8
body circle radius=0.5 position=0,3 restitution=0.8 friction=0
EOF
run run "$tmp/ball.scene" --events "$tmp/ball_events.csv"
expect_rc 0 "ball on a box"
check "ball on a box: at least one event" \
    test "$(wc -l <"$tmp/ball_events.csv")" -ge 2
awk -F, 'NR == 2 { found = 1; if ($2 != 0 || $3 != 1 || $4 + 0 != 0 || $5 + 0 != 1) bad = 1 }
         END { exit bad || !found }' "$tmp/ball_events.csv"
verdict $? "ball on a box: first event is box 0 / ball 1 with normal 0,1"
awk -F, '$1 == "1" { found = 1; if (!($3 + 0 > 0)) bad = 1 } END { exit bad || !found }' \
    "$tmp/out"
verdict $? "ball on a box: ball bounced back above the box"

# ---- bad scene files -----------------------------------------------------------

cat >"$tmp/bad_key.scene" <<'EOF'
carom-scene 1
world gravity=0,-10
body circle radius=0.5 colour=red
EOF
run run "$tmp/bad_key.scene"
expect_rc 2 "scene with an unknown key"
stderr_has "$tmp/bad_key.scene:3:" "unknown key: stderr has FILE:3:"
stderr_has "colour" "unknown key: stderr names the key"
check "unknown key: nothing on stdout" test ! -s "$tmp/out"

cat >"$tmp/bad_nan.scene" <<'EOF'
carom-scene 1
# comment

body circle radius=0.5 position=0,nan
EOF
run run "$tmp/bad_nan.scene"
expect_rc 2 "scene with NaN"
stderr_has "$tmp/bad_nan.scene:4:" "NaN: stderr has FILE:4:"
stderr_has "nan" "NaN: stderr quotes the value"

cat >"$tmp/bad_header.scene" <<'EOF'
carom-scene 7
EOF
run run "$tmp/bad_header.scene"
expect_rc 2 "scene with an unsupported version"
stderr_has "$tmp/bad_header.scene:1:" "unsupported version: stderr has FILE:1:"

run run "$tmp/missing.scene"
expect_rc 2 "missing scene file"
stderr_has "$tmp/missing.scene" "missing file: stderr names the file"

# ---- bad options ---------------------------------------------------------------

for args in "--steps abc" "--steps -1" "--steps 1.5" "--dt 0" "--dt -0.1" \
            "--dt nan" "--dt inf" "--dt abc" "--method bogus"; do
    # shellcheck disable=SC2086 # split "--opt value" on purpose
    run run "$default_scene" $args
    expect_rc 2 "$args"
    check "$args: message on stderr" test -s "$tmp/err"
done

run run "$default_scene" --method discrete --steps 10
expect_rc 0 "--method discrete"
check "--method discrete: one row per body" \
    test "$(wc -l <"$tmp/out")" -eq $((nbodies + 1))

run run "$default_scene" --method events --steps 10
expect_rc 0 "--method events"
check "--method events: one row per body" \
    test "$(wc -l <"$tmp/out")" -eq $((nbodies + 1))

run run "$default_scene" --method first-impact --steps 10
expect_rc 0 "--method first-impact"
check "--method first-impact: one row per body" \
    test "$(wc -l <"$tmp/out")" -eq $((nbodies + 1))

run run "$tmp/ball.scene" --dt 0.01 --steps 1
expect_rc 0 "--dt 0.01"
awk -F, '$1 == "1" { found = 1; d = 3 - $3; if (d < 0.00049 || d > 0.00051) bad = 1 }
         END { exit bad || !found }' "$tmp/out"
verdict $? "--dt 0.01: ball fell by g dt^2 / 2 = 0.0005 in one step"

# A light ball between a fast heavy slab and a wall hits many times per
# step: with max-events=4 the run must stop with exit 1 and say why.
cat > "$tmp/cap.scene" <<'EOS'
carom-scene 1
world gravity=0,0 steps=120 max-events=4 rest-speed=0
body box static half-extents=0.5,2 position=2.5,0 restitution=1 friction=0
body circle radius=0.1 position=1.5,0 restitution=1 friction=0
body box half-extents=0.5,1 position=0,0 velocity=3,0 density=1000 restitution=1 friction=0
EOS
run run "$tmp/cap.scene"
expect_rc 1 "event cap reached"
check "event cap: stderr names the cap" grep -q "max-events" "$tmp/err"

# ---- profile ------------------------------------------------------------------

run profile "$default_scene" --steps 20
expect_rc 0 "profile"
# shellcheck disable=SC2016 # the inner script expands its own variables
check "profile: table has every phase" \
    sh -c 'for p in integration broadphase narrowphase impact_timing impulse_resolution resting_contacts total; do grep -q "^$p " "$1" || exit 1; done' _ "$tmp/out"
check "profile: seed weights named" grep -q "weights seed: add 1 sub 1 mul 1.5 div 4 cmp 1 sqrt 6" "$tmp/out"

run profile "$default_scene" --steps 20 --json
expect_rc 0 "profile --json"
check "profile --json: one line" test "$(wc -l <"$tmp/out")" -eq 1
# shellcheck disable=SC2016 # the inner script expands its own variables
check "profile --json: required keys" \
    sh -c 'for k in steps bodies impacts weights phases total_cost integration resting_contacts; do grep -q "\"$k\"" "$1" || exit 1; done' _ "$tmp/out"
# total_cost equals the weighted sum of the phase counts (seed weights)
awk '{
    s = $0; sub(/.*"phases": /, "", s); total = s; sub(/.*"total_cost": /, "", total); sub(/}.*/, "", total)
    sum = 0
    while (match(s, /"(add|sub|mul|div|cmp|sqrt)": [0-9]+/)) {
        kv = substr(s, RSTART, RLENGTH); s = substr(s, RSTART + RLENGTH)
        split(kv, a, /": /); k = substr(a[1], 2)
        sum += (k == "mul" ? 1.5 : k == "div" ? 4 : k == "sqrt" ? 6 : 1) * a[2]
    }
    d = sum - total; if (d < 0) d = -d
    exit !(sum > 0 && d <= 1e-9 * sum + 0.5)
}' "$tmp/out"
verdict $? "profile --json: total_cost is the seed-weighted sum of the phase counts"

printf 'add 1\nsub 1\nmul 1\ndiv 14\ncmp 1\nsqrt 14  # M4F\n' > "$tmp/w.txt"
run profile "$default_scene" --steps 5 --weights "$tmp/w.txt"
expect_rc 0 "profile --weights FILE"
run profile "$default_scene" --steps 5 --weights cortex-m0
expect_rc 0 "profile --weights cortex-m0"
printf 'add 1\nsub 1\n' > "$tmp/w2.txt"
run profile "$default_scene" --weights "$tmp/w2.txt"
expect_rc 2 "profile: weights file missing kinds"
check "profile: missing kind named" grep -q "no weight for 'mul'" "$tmp/err"
printf 'add 1\nsub 1\nmul 1\ndiv 1\ncmp 1\nsqrt 1\nfma 2\n' > "$tmp/w3.txt"
run profile "$default_scene" --weights "$tmp/w3.txt"
expect_rc 2 "profile: unknown kind in weights file"
run profile "$default_scene" --weights no-such-preset
expect_rc 2 "profile: unknown weights preset"
run profile
expect_rc 2 "profile without a scene"

# ---- summary -------------------------------------------------------------------

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
