#!/bin/sh
# selftest.sh -- tests of build/stress_check on hand-made scenes and outputs
# with known answers (geometry, every check kind, bad input).
#
#   sh tools/stress/selftest.sh [build/stress_check]
#
# Exit status: 0 all good, 1 a test failed, 2 bad usage.
set -eu

checker=${1:-build/stress_check}
if [ ! -x "$checker" ]; then
    echo "selftest.sh: '$checker' not found or not executable" >&2
    exit 2
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0
n=0

scene() { # FILE, then the scene text on stdin
    cat > "$tmp/$1.scene"
}
final() { # rows "body,x,y,angle,vx,vy,omega" as arguments
    printf 'body,x,y,angle,vx,vy,omega\n' > "$tmp/final.csv"
    for r in "$@"; do
        printf '%s\n' "$r" >> "$tmp/final.csv"
    done
}
# expect NAME STATUS PATTERN [EXTRA ARGS]: run the checker on NAME.scene and
# final.csv; the exit status must be STATUS and the output (stdout and
# stderr) must contain PATTERN.
expect() {
    name=$1
    want=$2
    pat=$3
    shift 3
    n=$((n + 1))
    rc=0
    "$checker" "$tmp/$name.scene" "$tmp/final.csv" "$@" > "$tmp/out" 2>&1 || rc=$?
    if [ "$rc" != "$want" ] || ! grep -q -F -e "$pat" "$tmp/out"; then
        echo "selftest.sh: FAIL $name: want exit $want and '$pat', got exit $rc:" >&2
        sed 's/^/    /' "$tmp/out" >&2
        fails=$((fails + 1))
    fi
}

# ---- overlap depths (exact answers) -------------------------------------------------

scene cc <<'S'
carom-scene 1
# check: overlap max=0.1
body circle radius=1
body circle radius=1
S
final 0,0,0,0,0,0,0 1,1.5,0,0,0,0,0
expect cc 1 '*overlap 0.5 > 0.1 (bodies 0,1)'
final 0,0,0,0,0,0,0 1,2.5,0,0,0,0,0
expect cc 0 'overlap 0 <= 0.1'

scene cb <<'S'
carom-scene 1
# check: overlap max=1
body box static half-extents=1,0.5
body circle radius=0.5
S
final 0,0,0,0,0,0,0 1,0,0.8,0,0,0,0
expect cb 0 'overlap 0.2 <= 1'
final 0,0,0,0,0,0,0 1,0,0.4,0,0,0,0
expect cb 0 'overlap 0.6 <= 1'
# corner: 0.5 - 0.3 sqrt(2)
final 0,0,0,0,0,0,0 1,1.3,0.8,0,0,0,0
expect cb 0 'overlap 0.07574 <= 1'

scene bb <<'S'
carom-scene 1
# check: overlap max=1
body box half-extents=1,1
body box half-extents=1,1
body polygon vertices=0,0;0,1;1,0 position=10,10
body polygon vertices=0,0;1,0;0,1 position=10.5,10
S
final 0,0,0,0,0,0,0 1,1.8,0.5,0,0,0,0 2,10,10,0,0,0,0 3,30,30,0,0,0,0
expect bb 0 'overlap 0.2 <= 1 (bodies 0,1)'
# a corner of a box turned 45 degrees: 1 - (2.3 - sqrt(2))
final 0,0,0,0,0,0,0 1,2.3,0,0.785398163,0,0,0 2,10,10,0,0,0,0 3,30,30,0,0,0,0
expect bb 0 'overlap 0.1142 <= 1 (bodies 0,1)'
# triangles given clockwise and counter-clockwise: 0.6 / sqrt(2)
final 0,0,0,0,0,0,0 1,5,0,0,0,0,0 2,10,10,0,0,0,0 3,10.4,10,0,0,0,0
expect bb 0 'overlap 0.4243 <= 1 (bodies 2,3)'
# two static bodies are not a pair
scene ss <<'S'
carom-scene 1
# check: overlap max=0.1
body box static half-extents=1,1
body box static half-extents=1,1
S
final 0,0,0,0,0,0,0 1,0,0,0,0,0,0
expect ss 0 'overlap 0 <= 0.1'

# ---- stay, still, above, contain, order, rest -------------------------------------

scene st <<'S'
carom-scene 1
# check: stay body=1 tol=0.01
# check: still speed=0.01
body box static half-extents=5,0.5 position=0,-0.5
body box half-extents=0.5,0.5 position=1,0.5
S
final 0,0,-0.5,0,0,0,0 1,1.003,0.504,0,0.003,0.004,0
expect st 0 'PASS st: stay[1] 0.005 <= 0.01; speed 0.005 < 0.01 (body 1)'
final 0,0,-0.5,0,0,0,0 1,1.006,0.509,0,0.006,0.008,0
expect st 1 'FAIL st: *stay[1] 0.01082 > 0.01; *speed 0.01 >= 0.01 (body 1)'

scene ab <<'S'
carom-scene 1
# check: above y=-0.01
# check: contain xmin=-1 xmax=1 ymin=0
body box static half-extents=5,0.5 position=0,-0.5
body box half-extents=0.5,0.5 position=0,0.5
body circle radius=0.25 position=0,2
S
final 0,0,-0.5,0,0,0,0 1,0,0.5,0.785398163,0,0,0 2,0,0.3,0,0,0,0
expect ab 1 '*lowest -0.2071 <= -0.01 (end, body 1)'
final 0,0,-0.5,0,0,0,0 1,0,0.5,0,0,0,0 2,1.2,0.3,0,0,0,0
expect ab 1 '*escaped 1 > 0 (smallest margin -0.2, body 2)'
final 0,0,-0.5,0,0,0,0 1,0,0.5,0,0,0,0 2,0.5,0.3,0,0,0,0
expect ab 0 'PASS ab: lowest 0 > -0.01 (end, body 1); escaped 0 == 0'

scene tr <<'S'
carom-scene 1
# check: order upper=2 lower=1 over=trace
# check: above body=1 y=-0.01 over=trace
body box static half-extents=5,0.5 position=0,-0.5
body box half-extents=0.5,0.5 position=0,0.5
body box half-extents=0.5,0.5 position=0,1.5
S
final 0,0,-0.5,0,0,0,0 1,0,0.5,0,0,0,0 2,0,1.5,0,0,0,0
cat > "$tmp/trace.csv" <<'T'
step,t,body,x,y,angle,vx,vy,omega
0,0,0,0,-0.5,0,0,0,0
0,0,1,0,0.5,0,0,0,0
0,0,2,0,1.5,0,0,0,0
1,1,0,0,-0.5,0,0,0,0
1,1,1,0,0.48,0,0,0,0
1,1,2,0,0.7,0,0,0,0
2,2,0,0,-0.5,0,0,0,0
2,2,1,0,0.5,0,0,0,0
2,2,2,0,1.5,0,0,0,0
T
expect tr 1 '*lowest[1] -0.02 <= -0.01 (trace, body 1, t=1)' "$tmp/trace.csv"
expect tr 1 'y[2]-y[1] 0.22 > 0 (trace, t=1)' "$tmp/trace.csv"
expect tr 2 'needs TRACE.csv'

scene rs <<'S'
carom-scene 1
# check: rest body=1 y=0 tol=0.01 speed=0.01
body box static half-extents=20,0.005 position=0,-0.005
body box half-extents=2.5,0.005 position=0,5 angle=1.57079633
S
final 0,0,-0.005,0,0,0,0 1,3,0.004,0,0,0,0
expect rs 0 'rest[1].gap 0.001 <= 0.01; rest[1].tilt 0 <= 0.01; rest[1].speed 0 <= 0.01'
final 0,0,-0.005,0,0,0,0 1,3,0.5,0.2,0,0.02,0
expect rs 1 '*rest[1].tilt 0.9931 > 0.01; *rest[1].speed 0.02 > 0.01'

scene im <<'S'
carom-scene 1
# check: impacts count=2
body circle radius=1
S
final 0,0,0,0,0,0,0
printf 't,body_a,body_b,nx,ny,impulse,approach_speed\n1,0,1,1,0,1,1\n2,0,1,1,0,1,1\n' > "$tmp/ev.csv"
expect im 0 'impacts 2 == 2' "" "$tmp/ev.csv"
printf 't,body_a,body_b,nx,ny,impulse,approach_speed\n1,0,1,1,0,1,1\n' > "$tmp/ev.csv"
expect im 1 '*impacts 1 != 2' "" "$tmp/ev.csv"

# ---- bad input ----------------------------------------------------------------------

final 0,0,0,0,0,0,0
expect cc 2 'no row for body 1'
final 0,0,0,0,0,0,0 1,x,0,0,0,0,0
expect cc 2 'want 7 comma-separated finite numbers'
final 0,0,0,0,0,0,0 1,0,0,0,0,0,0 2,0,0,0,0,0,0
expect cc 2 'no body 2 in the scene'
scene bad <<'S'
carom-scene 1
# check: hover body=1
body circle radius=1
S
expect bad 2 "unknown kind 'hover'"
scene bad2 <<'S'
carom-scene 1
# check: stay body=0
body circle radius=1
S
expect bad2 2 'missing tol='
scene none <<'S'
carom-scene 1
body circle radius=1
S
expect none 2 "no '# check:' line"

if [ $fails -gt 0 ]; then
    echo "selftest.sh: $fails of $n tests failed" >&2
    exit 1
fi
echo "selftest.sh: all $n stress_check tests pass"
