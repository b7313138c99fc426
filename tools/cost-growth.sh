#!/bin/sh
# cost-growth.sh [CAROM] -- how the profiler's cost per step (seed weights,
# add units) grows with body count and with impacts per step. Generates
# elastic gases (density of bodies fixed, box grows with n) and piles of
# circles falling into a box, profiles 120 steps of each with
# `carom profile --json`, prints a markdown table and draws
# docs/cost-growth.png with gnuplot (if installed).
set -eu
carom="${1:-build/carom}"
out="${COST_OUT:-build/cost-growth}"
mkdir -p "$out"
gen() { # kind n file
    awk -v kind="$1" -v n="$2" 'BEGIN {
        srand(7); side = int(sqrt(n)) + 1; sp = 0.625; L = side * sp / 2
        print "carom-scene 1"
        if (kind == "gas")
            print "world gravity=0,0 dt=0.016666667 steps=120 rest-speed=0 max-pairs=" 16 * n
        else
            print "world gravity=0,-10 dt=0.016666667 steps=120 max-events=" 64 * n " max-pairs=" 16 * n
        w = 0.5
        printf "body box static half-extents=%g,%g position=0,%g restitution=1 friction=0\n", L + w, w, -L - w
        printf "body box static half-extents=%g,%g position=0,%g restitution=1 friction=0\n", L + w, w, L + w + (kind == "pile" ? 4 * L : 0)
        printf "body box static half-extents=%g,%g position=%g,0 restitution=1 friction=0\n", w, L + w + 4 * L, -L - w
        printf "body box static half-extents=%g,%g position=%g,0 restitution=1 friction=0\n", w, L + w + 4 * L, L + w
        k = 0
        for (i = 0; i < side && k < n; ++i)
            for (j = 0; j < side && k < n; ++j) {
                x = -L + sp * (i + 0.5); y = -L + sp * (j + 0.5)
                a = 6.2831853 * rand(); v = 0.5 + 2.5 * rand()
                if (kind == "gas")
                    printf "body circle radius=0.1 position=%.4f,%.4f velocity=%.4f,%.4f restitution=1 friction=0\n", x, y, v * cos(a), v * sin(a)
                else
                    printf "body circle radius=0.25 position=%.4f,%.4f restitution=0.3 friction=0.5\n", x, y
                ++k
            }
    }' > "$3"
}
printf '| scene | bodies | impacts per step | cost per step | cost per body-step | cost per impact |\n'
printf '|---|---|---|---|---|---|\n'
: > "$out/growth.dat"
for kind in gas pile; do
    for n in 100 200 400 800 1600 3200; do
        gen "$kind" "$n" "$out/$kind-$n.scene"
        "$carom" profile "$out/$kind-$n.scene" --json > "$out/$kind-$n.json"
        awk -v kind="$kind" -v n="$n" '{
            match($0, /"steps": [0-9]+/); steps = substr($0, RSTART + 9, RLENGTH - 9)
            match($0, /"impacts": [0-9]+/); imp = substr($0, RSTART + 11, RLENGTH - 11)
            match($0, /"total_cost": [0-9.e+]+/); cost = substr($0, RSTART + 14, RLENGTH - 14)
            printf "| %s | %d | %.1f | %.0f | %.0f | %s |\n", kind, n, imp / steps, cost / steps,
                   cost / steps / n, (imp > 0 ? sprintf("%.0f", cost / imp) : "-")
            printf "%s %d %.3f %.1f\n", kind, n, imp / steps, cost / steps >> "'"$out/growth.dat"'"
        }' "$out/$kind-$n.json"
    done
done
if command -v gnuplot >/dev/null 2>&1; then
    grep '^gas' "$out/growth.dat" > "$out/gas.dat"
    grep '^pile' "$out/growth.dat" > "$out/pile.dat"
    gnuplot <<EOG
set terminal pngcairo size 1000,420 noenhanced
set output 'docs/cost-growth.png'
set multiplot layout 1,2 title 'carom op-count cost per step (seed weights, add units), 120 steps, method events'
set logscale xy
set grid
set key top left
set xlabel 'bodies'
set ylabel 'cost per step'
plot '$out/gas.dat' using 2:4 with linespoints title 'elastic gas', \
     '$out/pile.dat' using 2:4 with linespoints title 'pile under gravity', \
     '$out/gas.dat' using 2:(\$2*3000) with lines dashtype 2 title 'linear in bodies (3000 n)'
set xlabel 'impacts per step'
plot '$out/gas.dat' using 3:4 with linespoints title 'elastic gas', \
     '$out/pile.dat' using 3:4 with linespoints title 'pile under gravity'
unset multiplot
EOG
    echo
    echo "(plot: docs/cost-growth.png)"
fi
