#!/usr/bin/env python3
"""more_scenes.py -- random families beyond the stress suite's own.

    python3 tools/stress/more_scenes.py START COUNT OUTDIR

Writes COUNT scenes, seeds START .. START+COUNT-1 (Python's random module
seeded with the number), cycling over the families below, as
OUTDIR/FAMILY-SEED.scene with their `# check:` criteria
(tools/stress/stress_check.c). FAMS=hopper (say) keeps to those families.
tools/stress/random_run.sh runs a directory of them; what a sweep found is
in docs/robustness.md ("More random families"). Every scene is scaled by
10^U(-2, 2) (ball pits and hoppers 10^U(-1.5, 1.5)) with its gravity.

hstack    2 to 8 light boxes (density 1) stacked on a floor, and on top a
          box or a circle 10 to 1000 times denser, 0.5 to 2 times as wide;
          dt 1/30 to 1/240 for 10 s. Pass: the heavy body stays above the
          top light box over the whole trace, the bottom box never sinks
          more than 2 % of a half-height into the floor, and the heavy body
          ends within 10 % of a half-height of its start.
fastdrop  a circle, a box or a thin rod (1 to 5 % as thick as long) thrown
          down at 50 to 600 of its sizes per second, spinning at up to 20
          rad/s, with restitution 0, 0.5 or 1, onto a static floor 2 to 50 %
          as thick as the body; 3 s. Pass: no point of it ever below the
          floor's bottom face.
ballpit   50 to 300 circles of radii 1 to 5 times apart and densities 0.1
          to 10, restitution and friction uniform in [0, 1], thrown down
          into a closed bin; 10 s. Pass: every centre inside the bin, worst
          overlap at most a tenth of the smallest radius.
hopper    30 to 120 circles, boxes (aspect up to 20) and 3- to 8-gons of
          densities 0.1 to 10, restitution 0 to 0.8, any friction, thrown
          from the top of a closed bin onto two slanted static ramps; dt
          1/30 to 1/120 for 10 s. Pass: every centre inside the bin, worst
          overlap at most a quarter of the body size.
mstack    2 to 12 boxes of widths 0.5 to 2 and heights 0.3 to 1 times a
          base size, densities 0.1 to 10 each, stacked at rest, each off
          the centre of the one below by up to a tenth of its width, one
          friction 0.4 to 1; dt 1/30 to 1/240 for 10 s. Every stack is
          statically stable (the load above each face has its centre well
          inside it). Pass: every box ends within a tenth of its
          half-height of its start. Drawn only when FAMS names it, so that
          the first four keep their seeds.
tower     10 to 30 boxes of one size (1 to 4 times as tall as wide), each
          off the one below by up to a tenth of its width, statically
          stable with a margin (the centre of the load above each face at
          least a tenth of the box width inside the face), one friction 0.4
          to 1, sleeping off; dt 1/60 or 1/120 for 20 s. Pass: every box ends
          within half its half-width of its start. Drawn only when FAMS names
          it.
"""
import math
import os
import random
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gen_scenes as g

num, vec = g.num, g.vec
DTS = [(30, 300), (60, 600), (120, 1200), (240, 2400)]


def world(r, s, secs=10, dts=DTS):
    dk, steps = r.choice(dts)
    return "gravity=%s dt=%s steps=%d" % (vec(0, -10.0 * s), num(1.0 / dk), steps * secs // 10), dk


def hstack(r, name):
    s = 10 ** r.uniform(-2, 2)
    k = r.randint(2, 8)
    hy = r.uniform(0.2, 1.0)
    hx = hy * r.uniform(0.5, 3.0)
    ratio = 10 ** r.uniform(1, 3)
    wide = r.uniform(0.5, 2.0)
    fr = r.uniform(0.3, 1.0)
    circ = r.random() < 0.25
    sc = g.Scene(name, "hstack", ["heavy on a stack"])
    sc.world, dk = world(r, s)
    sc.bodies.append("box static half-extents=%s position=%s" % (vec(50 * s, 0.5 * s), vec(0, -0.5 * s)))
    y = 0.0
    for _ in range(k):
        y += hy
        sc.bodies.append("box half-extents=%s position=%s density=1 friction=%s" % (
            vec(hx * s, hy * s), vec(0, y * s), num(fr)))
        y += hy
    if circ:
        rad = hx * wide
        sc.bodies.append("circle radius=%s position=%s density=%s friction=%s" % (
            num(rad * s), vec(0, (y + rad) * s), num(ratio), num(fr)))
    else:
        hh = hy * r.uniform(0.5, 1.5)
        sc.bodies.append("box half-extents=%s position=%s density=%s friction=%s" % (
            vec(hx * wide * s, hh * s), vec(0, (y + hh) * s), num(ratio), num(fr)))
    top = k + 1
    sc.checks.append("order upper=%d lower=%d over=trace" % (top, k))
    sc.checks.append("above body=1 y=%s over=trace" % num(-0.02 * hy * s))
    sc.checks.append("stay body=%d tol=%s" % (top, num(0.1 * hy * s)))
    return sc, dict(s=s, k=k, hy=hy, hx=hx, ratio=ratio, wide=wide, circ=circ, dt=dk)


def fastdrop(r, name):
    s = 10 ** r.uniform(-2, 2)
    kind = r.choice(["circle", "box", "rod"])
    size = r.uniform(0.05, 1.0)
    th = size * r.uniform(0.02, 0.5)  # the floor's half-thickness
    sc = g.Scene(name, "fastdrop", ["fast drop on a thin floor"])
    sc.world, dk = world(r, s, 3)
    speed = size * r.uniform(50, 600)
    # wide enough that a body sent sideways by the bounce stays over it
    sc.bodies.append("box static half-extents=%s position=%s" % (
        vec(max(30.0, 4 * speed) * s, th * s), vec(0, -th * s)))
    ang = r.uniform(0, math.pi)
    h0 = size * 4 + speed / dk * r.uniform(0, 1)
    mot = "velocity=%s angular-velocity=%s" % (
        vec(r.uniform(-0.3, 0.3) * speed * s, -speed * s), num(r.uniform(-20, 20)))
    e = num(r.choice([0, 0, 0.5, 1.0]))
    if kind == "circle":
        sc.bodies.append("circle radius=%s position=%s %s restitution=%s" % (
            num(size * s), vec(0, h0 * s), mot, e))
    else:
        thick = r.uniform(0.3, 1) if kind == "box" else r.uniform(0.01, 0.05)
        sc.bodies.append("box half-extents=%s position=%s angle=%s %s restitution=%s" % (
            vec(size * s, size * thick * s), vec(0, h0 * s), num(ang), mot, e))
    sc.checks.append("above body=1 y=%s over=trace" % num(-th * 2 * s * 0.999))
    return sc, dict(s=s, kind=kind, size=size, th=th, speed=speed, e=e, dt=dk)


def ballpit(r, name):
    s = 10 ** r.uniform(-1.5, 1.5)
    n = r.randint(50, 300)
    rmin = r.uniform(0.03, 0.1)
    rmax = rmin * r.uniform(1, 5)
    inner = rmax * r.uniform(8, 15)
    wall = r.uniform(0.02, 0.3)
    sc = g.Scene(name, "ballpit", ["ball pit"])
    sc.world, dk = world(r, s)
    sc.bodies.append("box static half-extents=%s position=%s" % (
        vec((inner + wall) * s, wall / 2 * s), vec(0, -wall / 2 * s)))
    height = 60 * inner
    for side in (-1, 1):
        sc.bodies.append("box static half-extents=%s position=%s" % (
            vec(wall / 2 * s, height / 2 * s), vec(side * (inner + wall / 2) * s, height / 2 * s)))
    pitch = 2.2 * rmax
    cols = max(1, int((2 * inner - pitch) / pitch))
    k = 0
    row = 0
    while k < n:
        for c in range(cols):
            if k == n:
                break
            x = -(cols - 1) / 2.0 * pitch + c * pitch
            y = 2 * rmax + row * pitch
            sc.bodies.append(
                "circle radius=%s position=%s velocity=%s restitution=%s friction=%s density=%s" % (
                    num(r.uniform(rmin, rmax) * s), vec(x * s, y * s),
                    vec(r.uniform(-3, 3) * s, r.uniform(-3, 0) * s), num(r.uniform(0, 1)),
                    num(r.uniform(0, 1)), num(10 ** r.uniform(-1, 1))))
            k += 1
        row += 1
    sc.checks.append("overlap max=%s" % num(0.1 * rmin * s))
    sc.checks.append("contain xmin=%s xmax=%s ymin=0" % (num(-inner * s), num(inner * s)))
    return sc, dict(s=s, n=n, rmin=rmin, rmax=rmax, inner=inner, dt=dk)


def polygon(r, rad, k):
    a0 = r.uniform(0, 2 * math.pi)
    return ";".join(vec(rad * math.cos(a0 + 2 * math.pi * i / k), rad * math.sin(a0 + 2 * math.pi * i / k))
                    for i in range(k))


def hopper(r, name):
    s = 10 ** r.uniform(-1.5, 1.5)
    n = r.randint(30, 120)
    size = r.uniform(0.05, 0.2)
    W = size * r.uniform(12, 25)
    wall = size * r.uniform(0.3, 3)
    sc = g.Scene(name, "hopper", ["hopper"])
    sc.world, dk = world(r, s, 10, DTS[:3])
    H = W * 3
    # a closed bin: floor, lid, two walls
    for y in (-wall, H + wall):
        sc.bodies.append("box static half-extents=%s position=%s" % (
            vec((W + wall) * s, wall * s), vec(0, y * s)))
    for side in (-1, 1):
        sc.bodies.append("box static half-extents=%s position=%s" % (
            vec(wall * s, (H / 2 + wall) * s), vec(side * (W + wall) * s, H / 2 * s)))
    # two ramps sloping down towards the middle
    ang = r.uniform(0.2, 0.7)
    for side in (-1, 1):
        L = W * 0.45
        sc.bodies.append("box static half-extents=%s position=%s angle=%s" % (
            vec(L / 2 * s, size * 0.3 * s), vec(side * (W - L * math.cos(ang) / 2 - size) * s, H * 0.5 * s),
            num(-side * ang)))
    for _ in range(n):
        x = r.uniform(-W * 0.8, W * 0.8)
        y = r.uniform(H * 0.65, H * 0.95)
        rad = size * r.uniform(0.5, 1.0)
        kind = r.random()
        mot = "velocity=%s angular-velocity=%s density=%s restitution=%s friction=%s" % (
            vec(r.uniform(-2, 2) * s, r.uniform(-2, 0) * s), num(r.uniform(-5, 5)),
            num(10 ** r.uniform(-1, 1)), num(r.choice([0, 0, 0.3, 0.8])), num(r.uniform(0, 1)))
        if kind < 0.3:
            sc.bodies.append("circle radius=%s position=%s %s" % (num(rad * s), vec(x * s, y * s), mot))
        elif kind < 0.55:
            sc.bodies.append("box half-extents=%s position=%s angle=%s %s" % (
                vec(rad * s, rad * r.uniform(0.05, 1) * s), vec(x * s, y * s), num(r.uniform(0, 3)), mot))
        else:
            sc.bodies.append("polygon vertices=%s position=%s %s" % (
                polygon(r, rad * s, r.randint(3, 8)), vec(x * s, y * s), mot))
    sc.checks.append("contain xmin=%s xmax=%s ymin=0" % (num(-W * s), num(W * s)))
    sc.checks.append("overlap max=%s" % num(0.25 * size * s))
    return sc, dict(s=s, n=n, size=size, W=W, wall=wall, ang=ang, dt=dk)


def mstack(r, name):
    s = 10 ** r.uniform(-2, 2)
    k = r.randint(2, 12)
    dk, steps = r.choice(DTS)
    sc = g.Scene(name, "mstack", ["mixed stack"])
    sc.world = "gravity=%s dt=%s steps=%d" % (vec(0, -10.0 * s), num(1.0 / dk), steps)
    sc.bodies.append("box static half-extents=%s position=%s" % (
        vec(50 * s, 0.5 * s), vec(0, -0.5 * s)))
    y = 0.0
    fr = r.uniform(0.4, 1.0)
    base = r.uniform(0.3, 1.0)
    for i in range(k):
        hx = base * r.uniform(0.5, 2.0)
        hy = base * r.uniform(0.3, 1.0)
        rho = 10 ** r.uniform(-1, 1)
        off = r.uniform(-0.1, 0.1) * hx
        y += hy
        sc.bodies.append("box half-extents=%s position=%s density=%s friction=%s" % (
            vec(hx * s, hy * s), vec(off * s, y * s), num(rho), num(fr)))
        y += hy
        sc.checks.append("stay body=%d tol=%s" % (i + 1, num(0.1 * hy * s)))
    return sc, dict(s=s, k=k, base=base, fr=fr, dt=dk)


def tower(r, name):
    s = 10 ** r.uniform(-2, 2)
    k = r.randint(10, 30)
    dk, steps = r.choice([(60, 1200), (120, 2400)])
    hx = 0.5
    hy = hx * r.uniform(1.0, 4.0)
    fr = r.uniform(0.4, 1.0)
    while True:  # a random walk of offsets, drawn again until it stands
        xs, x = [], 0.0
        for i in range(k):
            x += r.uniform(-0.1, 0.1) * 2 * hx
            xs.append(x)
        margin = min(
            min(sum(xs[j + 1:]) / (k - j - 1) - (max(xs[j], xs[j + 1]) - hx),
                (min(xs[j], xs[j + 1]) + hx) - sum(xs[j + 1:]) / (k - j - 1))
            for j in range(k - 1))
        if margin >= 0.2 * hx:
            break
    sc = g.Scene(name, "tower", ["offset tower"])
    sc.world = "gravity=%s dt=%s steps=%d sleep=off" % (vec(0, -10.0 * s), num(1.0 / dk), steps)
    sc.bodies.append("box static half-extents=%s position=%s" % (
        vec(50 * s, 0.5 * s), vec(0, -0.5 * s)))
    for i, x in enumerate(xs):
        sc.bodies.append("box half-extents=%s position=%s friction=%s" % (
            vec(hx * s, hy * s), vec(x * s, (2 * i + 1) * hy * s), num(fr)))
        sc.checks.append("stay body=%d tol=%s" % (i + 1, num(0.5 * hx * s)))
    return sc, dict(s=s, k=k, aspect=hy / hx, fr=fr, margin=margin / hx, dt=dk)


FAM = [hstack, fastdrop, ballpit, hopper]
EXTRA = [mstack, tower]  # only when FAMS names them


def main():
    if len(sys.argv) != 4 or sys.argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if len(sys.argv) == 2 else 2
    try:
        start, count = int(sys.argv[1]), int(sys.argv[2])
    except ValueError:
        print("more_scenes.py: START and COUNT must be integers (try --help)", file=sys.stderr)
        return 2
    out = sys.argv[3]
    names = os.environ.get("FAMS")
    fams = FAM if not names else [f for f in FAM + EXTRA if f.__name__ in names.split(",")]
    if not fams:
        print("more_scenes.py: FAMS names no family of %s" % ",".join(
            f.__name__ for f in FAM + EXTRA), file=sys.stderr)
        return 2
    os.makedirs(out, exist_ok=True)
    for seed in range(start, start + count):
        r = random.Random(seed)
        fam = fams[seed % len(fams)]
        name = "%s-%d" % (fam.__name__, seed)
        sc, info = fam(r, name)
        sc.desc = [str(info)]
        with open(os.path.join(out, name + ".scene"), "w") as f:
            f.write(sc.text())
    return 0


if __name__ == "__main__":
    sys.exit(main())
