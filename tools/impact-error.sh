#!/bin/sh
# impact-error.sh [CAROM] -- ERRATA 4, measured: the position error the
# discrete method leaves when an impact falls inside a step, against its
# derivation (docs/events.md). Two circles (m_A = 1, m_B = 3, e = 0.6) meet
# head-on at a quarter of a step; prints a markdown table over dt.
set -eu
carom="${1:-build/carom}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
e=0.6 va=0.5 vb=-0.3 ma=1 mb=3 phase=0.25
echo "| dt | t* in step | derived e v (dt - t*) m_B/M | without projection (1+e) v (dt - t*) m_B/M | measured discrete - events, x_A at t = 1 s |"
echo "|---|---|---|---|---|"
for dt in 0.2 0.1 0.05 0.025 0.0125; do
    # gap so that contact happens at phase * dt
    gap=$(awk -v dt="$dt" -v p="$phase" -v a="$va" -v b="$vb" 'BEGIN { printf "%.9g", (a - b) * p * dt }')
    xa=$(awk -v g="$gap" 'BEGIN { printf "%.9g", -0.5 - g }')
    steps=$(awk -v dt="$dt" 'BEGIN { printf "%d", 1 / dt + 0.5 }')
    for m in events discrete; do
        cat > "$tmp/s.scene" <<EOS
carom-scene 1
world gravity=0,0 dt=$dt steps=$steps method=$m rest-speed=0
body circle radius=0.5 position=$xa,0 velocity=$va,0 mass=$ma restitution=$e friction=0
body circle radius=0.5 position=0.5,0 velocity=$vb,0 mass=$mb restitution=$e friction=0
EOS
        "$carom" run "$tmp/s.scene" | awk -F, '$1 == "0" { print $2 }' > "$tmp/$m"
    done
    awk -v dt="$dt" -v p="$phase" -v e="$e" -v a="$va" -v b="$vb" -v ma="$ma" -v mb="$mb" \
        -v xe="$(cat "$tmp/events")" -v xd="$(cat "$tmp/discrete")" 'BEGIN {
        lost = dt * (1 - p); v = a - b; w = mb / (ma + mb)
        printf "| %s | %.4g | %.6f | %.6f | %.6f |\n", dt, p * dt, e * v * lost * w, (1 + e) * v * lost * w, xd - xe }'
done
