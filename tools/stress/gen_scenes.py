#!/usr/bin/env python3
"""gen_scenes.py -- generate the stress suite scenes (tools/scenes/stress/).

    python3 tools/stress/gen_scenes.py [--out DIR] [--check]

Writes every scene of the public stress suite as a carom scene file
(docs/scene-format.md) into DIR (default tools/scenes/stress), removing
*.scene files there that the suite no longer has. --check writes nothing:
it exits 1 if a file in DIR differs from what would be generated (or is
missing or extra), 0 if all match. The output is deterministic: no clock,
no Python random module (the pour uses its own 64-bit generator with a
fixed seed), numbers printed with '%.9g'.

Each scene carries its pass criterion in comment lines that
build/stress_check reads (grammar: tools/stress/stress_check.c and
docs/stability.md):

    # stress: NAME -- description            (one line, informative)
    # family: FAMILY                          (groups scenes in the report)
    # fast                                    (in the fast subset)
    # check: KIND key=value ...               (all must pass)
    # plot: QUANTITY key=value ...            (what the report's figure shows)

Only gravity=, dt= and steps= (and max-pairs= for the pour) appear on the
world lines, so that every engine harness reads the files; everything else
is carom's default (method events, rest-speed/slop/length-unit auto, sleep
on).
"""
import os
import sys

G = 10.0          # |gravity|, m/s^2, before scaling
FLOOR_HALF_Y = 0.5
DT = {30: "0.033333333", 60: "0.016666667", 240: "0.0041666667"}
STEPS_10S = {30: 300, 60: 600, 240: 2400}


def num(x):
    """A number as the scene files write it."""
    if x == 0:
        return "0"
    s = "%.9g" % x
    return s


def vec(x, y):
    return "%s,%s" % (num(x), num(y))


class Scene:
    def __init__(self, name, family, desc):
        self.name = name
        self.family = family
        self.desc = desc
        self.fast = False
        self.engines = None
        self.checks = []
        self.plot = None
        self.world = ""
        self.bodies = []

    def text(self):
        out = ["carom-scene 1"]
        out.append("# stress: %s" % self.name)
        out.extend("#   " + d for d in self.desc)
        out.append("# family: %s" % self.family)
        if self.fast:
            out.append("# fast")
        if self.engines:
            out.append("# engines: " + self.engines)
        out.extend("# check: " + c for c in self.checks)
        if self.plot:
            out.append("# plot: " + self.plot)
        out.append("world " + self.world)
        out.extend("body " + b for b in self.bodies)
        return "\n".join(out) + "\n"


def world(s, dt_key, steps, extra="", g_scale=None):
    gs = s if g_scale is None else g_scale
    w = "gravity=%s dt=%s steps=%d" % (vec(0, -G * gs), DT[dt_key], steps)
    return w + (" " + extra if extra else "")


def floor(s, half_width, half_y=FLOOR_HALF_Y):
    """Static floor, its top at y = 0."""
    return "box static half-extents=%s position=%s" % (
        vec(half_width * s, half_y * s), vec(0, -half_y * s))


def box(hx, hy, x, y, extra=""):
    b = "box half-extents=%s position=%s" % (vec(hx, hy), vec(x, y))
    return b + (" " + extra if extra else "")


def suffix(s):
    return "" if s == 1 else "-s%s" % num(s)


# ---- families ----------------------------------------------------------------

def stack(h, x, dtk, s=1.0, plot=False):
    xs = num(x)
    name = "stack-h%d-x%s-dt%d%s" % (h, xs, dtk, suffix(s))
    sc = Scene(name, "stack" if s == 1 else "scaled", [
        "%d unit boxes (half-extents 0.5,0.5) stacked exactly touching at x = %s"
        % (h, xs) + (", scaled by %s" % num(s) if s != 1 else "") + ",",
        "on a static floor (top at y = 0); dt = 1/%d, 10 s. Pass: the top box"
        % dtk,
        "ends within 1 cm of its start, every body slower than 1 cm/s"
        + (" (both x %s)." % num(s) if s != 1 else ".")])
    sc.world = world(s, dtk, STEPS_10S[dtk])
    sc.bodies.append(floor(s, 20))
    for i in range(h):
        sc.bodies.append(box(0.5 * s, 0.5 * s, x * s, (0.5 + i) * s))
    sc.checks.append("stay body=%d tol=%s" % (h, num(0.01 * s)))
    sc.checks.append("still speed=%s" % num(0.01 * s))
    if plot:
        sc.plot = "dy body=%d scale=%s" % (h, num(s))
    return sc


def pyramid(n, s=1.0, plot=True):
    name = "pyramid-b%d%s" % (n, suffix(s))
    count = n * (n + 1) // 2
    sc = Scene(name, "pyramid" if s == 1 else "scaled", [
        "a pyramid of unit boxes, %d in the base row, %d in all" % (n, count)
        + (", scaled by %s" % num(s) if s != 1 else "") + ".",
        "Rows touch exactly; boxes in a row are 1.0 m apart centre to centre,",
        "so neighbours touch too (no gaps); each box above the base rests on",
        "two. 10 s at dt = 1/60. Pass: the top box ends within 5 cm of its",
        "start; no box's lowest point at or below y = -0.01 m at the end"
        + (" (lengths x %s)." % num(s) if s != 1 else ".")])
    sc.world = world(s, 60, 600)
    sc.bodies.append(floor(s, max(20, n)))
    for r in range(n):
        k = n - r
        for i in range(k):
            x = -(k - 1) / 2.0 + i
            sc.bodies.append(box(0.5 * s, 0.5 * s, x * s, (0.5 + r) * s))
    top = count  # body 0 is the floor
    sc.checks.append("stay body=%d tol=%s" % (top, num(0.05 * s)))
    sc.checks.append("above y=%s" % num(-0.01 * s))
    if plot:
        sc.plot = "dy body=%d scale=%s" % (top, num(s))
    return sc


class Rng:
    """64-bit LCG (Knuth MMIX constants), top 53 bits as a uniform double."""

    def __init__(self, seed):
        self.x = seed & 0xFFFFFFFFFFFFFFFF

    def uniform(self, lo, hi):
        self.x = (self.x * 6364136223846793005 + 1442695040888963407) \
            & 0xFFFFFFFFFFFFFFFF
        u = (self.x >> 11) / float(1 << 53)
        return lo + (hi - lo) * u


def pour(s=1.0, plot=True, dtk=60, real_g=False):
    """real_g: lengths and speeds scaled by s, gravity kept at G (smaller
    bodies under the same gravity: a coarser step for them)."""
    n = 500
    inner = 1.5      # inner walls at x = -1.5, +1.5
    wall = 0.2       # wall and floor thickness
    height = 12.0    # wall top
    cols, pitch, y0 = 12, 0.25, 0.2
    name = "pour-%d%s%s%s" % (n, suffix(s), "-g10" if real_g else "",
                              "-dt%d" % dtk if dtk != 60 else "")
    notes = []
    if real_g:
        notes = ["Gravity is kept at %s m/s^2, not scaled: bodies %s m across"
                 % (num(G), num(0.2 * s)),
                 "under the same gravity, for which dt is %s times coarser."
                 % num(round((1 / s) ** 0.5, 2))]
    if dtk != 60 or real_g:
        notes.append("With a fixed 4 substeps this pile sinks into itself by"
                     " centimetres;")
        notes.append("the step takes more (docs/physics.md, \"Small bodies and"
                     " long steps\").")
    sc = Scene(name, "pour" if s == 1 or real_g else "scaled", [
        "%d bodies, circles (radius 0.1) and boxes (half-extents 0.1,0.1)"
        % n + (", scaled by %s," % num(s) if s != 1 else "") + " in a",
        "checkerboard of a %d-column grid (pitch %s m, jitter +-0.01 m) from"
        % (cols, num(pitch)),
        "y = 0.2 m up, with random velocities (|vx| <= 0.5, -0.5 <= vy <= 0,",
        "|omega| <= 2; LCG seed 20240601), poured into a static container:",
        "floor (top at y = 0) and two walls 0.2 m thick, inner faces at",
        "x = -1.5 and 1.5 m, 12 m tall. 10 s at dt = 1/%d. Pass: every centre"
        % dtk,
        "inside the inner walls and above the floor top at the end; worst",
        "pairwise overlap <= 1 cm" + (" (lengths x %s)." % num(s) if s != 1
                                      else "."),
        "max-pairs is raised for the packed pile (12 per body)."] + notes)
    rng = Rng(20240601)
    sc.world = world(s, dtk, STEPS_10S[dtk], "max-pairs=%d" % (12 * (n + 3)),
                     g_scale=1.0 if real_g else None)
    # floor under the walls too; walls stand on it
    sc.bodies.append("box static half-extents=%s position=%s" % (
        vec((inner + wall) * s, wall / 2 * s), vec(0, -wall / 2 * s)))
    for side in (-1, 1):
        sc.bodies.append("box static half-extents=%s position=%s" % (
            vec(wall / 2 * s, height / 2 * s),
            vec(side * (inner + wall / 2) * s, height / 2 * s)))
    k = 0
    row = 0
    while k < n:
        for c in range(cols):
            if k == n:
                break
            x = -(cols - 1) / 2.0 * pitch + c * pitch + rng.uniform(-0.01, 0.01)
            y = y0 + row * pitch + rng.uniform(-0.01, 0.01)
            vx = rng.uniform(-0.5, 0.5)
            vy = rng.uniform(-0.5, 0.0)
            w = rng.uniform(-2.0, 2.0)
            motion = "velocity=%s angular-velocity=%s" % (
                vec(round(vx, 4) * s, round(vy, 4) * s), num(round(w, 4)))
            pos = vec(round(x, 4) * s, round(y, 4) * s)
            if (row + c) % 2 == 0:
                sc.bodies.append("circle radius=%s position=%s %s" % (
                    num(0.1 * s), pos, motion))
            else:
                sc.bodies.append("box half-extents=%s position=%s %s" % (
                    vec(0.1 * s, 0.1 * s), pos, motion))
            k += 1
        row += 1
    sc.checks.append("overlap max=%s" % num(0.01 * s))
    sc.checks.append("contain xmin=%s xmax=%s ymin=0" % (
        num(-inner * s), num(inner * s)))
    if plot:
        sc.plot = "snapshot"
    return sc


def heavy_on_light(ratio, s=1.0, plot=True):
    name = "heavy-on-light-m%d%s" % (ratio, suffix(s))
    if s == 1:
        what = ["a light unit box (density 1, so mass 1) on the floor and a unit",
                "box of density %d (mass %d) resting on it, exactly touching;"
                % (ratio, ratio)]
    else:
        what = ["heavy-on-light-m%d scaled by %s: boxes of half-extent %s,"
                % (ratio, num(s), num(0.5 * s)),
                "densities 1 and %d (masses %s and %s), gravity %s;"
                % (ratio, num(s * s), num(ratio * s * s), num(G * s))]
    sc = Scene(name, "heavy-on-light" if s == 1 else "scaled", what + [
        "10 s at dt = 1/60. Pass, over the whole trace: the heavy centre",
        "stays above the light one, and the light box's bottom is never more",
        "than %s m below the floor top." % num(0.01 * s)])
    sc.world = world(s, 60, 600)
    sc.bodies.append(floor(s, 20))
    sc.bodies.append(box(0.5 * s, 0.5 * s, 0, 0.5 * s, "density=1"))
    sc.bodies.append(box(0.5 * s, 0.5 * s, 0, 1.5 * s, "density=%d" % ratio))
    sc.checks.append("order upper=2 lower=1 over=trace")
    sc.checks.append("above body=1 y=%s over=trace" % num(-0.01 * s))
    if plot:
        sc.plot = "bottom body=1 scale=%s" % num(s)
    return sc


ANGLE_90 = "1.57079633"
ANGLE_80 = 80.0 / 180.0 * 3.141592653589793


def rod(hx, pose, s=1.0, plot=True):
    import math
    hy = 0.005
    length = 2 * hx
    name = "rod-l%s-%s%s" % (num(length), pose, suffix(s))
    if pose == "stand":
        how = ["standing on end (angle pi/2), pushed over with angular",
               "velocity 0.2 rad/s"]
        ang = ANGLE_90
        cy = hx
        extra = "angular-velocity=0.2"
    else:
        how = ["tilted 80 degrees from horizontal, its lowest corner on the",
               "floor, released at rest"]
        ang = num(ANGLE_80)
        cy = hx * math.sin(ANGLE_80) + hy * math.cos(ANGLE_80)
        extra = ""
    sc = Scene(name, "rod" if s == 1 else "scaled", [
        "a rod %s m long and 1 cm thick (half-extents %s,0.005)"
        % (num(length), num(hx)) + (", scaled by %s," % num(s) if s != 1
                                    else ","),
        how[0], how[1] + ", toppling onto a static floor 1 cm thick (top",
        "at y = 0, bottom at -0.01); 10 s at dt = 1/60. Pass: every rod vertex",
        "above the floor's bottom face (y > -0.01) over the whole trace, and",
        "at the end the rod lies on the floor: lowest point within 1 cm of",
        "y = 0, vertical extent at most thickness + 1 cm, speed <= 1 cm/s"
        + (" (lengths x %s)." % num(s) if s != 1 else ".")])
    sc.world = world(s, 60, 600)
    sc.bodies.append(floor(s, 20, 0.005))
    b = "box half-extents=%s position=%s angle=%s" % (
        vec(hx * s, hy * s), vec(0, cy * s), ang)
    sc.bodies.append(b + (" " + extra if extra else ""))
    sc.checks.append("above body=1 y=%s over=trace" % num(-0.01 * s))
    sc.checks.append("rest body=1 y=0 tol=%s speed=%s" % (
        num(0.01 * s), num(0.01 * s)))
    if plot:
        sc.plot = "bottom body=1 scale=%s" % num(s)
    return sc


def pi_billiard(circles=False):
    # Light block (mass 1, 0.1 m wide) at rest 40 m from the wall, heavy
    # block (mass 1e6, 0.2 m wide) 40 m further, approaching at 0.1 m/s. An
    # exact (double) event simulation gives 3141 impacts, the last at
    # t = 1473.7 s, at most 42 in any 1/60 s step (carom records 64 events
    # per step by default). The exact count is the events method's claim:
    # the discrete method and Box2D resolve impacts at step ends.
    if circles:
        sc = Scene("pi-billiard-1e6-circles", "billiard", [
            "pi-billiard-1e6 with circles for blocks (radius 0.05 and 0.1, same",
            "centres, masses and speed): their contacts pass through the",
            "centres, so no spin can arise and only the impact sequence is",
            "tested. Pass: exactly 3141 rows in the events file."])
        light = "circle radius=0.05"
        heavy = "circle radius=0.1"
    else:
        sc = Scene("pi-billiard-1e6", "billiard", [
            "two blocks on a frictionless line, no gravity, restitution 1: a",
            "static wall (face at x = 0); a light block (mass 1, half-extents",
            "0.05,0.05) at rest, its left face 40 m from the wall; a heavy block",
            "(mass 1e6, half-extents 0.1,0.1) 40 m further, moving towards it",
            "at 0.1 m/s. Exact answer: floor(pi 10^3) = 3141 impacts, the last",
            "at t = 1473.7 s, at most 42 in one 1/60 s step. Default settings,",
            "1500 s. Pass: exactly 3141 rows in the events file."])
        light = "box half-extents=0.05,0.05"
        heavy = "box half-extents=0.1,0.1"
    sc.world = "gravity=0,0 dt=%s steps=90000" % DT[60]
    sc.bodies.append("box static half-extents=0.5,2 position=-0.5,0 "
                     "restitution=1 friction=0")
    sc.bodies.append(light + " position=40.05,0 mass=1 "
                     "restitution=1 friction=0")
    sc.bodies.append(heavy + " position=80.2,0 mass=1000000 "
                     "velocity=-0.1,0 restitution=1 friction=0")
    sc.checks.append("impacts count=3141")
    sc.engines = "events"
    sc.plot = "impacts"
    return sc


def mixed_pour(seed=31094):
    """A pour of tools/stress/random_scenes.py (its seed 31094) kept as a
    regression scene: 300 circles, boxes and 3- to 8-gons 2 to 4 cm across
    at dt = 1/30, which once left a circle wedged 17 mm into a box beside
    a wall for 7 s (docs/robustness.md, "A seventh review")."""
    import random
    import random_scenes as rs
    saved = os.environ.pop("NO30", None)
    real_g, rs.REAL_G = rs.REAL_G, False
    try:
        sc, info = rs.pour(random.Random(seed), "pour-mixed-dt30")
    finally:
        rs.REAL_G = real_g
        if saved is not None:
            os.environ["NO30"] = saved
    sc.family = "pour"
    sc.desc = [
        "random_scenes.py's pour of seed %d: %d circles, boxes and 3- to"
        % (seed, info["n"]),
        "8-gons of radius %s to %s m from a grid into a container %s m"
        % (num(0.6 * info["size"] * info["s"]), num(info["size"] * info["s"]),
           num(2 * info["inner"] * info["s"])),
        "wide, 10 s at dt = 1/%d, gravity scaled with the scene. Pass: the"
        % info["dt"],
        "worst overlap at most a tenth of the largest body radius, every",
        "centre inside the walls and above the floor."]
    return sc


def more_scene(fam, seed, name, family, desc):
    """A scene of tools/stress/more_scenes.py kept as a regression scene."""
    import random
    import more_scenes as ms
    sc, info = getattr(ms, fam)(random.Random(seed), name)
    sc.family = family
    sc.desc = desc(info)
    return sc


def ballpit_mixed(seed=80114):
    """A ball pit of more_scenes.py (its seed 80114): a light ball under
    heavier ones was crushed 0.2 m deep, three times the criterion, before
    the substeps for unlike masses (docs/physics.md, "Unlike masses leaning
    on each other")."""
    def desc(info):
        return [
            "more_scenes.py's ball pit of seed %d: %d circles of radius %s to %s m,"
            % (seed, info["n"], num(info["rmin"] * info["s"]), num(info["rmax"] * info["s"])),
            "densities 0.1 to 10, thrown into a closed bin %s m wide, 10 s at"
            % num(2 * info["inner"] * info["s"]),
            "dt = 1/%d. Pass: the worst overlap at most a tenth of the smallest"
            % info["dt"],
            "radius, every centre inside the bin."]
    return more_scene("ballpit", seed, "ballpit-mixed", "pour", desc)


def stack_mixed(seed=90029):
    """A stack of more_scenes.py's mstack family (its seed 90029), statically
    stable, which toppled before the substeps for unlike masses."""
    def desc(info):
        return [
            "more_scenes.py's mixed stack of seed %d: %d boxes of their own"
            % (seed, info["k"]),
            "widths, heights and densities (0.1 to 10), each off the one below",
            "by up to a tenth of its width, friction %s, 10 s at dt = 1/%d."
            % (num(info["fr"]), info["dt"]),
            "Pass: every box ends within a tenth of its half-height of its start."]
    return more_scene("mstack", seed, "stack-mixed", "stack", desc)


def tower_offset(seed=95029):
    """A tower of more_scenes.py's tower family (its seed 95029), statically
    stable, sleeping off: it stands with the default 4 substeps, where
    the tallest of the family rock until they fall (docs/physics.md, "Tall
    columns of offset boxes")."""
    def desc(info):
        return [
            "more_scenes.py's tower of seed %d: %d boxes %s times as tall as"
            % (seed, info["k"], num(info["aspect"])),
            "wide, each off the one below by up to a tenth of its width,",
            "friction %s, sleeping off, 20 s at dt = 1/%d. Pass: every box ends"
            % (num(info["fr"]), info["dt"]),
            "within half its half-width of its start."]
    return more_scene("tower", seed, "tower-offset", "stack", desc)


def all_scenes():
    scenes = []
    for h in (10, 20, 40):
        for x in (0, 1.85, 3.7, 7.77):
            scenes.append(stack(h, x, 60, plot=(x == 0)))
        for dtk in (30, 240):
            scenes.append(stack(h, 0, dtk, plot=(h == 40)))
    scenes.append(pyramid(20))
    scenes.append(pyramid(40))
    scenes.append(pour())
    # long steps and small bodies (docs/physics.md, "Small bodies and long
    # steps"): the substeps grow with dt sqrt(g / L)
    scenes.append(pour(dtk=30, plot=False))
    scenes.append(pour(0.3, plot=False, real_g=True))
    scenes.append(mixed_pour())
    scenes.append(ballpit_mixed())
    scenes.append(stack_mixed())
    scenes.append(tower_offset())
    for r in (10, 100, 1000):
        scenes.append(heavy_on_light(r))
    for hx in (1.0, 2.5, 5.0):
        for pose in ("stand", "tilt80"):
            scenes.append(rod(hx, pose))
    for s in (0.01, 100.0):
        scenes.append(stack(10, 0, 60, s, plot=True))
        scenes.append(pyramid(20, s, plot=False))
        scenes.append(pour(s, plot=False))
        scenes.append(heavy_on_light(100, s, plot=True))
        for hx in (1.0, 2.5, 5.0):
            for pose in ("stand", "tilt80"):
                scenes.append(rod(hx, pose, s, plot=False))
    scenes.append(pi_billiard())
    scenes.append(pi_billiard(circles=True))
    fast = {"stack-h10-x7.77-dt60", "heavy-on-light-m100", "rod-l5-tilt80",
            "pyramid-b20", "stack-h10-x0-dt60-s100", "pour-mixed-dt30",
            "ballpit-mixed", "stack-mixed", "tower-offset"}
    for sc in scenes:
        sc.fast = sc.name in fast
    names = [sc.name for sc in scenes]
    assert len(set(names)) == len(names), "duplicate scene names"
    assert fast <= set(names), "a fast scene is missing"
    return scenes


def hand_written(path):
    """A scene written by hand (its third line says so): kept, not checked."""
    with open(path) as fh:
        head = [fh.readline() for _ in range(3)]
    return head[2].startswith("# hand-written")


def main(argv):
    out = "tools/scenes/stress"
    check = False
    i = 1
    while i < len(argv):
        a = argv[i]
        if a == "--out" and i + 1 < len(argv):
            out = argv[i + 1]
            i += 2
        elif a == "--check":
            check = True
            i += 1
        elif a in ("-h", "--help"):
            print(__doc__.strip())
            return 0
        else:
            sys.stderr.write("gen_scenes.py: unknown argument '%s' (try --help)\n" % a)
            return 2
    scenes = all_scenes()
    want = {sc.name + ".scene": sc.text() for sc in scenes}
    have = set(f for f in os.listdir(out) if f.endswith(".scene")
               and not hand_written(os.path.join(out, f))) \
        if os.path.isdir(out) else set()
    if check:
        bad = 0
        for f in sorted(want):
            path = os.path.join(out, f)
            try:
                with open(path) as fh:
                    same = fh.read() == want[f]
            except OSError:
                same = False
            if not same:
                sys.stderr.write("gen_scenes.py: %s is missing or differs\n" % path)
                bad = 1
        for f in sorted(have - set(want)):
            sys.stderr.write("gen_scenes.py: %s is not generated\n"
                             % os.path.join(out, f))
            bad = 1
        return bad
    os.makedirs(out, exist_ok=True)
    for f in sorted(have - set(want)):
        os.remove(os.path.join(out, f))
    for f, text in sorted(want.items()):
        with open(os.path.join(out, f), "w") as fh:
            fh.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
