#!/usr/bin/env python3
"""hotspots.py -- markdown tables of callgrind profiles (tools/bench/bench.sh).

usage: hotspots.py [--top N] LABEL=CALLGRIND_OUT ...

For each profile (valgrind --tool=callgrind --toggle-collect=
bench_timed_steps, so only the timed steps count): the top N functions of
the library by inclusive and by self instructions, as a share of the
instructions of the timed steps. Code inlined from another file (the
arithmetic layer, src/arith.h) is counted in the function it was inlined
into (callgrind lists it apart, by file). Needs callgrind_annotate. Exit status: 0 ok, 2 bad usage or a
profile that cannot be read.
"""
import re
import subprocess
import sys


def annotate(path, inclusive):
    args = ["callgrind_annotate", "--threshold=100"]
    if inclusive:
        args.append("--inclusive=yes")
    args.append(path)
    out = subprocess.run(args, capture_output=True, text=True, check=True).stdout
    total, per = None, {}
    for line in out.splitlines():
        m = re.match(r"\s*([\d,]+)\s+(?:\(\s*[\d.]+%\)\s+)?(.*)$", line)
        if not m:
            continue
        n, rest = int(m.group(1).replace(",", "")), m.group(2)
        if "PROGRAM TOTALS" in rest:
            total = n
            continue
        m2 = re.match(r"(\S+?):(\S+)(?:\s+\[.*\])?$", rest.strip())
        if not m2:
            continue
        path_, fn = m2.group(1), m2.group(2)
        if "/src/" not in path_ and not path_.startswith("src/"):
            continue
        fn = re.sub(r"\.(isra|constprop|part|cold)\.\d+", "", fn)
        fn = re.sub(r"\.(isra|constprop|part|cold)\.\d+", "", fn)
        file_ = path_.split("/src/")[-1] if "/src/" in path_ else path_[4:]
        key = fn
        e = per.setdefault(key, [0, set()])
        # self: the parts in different files add up; inclusive: the part
        # in the function's own file already holds the inlined parts
        e[0] = max(e[0], n) if inclusive else e[0] + n
        e[1].add(file_)
    return total, per


def main(argv):
    top = 12
    args = argv[1:]
    if len(args) >= 2 and args[0] == "--top":
        top = int(args[1])
        args = args[2:]
    if not args or any("=" not in a for a in args):
        print(__doc__, file=sys.stderr)
        return 2
    out = []
    for a in args:
        label, path = a.split("=", 1)
        try:
            total, inc = annotate(path, True)
            _t, slf = annotate(path, False)
        except (OSError, subprocess.CalledProcessError) as e:
            print(f"hotspots.py: {path}: {e}", file=sys.stderr)
            return 2
        if not total:
            print(f"hotspots.py: {path}: no instructions recorded", file=sys.stderr)
            return 2
        inc.pop("carom_world_step", None)
        out.append(f"**{label}** ({total:,} instructions in the timed steps)")
        out.append("")
        out.append("| inclusive | function | | self | function |")
        out.append("|---|---|---|---|---|")
        irows = sorted(inc.items(), key=lambda kv: -kv[1][0])[:top]
        srows = sorted(slf.items(), key=lambda kv: -kv[1][0])[:top]
        for i in range(max(len(irows), len(srows))):
            left = right = "| |"
            if i < len(irows):
                k, (n, files) = irows[i]
                left = f"| {100 * n / total:.1f} % | {'/'.join(sorted(files))}: `{k}` |"
            if i < len(srows):
                k, (n, files) = srows[i]
                right = f" {100 * n / total:.1f} % | {'/'.join(sorted(files))}: `{k}` |"
            else:
                right = " | |"
            out.append(left + " |" + right)
        out.append("")
    sys.stdout.write("\n".join(out) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
