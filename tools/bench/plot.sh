#!/bin/sh
# plot.sh TIME_RECORDS DIR [WORK] -- DIR/bench-gas.png and DIR/bench-pile.png
# from the time records of carom-bench (tools/bench/bench.sh runs it): CPU
# time per step against bodies, log-log, one line per engine. The pile's
# 10^5 row (free fall only, see docs/benchmarks.md) is left out. Without
# gnuplot it says so and does nothing.
set -eu
case "${1:-}" in -h|--help) sed -n '2,6p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;; esac
[ $# -ge 2 ] || { echo "plot.sh: usage: plot.sh TIME_RECORDS DIR [WORK]" >&2; exit 2; }
records=$1
dir=$2
work=${3:-$(dirname "$records")}
[ -r "$records" ] || { echo "plot.sh: cannot read '$records'" >&2; exit 2; }
if ! command -v gnuplot >/dev/null 2>&1; then
    echo "plot.sh: no gnuplot: no figures" >&2
    exit 0
fi
mkdir -p "$dir" "$work"
for scene in gas pile; do
    max=1000000
    [ "$scene" = pile ] && max=10000
    for e in events discrete box2d box2d-v3; do
        sed -n "s/^time scene=$scene n=\([0-9]*\) .*engine=$e .*ns_step=\([0-9.]*\) .*/\1 \2/p" \
            "$records" | awk -v m="$max" '$1 <= m' > "$work/fig.$scene.$e.dat"
    done
    gnuplot <<EOG
set terminal pngcairo size 800,520 noenhanced
set output '$dir/bench-$scene.png'
set title '$scene: CPU time per step (median of alternated runs), make bench'
set logscale xy
set grid
set key top left
set xlabel 'bodies'
set ylabel 'ms per step'
plot '$work/fig.$scene.events.dat' using 1:(\$2/1e6) with linespoints title 'carom events', \
     '$work/fig.$scene.discrete.dat' using 1:(\$2/1e6) with linespoints title 'carom discrete', \
     '$work/fig.$scene.box2d.dat' using 1:(\$2/1e6) with linespoints title 'Box2D 2.4.1', \
     '$work/fig.$scene.box2d-v3.dat' using 1:(\$2/1e6) with linespoints title 'Box2D v3', \
     '$work/fig.$scene.discrete.dat' using 1:(1e-3 * \$1) with lines dashtype 2 title 'linear: 1 us per body'
EOG
done
echo "plot.sh: wrote $dir/bench-gas.png, $dir/bench-pile.png" >&2
