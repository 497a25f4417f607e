#!/usr/bin/env python3
"""Observed convergence of the 2D dam break (docs/sph.md, "Low dissipation").

Reads the history.csv of three runs of validation/dam_break/scene.json at
a/dp 20, 40, 80 (plab run ... --out DIR) and prints, for the front Z(T) and
the back-wall height Hb(T), the mean relative difference between successive
resolutions over 0.2 <= T <= T_END (on a grid of step 0.01, linear
interpolation),
    d(20,40) = mean |q20 - q40| / |q40|,  d(40,80) = mean |q40 - q80| / |q80|,
and the observed order p = log2(d(20,40) / d(40,80)) (p > 0: the
differences shrink; p = 1 or 2: first or second order).

    scripts/dam_break_convergence.py DIR20 DIR40 DIR80 [--to 3]
"""
import csv
import math
import sys


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    cols = {k: [float(r[k]) for r in rows] for k in rows[0]}
    return cols


def interp(xs, ys, x):
    lo, hi = 0, len(xs) - 1
    if x <= xs[0]:
        return ys[0]
    if x >= xs[-1]:
        return ys[-1]
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if xs[mid] <= x:
            lo = mid
        else:
            hi = mid
    t = (x - xs[lo]) / (xs[hi] - xs[lo])
    return ys[lo] + t * (ys[hi] - ys[lo])


def mean_rel_diff(a, b, key, grid):
    s = [abs(interp(a["T"], a[key], x) - interp(b["T"], b[key], x)) / abs(interp(b["T"], b[key], x)) for x in grid]
    return sum(s) / len(s)


def main(argv):
    to = 3.0
    if "--to" in argv:
        i = argv.index("--to")
        to = float(argv[i + 1])
        del argv[i:i + 2]
    if len(argv) != 3:
        sys.exit(__doc__)
    runs = [read(d.rstrip("/") + "/history.csv") for d in argv]
    grid = [0.2 + 0.01 * k for k in range(int(round((to - 0.2) / 0.01)) + 1)]
    for key in ("Z", "Hb"):
        d1 = mean_rel_diff(runs[0], runs[1], key, grid)
        d2 = mean_rel_diff(runs[1], runs[2], key, grid)
        p = math.log2(d1 / d2) if d1 > 0 and d2 > 0 else float("nan")
        print(f"{key}: d(20,40) = {100 * d1:.3f} %, d(40,80) = {100 * d2:.3f} %, observed order p = {p:.2f}")


if __name__ == "__main__":
    main(sys.argv[1:])
