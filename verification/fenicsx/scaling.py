#!/usr/bin/env python3
"""Table and fitted exponents of the runs scaling.sh left in DIR (issue 20).

For each run: free dofs, Newton iterations, process wall and CPU (user +
sys, /usr/bin/time), CPU per Newton iteration, peak RSS, factor nonzeros.
Fitted exponents: least squares of log(y) against log(free dofs), over all
sizes of a dimension and over its larger half (the asymptotic rate; small
sizes carry the process's fixed cost).

Usage: scaling.py DIR
"""

import glob
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from sphere3d import process  # noqa: E402  (the /usr/bin/time file of a run)


def run_2d(d):
    with open(os.path.join(d, "bench.json")) as f:
        b = json.load(f)
    t = process(d)
    wall, cpu, rss = t["process_wall"], t["cpu_time"], t["peak_rss_mib"]
    return {
        "label": os.path.basename(d)[3:],
        "dofs": b["free_dofs"],
        "its": b["newton_iterations"],
        "wall": wall,
        "cpu": cpu,
        "rss": rss,
        "factor": b.get("factor_nonzeros", 0),
    }


def run_3d(d):
    with open(os.path.join(d, "run", "summary.json")) as f:
        s = json.load(f)
    t = process(d)
    wall, cpu, rss = t["process_wall"], t["cpu_time"], t["peak_rss_mib"]
    return {
        "label": "N = " + os.path.basename(d)[3:],
        "dofs": s["free_dofs"],
        "its": s["newton_iterations"],
        "wall": wall,
        "cpu": cpu,
        "rss": rss,
        "factor": s.get("factor_nonzeros", 0),
    }


def slope(rows, key):
    """Least-squares exponent p of key ~ dofs^p."""
    xs = [math.log(r["dofs"]) for r in rows]
    ys = [math.log(r[key]) for r in rows]
    n = len(xs)
    if n < 2:
        return float("nan")
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    sxy = sum((x - mx) * (y - my) for x, y in zip(xs, ys))
    return sxy / sxx


def table(title, rows):
    rows = sorted(rows, key=lambda r: r["dofs"])
    print(f"### {title}\n")
    print("| size | free dofs | Newton its | wall [s] | CPU [s] | CPU per it. [s] | peak RSS [MiB] | factor nonzeros |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(
            f"| {r['label']} | {r['dofs']:,} | {r['its']} | {r['wall']:.2f} | {r['cpu']:.2f} | "
            f"{r['cpu'] / r['its']:.3f} | {r['rss']:.0f} | {r['factor']:,} |"
        )
    for r in rows:
        r["cpu_it"] = r["cpu"] / r["its"]
    upper = rows[len(rows) // 2 :] if len(rows) >= 4 else rows
    print()
    print("| fitted exponent (y ~ dofs^p) | all sizes | larger half |")
    print("|---|---|---|")
    for key, name in [("cpu", "process CPU"), ("cpu_it", "CPU per Newton iteration"),
                      ("rss", "peak RSS"), ("factor", "factor nonzeros")]:
        if all(r[key] > 0 for r in rows):
            print(f"| {name} | {slope(rows, key):.2f} | {slope(upper, key):.2f} |")
    print()


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    directory = sys.argv[1]
    two = [run_2d(d) for d in glob.glob(os.path.join(directory, "2d_*")) if os.path.exists(os.path.join(d, "bench.json"))]
    three = [run_3d(d) for d in glob.glob(os.path.join(directory, "3d_*")) if os.path.exists(os.path.join(d, "run", "summary.json"))]
    if two:
        table("2D Hertz (`ctc bench --size S`)", two)
    if three:
        table("3D Hertz sphere (sphere3d.py mesh, `ctc run`)", three)
    load = os.path.join(directory, "load.txt")
    if os.path.exists(load):
        print("Load average (1, 5, 15 min) around each run:\n\n```text")
        print(open(load).read().rstrip())
        print("```")


if __name__ == "__main__":
    main()
