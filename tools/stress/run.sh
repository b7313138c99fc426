#!/bin/sh
# run.sh -- the stress suite: every scene of tools/scenes/stress through
# every engine, each result checked against the scene's own criterion.
#
#   sh tools/stress/run.sh [--fast] [--only LIST] [--targets]
#       [--report FILE] [--jobs N] [--v3 PATH] [--carom PATH] [--box2d PATH]
#       [--checker PATH] [--scenes DIR] [--timeout SEC] [--keep DIR]
#
# Engines: build/carom (or --carom PATH; the Makefile gives
# build/carom-plain, the same tool on the library without op counters)
# with --method events and with --method discrete;
# build/carom-box2d (Box2D 2.4.1, run with --quiet; skipped with a note if
# it is not built); with --v3 PATH, a Box2D v3 harness taking the same
# 'run SCENE [--trace F] [--events F]' interface. Each run writes the final
# state; the trace and the events are written (in a second, untimed run)
# only when the scene's criterion needs them, or, with --report, its
# figure. build/stress_check (tools/stress/stress_check.c) then reads the
# scene's '# check:' lines and prints PASS or FAIL with the measured values.
# A criterion that needs events an engine cannot write is 'n/a'.
#
# Time per step: for carom, the wall time of the run that writes only the
# final state (the best of three if it is quick), minus the best of three
# runs of the same command with --steps 0 (start-up, parsing, output),
# divided by the steps; for the Box2D harnesses, their own --time figure
# (the Step() calls only).
#
# Prints a table (scene x engine: PASS/FAIL with the measured value) and
# the time per step to stdout; progress goes to stderr when it is a
# terminal.
#   --fast         only the scenes marked '# fast' (about 20 s)
#   --only LIST    only these scenes (comma-separated names, without .scene)
#   --targets      after the time table, carom's time per step over Box2D
#                  2.4.1's for each scene, against the speed targets:
#                  events within 2x Box2D 2.4.1, discrete no slower (make
#                  bench-box2d); reported, never fatal
#   --report FILE  also write FILE (docs/stability.md) and, next to it, one
#                  gnuplot figure per scene family (FILE's name without .md,
#                  then -FAMILY.png: docs/stability-stack.png, ...)
#   --jobs N       run N engine runs at once (default 1)
#   --timeout SEC  kill an engine run after SEC seconds (default 900)
#   --keep DIR     keep every output file in DIR
#
# Exit status: 0 every carom result (events and discrete) passed; 1 one
# failed, or an engine run of carom failed; 2 bad usage or missing tools.
# Box2D failures are reported, never fatal. Needs sh, awk and (for the
# figures) gnuplot.
set -eu

carom=build/carom
box2d=build/carom-box2d
v3=
checker=build/stress_check
dir=tools/scenes/stress
fast=0
only=
targets=0
report=
jobs=1
timeout=900
keep=

usage() {
    awk 'NR == 1 { next } !/^#/ { exit } { sub(/^# ?/, ""); print }' "$0"
}
die() {
    echo "run.sh: $*" >&2
    exit 2
}
need_arg() {
    [ "$1" -ge 2 ] || die "$2 needs a value (try --help)"
}
while [ $# -gt 0 ]; do
    case "$1" in
    --fast) fast=1; shift ;;
    --only) need_arg $# "$1"; only=$2; shift 2 ;;
    --targets) targets=1; shift ;;
    --report) need_arg $# "$1"; report=$2; shift 2 ;;
    --jobs) need_arg $# "$1"; jobs=$2; shift 2 ;;
    --v3) need_arg $# "$1"; v3=$2; shift 2 ;;
    --carom) need_arg $# "$1"; carom=$2; shift 2 ;;
    --box2d) need_arg $# "$1"; box2d=$2; shift 2 ;;
    --checker) need_arg $# "$1"; checker=$2; shift 2 ;;
    --scenes) need_arg $# "$1"; dir=$2; shift 2 ;;
    --timeout) need_arg $# "$1"; timeout=$2; shift 2 ;;
    --keep) need_arg $# "$1"; keep=$2; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) die "unknown argument '$1' (try --help)" ;;
    esac
done
case "$jobs" in ''|*[!0-9]*|0) die "--jobs: want a positive integer, got '$jobs'" ;; esac
case "$timeout" in ''|*[!0-9]*|0) die "--timeout: want a positive integer, got '$timeout'" ;; esac
[ -x "$carom" ] || die "'$carom' not found or not executable (build it: make all)"
[ -x "$checker" ] || die "'$checker' not found or not executable (build it: make -f Makefile -f tools/stress/stress.mk $checker)"
[ -z "$v3" ] || [ -x "$v3" ] || die "--v3: '$v3' not found or not executable"
[ -d "$dir" ] || die "no scene directory '$dir' (run from the repository root)"

progress=0
[ -t 2 ] && progress=1
start=$(date +%s)

if [ -n "$keep" ]; then
    mkdir -p "$keep"
    tmp=$keep
else
    tmp=$(mktemp -d)
    trap 'rm -rf "$tmp"' EXIT
    trap 'exit 130' INT TERM
fi
rm -rf "$tmp/info" "$tmp/run" "$tmp/res" "$tmp/plot" "$tmp/claim"
mkdir -p "$tmp/info" "$tmp/run" "$tmp/res" "$tmp/plot" "$tmp/claim"

# ---- engines -------------------------------------------------------------------

engines="events discrete"
box2d_note=
if [ -x "$box2d" ]; then
    engines="$engines box2d"
else
    box2d_note="Box2D 2.4.1: '$box2d' is not built (make box2d), not run."
    echo "run.sh: note: $box2d_note" >&2
fi
[ -n "$v3" ] && engines="$engines v3"

engine_label() {
    case "$1" in
    events) echo "carom events" ;;
    discrete) echo "carom discrete" ;;
    box2d) echo "Box2D 2.4.1" ;;
    v3) echo "Box2D v3" ;;
    esac
}
engine_exe() {
    case "$1" in
    events|discrete) echo "$carom" ;;
    box2d) echo "$box2d" ;;
    v3) echo "$v3" ;;
    esac
}
# Does the engine write --events? (Its --help mentions the option.)
for e in $engines; do
    if "$(engine_exe "$e")" --help 2>&1 | grep -q -e '--events'; then
        : > "$tmp/info/.events-$e"
    fi
done

# ---- scenes ----------------------------------------------------------------------

: > "$tmp/scenes"
for f in "$dir"/*.scene; do
    [ -f "$f" ] || continue
    n=$(basename "$f" .scene)
    "$checker" --info "$f" > "$tmp/info/$n" || die "$f: bad scene or criterion"
    if [ $fast = 1 ] && ! grep -q '^fast 1$' "$tmp/info/$n"; then
        continue
    fi
    if [ -n "$only" ]; then
        case ",$only," in *",$n,"*) ;; *) continue ;; esac
    fi
    echo "$n" >> "$tmp/scenes"
done
[ -s "$tmp/scenes" ] || die "no scenes in '$dir'$([ $fast = 1 ] && echo ' marked # fast')"
if [ -n "$only" ]; then
    for n in $(echo "$only" | tr ',' ' '); do
        grep -qx "$n" "$tmp/scenes" || die "--only: no scene '$n' in '$dir'$([ $fast = 1 ] && echo ' marked # fast')"
    done
fi

info() { # NAME KEY
    awk -v k="$2" '$1 == k { print $2; exit }' "$tmp/info/$1"
}

# Family order for the tables and figures; scenes by name within a family.
awk -v d="$tmp/info" '
    BEGIN { n = split("stack pyramid pour heavy-on-light rod scaled billiard", o, " ")
            for (i = 1; i <= n; i++) rank[o[i]] = i }
    { f = ""; file = d "/" $1
      while ((getline line < file) > 0) if (line ~ /^family /) f = substr(line, 8)
      close(file)
      printf "%d %s %s\n", (f in rank) ? rank[f] : 99, f, $1 }
' "$tmp/scenes" | sort -k1,1n -k3,3 > "$tmp/order"

# Tasks, the most expensive first (bodies x steps, carom events weighted up),
# claimed by the workers one at a time (mkdir is atomic).
awk -v d="$tmp/info" -v engines="$engines" '
    { file = d "/" $3; b = 0; s = 0
      while ((getline line < file) > 0) {
          split(line, w, " ")
          if (w[1] == "bodies") b = w[2]
          if (w[1] == "steps") s = w[2]
      }
      close(file)
      n = split(engines, e, " ")
      for (i = 1; i <= n; i++) {
          c = b * s * (e[i] == "events" ? 4 : e[i] == "v3" ? 0.5 : 1)
          printf "%.0f %s %s\n", c, $3, e[i]
      } }
' "$tmp/order" | sort -k1,1nr | awk '{ print NR, $2, $3 }' > "$tmp/tasks"
ntasks=$(awk 'END { print NR }' "$tmp/tasks")

# ---- one run -----------------------------------------------------------------------

# Cell text from a verdict line: PASS and the first check's value, or FAIL
# and the first failed check's label=value.
cell_of() {
    awk '{
        st = $1; line = $0; sub(/^[A-Z]+ [^:]*: /, "", line)
        n = split(line, seg, /; /); pick = seg[1]
        for (i = 1; i <= n; i++) if (substr(seg[i], 1, 1) == "*") { pick = seg[i]; break }
        split(pick, w, " "); label = w[1]; sub(/^\*/, "", label)
        if (st == "PASS") printf "PASS %.3g\n", w[2]
        else printf "FAIL %s=%.3g\n", label, w[2]
    }' "$1"
}

result() { # NAME ENGINE STATUS CELL US DETAIL
    printf '%s\t%s\t%s\t%s\n' "$3" "$4" "$5" "$6" > "$tmp/res/$1.$2"
    if [ $progress = 1 ]; then
        done_n=$(find "$tmp/res" -type f | awk 'END { print NR }')
        printf 'stress: [%d/%d] %s %s: %s\n' "$done_n" "$ntasks" "$1" "$2" "$4" >&2
    fi
}

run_one() { # NAME ENGINE
    name=$1
    eng=$2
    scene=$dir/$name.scene
    o=$tmp/run/$name.$eng
    exe=$(engine_exe "$eng")
    steps=$(info "$name" steps)
    need_tr=$(info "$name" trace)
    need_ev=$(info "$name" events)
    pin=$(info "$name" plot-input)
    applies=$(info "$name" engines)
    case ",$applies," in
    ,all,|*",$eng,"*) ;;
    *)
        result "$name" "$eng" NA "n/a" "" "n/a: the criterion is a claim of $(echo "$applies" | tr , ' ') only"
        return 0 ;;
    esac
    can_ev=0
    [ -f "$tmp/info/.events-$eng" ] && can_ev=1
    if [ "$need_ev" = 1 ] && [ $can_ev = 0 ]; then
        result "$name" "$eng" NA "n/a" "" "n/a: the criterion needs --events, which $(engine_label "$eng") does not write"
        return 0
    fi
    want_tr=$need_tr
    want_ev=$need_ev
    if [ -n "$report" ]; then
        [ "$pin" = trace ] && want_tr=1
        [ "$pin" = events ] && [ $can_ev = 1 ] && want_ev=1
    fi
    case "$eng" in
    events|discrete) set -- "$exe" run "$scene" --method "$eng" ;;
    *) set -- "$exe" run "$scene" --quiet --time ;;
    esac

    # the timed run: final state only
    rc=0
    "$checker" --time "$o.sec" --limit "$timeout" "$@" < /dev/null > "$o.final" 2> "$o.err" || rc=$?
    if [ $rc != 0 ]; then
        msg=$(grep -v -e ': time: ' "$o.err" | head -n 1 | cut -c 1-200)
        if [ $rc = 124 ]; then
            result "$name" "$eng" ERR "TIMEOUT" "" "killed after ${timeout} s"
        else
            result "$name" "$eng" ERR "ERR exit $rc" "" "exit $rc: $msg"
        fi
        return 0
    fi
    case "$eng" in
    events|discrete)
        # start-up: the best of three runs of no steps; a quick run (under
        # 0.2 s) is repeated twice more and its best time kept
        for _ in 1 2 3; do
            "$checker" --time "$o.t" "$@" --steps 0 < /dev/null > /dev/null 2>&1 || true
            cat "$o.t" >> "$o.sec0" 2>/dev/null || true
        done
        if awk '{ exit !($1 < 0.2) }' "$o.sec"; then
            for _ in 1 2; do
                "$checker" --time "$o.t" "$@" < /dev/null > /dev/null 2>&1 || true
                cat "$o.t" >> "$o.sec" 2>/dev/null || true
            done
        fi
        us=$(awk -v s="$steps" '
            function lo(a, b) { return a == "" || b < a ? b : a }
            NR == FNR { t = lo(t, $1 + 0); next } { t0 = lo(t0, $1 + 0) }
            END { if (s > 0 && t0 != "") { u = (t - t0) / s * 1e6; if (u < 0) u = 0; printf "%.3g", u } }' "$o.sec" "$o.sec0")
        ;;
    *)
        us=$(awk '/: time: / { for (i = 1; i <= NF; i++) if ($i == "ns/step," || $i == "ns/step") { printf "%.3g", $(i - 1) / 1000; exit } }' "$o.err")
        ;;
    esac

    # trace and events, when needed: a second run
    trace_arg=
    ev_arg=
    if [ "$want_tr" = 1 ] || [ "$want_ev" = 1 ]; then
        [ "$want_tr" = 1 ] && set -- "$@" --trace "$o.trace"
        [ "$want_ev" = 1 ] && set -- "$@" --events "$o.events"
        rc=0
        "$checker" --time "$o.sec2" --limit "$timeout" "$@" < /dev/null > "$o.final" 2> "$o.err2" || rc=$?
        if [ $rc != 0 ]; then
            msg=$(head -n 1 "$o.err2" | cut -c 1-200)
            result "$name" "$eng" ERR "ERR exit $rc" "$us" "run with --trace/--events: exit $rc: $msg"
            return 0
        fi
        [ "$need_tr" = 1 ] && trace_arg=$o.trace
        [ "$need_ev" = 1 ] && ev_arg=$o.events
    fi

    rc=0
    "$checker" "$scene" "$o.final" "$trace_arg" "$ev_arg" > "$o.verdict" 2> "$o.cerr" || rc=$?
    case $rc in
    0|1)
        st=PASS
        [ $rc = 1 ] && st=FAIL
        result "$name" "$eng" "$st" "$(cell_of "$o.verdict")" "$us" "$(cat "$o.verdict")"
        ;;
    *)
        result "$name" "$eng" ERR "BAD output" "$us" "$(head -n 1 "$o.cerr")"
        ;;
    esac

    if [ -n "$report" ]; then
        pf=
        case "$pin" in
        trace) pf=$o.trace ;;
        events) pf=$o.events ;;
        final) pf=$o.final ;;
        esac
        if [ -n "$pf" ] && [ -f "$pf" ]; then
            "$checker" --plot "$scene" "$pf" > "$tmp/plot/$name.$eng.dat" 2>/dev/null ||
                rm -f "$tmp/plot/$name.$eng.dat"
        fi
    fi
    [ -n "$keep" ] || rm -f "$o.trace" "$o.events"
    return 0
}

worker() {
    while read -r idx name eng; do
        mkdir "$tmp/claim/$idx" 2>/dev/null || continue
        run_one "$name" "$eng"
    done < "$tmp/tasks"
}

i=0
while [ $i -lt "$jobs" ]; do
    worker &
    i=$((i + 1))
done
wait

elapsed=$(( $(date +%s) - start ))

# ---- tables --------------------------------------------------------------------------

# One row per scene: name, then per engine status, cell, us.
awk -v d="$tmp/res" -v engines="$engines" '
    BEGIN { FS = "\t"; n = split(engines, e, " ") }
    { split($0, w, " "); name = w[3]
      row = name
      for (i = 1; i <= n; i++) {
          file = d "/" name "." e[i]; st = "ERR"; cell = "not run"; us = ""
          if ((getline line < file) > 0) { split(line, f, "\t"); st = f[1]; cell = f[2]; us = f[3] }
          close(file)
          row = row "\t" st "\t" cell "\t" us
      }
      print row }
' FS=' ' "$tmp/order" > "$tmp/table"

labels=
for e in $engines; do
    labels="$labels|$(engine_label "$e")"
done

# Text tables on stdout.
awk -v labels="$labels" '
    BEGIN { FS = "\t"; n = split(substr(labels, 2), lab, "|") }
    { rows[NR] = $0 }
    END {
        w0 = length("scene"); for (i = 1; i <= n; i++) { w[i] = length(lab[i]); wt[i] = length(lab[i]) }
        for (r = 1; r <= NR; r++) {
            split(rows[r], f, "\t"); if (length(f[1]) > w0) w0 = length(f[1])
            for (i = 1; i <= n; i++) {
                if (length(f[3 * i]) > w[i]) w[i] = length(f[3 * i])
                if (length(f[3 * i + 1]) > wt[i]) wt[i] = length(f[3 * i + 1])
            }
        }
        printf "%-*s", w0, "scene"; for (i = 1; i <= n; i++) printf "  %-*s", w[i], lab[i]; printf "\n"
        for (r = 1; r <= NR; r++) {
            split(rows[r], f, "\t"); printf "%-*s", w0, f[1]
            for (i = 1; i <= n; i++) printf "  %-*s", w[i], f[3 * i]
            printf "\n"
        }
        printf "\ntime per step, microseconds (carom: wall time minus start-up; Box2D: its --time)\n"
        printf "%-*s", w0, "scene"; for (i = 1; i <= n; i++) printf "  %*s", wt[i], lab[i]; printf "\n"
        for (r = 1; r <= NR; r++) {
            split(rows[r], f, "\t"); printf "%-*s", w0, f[1]
            for (i = 1; i <= n; i++) printf "  %*s", wt[i], (f[3 * i + 1] == "" ? "-" : f[3 * i + 1])
            printf "\n"
        }
    }' "$tmp/table"

# Totals per engine; carom failures decide the exit status.
summary=$(awk -v engines="$engines" -v labels="$labels" '
    BEGIN { FS = "\t"; n = split(engines, e, " "); split(substr(labels, 2), lab, "|") }
    { for (i = 1; i <= n; i++) { st = $(3 * i - 1); c[i, st]++ } }
    END {
        for (i = 1; i <= n; i++) {
            s = sprintf("%s: %d pass, %d fail", lab[i], c[i, "PASS"], c[i, "FAIL"])
            if (c[i, "ERR"]) s = s sprintf(", %d error", c[i, "ERR"])
            if (c[i, "NA"]) s = s sprintf(", %d n/a", c[i, "NA"])
            printf "%s%s", (i > 1 ? "; " : ""), s
        }
    }' "$tmp/table")
nscenes=$(awk 'END { print NR }' "$tmp/order")
printf '\n%d scenes, %d runs, %d s: %s\n' "$nscenes" "$ntasks" "$elapsed" "$summary"

# Speed targets against Box2D 2.4.1 (reported, never fatal).
if [ $targets = 1 ]; then
    case " $engines " in
    *" box2d "*)
        printf '\nspeed targets: time per step over Box2D 2.4.1 (events <= 2, discrete <= 1)\n'
        awk -F '\t' '
            function ratio(c, b) { return (c == "" || b == "" || b + 0 <= 0) ? "" : c / b }
            function verdict(r, lim) { return r == "" ? "n/a" : (r <= lim ? "met" : "MISSED") }
            BEGIN { printf "%-28s %14s %14s\n", "scene", "events/2.4.1", "discrete/2.4.1" }
            { re = ratio($4, $10); rd = ratio($7, $10)
              printf "%-28s %8s %-5s %8s %-5s\n", $1,
                     (re == "" ? "-" : sprintf("%.2f", re)), verdict(re, 2),
                     (rd == "" ? "-" : sprintf("%.2f", rd)), verdict(rd, 1)
              if (re != "") { ne++; if (re <= 2) me++ }
              if (rd != "") { nd++; if (rd <= 1) md++ } }
            END { printf "events within 2x Box2D 2.4.1: %d of %d scenes; discrete no slower: %d of %d\n",
                         me, ne, md, nd }' "$tmp/table"
        ;;
    *) echo "run.sh: --targets: Box2D 2.4.1 did not run; no speed targets" >&2 ;;
    esac
fi
carom_bad=$(awk -F '\t' '($2 != "PASS" && $2 != "NA") || ($5 != "PASS" && $5 != "NA") { n++ } END { print n + 0 }' "$tmp/table")

# ---- report ------------------------------------------------------------------------------

if [ -n "$report" ]; then
    rdir=$(dirname "$report")
    rbase=$(basename "$report" .md)
    mkdir -p "$rdir"
    have_gnuplot=1
    command -v gnuplot >/dev/null 2>&1 || have_gnuplot=0
    figs=
    if [ $have_gnuplot = 1 ]; then
        awk '!seen[$2]++ { print $2 }' "$tmp/order" > "$tmp/families"
        while read -r fam; do
            # scenes of the family that have a figure
            : > "$tmp/fam"
            while read -r _ f n; do
                [ "$f" = "$fam" ] || continue
                q=$(info "$n" plot)
                [ "$q" = none ] || echo "$n $q $(info "$n" plot-ref)" >> "$tmp/fam"
            done < "$tmp/order"
            [ -s "$tmp/fam" ] || continue
            png=$rdir/$rbase-$fam.png
            awk -v eng="$engines" -v labels="$labels" -v pd="$tmp/plot" -v png="$png" -v fam="$fam" '
                BEGIN { ne = split(eng, e, " "); split(substr(labels, 2), lab, "|")
                        col["events"] = "#1f77b4"; col["discrete"] = "#2ca02c"
                        col["box2d"] = "#d62728"; col["v3"] = "#9467bd" }
                { name[NR] = $1; q[NR] = $2; ref[NR] = $3 }
                function exists(f,   l, r) { r = (getline l < f) > 0; close(f); return r }
                END {
                    # panels: one per scene, or per engine for snapshots
                    np = 0
                    for (r = 1; r <= NR; r++) {
                        if (q[r] == "snapshot") { for (i = 1; i <= ne; i++) { np++; pn[np] = r; pe[np] = i } }
                        else { np++; pn[np] = r; pe[np] = 0 }
                    }
                    snap = 1; for (p = 1; p <= np; p++) if (q[pn[p]] != "snapshot") snap = 0
                    if (snap) { cols = np <= 4 ? np : 4; pw = 300; ph = 560 }
                    else { cols = np <= 2 ? np : (np <= 4 ? 2 : 3); pw = 520; ph = 380 }
                    rows = int((np + cols - 1) / cols)
                    printf "set terminal pngcairo size %d,%d font \"sans,9\"\n", pw * cols, ph * rows
                    printf "set output \"%s\"\n", png
                    printf "set multiplot layout %d,%d\nset grid\nset key top right\n", rows, cols
                    for (p = 1; p <= np; p++) {
                        r = pn[p]; n = name[r]
                        printf "reset\nset grid\nset key top right font \",8\"\nset xlabel \"t (s)\"\nset autoscale xfixmax\n"
                        if (q[r] == "dy") {
                            printf "set ylabel \"y - y_{start} (m, unscaled)\"\nset yrange [-0.1:0.1]\n"
                        } else if (q[r] == "bottom") {
                            printf "set ylabel \"lowest point y (m, unscaled)\"\nset yrange [-0.03:0.03]\n"
                        } else if (q[r] == "impacts") {
                            printf "set ylabel \"impacts so far\"\nset logscale y\nset yrange [1:10000]\nset key top left\n"
                        }
                        if (q[r] == "snapshot") {
                            i = pe[p]; f = pd "/" n "." e[i] ".dat"
                            printf "set title \"%s: %s, final state\" noenhanced\n", n, lab[i]
                            printf "set size ratio -1\nunset key\nset xlabel \"x (m)\"\nset ylabel \"y (m)\"\nset xtics 1\nset autoscale xfix\nset autoscale yfix\n"
                            if (exists(f))
                                printf "plot \"%s\" index 0 with circles lc rgb \"%s\" fs solid 0.4, \"%s\" index 1 using 1:2 with lines lc rgb \"black\"\n", f, col[e[i]], f
                            else
                                printf "set label 1 \"no data\" at graph 0.4,0.5\nplot [0:1] [0:1] NaN notitle\n"
                            continue
                        }
                        printf "set title \"%s\" noenhanced\n", n
                        s = ""
                        for (i = 1; i <= ne; i++) {
                            f = pd "/" n "." e[i] ".dat"
                            if (!exists(f)) continue
                            # carom events drawn wide, discrete dashed on top:
                            # when the two agree both stay visible
                            st = e[i] == "events" ? "lw 4" : (e[i] == "discrete" ? "lw 1.5 dt 2" : "lw 1.5")
                            s = s (s == "" ? "plot " : ", ") sprintf("\"%s\" using 1:2 with lines %s lc rgb \"%s\" title \"%s\"", f, st, col[e[i]], lab[i])
                        }
                        if (s != "" && ref[r] != "")
                            s = s sprintf(", %s with lines lw 1 dt 3 lc rgb \"black\" title \"exact (%s)\"", ref[r], ref[r])
                        if (s == "") s = "plot [0:1] [0:1] NaN notitle"
                        print s
                    }
                    print "unset multiplot"
                }' "$tmp/fam" > "$tmp/fig.gp"
            if gnuplot "$tmp/fig.gp" < /dev/null 2> "$tmp/gnuplot.err"; then
                figs="$figs $fam"
            else
                echo "run.sh: gnuplot could not draw $png: $(head -n 1 "$tmp/gnuplot.err")" >&2
            fi
        done < "$tmp/families"
    else
        echo "run.sh: gnuplot not found: no figures (apt-get install gnuplot-nox)" >&2
    fi

    R=$tmp/report.md
    {
        cat <<'EOF'
# Stability: the stress suite

Generated by `tools/stress/run.sh --report` (`make stress`); do not edit by
hand. The scenes are in `tools/scenes/stress/`, written by
`tools/stress/gen_scenes.py`; each carries its own pass criterion in
`# check:` comment lines, which `build/stress_check`
(`tools/stress/stress_check.c`) evaluates, in double precision, on an
engine's output: the final state, and the trace or the impact events when
the criterion needs them. The figures below are drawn from the traces.

The suite is meant to fail where the engine is weak: a failing carom cell
is a known problem to fix, not a broken test. `make stress` exits non-zero
while any carom cell fails; Box2D failures are reported only.

## What each criterion checks

All scenes run 10 s of simulated time unless noted; unit boxes have
half-extents 0.5,0.5; the static floor is a wide box with its top at
y = 0; friction is the default 0.6, restitution 0, carom's other settings
its defaults (method as in the column, tolerances `auto`, sleeping on).

| family | scenes | pass when | cell shows (PASS) |
| --- | --- | --- | --- |
| stack | 10, 20 and 40 boxes placed exactly touching; at x = 0, 1.85, 3.7, 7.77 with dt = 1/60, and at x = 0 with dt = 1/30 and 1/240; `stack-mixed`: 9 boxes of their own widths, heights and densities (0.1 to 10), each a little off the one below, statically stable, a stack of `more_scenes.py`'s mstack family (seed 90029; criteria: every box ends within a tenth of its half-height of its start); `tower-offset`: 26 boxes twice as tall as wide, each off the one below by up to a tenth of its width, sleeping off, 20 s, a tower of `more_scenes.py`'s tower family (seed 95029; criteria: every box ends within half its half-width of its start) | the top box ends within 1 cm of its start, and every dynamic body's speed is below 1 cm/s at the end | top box displacement (m) |
| pyramid | 20- and 40-box base; rows touch exactly and boxes in a row are 1.0 m apart centre to centre, so neighbours touch (no gaps) | the top box ends within 5 cm of its start; every box's lowest point is above y = -0.01 m at the end | top box displacement (m) |
| pour | 500 bodies, circles r = 0.1 and boxes of half-extent 0.1 in a checkerboard, dropped from a 12-column grid with small random velocities (fixed seed) into a static container 3 m wide inside (floor and walls 0.2 m thick); `-dt30`: the same at dt = 1/30; `-s0.3-g10`: every length and speed scaled by 0.3 with gravity kept at 10 m/s^2 (bodies 6 cm across: a step 1.8 times coarser for them; criteria scaled by 0.3); `pour-mixed-dt30`: 300 circles, boxes and 3- to 8-gons of radius 1.3 to 2.2 cm, a pour of `random_scenes.py` (seed 31094) at dt = 1/30 in a container 48 cm wide (criteria: a tenth of the largest radius, 2.2 mm); `rotor-elastic-pile-dt30`: 119 circles and boxes of 2 to 6 cm, some elastic, stirred in a 4 m box by a kinematic bar turning at 25.6 rad/s, dt = 1/30 (a scene of the random kinematic family, seed 1019; only "contain": every centre inside the box); `ballpit-mixed`: 124 circles of radii 0.66 to 2.7 m and densities 0.1 to 10 thrown into a bin 51 m wide at dt = 1/30, a ball pit of `more_scenes.py` (seed 80114; criteria: a tenth of the smallest radius, every centre inside the bin) | at the end the worst pairwise overlap is at most 1 cm (exact circle-circle and circle-box depth, SAT minimum translation distance for box-box, over all pairs with a dynamic body), and every centre is inside the inner walls and above the floor top | worst overlap (m) |
| heavy-on-light | a light unit box (mass 1) on the floor with a unit box of mass 10, 100 or 1000 on it | over the whole trace, the heavy centre stays above the light one and the light box's bottom never goes more than 1 cm below the floor top | smallest y(heavy) - y(light) (m) |
| rod | rods 1 cm thick, 2, 5 and 10 m long (half-extents 1, 2.5, 5 by 0.005), standing on end (pushed over with 0.2 rad/s) or tilted 80 degrees from horizontal, toppling onto a static floor 1 cm thick | every rod vertex stays above the floor's bottom face (y > -0.01) over the whole trace; at the end the rod lies on the floor: lowest point within 1 cm of y = 0, vertical extent at most its thickness + 1 cm, speed at most 1 cm/s | lowest rod point over the trace (m) |
| scaled | stack-10 (x = 0, dt = 1/60), pyramid-20, pour, heavy-on-light 100 and the six rods with every length, position, velocity and gravity multiplied by 0.01 (`-s0.01`) and by 100 (`-s100`); masses from density | the same criteria with every length and speed limit scaled likewise | as the family above |
| billiard | pi billiard, mass ratio 10^6: no gravity, a static wall, a light block at rest between the wall and a heavy block moving towards it, restitution 1, frictionless, default settings, 1500 s; `-circles`: the same with two circles | exactly 3141 impacts (rows of the `--events` file), floor(pi 10^3) | impacts |

A FAIL cell names the first failed check and its measured value:
`stay` top-box displacement, `speed` largest final speed, `lowest` lowest
point, `escaped` bodies outside the container, `overlap` worst overlap,
`y[a]-y[b]` height of the heavy centre over the light one,
`rest[1].gap` / `.tilt` / `.speed` the rod's distance from the floor, its
tilt (vertical extent minus thickness) and speed, `impacts` the count.
`ERR exit N` is an engine run that failed (N its exit status; carom: 1 a
simulation error such as a capacity, 2 a scene it rejects), `n/a` a
criterion the engine cannot be checked on (the Box2D v3 harness writes no
events). Every measured value, and the failures' details, are in
"Details" at the end.

Notes on Box2D: 2.4.1 gives every polygon a skin of 0.01 m
(`b2_polygonRadius`), so its boxes rest about 1 to 2 cm apart; stacks
grow by that much per box, and a rod rests about 1.5 cm above the floor.
Box2D v3's contacts are soft: a resting contact keeps an overlap of about
its linear slop (0.005 m, compiled in) and more under a heavy load, so a
column of boxes stands lower than it started (at dt 1/60: 3 cm for 10
boxes, 14 cm for 20, 55 cm for 40) and fails `stay` without falling.
Both Box2D harnesses reject polygons thinner than their welding distance
(`ERR exit 2`): 2.4.1 the 0.01-scale rods and boxes; v3, which welds
vertices closer than 0.02 m, also every 1 cm thick rod.
EOF
        printf '\n## Results\n\n'
        printf '%s scenes, %s engine runs, %s s wall time' "$nscenes" "$ntasks" "$elapsed"
        printf ' (%s at once)' "$jobs"
        [ $fast = 1 ] && printf ', the fast subset only'
        printf '. %s.\n' "$summary"
        [ -n "$box2d_note" ] && printf '\n%s\n' "$box2d_note"
        printf '\n'
        awk -v labels="$labels" '
            BEGIN { FS = "\t"; n = split(substr(labels, 2), lab, "|")
                    printf "| scene |"; for (i = 1; i <= n; i++) printf " %s |", lab[i]; printf "\n"
                    printf "| --- |"; for (i = 1; i <= n; i++) printf " --- |"; printf "\n" }
            { printf "| %s |", $1
              for (i = 1; i <= n; i++) { c = $(3 * i); if ($(3 * i - 1) == "FAIL" || $(3 * i - 1) == "ERR") c = "**" c "**"; printf " %s |", c }
              printf "\n" }' "$tmp/table"
        printf '\n## Time per step\n\n'
        cat <<'EOF'
Microseconds per step. carom: wall time of `build/carom-plain run` writing
the final state only (best of three when under 0.2 s), minus the best of
three runs of the same command with `--steps 0`, divided by the steps
(`build/carom-plain` is `build/carom` linked with the plain library, the
one a program links: no op counters, the same bits;
docs/benchmarks.md times `carom_world_step` alone). Box2D: the harness's
own `--time` (its Step() calls only, one run). A carom body that sleeps
costs almost nothing, so resting scenes are cheap in carom by design.
EOF
        printf 'The machine ran %s engine run(s) at once: rough figures.\n\n' "$jobs"
        awk -v labels="$labels" '
            BEGIN { FS = "\t"; n = split(substr(labels, 2), lab, "|")
                    printf "| scene |"; for (i = 1; i <= n; i++) printf " %s |", lab[i]; printf "\n"
                    printf "| --- |"; for (i = 1; i <= n; i++) printf " ---: |"; printf "\n" }
            { printf "| %s |", $1
              for (i = 1; i <= n; i++) printf " %s |", ($(3 * i + 1) == "" ? "-" : $(3 * i + 1))
              printf "\n" }' "$tmp/table"
        case " $engines " in
        *" box2d "*)
            cat <<'TXT'

Speed targets on the pyramid and pour scenes: carom events within 2x
Box2D 2.4.1's time per step, carom discrete no slower (`make bench-box2d`
times them one run at a time).

TXT
            awk -F '\t' -v d="$tmp/info" '
                function ratio(c, b) { return (c == "" || b == "" || b + 0 <= 0) ? "" : c / b }
                function cell(r, lim) { return r == "" ? "-" : sprintf("%.2f (%s)", r, r <= lim ? "met" : "**missed**") }
                BEGIN { print "| scene | events / Box2D 2.4.1 | discrete / Box2D 2.4.1 |"; print "| --- | ---: | ---: |" }
                { fam = ""; file = d "/" $1
                  while ((getline line < file) > 0) if (line ~ /^family /) fam = substr(line, 8)
                  close(file)
                  if (fam != "pyramid" && fam != "pour" && $1 !~ /^(pyramid|pour)-/) next
                  printf "| %s | %s | %s |\n", $1, cell(ratio($4, $10), 2), cell(ratio($7, $10), 1) }' "$tmp/table"
            ;;
        esac
        printf '\n## Figures\n'
        if [ -z "$figs" ]; then
            printf '\n(No figures: gnuplot was not available or failed.)\n'
        fi
        for fam in $figs; do
            printf '\n### %s\n\n' "$fam"
            case "$fam" in
            stack) printf 'Height of the top box over its start (m); the criterion allows 1 cm\nat the end. Curves leaving the window (0.1 m) failed.\n' ;;
            pyramid) printf 'Height of the top box over its start (m); the criterion allows 5 cm.\n' ;;
            pour) printf 'Final state of the pour in each engine (circles filled, boxes outlined;\nthe container in black).\n' ;;
            heavy-on-light) printf 'Lowest point of the light box (m): how far the heavy box presses it\ninto the floor (the criterion allows 1 cm below y = 0).\n' ;;
            rod) printf 'Lowest point of the rod (m); the floor is y in [-0.01, 0]; a curve\nleaving the window at the bottom went through it.\n' ;;
            scaled) printf 'The scaled scenes, every length divided by the scale so the curves\ncompare with the unscaled ones: top-box height over its start for the\nstacks, the light box'"'"'s lowest point for heavy-on-light.\n' ;;
            billiard) printf 'Impacts so far (the events file, logarithmic scale); dotted: the exact\ncount, 3141.\n' ;;
            esac
            printf '\n![%s](%s-%s.png)\n' "$fam" "$rbase" "$fam"
        done
        cat <<'EOF'

## Details

Every check of every run, as `build/stress_check` printed it: LABEL VALUE
OP LIMIT, OP the comparison that held; a `*` marks a failed check.

EOF
        for e in $engines; do
            printf '### %s\n\n```\n' "$(engine_label "$e")"
            while read -r _ _ n; do
                f=$tmp/res/$n.$e
                [ -f "$f" ] || continue
                awk -F '\t' -v n="$n" '{ d = $4; if ($1 != "PASS" && $1 != "FAIL") d = $1 " " n ": " d; print d }' "$f"
            done < "$tmp/order"
            printf '```\n\n'
        done
        cat <<'EOF'
## Running it

```sh
make stress                  # everything; writes this file and its figures
make stress-check            # the fast subset ('# fast' scenes), no report
make stress B2V3_DIR=PREFIX  # also Box2D v3 (tools/box2d_v3/BUILDING.md)
make stress STRESS_V3=PATH   # or any harness of the same interface
sh tools/stress/run.sh --help
python3 tools/stress/gen_scenes.py          # regenerate the scenes
python3 tools/stress/gen_scenes.py --check  # are the checked-in ones current?
build/stress_check SCENE FINAL.csv [TRACE.csv] [EVENTS.csv]
```

The criterion grammar (`# check:` and `# plot:` lines) is documented at
the top of `tools/stress/stress_check.c`.
EOF
    } > "$R"
    cp "$R" "$report"
    echo "run.sh: wrote $report$([ -n "$figs" ] && echo " and figures for:$figs")" >&2
fi

if [ "$carom_bad" -gt 0 ]; then
    exit 1
fi
exit 0
