#!/usr/bin/env python3
"""report.py -- docs/benchmarks.md from the records of one `make bench` run.

usage: report.py --time FILE [--ops FILE] [--overhead FILE] [--hotspots FILE]
                 [--build TEXT] [--seconds S] [--quick] [--out FILE]

FILE: the record lines carom-bench and carom-bench-ops print (KIND
key=value ..., msg= last), or the hotspot summaries tools/bench/bench.sh
writes. Every number in the report comes from these files; nothing is
typed in. Exit status: 0 ok, 2 bad usage or unreadable input.
"""
import argparse
import sys

NS = 1e9


def parse(path):
    recs = []
    with open(path, encoding="utf-8") as f:
        for line in f:
            line = line.rstrip("\n")
            if not line or line.startswith("#"):
                continue
            msg = None
            if " msg=" in line:
                line, msg = line.split(" msg=", 1)
            parts = line.split()
            r = {"kind": parts[0]}
            for p in parts[1:]:
                if "=" in p:
                    k, v = p.split("=", 1)
                    r[k] = v
            if msg is not None:
                r["msg"] = msg
            recs.append(r)
    return recs


def num(r, k, default=None):
    try:
        return float(r[k])
    except (KeyError, ValueError, TypeError):
        return default


def fmt_time(ns):
    """ns per step as us or ms, 3 significant digits"""
    if ns is None:
        return "-"
    us = ns / 1000.0
    if us >= 1000.0:
        ms = us / 1000.0
        return f"{ms:.3g} ms" if ms < 1000 else f"{ms:.0f} ms"
    return f"{us:.3g} µs"


def fmt_ratio(x):
    if x is None:
        return "-"
    return f"{x:.2f}" if x < 10 else f"{x:.0f}"


def pct(x):
    p = 100.0 * x
    return f"{p:.0f} %" if p >= 10 else f"{p:.2g} %"


def fmt_int(x):
    return "-" if x is None else f"{x:,.0f}"


ENGINES = ["events", "discrete", "first-impact", "box2d", "box2d-v3"]
LABEL = {"events": "carom events", "discrete": "carom discrete",
         "first-impact": "carom first-impact", "box2d": "Box2D 2.4.1",
         "box2d-v3": "Box2D v3"}


class Data:
    def __init__(self, recs):
        self.machine = next((r for r in recs if r["kind"] == "machine"), {})
        self.layout = next((r for r in recs if r["kind"] == "layout"), None)
        self.time = {}
        for r in recs:
            if r["kind"] == "time":
                self.time[(r["scene"], int(r["n"]), r["engine"])] = r
        self.fails = [r for r in recs if r["kind"] == "fail"]
        self.settle = [r for r in recs if r["kind"] == "settle"]
        self.sizes = {}
        for (scene, n, _e) in self.time:
            self.sizes.setdefault(scene, set()).add(n)

    def ns(self, scene, n, engine):
        r = self.time.get((scene, n, engine))
        return num(r, "ns_step") if r else None

    def engines(self, scene):
        have = {e for (s, _n, e) in self.time if s == scene}
        return [e for e in ENGINES if e in have]


def time_table(d, scene, v3_built, out):
    sizes = sorted(d.sizes.get(scene, []))
    engines = d.engines(scene)
    if not v3_built and "box2d-v3" not in engines:
        engines.append("box2d-v3")
    head = ["bodies", "steps timed"]
    for e in engines:
        head += [LABEL[e], "×"]
    out.append("| " + " | ".join(head) + " |")
    out.append("|" + "---|" * len(head))
    for i, n in enumerate(sizes):
        any_r = next((d.time[(scene, n, e)] for e in engines if (scene, n, e) in d.time), {})
        row = [f"{n:,}", any_r.get("steps", "-")]
        for e in engines:
            if e == "box2d-v3" and not v3_built:
                row += ["not built", ""]
                continue
            t = d.ns(scene, n, e)
            prev = d.ns(scene, sizes[i - 1], e) if i > 0 else None
            cell = fmt_time(t)
            r = d.time.get((scene, n, e))
            if r and r.get("caps") == "raised":
                cell += " †"
            row += [cell, fmt_ratio(t / prev) if t and prev else "-"]
        out.append("| " + " | ".join(row) + " |")


def target_rows(d, v3_built):
    """(target, what, N, measured, limit, met)"""
    rows = []

    def ratio(scene, n, a, b):
        x, y = d.ns(scene, n, a), d.ns(scene, n, b)
        return x / y if x and y else None

    gas = sorted(d.sizes.get("gas", []))
    pile = sorted(d.sizes.get("pile", []))
    for n in gas:
        rows.append(("events gas ≤ 0.5× Box2D 2.4.1", n, ratio("gas", n, "events", "box2d"), 0.5))
    for n in gas:
        rows.append(("events gas ≤ 1× Box2D v3", n,
                     ratio("gas", n, "events", "box2d-v3") if v3_built else None, 1.0))
    for i, n in enumerate(gas):
        if i == 0:
            continue
        a, b = d.ns("gas", n, "events"), d.ns("gas", gas[i - 1], "events")
        rows.append((f"events gas growth ≤ 13× per 10× ({gas[i - 1]:,} → {n:,})", n,
                     a / b if a and b else None, 13.0))
    for n in gas:
        rows.append(("discrete gas ≤ 0.25× Box2D 2.4.1", n, ratio("gas", n, "discrete", "box2d"), 0.25))
    for n in pile:
        if n in (1000, 10000):
            rows.append(("pile events ≤ 1.5× discrete", n, ratio("pile", n, "events", "discrete"), 1.5))
    for n in pile:
        if n in (1000, 10000):
            rows.append(("pile discrete ≤ 1× Box2D v3", n,
                         ratio("pile", n, "discrete", "box2d-v3") if v3_built else None, 1.0))
    for s in d.settle:
        if s["engine"] in ("events", "discrete"):
            mv, st = num(s, "ns_moving"), num(s, "ns_settled")
            asleep = s.get("awake_after") == "0"
            rows.append((f"settled pile ≤ 10 % of moving ({s['engine']}, sleeping on"
                         + ("" if asleep else f"; {s.get('awake_after')} bodies still awake "
                            f"after {s.get('settle_steps')} steps") + ")",
                         int(s["n"]), st / mv if mv and st and st > 0 else None, 0.10))
    if d.layout:
        for n in gas:
            r = d.time.get(("gas", n, "events"))
            if r and num(r, "bytes_default"):
                rows.append(("memory ≤ 500 B per body, default capacities", n,
                             num(r, "bytes_default") / int(r["bodies"]), 500.0))
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--time", required=True)
    ap.add_argument("--ops")
    ap.add_argument("--overhead")
    ap.add_argument("--hotspots")
    ap.add_argument("--build", default="")
    ap.add_argument("--seconds", type=float)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--out", default="-")
    a = ap.parse_args()
    try:
        d = Data(parse(a.time))
        ops = parse(a.ops) if a.ops else []
        over = parse(a.overhead) if a.overhead else []
        hot = open(a.hotspots, encoding="utf-8").read() if a.hotspots else ""
    except OSError as e:
        print(f"report.py: {e}", file=sys.stderr)
        return 2
    m = d.machine
    v3_built = m.get("box2d_v3", "not") not in ("not", "not-built")
    o = []
    o.append("# Benchmarks: carom against Box2D 2.4.1 and Box2D v3")
    o.append("")
    o.append("<!-- Generated by tools/bench/bench.sh (make bench): do not edit. -->")
    o.append("")
    o.append(f"*Regenerated by `make bench`{' (quick run: `make bench-quick`)' if a.quick else ''}. "
             f"Machine: {m.get('msg', 'unknown CPU')}, {m.get('cpus', '?')} CPUs (shared: "
             "other processes ran too, so the spread of repeated runs is given). "
             f"carom {m.get('carom', '?')}, {a.build}. Box2D 2.4.1: Debian's libbox2d. "
             f"Box2D v3: {m.get('box2d_v3') if v3_built else 'not built (make bench B2V3_DIR=...)'}"
             f"{', upstream erincatto/box2d, Release, one worker, 4 substeps' if v3_built else ''}."
             + (f" The whole run took {a.seconds:.0f} s." if a.seconds else "") + "*")
    o.append("")
    o.append("""How it is measured: `build/carom-bench` (tools/bench/) generates each
scene in memory (tools/bench/scenes.c) and hands the same bodies, as floats,
to every engine through its public API: same positions, sizes, densities,
velocities, restitutions and frictions. Each run makes a fresh world, takes
one untimed step, then times the next steps: the thread's CPU time over
them (CLOCK_THREAD_CPUTIME_ID, so that other processes on a shared machine
do not count; CLOCK_MONOTONIC around each step call, about 0.2 µs, is
inside it for every engine alike). A figure is the median over repeated
runs of a run's mean CPU time per step; in each repetition the engines
take turns, in a rotated order,
in the same process. Sleeping is off for every engine (as Box2D's harness
sets it) except in the settled-pile table. Box2D 2.4.1 runs 8 velocity and
3 position iterations; Box2D v3 4 substeps; carom its defaults (4
substeps). "×" is the growth over the row above, for 10 times the bodies
(10 = linear). At 10^5 bodies fewer steps are timed, from the start, so
that row's growth compares different stretches of the motion.

- **gas N**: N circles (r = 0.1 m, e = 1, no friction) in a closed square
  box of static walls, no gravity, 0.4 m² per circle, on a grid,
  velocities uniform in [-1.5, 1.5]² m/s; every meeting bounces (carom's
  rest speed and Box2D's restitution threshold 0).
- **pile N**: N bodies, circles r = 0.25 m and 0.5 m boxes alternating,
  released at rest from a grid with 5 cm gaps into a container, gravity
  10 m/s², friction 0.6, restitution 0; the first second is timed
  (falling, landing, packing).
""")
    o.append("## Elastic gas: time per step")
    o.append("")
    time_table(d, "gas", v3_built, o)
    o.append("")
    o.append("## Pile: time per step")
    o.append("")
    time_table(d, "pile", v3_built, o)
    o.append("")
    big = [n for n in d.sizes.get("pile", []) if n >= 100000]
    if big:
        o.append(f"At {big[0]:,} bodies only the first steps are timed: the pile is still "
                 "falling freely (almost no contacts), so that row measures free fall, not a "
                 "pile, and its growth factor means nothing.")
        o.append("")
    if any(r.get("caps") == "raised" for r in d.time.values()):
        o.append("† carom failed with its default capacities (see Failures below) and was "
                 "timed with the capacity that ran out doubled until the run went through.")
        o.append("")

    # ratios
    o.append("## Ratios")
    o.append("")
    o.append("Time per step over the other engine's, same scene and size (below 1: carom is faster).")
    o.append("")
    o.append("| scene | bodies | events / 2.4.1 | events / v3 | discrete / 2.4.1 | discrete / v3 | events / discrete | v3 / 2.4.1 |")
    o.append("|---|---|---|---|---|---|---|---|")
    for scene in ("gas", "pile"):
        for n in sorted(d.sizes.get(scene, [])):
            def r(x, y):
                a_, b_ = d.ns(scene, n, x), d.ns(scene, n, y)
                return fmt_ratio(a_ / b_) if a_ and b_ else "-"
            o.append(f"| {scene} | {n:,} | {r('events', 'box2d')} | {r('events', 'box2d-v3')} | "
                     f"{r('discrete', 'box2d')} | {r('discrete', 'box2d-v3')} | "
                     f"{r('events', 'discrete')} | {r('box2d-v3', 'box2d')} |")
    o.append("")

    # targets
    o.append("## Targets")
    o.append("")
    o.append("| target | bodies | measured | limit | |")
    o.append("|---|---|---|---|---|")
    for what, n, x, lim in target_rows(d, v3_built):
        verdict = "not measured" if x is None else ("met" if x <= lim else "**missed**")
        shown = "-" if x is None else (f"{x:.0f} B" if lim == 500.0 else
                                        (pct(x) if lim == 0.10 else f"{x:.2f}"))
        limit = f"{lim:.0f} B" if lim == 500.0 else (f"{100 * lim:.0f} %" if lim == 0.10 else f"{lim:g}")
        o.append(f"| {what} | {n:,} | {shown} | {limit} | {verdict} |")
    o.append("")

    # impacts, awake, contacts
    o.append("## Impacts, contacts and awake bodies")
    o.append("")
    o.append("Per step over the timed steps (impacts: carom's counter, events taken by the "
             "events methods, restitution contacts by discrete); contacts and awake bodies "
             "after the last timed step.")
    o.append("")
    o.append("| scene | bodies | impacts / step (events) | impacts / step (discrete) | contacts (carom events) | contacts (Box2D v3) | awake (carom) | awake (v3) |")
    o.append("|---|---|---|---|---|---|---|---|")
    for scene in ("gas", "pile"):
        for n in sorted(d.sizes.get(scene, [])):
            ev = d.time.get((scene, n, "events"), {})
            di = d.time.get((scene, n, "discrete"), {})
            v3 = d.time.get((scene, n, "box2d-v3"), {})
            o.append(f"| {scene} | {n:,} | {ev.get('impacts_per_step', '-')} | "
                     f"{di.get('impacts_per_step', '-')} | {ev.get('contacts', '-')} | "
                     f"{v3.get('contacts', '-')} | {ev.get('awake', '-')} | {v3.get('awake', '-')} |")
    o.append("")

    # memory
    o.append("## Memory per body")
    o.append("")
    if d.layout:
        L = d.layout
        o.append("carom's world is one caller buffer of `carom_world_buffer_size` bytes. "
                 f"From that function alone: {num(L, 'bytes_per_pair'):.0f} B per candidate pair "
                 f"(default {L.get('pairs_per_body')} per body), "
                 f"{num(L, 'bytes_per_contact'):.0f} B per contact (default "
                 f"{L.get('contacts_per_body')} per body), {num(L, 'bytes_per_event'):.0f} B per "
                 f"recorded event (default {L.get('events_per_body')} per body); the rest is per "
                 "body slot plus a fixed part. \"needed\": the buffer for the capacities the run "
                 "used (`carom_stats` max_pairs_used, max_contacts_used, max_impacts_used as "
                 "impacts and events). Box2D 2.4.1: malloc'd bytes in use after the run "
                 "(mallinfo2, world made and stepped); Box2D v3: its own byte count "
                 "(b2World_GetCounters) after the run.")
        o.append("")
    o.append("| scene | bodies | carom, default capacities | carom, capacities needed | pairs used / body | contacts used / body | Box2D 2.4.1 | Box2D v3 |")
    o.append("|---|---|---|---|---|---|---|---|")
    for scene in ("gas", "pile"):
        for n in sorted(d.sizes.get(scene, [])):
            rs = [d.time.get((scene, n, e)) for e in ("events", "discrete", "first-impact")]
            rs = [r for r in rs if r]
            if not rs:
                continue
            bodies = int(rs[0]["bodies"])
            bdef = num(rs[0], "bytes_default")
            bneed = max(num(r, "bytes_needed", 0) for r in rs)
            pu = max(num(r, "max_pairs_used", 0) for r in rs)
            cu = max(num(r, "max_contacts_used", 0) for r in rs)
            b2 = d.time.get((scene, n, "box2d"), {})
            v3 = d.time.get((scene, n, "box2d-v3"), {})
            b2h, v3h = num(b2, "heap_bytes"), num(v3, "heap_bytes")
            o.append(f"| {scene} | {n:,} | {bdef / bodies:,.0f} B | {bneed / bodies:,.0f} B | "
                     f"{pu / bodies:.2f} | {cu / bodies:.2f} | "
                     f"{'-' if b2h is None else f'{b2h / bodies:,.0f} B'} | "
                     f"{'-' if v3h is None else f'{v3h / bodies:,.0f} B'} |")
    o.append("")

    # settled
    if d.settle:
        o.append("## Settled against moving pile (sleeping on)")
        o.append("")
        o.append("Each engine with sleeping on, one run: the mean CPU time per step of the "
                 "first second (moving), then steps until every body sleeps (or the limit), "
                 "then the mean of 60 more steps (settled).")
        o.append("")
        o.append("| bodies | engine | moving | settled | settled / moving | steps until asleep | awake at the end |")
        o.append("|---|---|---|---|---|---|---|")
        for s in d.settle:
            mv, st = num(s, "ns_moving"), num(s, "ns_settled")
            o.append(f"| {int(s['n']):,} | {LABEL.get(s['engine'], s['engine'])} | {fmt_time(mv)} | "
                     f"{fmt_time(st)} | {pct(st / mv) if mv and st and st > 0 else '-'} | "
                     f"{s.get('settle_steps')} | {s.get('awake_after')} |")
        o.append("")

    # ops
    if ops:
        o.append("## Operations per body-step")
        o.append("")
        o.append("From the profiling build (`build/carom-bench-ops`, linked with "
                 "build/profile/libcarom.a): float operations of every kind (add, sub, mul, "
                 "div, compare, sqrt), per body and step, over the same timed steps, beside the "
                 "timing build's CPU ns per body-step. \"ns / op\" is the time per counted float "
                 "operation: a core doing nothing but this arithmetic would retire several "
                 "per ns (under 0.3 ns / op); the rest of the time goes to loads, branches, "
                 "integer work and bookkeeping.")
        o.append("")
        phases = ["integration", "broadphase", "narrowphase", "impact_timing",
                  "impulse_resolution", "resting_contacts"]
        o.append("| scene | bodies | method | ops / body-step | " + " | ".join(phases)
                 + " | ns / body-step | ns / op |")
        o.append("|" + "---|" * (len(phases) + 6))
        for r in ops:
            if r["kind"] != "ops":
                continue
            bs = num(r, "body_steps")
            tot = sum(num(r, p, 0) for p in phases)
            t = d.time.get((r["scene"], int(r["n"]), r["engine"]))
            nsb = num(t, "ns_step") / int(t["bodies"]) if t else None
            per = [f"{num(r, p, 0) / bs:,.0f}" for p in phases]
            o.append(f"| {r['scene']} | {int(r['n']):,} | {r['engine']} | {tot / bs:,.0f} | "
                     + " | ".join(per)
                     + f" | {'-' if nsb is None else f'{nsb:,.0f}'} | "
                     + (f"{nsb / (tot / bs):.2f}" if nsb and tot else "-") + " |")
        o.append("")

    if over:
        o.append("## The profiler's cost")
        o.append("")
        o.append("The same scene through the library built four ways, timed in one run "
                 "(median ns per step): default (CAROM_ENABLE_PROFILE=0), plain (the "
                 "arithmetic layer replaced by bare C operators, CR_ARITH_PLAIN), detached "
                 "(CAROM_ENABLE_PROFILE=1, no profile attached), counting (attached).")
        o.append("")
        o.append("| scene | bodies | method | default | plain | detached | counting | plain / default | detached / default | counting / default |")
        o.append("|---|---|---|---|---|---|---|---|---|---|")
        for r in over:
            if r["kind"] != "overhead":
                continue
            dft, pl, de, co = (num(r, k) for k in ("default", "plain", "detached", "counting"))
            o.append(f"| {r['scene']} | {int(r['n']):,} | {r['engine']} | {fmt_time(dft)} | "
                     f"{fmt_time(pl)} | {fmt_time(de)} | {fmt_time(co)} | {pl / dft:.3f} | "
                     f"{de / dft:.3f} | {co / dft:.3f} |")
        o.append("")

    if hot:
        o.append("## Where the time goes (callgrind)")
        o.append("")
        o.append(hot.rstrip())
        o.append("")

    o.append("## Failures")
    o.append("")
    if not d.fails:
        o.append("None: every engine stepped every scene with its default capacities.")
    else:
        o.append("| what | scene | bodies | engine | status | step | capacities | message |")
        o.append("|---|---|---|---|---|---|---|---|")
        for f in d.fails:
            o.append(f"| {f.get('what')} | {f.get('scene')} | {int(f.get('n', 0)):,} | "
                     f"{f.get('engine')} | {f.get('status')} | {f.get('step')} | "
                     f"{f.get('caps', '-')} | {f.get('msg', '')} |")
    o.append("")
    text = "\n".join(o)
    if a.out == "-":
        sys.stdout.write(text)
    else:
        with open(a.out, "w", encoding="utf-8") as f:
            f.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
