#!/usr/bin/env python3
"""random_scenes.py -- random variants of the stress suite's families.

    python3 tools/stress/random_scenes.py START COUNT OUTDIR

Writes COUNT scenes, seeds START .. START+COUNT-1 (Python's random module
seeded with the number: the same seed gives the same scene), cycling over
the families stack, pyramid, hol (heavy on light), rod and pour, as
OUTDIR/FAMILY-SEED.scene, each with its family's `# check:` criterion
scaled to its bodies (tools/stress/stress_check.c). The environment
variable FAMS=pour,rod (say) keeps to those families; NO30=1 leaves dt 1/30
out of the pours; REAL_G=1 keeps gravity at 10 m/s^2 instead of scaling it
with the scene (small bodies then see a coarser step, large ones a finer
one). The first comment line records the drawn parameters.
tools/stress/random_run.sh runs a directory of them. What a sweep found:
docs/robustness.md ("The stress families at random").

Ranges: every scene scaled by 10^U(-2, 2) with its gravity (rods 10^U(-1,
1), pours 10^U(-1.5, 1.5)); dt 1/30, 1/60, 1/120 or 1/240 for 10 s.
Stacks: 3 to 25 boxes, half-heights 0.1 to 1, aspect 0.5 to 3, widths and
densities varying along half of them, friction 0.3 to 1; pass: the top box
within 2 % of a half-height of its start, all slower than that per second.
Pyramids: 3 to 22 in the base, gaps up to half a box; top box within 10 %
of a half-height. Heavy on light: density ratio 10^U(0.3, 3), a box or a
circle on a box; the heavy one stays above. Rods: 1 to 12 m long, 0.6 to
10 cm thick, on end and pushed hard enough to topple, or tilted past their
corner; they end lying on the floor. Pours: 100 to 350 circles, boxes and
3- to 8-gons of radius 3 to 20 cm from a grid into a tall container; the
worst overlap at most a tenth of the body size, every body inside.
"""
import math, os, random, sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gen_scenes as g

num, vec = g.num, g.vec
REAL_G = os.environ.get("REAL_G") == "1"
DTS = [(30, 300), (60, 600), (120, 1200), (240, 2400)]

def world(r, s, extra="", no30=False):
    dk, steps = r.choice(DTS[1:] if no30 else DTS)
    g = 10.0 if REAL_G else 10.0 * s
    if REAL_G and s > 1.0:
        steps = int(steps * math.sqrt(s))  # its motion is sqrt(s) slower
    return "gravity=%s dt=%s steps=%d%s" % (vec(0, -g), num(1.0 / dk), steps, extra), dk

def floorline(s, hw, hy):
    return "box static half-extents=%s position=%s" % (vec(hw * s, hy * s), vec(0, -hy * s))

def stack(r, name):
    s = 10 ** r.uniform(-2, 2)
    h = r.randint(3, 25)
    hy = r.uniform(0.1, 1.0)
    hx = hy * r.uniform(0.5, 3.0)
    vary = r.random() < 0.5
    fr = r.uniform(0.3, 1.0)
    sc = g.Scene(name, "rstack", ["random stack"])
    sc.world, dk = world(r, s)
    sc.bodies.append(floorline(s, 50, r.uniform(0.05, 1.0)))
    y = 0.0
    x0 = r.uniform(-5, 5)
    for i in range(h):
        w = hx * (r.uniform(0.7, 1.3) if vary else 1.0)
        d = r.uniform(0.5, 2.0) if vary else 1.0
        y += hy
        sc.bodies.append("box half-extents=%s position=%s density=%s friction=%s" % (
            vec(w * s, hy * s), vec(x0 * s, y * s), num(d), num(fr)))
        y += hy
    sc.checks.append("stay body=%d tol=%s" % (h, num(0.02 * hy * s)))
    sc.checks.append("still speed=%s" % num(0.02 * hy * s))
    return sc, dict(s=s, h=h, hy=hy, hx=hx, vary=vary, fr=fr, dt=dk)

def pyramid(r, name):
    s = 10 ** r.uniform(-2, 2)
    n = r.randint(3, 22)
    hy = r.uniform(0.2, 1.0)
    hx = hy * r.uniform(0.5, 2.0)
    gap = r.choice([0.0, 0.0, r.uniform(0, 0.5)]) * hx
    fr = r.uniform(0.5, 1.0)
    sc = g.Scene(name, "rpyramid", ["random pyramid"])
    sc.world, dk = world(r, s)
    pitch = 2 * hx + gap
    sc.bodies.append(floorline(s, max(50, n * pitch), 0.5))
    for row in range(n):
        k = n - row
        for i in range(k):
            x = (-(k - 1) / 2.0 + i) * pitch
            sc.bodies.append("box half-extents=%s position=%s friction=%s" % (
                vec(hx * s, hy * s), vec(x * s, (hy + 2 * hy * row) * s), num(fr)))
    top = n * (n + 1) // 2
    sc.checks.append("stay body=%d tol=%s" % (top, num(0.1 * hy * s)))
    sc.checks.append("above y=%s" % num(-0.02 * hy * s))
    return sc, dict(s=s, n=n, hy=hy, hx=hx, gap=gap, fr=fr, dt=dk)

def hol(r, name):
    s = 10 ** r.uniform(-2, 2)
    ratio = 10 ** r.uniform(0.3, 3)
    lhx, lhy = r.uniform(0.2, 1), r.uniform(0.2, 1)
    circle_top = r.random() < 0.3
    hhx = lhx * r.uniform(0.5, 2.0)
    hhy = r.uniform(0.2, 1)
    sc = g.Scene(name, "rhol", ["random heavy on light"])
    sc.world, dk = world(r, s)
    sc.bodies.append(floorline(s, 50, 0.5))
    sc.bodies.append("box half-extents=%s position=%s density=1" % (vec(lhx * s, lhy * s), vec(0, lhy * s)))
    if circle_top:
        rad = hhx
        sc.bodies.append("circle radius=%s position=%s density=%s" % (num(rad * s), vec(r.uniform(-0.3, 0.3) * lhx * s, (2 * lhy + rad) * s), num(ratio)))
    else:
        sc.bodies.append("box half-extents=%s position=%s density=%s" % (vec(hhx * s, hhy * s), vec(0, (2 * lhy + hhy) * s), num(ratio)))
    sc.checks.append("order upper=2 lower=1 over=trace")
    sc.checks.append("above body=1 y=%s over=trace" % num(-0.02 * lhy * s))
    return sc, dict(s=s, ratio=ratio, circle=circle_top, lhx=lhx, lhy=lhy, hhx=hhx, hhy=hhy, dt=dk)

def rod(r, name):
    s = 10 ** r.uniform(-1, 1)
    hx = r.uniform(0.5, 6)
    hy = r.uniform(0.003, 0.05)
    fhy = r.uniform(0.003, 0.5)
    stand = r.random() < 0.5
    sc = g.Scene(name, "rrod", ["random rod"])
    sc.world, dk = world(r, s)
    sc.bodies.append(floorline(s, 30, fhy))
    if stand:
        # pushed hard enough to topple: about its corner it turns at a
        # quarter of the push (angular momentum about the corner), and
        # that turn must lift the centre over the corner; 1.5 to 10 times
        # the energy it needs
        ang = math.pi / 2
        cy = hx
        lift = (10.0 / s if REAL_G else 10.0) * (math.hypot(hx, hy) - hx)
        w_min = 4.0 * math.sqrt(2.0 * lift / ((4.0 / 3.0) * (hx * hx + hy * hy)))
        w = w_min * math.sqrt(r.uniform(1.5, 10.0))
        extra = " angular-velocity=%s" % num(w * r.choice([-1, 1]))
    else:
        # tilted past its corner (its centre beyond the corner it stands on)
        lean = math.atan2(hy, hx)
        ang = r.uniform(math.radians(30), math.pi / 2 - 1.5 * lean)
        cy = hx * math.sin(ang) + hy * math.cos(ang)
        extra = ""
    sc.bodies.append("box half-extents=%s position=%s angle=%s%s" % (vec(hx * s, hy * s), vec(0, cy * s), num(ang), extra))
    sc.checks.append("above body=1 y=%s over=trace" % num(-fhy * 2 * s * 0.999))
    sc.checks.append("rest body=1 y=0 tol=%s speed=%s" % (num(0.01 * s), num(0.01 * s)))
    return sc, dict(s=s, hx=hx, hy=hy, fhy=fhy, stand=stand, dt=dk)

def poly(r, rad):
    k = r.randint(3, 8)
    a0 = r.uniform(0, 2 * math.pi)
    pts = [(rad * math.cos(a0 + 2 * math.pi * i / k), rad * math.sin(a0 + 2 * math.pi * i / k)) for i in range(k)]
    return ";".join(vec(x, y) for x, y in pts)

def pour(r, name):
    s = 10 ** r.uniform(-1.5, 1.5)
    n = r.randint(100, 350)
    size = r.uniform(0.05, 0.2)
    inner = size * r.uniform(10, 20)
    wall = r.uniform(0.05, 0.5)
    sc = g.Scene(name, "rpour", ["random pour"])
    sc.world, dk = world(r, s, "", os.environ.get("NO30") == "1")
    sc.bodies.append("box static half-extents=%s position=%s" % (vec((inner + wall) * s, wall / 2 * s), vec(0, -wall / 2 * s)))
    height = 400 * size
    for side in (-1, 1):
        sc.bodies.append("box static half-extents=%s position=%s" % (vec(wall / 2 * s, height / 2 * s), vec(side * (inner + wall / 2) * s, height / 2 * s)))
    pitch = 2.6 * size
    cols = int((2 * inner - pitch) / pitch)
    k = 0; row = 0
    while k < n:
        for c in range(cols):
            if k == n: break
            x = -(cols - 1) / 2.0 * pitch + c * pitch
            y = 2 * size + row * pitch
            mot = "velocity=%s angular-velocity=%s" % (vec(r.uniform(-.5, .5) * s, r.uniform(-.5, 0) * s), num(r.uniform(-2, 2)))
            kind = r.random()
            rad = size * r.uniform(0.6, 1.0)
            if kind < 0.35:
                sc.bodies.append("circle radius=%s position=%s %s" % (num(rad * s), vec(x * s, y * s), mot))
            elif kind < 0.7:
                sc.bodies.append("box half-extents=%s position=%s %s" % (vec(rad * s, rad * r.uniform(0.4, 1) * s), vec(x * s, y * s), mot))
            else:
                sc.bodies.append("polygon vertices=%s position=%s %s" % (poly(r, rad * s), vec(x * s, y * s), mot))
            k += 1
        row += 1
    sc.checks.append("overlap max=%s" % num(0.1 * size * s))
    sc.checks.append("contain xmin=%s xmax=%s ymin=0" % (num(-inner * s), num(inner * s)))
    return sc, dict(s=s, n=n, size=size, inner=inner, wall=wall, dt=dk)

FAM = [stack, pyramid, hol, rod, pour]

def main():
    if len(sys.argv) != 4 or sys.argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if len(sys.argv) == 2 else 2
    start, count, out = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
    fams = os.environ.get("FAMS")
    os.makedirs(out, exist_ok=True)
    for seed in range(start, start + count):
        r = random.Random(seed)
        fam = FAM[seed % len(FAM)] if not fams else [f for f in FAM if f.__name__ in fams.split(",")][seed % len(fams.split(","))]
        name = "%s-%d" % (fam.__name__, seed)
        sc, info = fam(r, name)
        sc.desc = [str(info)]
        with open(os.path.join(out, name + ".scene"), "w") as f:
            f.write(sc.text())
    return 0


if __name__ == "__main__":
    sys.exit(main())
