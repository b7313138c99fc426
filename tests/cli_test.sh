#!/bin/sh
# cli_test.sh -- end-to-end tests of the carom command-line tool.
#
# usage: sh tests/cli_test.sh build/carom [build/carom-plain]
#
# With the second tool (the same command linked with the plain library,
# no counters), its results must be build/carom's, bit for bit: counting
# never changes the arithmetic.
#
# Prints one "ok - ..." / "not ok - ..." line per check, then
# "N passed, M failed"; exits non-zero if any check failed.

set -u

if [ $# -lt 1 ] || [ $# -gt 2 ]; then
    echo "usage: sh tests/cli_test.sh PATH-TO-CAROM [PATH-TO-CAROM-PLAIN]" >&2
    exit 2
fi
cli=$1
plain=${2:-}
case $cli in
    /*) ;;
    *) cli=$(pwd)/$cli ;;
esac
if [ ! -x "$cli" ]; then
    echo "cli_test.sh: '$cli' is not an executable" >&2
    exit 2
fi
if [ -n "$plain" ] && [ ! -x "$plain" ]; then
    echo "cli_test.sh: '$plain' is not an executable" >&2
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

# A normal the library computes as (-1, -0) (a static box listed before
# the ball that hits its face) is written -1,0: no CSV field is -0.
cat >"$tmp/negzero.scene" <<'EOF'
carom-scene 1
world gravity=0,0 steps=40
body box static half-extents=0.5,2 position=3,0
body circle radius=0.5 position=0,0 velocity=5,0 restitution=1
EOF
run run "$tmp/negzero.scene" --events "$tmp/negzero_events.csv" --trace "$tmp/negzero_trace.csv"
expect_rc 0 "a ball hitting the left face of a box"
awk -F, 'NR == 2 { found = 1; if ($4 != "-1" || $5 != "0") bad = 1 }
         END { exit bad || !found }' "$tmp/negzero_events.csv"
verdict $? "--events: the normal (-1, -0) is written -1,0"
check "--events, --trace, final state: no field is -0" \
    test "$(cat "$tmp/negzero_events.csv" "$tmp/negzero_trace.csv" "$tmp/out" |
            grep -c -E '(^|,)-0(,|$)')" -eq 0

# '-' is not standard output for --trace and --events (standard output
# holds the result): an option error, and no file named '-'.
for opt in --trace --events; do
    (cd "$tmp" && "$cli" run "$tmp/ball.scene" --steps 3 "$opt" - >"$tmp/out" 2>"$tmp/err")
    rc=$?
    expect_rc 2 "$opt -"
    stderr_has "$opt: '-' (standard output) is not possible" "$opt -: stderr says '-' is refused"
    check "$opt -: no file named '-'" test ! -e "$tmp/-"
    check "$opt -: nothing on stdout" test ! -s "$tmp/out"
done
run run "$tmp/ball.scene" --steps 3 --trace "$tmp/./-"
expect_rc 0 "--trace DIR/./- (a file named '-', written as a path)"
check "--trace DIR/./-: the file is written" test -s "$tmp/-"
rm -f "$tmp/-"
run run --help
check "--help: --trace says '-' is refused" grep -q "'-' is refused" "$tmp/out"

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

printf 'carom-scene 1 extra\n' >"$tmp/header_extra.scene"
run run "$tmp/header_extra.scene"
expect_rc 2 "header with text after the version"
stderr_has "$tmp/header_extra.scene:1: the header line has trailing text after the version: 'extra'" \
    "header with trailing text: stderr names the line and the text"
check "header with trailing text: not called an unsupported version" \
    test "$(grep -c unsupported "$tmp/err")" -eq 0

# A mass or density that gives a mass or inertia outside carom's range:
# the key, its value and the range, once.
for kv in density=1e30 mass=1e-30; do
    printf 'carom-scene 1\nbody circle radius=1 %s\n' "$kv" >"$tmp/mass.scene"
    run run "$tmp/mass.scene"
    expect_rc 2 "body $kv"
    stderr_has "$tmp/mass.scene:2: body 0: $kv: a dynamic body's mass and moment of inertia must be in [1e-20, 1e+20]" \
        "body $kv: stderr names the key, the value and the range"
    check "body $kv: the range is given once" \
        test "$(grep -o -F -e '1e-20' -e 'CAROM_LIMIT_MIN_MASS' "$tmp/err" | wc -l)" -eq 2
done

run run "$tmp/missing.scene"
expect_rc 2 "missing scene file"
stderr_has "$tmp/missing.scene" "missing file: stderr names the file"

# ---- output that cannot be written ----------------------------------------------

# Standard output on a full device: the report is lost, so the run fails
# (exit 1, as for a --trace file that cannot be written), for every
# command that writes its result there.
if [ -w /dev/full ]; then
    for cmd in run profile "profile --json"; do
        # shellcheck disable=SC2086 # split "profile --json" on purpose
        "$cli" $cmd "$default_scene" >/dev/full 2>"$tmp/err"
        rc=$?
        expect_rc 1 "$cmd to a full standard output"
        stderr_has "error writing standard output" "$cmd to a full standard output: stderr says so"
    done
fi

# ---- bad options ---------------------------------------------------------------

# --dt outside carom's range names the option, not the scene; a world
# value outside it names its key and the range.
run run "$default_scene" --dt 100
expect_rc 2 "--dt 100"
stderr_has "--dt: the time step must be in [1e-07, 10] s" "--dt 100: stderr names the option and the range"
for kv in "dt=100|dt=100: the time step must be in [1e-07, 10] s" \
          "gravity=0,-1e13|gravity=0,-1e+13: each component must be within 1e+12 m/s^2" \
          "rest-speed=1e9|rest-speed=1e+09: must be auto or in [0, 1e+08] m/s" \
          "slop=1e9|slop=1e+09: must be auto or in [0, 1e+08] m" \
          "length-unit=1e-7|length-unit=1e-07: must be auto or in [1e-06, 1e+08] m"; do
    printf 'carom-scene 1\nworld %s\nbody circle radius=1\n' "${kv%%|*}" >"$tmp/range.scene"
    run run "$tmp/range.scene"
    expect_rc 2 "world ${kv%%|*}"
    stderr_has "world: ${kv#*|}" "world ${kv%%|*}: stderr names the key and the range"
done

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
# step: with max-events=4 the impacts that do not fit are counted, not an
# error; the run goes on and warns that --events misses some.
cat > "$tmp/cap.scene" <<'EOS'
carom-scene 1
world gravity=0,0 steps=120 max-events=4 rest-speed=0
body box static half-extents=0.5,2 position=2.5,0 restitution=1 friction=0
body circle radius=0.1 position=1.5,0 restitution=1 friction=0
body box half-extents=0.5,1 position=0,0 velocity=3,0 density=1000 restitution=1 friction=0
EOS
run run "$tmp/cap.scene" --events "$tmp/cap_events.csv"
expect_rc 0 "event cap: more impacts than max-events in a step"
stderr_has "not recorded" "event cap: stderr warns that --events misses impacts"
run run "$tmp/cap.scene"
check "event cap without --events: nothing on stderr" test ! -s "$tmp/err"

# More candidate pairs than max-pairs stops the run (exit 1) and says why.
cat > "$tmp/pairs.scene" <<'EOS'
carom-scene 1
world gravity=0,-10 steps=10 max-pairs=1
body box static half-extents=5,0.5 position=0,-0.5
body circle radius=0.5 position=0,0.5
body circle radius=0.5 position=2,0.5
body circle radius=0.5 position=-2,0.5
EOS
run run "$tmp/pairs.scene"
expect_rc 1 "pair capacity exceeded"
stderr_has "max-pairs" "pair capacity: stderr names max-pairs="

# Without max-pairs or max-contacts the CLI's world grows on demand: 25
# balls at 1000 m/s in a 5 m box (each sweeps the whole box every step,
# 12x the default pair capacity) run to the end in every method, and
# with the events method (which takes each wall hit at its instant, up to
# 30 a step here) every ball stays inside the box. (The discrete and
# first-impact methods answer one hit per pair and step: balls that cross
# the box more than once a step leave it; docs/robustness.md.)
{
    echo 'carom-scene 1'
    echo 'world gravity=0,0 steps=6'
    echo 'body box static half-extents=4.5,1 position=0,-3.5 restitution=1 friction=0'
    echo 'body box static half-extents=4.5,1 position=0,3.5 restitution=1 friction=0'
    echo 'body box static half-extents=1,4.5 position=-3.5,0 restitution=1 friction=0'
    echo 'body box static half-extents=1,4.5 position=3.5,0 restitution=1 friction=0'
    for i in 0 1 2 3 4; do
        for j in 0 1 2 3 4; do
            echo "body circle radius=0.4 position=$((i - 2)),$((j - 2)) velocity=$((600 - 300 * j)),$((800 - 150 * i)) restitution=1 friction=0"
        done
    done
} > "$tmp/fastgas.scene"
for m in events discrete first-impact; do
    run run "$tmp/fastgas.scene" --method "$m"
    expect_rc 0 "fast gas, $m: the world grows past the default pair capacity"
done
run run "$tmp/fastgas.scene" --method events
# shellcheck disable=SC2016 # awk's own variables
check "fast gas, events: every ball inside the box" \
    awk -F, 'NR > 1 && $1 >= 4 && ($2 < -2.5 || $2 > 2.5 || $3 < -2.5 || $3 > 2.5) { bad = 1 } END { exit bad }' "$tmp/out"

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

# No bodies, or no steps: no work, so every share is 0.0 %, the total's too.
printf 'carom-scene 1\nworld steps=10\n' > "$tmp/nobodies.scene"
for args in "$tmp/nobodies.scene" "$tmp/ball.scene --steps 0"; do
    # shellcheck disable=SC2086 # split "SCENE --steps 0" on purpose
    run profile $args
    expect_rc 0 "profile $(basename "$args")"
    check "profile $(basename "$args"): the total's share is 0.0%" \
        grep -q '^total .* 0\.0%$' "$tmp/out"
    check "profile $(basename "$args"): no 100% and no nan" \
        test "$(grep -c -i -e '100\.0%' -e nan "$tmp/out")" -eq 0
done

# ---- --version -----------------------------------------------------------------

hver=$(awk '$1 == "#define" && $2 ~ /^CAROM_VERSION_(MAJOR|MINOR|PATCH)$/ { v = v (v == "" ? "" : ".") $3 }
            END { print v }' "$root/include/carom.h")
run --version
expect_rc 0 "--version"
check "--version prints 'carom $hver' (carom.h's CAROM_VERSION_*)" \
    test "$(cat "$tmp/out")" = "carom $hver"

# ---- reading scene files -----------------------------------------------------------

run run "$tmp"
expect_rc 2 "a directory as the scene"
stderr_has "is a directory" "a directory: stderr says 'is a directory'"
check "a directory: nothing on stdout" test ! -s "$tmp/out"

run run "$tmp/ball.scene" --steps 30
cp "$tmp/out" "$tmp/ball30.csv"
# the same scene with a UTF-8 byte-order mark, CR LF and CR-only line ends
printf '\357\273\277' > "$tmp/bom.scene"
cat "$tmp/ball.scene" >> "$tmp/bom.scene"
run run "$tmp/bom.scene" --steps 30
expect_rc 0 "scene with a UTF-8 byte-order mark"
check "byte-order mark: same result as without" cmp -s "$tmp/out" "$tmp/ball30.csv"
awk '{ printf "%s\r\n", $0 }' "$tmp/ball.scene" > "$tmp/crlf.scene"
run run "$tmp/crlf.scene" --steps 30
expect_rc 0 "scene with CR LF line ends"
check "CR LF: same result as LF" cmp -s "$tmp/out" "$tmp/ball30.csv"
tr '\n' '\r' < "$tmp/ball.scene" > "$tmp/cr.scene"
run run "$tmp/cr.scene" --steps 30
expect_rc 0 "scene with CR-only line ends"
check "CR only: same result as LF" cmp -s "$tmp/out" "$tmp/ball30.csv"
tr '\n' '\r' < "$tmp/bad_key.scene" > "$tmp/bad_key_cr.scene"
run run "$tmp/bad_key_cr.scene"
expect_rc 2 "CR-only scene with an unknown key"
stderr_has "$tmp/bad_key_cr.scene:3:" "CR only: errors keep their line numbers"
printf '\377\376c\000a\000r\000' > "$tmp/utf16.scene"
run run "$tmp/utf16.scene"
expect_rc 2 "UTF-16 scene"
stderr_has "UTF-16" "UTF-16: stderr names the encoding"
"$cli" run - --steps 30 < "$tmp/ball.scene" > "$tmp/out" 2> "$tmp/err"
rc=$?
expect_rc 0 "scene '-' read from stdin"
check "stdin: same result as the file" cmp -s "$tmp/out" "$tmp/ball30.csv"

# ---- --opt=value ------------------------------------------------------------------

run run "$tmp/ball.scene" --steps 7 --dt 0.01 --method discrete \
    --trace "$tmp/t1.csv" --events "$tmp/e1.csv" --max-output 100
cp "$tmp/out" "$tmp/o1.csv"
run run "$tmp/ball.scene" --steps=7 --dt=0.01 --method=discrete \
    --trace="$tmp/t2.csv" --events="$tmp/e2.csv" --max-output=100
expect_rc 0 "run with --opt=value options"
check "--opt=value: same state as --opt value" cmp -s "$tmp/out" "$tmp/o1.csv"
check "--opt=value: same --trace" cmp -s "$tmp/t1.csv" "$tmp/t2.csv"
check "--opt=value: same --events" cmp -s "$tmp/e1.csv" "$tmp/e2.csv"
run profile "$tmp/ball.scene" --steps 5 --weights cortex-m0 --json
cp "$tmp/out" "$tmp/p1.json"
run profile "$tmp/ball.scene" --steps=5 --weights=cortex-m0 --json
expect_rc 0 "profile --weights=NAME"
check "profile --weights=NAME: same as --weights NAME" cmp -s "$tmp/out" "$tmp/p1.json"
run render "$tmp/ball.scene" --steps 20 --every 4 --size 300 -o "$tmp/r1.svg"
run render "$tmp/ball.scene" --steps=20 --every=4 --size=300 --output="$tmp/r2.svg"
expect_rc 0 "render with --opt=value options"
check "render --opt=value: same SVG" cmp -s "$tmp/r1.svg" "$tmp/r2.svg"
run render "$tmp/ball.scene" --steps=20 --fps=10 -o"$tmp/r3.svg"
run render "$tmp/ball.scene" --steps 20 --fps 10 -o "$tmp/r4.svg"
check "render -oFILE and --fps=N: same SVG as -o FILE --fps N" cmp -s "$tmp/r3.svg" "$tmp/r4.svg"
run run "$tmp/ball.scene" --steps=
expect_rc 2 "--steps= (empty value)"
run profile "$tmp/ball.scene" --json=yes
expect_rc 2 "a flag given a value (--json=yes)"
stderr_has "takes no value" "--json=yes: stderr says the flag takes no value"
run run "$tmp/ball.scene" --json
expect_rc 2 "an option of another command (run --json)"
stderr_has "profile" "run --json: stderr names the command that has it"
run run "$tmp/ball.scene" --frobnicate=1
expect_rc 2 "unknown --opt=value"
stderr_has "--frobnicate" "unknown --opt=value: stderr names the option"

# An option with a value given twice is an error naming it, however
# written; a flag may repeat.
for args in "--steps 3 --steps 5" "--steps=3 --steps 3" "--dt 0.01 --dt=0.02" \
            "--method events --method discrete" "--trace $tmp/t3.csv --trace $tmp/t4.csv"; do
    # shellcheck disable=SC2086 # split the options on purpose
    run run "$tmp/ball.scene" $args
    opt=${args%% *}
    opt=${opt%%=*}
    expect_rc 2 "run $args"
    stderr_has "carom: $opt given twice" "run $args: stderr says $opt was given twice"
done
check "--trace given twice: no file written" test ! -e "$tmp/t3.csv" -a ! -e "$tmp/t4.csv"
run render "$tmp/ball.scene" -o "$tmp/r6.svg" --output "$tmp/r7.svg"
expect_rc 2 "render -o FILE --output FILE"
stderr_has "carom: --output given twice" "render -o and --output: stderr names --output"
run lean "$tmp/ball.scene" --margin 10 --margin 20
expect_rc 2 "lean --margin twice"
run run "$tmp/ball.scene" --steps 3 --no-progress --no-progress
expect_rc 0 "a flag given twice (--no-progress)"

run render "$tmp/ball.scene" --steps=20 --fps=10 -o="$tmp/r5.svg"
check "render -o=FILE: same SVG as -o FILE" cmp -s "$tmp/r5.svg" "$tmp/r4.svg"
run run --steps 7 -- "$tmp/ball.scene"
expect_rc 0 "-- before the scene"
run run -- "$tmp/ball.scene" --steps
expect_rc 2 "after --, an option is an operand"
stderr_has "more than one scene given ('--steps')" "after --: --steps is a second scene"
run run "$tmp/ball.scene" --steps
expect_rc 2 "an option without its value (--steps)"
check "--steps without its value: the message and the hint, exactly" \
    test "$(cat "$tmp/err")" = "carom: --steps needs a value (N)
(try 'carom --help')"

# ---- large --trace ----------------------------------------------------------------

run run "$tmp/ball.scene" --steps 5000000 --trace "$tmp/huge.csv"
expect_rc 2 "--trace estimated above 300 MB"
stderr_has "--force" "large --trace: stderr says --force writes it"
stderr_has "MB" "large --trace: stderr gives the estimated size"
check "large --trace: no file written" test ! -e "$tmp/huge.csv"
run run "$tmp/ball.scene" --steps 10 --trace "$tmp/small.csv" --max-output 0.0001
expect_rc 2 "--trace above --max-output"
run run "$tmp/ball.scene" --steps 10 --trace "$tmp/small.csv" --max-output 0.0001 --force
expect_rc 0 "--trace above --max-output with --force"
stderr_has "warning" "--force: stderr warns about the size"
check "--force: the trace is written (11 x 2 rows)" \
    test "$(($(wc -l < "$tmp/small.csv") - 1))" -eq 22

# ---- partial results -------------------------------------------------------------

# A body leaving carom's range at step 3 (|x| > 1e8 m): exit 1, and the
# state after step 2 is still written, marked partial.
cat > "$tmp/far.scene" <<'EOS'
carom-scene 1
world gravity=0,0 dt=1 steps=5
body circle radius=0.5 position=0,0
body circle radius=0.5 position=0,5 velocity=4e7,0
EOS
run run "$tmp/far.scene"
expect_rc 1 "a body leaves carom's range"
check "partial: first line is '# partial: stopped at step 3 of 5: ...'" \
    grep -q "^# partial: stopped at step 3 of 5: " "$tmp/out"
check "partial: first line names body 1" \
    test "$(head -n 1 "$tmp/out" | grep -c -F "(body 1)")" -eq 1
check "partial: then the CSV header" \
    test "$(sed -n 2p "$tmp/out")" = "body,x,y,angle,vx,vy,omega"
awk -F, 'NR > 2 { n++ } $1 == "1" { if ($2 + 0 != 8e7) bad = 1 } END { exit bad || n != 2 }' "$tmp/out"
verdict $? "partial: the state after step 2 (body 1 at x = 8e7)"
stderr_has "step 3" "partial: stderr names the failing step"
run run "$tmp/pairs.scene"
check "pair capacity: partial output too" grep -q "^# partial: stopped at step 1 of 10: " "$tmp/out"
run profile "$tmp/far.scene"
expect_rc 1 "profile of a run that fails"
check "profile: partial table" grep -q "^# partial: stopped at step 3 of 5" "$tmp/out"
check "profile: the table of the steps taken" grep -q "^total " "$tmp/out"
run profile "$tmp/far.scene" --json
check "profile --json: a \"partial\" key" grep -q '^{"partial": "stopped at step 3 of 5' "$tmp/out"
# make run (tools/run-default.sh) of a run that stops early shows what it
# did until then, and the error, and fails
sh "$root/tools/run-default.sh" "$cli" "$tmp/far.scene" > "$tmp/out" 2> "$tmp/err"
rc=$?
expect_rc 1 "run-default.sh (make run) of a run that fails"
check "run-default.sh: the partial line" grep -q "^partial: stopped at step 3 of 5: " "$tmp/out"
check "run-default.sh: the state reached" grep -q "^state reached:" "$tmp/out"
awk '$1 == "1" && $2 == "80000000" { found = 1 } END { exit !found }' "$tmp/out"
verdict $? "run-default.sh: body 1 at x = 8e7 after step 2"
check "run-default.sh: the operation counts of the steps taken" grep -q "^total " "$tmp/out"
stderr_has "step 3 (t = 2 s)" "run-default.sh: stderr has carom's error"
sh "$root/tools/run-default.sh" "$cli" "$tmp/ball.scene" > "$tmp/out" 2> "$tmp/err"
rc=$?
expect_rc 0 "run-default.sh of a run that succeeds"
check "run-default.sh: the final state" grep -q "^final state:" "$tmp/out"
check "run-default.sh: nothing on stderr" test ! -s "$tmp/err"

# ---- progress ---------------------------------------------------------------------

run run "$tmp/ball.scene" --progress
expect_rc 0 "--progress"
stderr_has "step 120 of 120 (100%)" "--progress: the last count on stderr"
check "--progress: stdout unchanged" test "$(wc -l < "$tmp/out")" -eq 3
run run "$tmp/ball.scene"
check "no terminal: no progress" test ! -s "$tmp/err"
if command -v script > /dev/null 2>&1 &&
   script -qec true /dev/null > /dev/null 2>&1; then
    # script(1) gives the command a terminal; stderr goes there too
    script -qec "'$cli' run '$tmp/ball.scene' > '$tmp/tty.out'" /dev/null > "$tmp/tty.err" 2>&1
    check "terminal: progress shown" grep -q "step [0-9]* of 120" "$tmp/tty.err"
    check "terminal: the line is erased at the end" grep -q "$(printf '\r\033')\[K" "$tmp/tty.err"
    check "terminal: stdout unchanged" test "$(wc -l < "$tmp/tty.out")" -eq 3
    script -qec "'$cli' run '$tmp/ball.scene' --no-progress > '$tmp/tty.out'" /dev/null > "$tmp/tty.err" 2>&1
    check "terminal with --no-progress: quiet" test ! -s "$tmp/tty.err"
else
    ok "terminal progress # SKIP script(1) not available"
fi

# ---- render ----------------------------------------------------------------------

if command -v xmllint > /dev/null 2>&1; then
    have_xmllint=1
else
    have_xmllint=0
    echo "# xmllint not found (apt-get install libxml2-utils): SVG checks skipped"
fi

# xpath FILE EXPR: evaluate an XPath expression on an SVG (namespace-free)
xpath() {
    xmllint --xpath "$2" "$1" 2>/dev/null
}

# svg_checks NAME FILE FRAMES: well-formed, FRAMES frames
svg_checks() {
    if [ "$have_xmllint" = 0 ]; then
        ok "$1: SVG checks # SKIP no xmllint"
        return
    fi
    check "$1: SVG is well-formed (xmllint)" xmllint --noout "$2"
    n=$(xpath "$2" "count(//*[local-name()='text'][@class='time'])")
    check "$1: $3 frames (time labels), got $n" test "$n" = "$3"
    v=$(xpath "$2" "string((//*[local-name()='animateTransform'][@type='translate'])[1]/@values)" |
        awk -F';' '{ print NF }')
    check "$1: $3 frames (values of a body's animation), got $v" test "$v" = "$3"
}

# ball.scene: 120 steps of 1/60 s; default 30 fps: a frame every 2 steps
run render "$tmp/ball.scene" -o "$tmp/ball.svg"
expect_rc 0 "render ball.scene"
check "render: nothing on stderr" test ! -s "$tmp/err"
svg_checks "render (30 fps)" "$tmp/ball.svg" 61
# a frame every 7 steps: 0, 7, ..., 119 and the last step 120
run render "$tmp/ball.scene" -o "$tmp/ball7.svg" --every 7
expect_rc 0 "render --every 7"
svg_checks "render --every 7" "$tmp/ball7.svg" 19
if [ "$have_xmllint" = 1 ]; then
    k=$(xpath "$tmp/ball7.svg" "string((//*[local-name()='animateTransform'])[1]/@keyTimes)" |
        awk -F';' '{ print NF }')
    check "render --every 7: keyTimes for the uneven last frame" test "$k" = 19
    w=$(xpath "$tmp/ball.svg" "string(/*/@width)")
    h=$(xpath "$tmp/ball.svg" "string(/*/@height)")
    # every body origin of every frame inside the picture (auto-fit)
    xpath "$tmp/ball.svg" "//*[local-name()='animateTransform'][@type='translate']/@values" |
        tr -s '";' '\n' | awk -F, -v w="$w" -v h="$h" '
        /^ *values=/ { next } NF == 2 { n++; if ($1 < 0 || $1 > w || $2 < 0 || $2 > h) bad = 1 }
        END { exit bad || n == 0 }'
    verdict $? "render: the view fits every frame (${w}x${h})"
    # y up: the falling ball goes down the picture
    xpath "$tmp/ball.svg" "string(//*[@id='body1']/*[local-name()='animateTransform']/@values)" |
        tr ';' '\n' | awk -F, 'NR == 1 { y0 = $2 } NR == 20 { exit !($2 > y0 + 10) }'
    verdict $? "render: y up (the falling ball moves down the picture)"
fi
run render "$tmp/ball.scene" -o "$tmp/ball10.svg" --fps 10
svg_checks "render --fps 10" "$tmp/ball10.svg" 21
# --view: that rectangle (5 m tall at --size 300: 60 px/m, 24 px of label;
# 2 m wide: 120 px, widened to the least width, 260 px)
run render "$tmp/ball.scene" -o "$tmp/view.svg" --view=-1,-1,1,4 --size 300
expect_rc 0 "render --view"
check "render --view: 300 px of view under the label" \
    grep -q '<svg [^>]* height="324"' "$tmp/view.svg"
check "render --view: the least width, 260 px" \
    grep -q '<svg [^>]* width="260"' "$tmp/view.svg"
# --size below the least width is an option error that states it
run render "$tmp/ball.scene" -o "$tmp/x.svg" --size 259
expect_rc 2 "render --size 259"
stderr_has "--size: want an integer in [260, 16384]" "render --size 259: stderr states the least size"
check "render --size 259: no file written" test ! -e "$tmp/x.svg"
run render "$tmp/ball.scene" -o "$tmp/x.svg" --size 260 --steps 10
expect_rc 0 "render --size 260"
rm -f "$tmp/x.svg"
run --help
check "--help: --size says 260 is the least" grep -q -e "--size PX .*260 to 16384" "$tmp/out"
for v in "1,1,0,2" "0,0,1" "0,0,1,1,2" "a,0,1,1"; do
    run render "$tmp/ball.scene" -o "$tmp/x.svg" --view "$v"
    expect_rc 2 "render --view $v"
done
run render "$tmp/ball.scene" -o - --steps 10 --every 5
expect_rc 0 "render -o - (stdout)"
check "render -o -: SVG on stdout" grep -q "^<svg " "$tmp/out"

# --impacts: one marker per impact of --events
run render "$tmp/ball.scene" -o "$tmp/impacts.svg" --impacts --events "$tmp/ball_ev.csv"
expect_rc 0 "render --impacts"
if [ "$have_xmllint" = 1 ]; then
    m=$(xpath "$tmp/impacts.svg" "count(//*[local-name()='circle'][@class='impact'])")
    e=$(($(wc -l < "$tmp/ball_ev.csv") - 1))
    check "render --impacts: one marker per impact ($e), got $m" test "$m" = "$e" -a "$e" -gt 0
    m=$(xpath "$tmp/ball.svg" "count(//*[local-name()='circle'][@class='impact'])")
    check "render without --impacts: no markers" test "$m" = 0
fi

# a spinning box: a rotate animation
cat > "$tmp/spin.scene" <<'EOS'
carom-scene 1
world gravity=0,0 steps=30
body box half-extents=1,0.5 angular-velocity=3
EOS
run render "$tmp/spin.scene" -o "$tmp/spin.svg"
expect_rc 0 "render a spinning box"
check "render: the spinning box has a rotate animation" \
    grep -q 'type="rotate"' "$tmp/spin.svg"

# a failing run: the frames up to the failure, marked partial, exit 1
run render "$tmp/far.scene" -o "$tmp/far.svg" --every 1
expect_rc 1 "render of a run that fails"
svg_checks "render of a failing run" "$tmp/far.svg" 3
check "render of a failing run: marked partial" grep -q 'class="note".*partial' "$tmp/far.svg"

run render "$tmp/ball.scene" -o "$tmp/huge.svg" --steps 100000000
expect_rc 2 "render: an SVG estimated above 300 MB"
stderr_has "--every" "large SVG: stderr suggests fewer frames"
check "large SVG: no file written" test ! -e "$tmp/huge.svg"
run render "$tmp/ball.scene"
expect_rc 2 "render without -o or --png"
for args in "--fps 0" "--fps 61" "--fps abc" "--every 0" "--size 5" "--fps 10 --every 2"; do
    # shellcheck disable=SC2086 # split "--opt value" on purpose
    run render "$tmp/ball.scene" -o "$tmp/x.svg" $args
    expect_rc 2 "render $args"
done
run render "$tmp/ball.scene" -o "$tmp/no/such/dir/x.svg"
expect_rc 2 "render -o into a missing directory"

# --png: frames through gnuplot, or a clear error without it
run render "$tmp/ball.scene" --png "$tmp/frames" --steps 12 --every 3
if command -v gnuplot > /dev/null 2>&1; then
    expect_rc 0 "render --png"
    check "render --png: 5 frames" \
        test "$(find "$tmp/frames" -name 'frame-*.png' | wc -l)" -eq 5
    check "render --png: frames are PNG files" \
        test "$(head -c 4 "$tmp/frames/frame-00004.png" | tail -c 3)" = PNG
else
    ok "render --png # SKIP gnuplot not installed"
fi
PATH=/nonexistent "$cli" render "$tmp/ball.scene" --png "$tmp/frames2" > "$tmp/out" 2> "$tmp/err"
rc=$?
expect_rc 2 "render --png without gnuplot"
stderr_has "gnuplot" "render --png without gnuplot: stderr names gnuplot"

# ---- profile --calibration ----------------------------------------------------------

# A calibration of 1 per float operation in every phase and 1000 per step
# outside them: the prediction is the op count plus 1000 x steps.
cat > "$tmp/ops.cal" <<'EOS'
carom-calibration 1
name ops-plus-steps  # a test
unit instructions
integration        1 0 0 0 0
broadphase         1 0 0 0 0
narrowphase        1 0 0 0 0
impact_timing      1 0 0 0 0
impulse_resolution 1 0 0 0 0
resting_contacts   1 0 0 0 0
step               0 1000 0 0 0
EOS
run profile "$default_scene" --steps 30 --json --calibration "$tmp/ops.cal"
expect_rc 0 "profile --calibration"
awk '{
    sub(/"weights": \{[^}]*\}/, "")
    n = split($0, a, /[^0-9a-z_]+/); ops = 0
    for (i = 1; i < n; i++)
        if (a[i] ~ /^(add|sub|mul|div|cmp|sqrt)$/ && a[i + 1] ~ /^[0-9]+$/) ops += a[i + 1]
    s = $0; sub(/.*"calibrated".*"total": /, "", s); sub(/[}, ].*/, "", s)
    exit (s + 0 != ops + 30 * 1000)
}' "$tmp/out"
verdict $? "profile --calibration: total = float operations + 1000 x steps"
check "profile --calibration --json: the calibration's name" \
    grep -q '"calibrated": {"name": "ops-plus-steps", "unit": "instructions"' "$tmp/out"
run profile "$default_scene" --steps 30 --calibration "$tmp/ops.cal"
check "profile --calibration: a calibrated table" grep -q "^calibrated (ops-plus-steps" "$tmp/out"
check "profile: awake body-steps and contact-steps" grep -q "^awake body-steps [0-9]*, contact-steps [0-9]*$" "$tmp/out"
if [ -f "$root/tools/embedded/cortex-m4f.cal" ]; then
    run profile "$default_scene" --steps 30 --calibration "$root/tools/embedded/cortex-m4f.cal"
    expect_rc 0 "profile --calibration tools/embedded/cortex-m4f.cal"
fi
sed '/^step/d' "$tmp/ops.cal" > "$tmp/nostep.cal"
sed 's/^broadphase         1/broadphase         -1/' "$tmp/ops.cal" > "$tmp/neg.cal"
sed '1d' "$tmp/ops.cal" > "$tmp/nohead.cal"
sed 's/^integration        1 0 0 0 0/integration 1 0 0 0/' "$tmp/ops.cal" > "$tmp/short.cal"
for bad in nostep neg nohead short no-such; do
    run profile "$default_scene" --steps 5 --calibration "$tmp/$bad.cal"
    expect_rc 2 "profile --calibration: $bad"
done
stderr_has "no-such.cal" "profile --calibration of a missing file: stderr names it"
run run "$default_scene" --calibration "$tmp/ops.cal"
expect_rc 2 "--calibration is an option of profile only"

# ---- lean -------------------------------------------------------------------------

run lean --help
expect_rc 0 "lean --help"
check "lean --help: usage names lean" grep -q "carom lean SCENE" "$tmp/out"
check "lean --help: lists --margin" grep -q -e "--margin PCT" "$tmp/out"
run lean
expect_rc 2 "lean without a scene"
run lean "$tmp/no-such.scene"
expect_rc 2 "lean of a missing scene"
stderr_has "no-such.scene" "lean of a missing scene: stderr names it"
for args in "--margin -1" "--margin abc" "--slack -2" "--trace x.csv"; do
    # shellcheck disable=SC2086 # split "--opt value" on purpose
    run lean "$default_scene" $args
    expect_rc 2 "lean $args"
done
stderr_has "not of lean" "lean --trace: stderr says --trace is not an option of lean"

# header_has HEADER NAME VALUE: '#define NAME VALUE' in the header
header_has() {
    grep -q "^#define $2 $3\\( \\|\$\\)" "$1"
}

# Two frictionless circles meeting head on in zero gravity: circles only,
# nothing turns, no friction, no forces; the events method; one pair.
cat > "$tmp/twoballs.scene" <<'EOS'
carom-scene 1
world gravity=0,0 steps=90 method=events
body circle radius=0.5 position=-2,0 velocity=2,0 restitution=1 friction=0
body circle radius=0.5 position=2,0 velocity=-2,0 restitution=1 friction=0
EOS
run lean "$tmp/twoballs.scene"
expect_rc 0 "lean of two frictionless balls"
cp "$tmp/out" "$tmp/twoballs.h"
check "lean: nothing on stderr" test ! -s "$tmp/err"
for sw in POLYGONS DYNAMIC_POLYGONS POLYGON_POLYGON ROTATION FRICTION FORCES SLEEP KINEMATIC \
    ANGLES BODY_EDITS DISCRETE; do
    check "lean two balls: CAROM_ENABLE_$sw 0" header_has "$tmp/twoballs.h" "CAROM_ENABLE_$sw" 0
done
# an angle without rotation keeps the angle helpers (the scene's angle= needs them)
sed 's/restitution=1 friction=0$/restitution=1 friction=0 angle=0.5/' "$tmp/twoballs.scene" \
    > "$tmp/angleballs.scene"
run lean "$tmp/angleballs.scene"
check "lean two balls at an angle: CAROM_ENABLE_ANGLES 1" header_has "$tmp/out" CAROM_ENABLE_ANGLES 1
check "lean two balls at an angle: CAROM_ENABLE_ROTATION 0" header_has "$tmp/out" CAROM_ENABLE_ROTATION 0
check "lean two balls: CAROM_ENABLE_EVENTS 1 (method events)" \
    header_has "$tmp/twoballs.h" CAROM_ENABLE_EVENTS 1
check "lean two balls: CAROM_LEAN_MAX_BODIES 2" header_has "$tmp/twoballs.h" CAROM_LEAN_MAX_BODIES 2
# one pair at most: 1 + 25 % of 1 rounded up + 4 = 6
check "lean two balls: CAROM_LEAN_MAX_PAIRS 6 (1 + 25 % + 4)" \
    header_has "$tmp/twoballs.h" CAROM_LEAN_MAX_PAIRS 6
check "lean two balls: every switch has a reason" \
    test "$(grep -c '^#define CAROM_ENABLE_[A-Z_]* [01] /\* o[nf]*: ..*\*/$' "$tmp/twoballs.h")" -eq \
         "$(grep -c '^#define CAROM_ENABLE_' "$tmp/twoballs.h")"
sed -n 's/^#ifndef \(CAROM_ENABLE_[A-Z0-9_]*\).*/\1/p' "$root/include/carom_config.h" \
    > "$tmp/switches"
while read -r sw; do
    grep -q "^#define $sw " "$tmp/twoballs.h" || missing_sw="${missing_sw:-} $sw"
done < "$tmp/switches"
check "lean: the header sets every switch of carom_config.h${missing_sw:+ (missing:$missing_sw)}" \
    test -z "${missing_sw:-}"
run lean "$tmp/twoballs.scene" --margin 0 --slack 0
check "lean --margin 0 --slack 0: CAROM_LEAN_MAX_PAIRS 1, the worst case met" \
    header_has "$tmp/out" CAROM_LEAN_MAX_PAIRS 1
check "lean --margin 0 --slack 0: CAROM_LEAN_MAX_IMPACTS 1" \
    header_has "$tmp/out" CAROM_LEAN_MAX_IMPACTS 1
run lean "$tmp/twoballs.scene" --margin=100 --slack=1
check "lean --margin=100 --slack=1: CAROM_LEAN_MAX_PAIRS 3" \
    header_has "$tmp/out" CAROM_LEAN_MAX_PAIRS 3
run lean "$tmp/twoballs.scene" --method discrete
check "lean --method discrete: CAROM_ENABLE_EVENTS 0" \
    header_has "$tmp/out" CAROM_ENABLE_EVENTS 0
check "lean --method discrete: CAROM_ENABLE_DISCRETE 1" \
    header_has "$tmp/out" CAROM_ENABLE_DISCRETE 1
check "lean --method discrete: CAROM_ENABLE_CONTINUOUS 0 (nothing turns)" \
    header_has "$tmp/out" CAROM_ENABLE_CONTINUOUS 0
# the octagon spinning 7.5 turns a step into a wall: the discrete method
# needs the continuous guard, the events method does not
run lean tools/scenes/limits/spinning-octagon-tunnels.scene --method discrete
check "lean of a spinning octagon, discrete: CAROM_ENABLE_CONTINUOUS 1" \
    header_has "$tmp/out" CAROM_ENABLE_CONTINUOUS 1
run lean tools/scenes/limits/spinning-octagon-tunnels.scene
check "lean of a spinning octagon, events: CAROM_ENABLE_CONTINUOUS 0" \
    header_has "$tmp/out" CAROM_ENABLE_CONTINUOUS 0
# the header compiles, and a world sized by it can be made
if command -v cc > /dev/null 2>&1; then
    cat > "$tmp/lean_prog.c" <<'EOS'
#include <stdio.h>
#include "carom.h"
int main(void)
{
    static unsigned char mem[CAROM_LEAN_WORLD_BYTES];
    carom_world_def wd = carom_default_world_def();
    CAROM_LEAN_SET_CAPACITIES(&wd);
    printf("%d %lu\n", CAROM_ENABLE_POLYGONS, (unsigned long)sizeof mem);
    return carom_world_buffer_size(&wd) > 0 ? 0 : 1;
}
EOS
    # only compiled, not linked: no library of this configuration here
    check "lean: the header compiles with carom.h (-include)" \
        cc -std=c99 -pedantic -Wall -Werror -I"$root/include" -include "$tmp/twoballs.h" \
            -c "$tmp/lean_prog.c" -o "$tmp/lean_prog.o"
else
    ok "lean: the header compiles # SKIP no cc"
fi

# A box spinning onto a static box floor, with friction: polygons that
# move and meet polygons, rotation, friction.
cat > "$tmp/spinbox.scene" <<'EOS'
carom-scene 1
world gravity=0,-10 steps=120
body box static half-extents=5,0.5 position=0,-0.5
body box half-extents=0.5,0.5 position=0,2 angular-velocity=3
EOS
run lean "$tmp/spinbox.scene"
expect_rc 0 "lean of a spinning box on a floor"
for sw in POLYGONS DYNAMIC_POLYGONS POLYGON_POLYGON ROTATION FRICTION; do
    check "lean spinning box: CAROM_ENABLE_$sw 1" header_has "$tmp/out" "CAROM_ENABLE_$sw" 1
done
check "lean spinning box: CAROM_ENABLE_FORCES 0" header_has "$tmp/out" CAROM_ENABLE_FORCES 0
check "lean spinning box: CAROM_ENABLE_ANGLES 1" header_has "$tmp/out" CAROM_ENABLE_ANGLES 1
# a constant force needs CAROM_ENABLE_FORCES
sed 's/angular-velocity=3/force=1,0/' "$tmp/spinbox.scene" > "$tmp/forcebox.scene"
run lean "$tmp/forcebox.scene"
check "lean with a force: CAROM_ENABLE_FORCES 1" header_has "$tmp/out" CAROM_ENABLE_FORCES 1
# the failing scene cannot be measured: exit 1, reason on stderr
run lean "$tmp/far.scene"
expect_rc 1 "lean of a scene that fails"
stderr_has "step 3" "lean of a failing scene: stderr names the step"
printf 'carom-scene 1\nworld gravity=0,0\n' > "$tmp/empty.scene"
run lean "$tmp/empty.scene"
expect_rc 2 "lean of a scene without bodies"

# ---- inputs an adversarial review found mishandled ------------------------------

# category= and mask= are decimal unless 0x: a leading 0 is not octal (010
# is ten, which meets mask=2; as octal, eight, the balls passed through)
cat > "$tmp/cat.scene" <<'EOS'
carom-scene 1
world gravity=0,0 steps=120
body circle radius=0.5 position=0,0 velocity=1,0 category=010
body circle radius=0.5 position=3,0 mask=2
EOS
run run "$tmp/cat.scene"
expect_rc 0 "category=010"
awk -F, '$1 == "0" { x0 = $2 } $1 == "1" { x1 = $2 } END { exit !(x1 > x0 + 0.99) }' "$tmp/out"
verdict $? "category=010 is ten: the balls collide, body 0 stays behind body 1"
sed 's/category=010/category=09/' "$tmp/cat.scene" > "$tmp/cat9.scene"
run run "$tmp/cat9.scene"
expect_rc 0 "category=09 is the decimal 9"
sed 's/category=010/category=0x/' "$tmp/cat.scene" > "$tmp/catx.scene"
run run "$tmp/catx.scene"
expect_rc 2 "category=0x (no digits)"
# a control byte in a line is shown escaped in the message
printf 'carom-scene 1\nbody\vcircle radius=1\n' > "$tmp/vt.scene"
run run "$tmp/vt.scene"
expect_rc 2 "a vertical tab inside a line type"
stderr_has "'body\\x0bcircle'" "the vertical tab is shown as \\x0b"
printf 'carom-scene\n' > "$tmp/nover.scene"
run run "$tmp/nover.scene"
stderr_has "the header line has no version" "a header without its version"
printf 'carom-scene 1\nworld steps=99999999999999999999\n' > "$tmp/bigsteps.scene"
run run "$tmp/bigsteps.scene"
stderr_has "steps: '99999999999999999999' is out of range" "steps= past a long: out of range"
printf 'carom-scene 1\nbody circle radius=1 position=\n' > "$tmp/novec.scene"
run run "$tmp/novec.scene"
stderr_has "position: missing value" "position= without its value"
printf 'carom-scene 1\nworld dt=10.000001\n' > "$tmp/dt.scene"
run run "$tmp/dt.scene"
stderr_has "dt=10.000001:" "a refused dt is quoted to the digit that puts it past the limit"
run run "$default_scene" --steps ' 5'
expect_rc 2 "--steps with a leading blank (as the scene reader)"
run profile "$default_scene" --weights "$tmp"
stderr_has "Is a directory" "--weights DIRECTORY says it is a directory"
awk 'BEGIN { printf "add 1"; for (i = 0; i < 300; i++) printf " "; print "" }' > "$tmp/long.w"
run profile "$default_scene" --weights "$tmp/long.w"
stderr_has "long.w:1: line longer than" "a weights line too long for the reader is named, not split"
# render: an output that cannot be made is a usage error before any step;
# a view no picture can show is refused; a tiny --fps is one frame a run
run render "$default_scene" --png /nonexistent-dir-carom/x --steps 5
expect_rc 2 "render --png into a directory that cannot be made"
for view in -1e308,-1e308,1e308,1e308 0,0,1e-300,1e-300 0,0,1,1e-320; do
    run render "$default_scene" -o "$tmp/v.svg" --steps 5 --view="$view"
    expect_rc 2 "render --view=$view"
done
run render "$default_scene" -o "$tmp/fps.svg" --steps 50 --fps 1e-300
expect_rc 0 "render --fps 1e-300"

# ---- the plain build -------------------------------------------------------------
# Same final states, traces and impacts as the profiling build, both
# methods, on scenes that take every phase (polygons, rotation, friction,
# impacts, resting contact, a kinematic rotor); `profile` says it cannot.
if [ -n "$plain" ]; then
    for scene in "$default_scene" "$root/tools/scenes/stress/heavy-on-light-m100.scene" \
        "$root/tools/scenes/stress/rod-l2-tilt80.scene" \
        "$root/tools/scenes/stress/rotor-elastic-pile-dt30.scene"; do
        for method in events discrete; do
            name="$(basename "$scene") --method $method"
            "$cli" run "$scene" --method "$method" --steps 120 --trace "$tmp/t1" \
                --events "$tmp/e1" >"$tmp/f1" 2>/dev/null
            "$plain" run "$scene" --method "$method" --steps 120 --trace "$tmp/t2" \
                --events "$tmp/e2" >"$tmp/f2" 2>/dev/null
            check "plain build: $name: final state, trace and impacts the same bits" \
                sh -c "cmp -s '$tmp/f1' '$tmp/f2' && cmp -s '$tmp/t1' '$tmp/t2' && \
                       cmp -s '$tmp/e1' '$tmp/e2' && test -s '$tmp/f1'"
        done
    done
    "$plain" profile "$default_scene" >"$tmp/out" 2>"$tmp/err"
    rc=$?
    expect_rc 2 "plain build: profile refused"
    stderr_has "no profiler" "plain build: profile says the build has no profiler"
fi

# ---- summary -------------------------------------------------------------------

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
