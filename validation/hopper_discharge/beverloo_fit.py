#!/usr/bin/env python3
"""Beverloo's C and k fitted to the silo's discharge rates at three orifices.

    python3 beverloo_fit.py PLAB OUT [--jobs 2] [--quick]

Runs the case's full runs (case.json, "in": "full"; --quick: its quick run)
with `PLAB run scene.json --set ...`, each into OUT/<label>/ (a run whose
summary.json says it finished is not run again), and reads from each
summary.json the metrics `rate` (W, kg/s: the slope of the outlet's mass
against time between window_from and window_to of the mass fed) and `phi`
(the solid fraction of the settled bed, from the centres in a core box).

Beverloo's law for a circular orifice in a flat floor,
    W = C rho_b sqrt(g) (D - k d)^(5/2),   rho_b = phi rho_p,
is linear in D once each rate is divided by its own rho_b sqrt(g) and
raised to 2/5:
    y = (W / (rho_b sqrt(g)))^(2/5) = C^(2/5) (D - k d),
so a least-squares line y = a D + b gives C = a^(5/2) and k = -b / (a d).
Printed: each run's W, phi and its ratio to Beverloo with C 0.58, k 1.5;
the fitted C and k against the published ranges (C 0.55-0.65, k 1.4-1.6;
Beverloo et al. 1961, Nedderman 1992 ch. 10). Python 3 standard library only.
"""
import argparse
import concurrent.futures
import json
import math
import os
import subprocess

HERE = os.path.dirname(os.path.abspath(__file__))
C_REF, K_REF = 0.58, 1.5


def run(plab, out, run_spec):
    folder = os.path.join(out, run_spec["label"].replace(" ", "_").replace(",", "").replace("(", "").replace(")", ""))
    summary = os.path.join(folder, "summary.json")
    if os.path.exists(summary) and json.load(open(summary)).get("finished"):
        return folder
    cmd = [plab, "run", os.path.join(HERE, run_spec.get("scene", "scene.json")), "--out", folder, "--quiet"]
    for path, value in run_spec.get("set", {}).items():
        cmd += ["--set", f"{path}={value}"]
    subprocess.run(cmd, check=True)
    return folder


def metric(summary, name):
    for m in summary["metrics"]:
        if m["name"] == name:
            return m.get("value")
    raise SystemExit(f"no metric {name!r} in the summary")


def line_fit(xs, ys):
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    a = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    return a, my - a * mx


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("plab")
    ap.add_argument("out")
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args()
    case = json.load(open(os.path.join(HERE, "case.json")))
    var = json.load(open(os.path.join(HERE, "scene.json")))["variables"]
    d, rho_p, g = var["d"], var["rho_p"], var["g"]
    mode = "quick" if a.quick else "full"
    runs = [r for r in case["runs"] if mode in r.get("in", ["quick", "full"])]
    with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as pool:
        folders = list(pool.map(lambda r: run(a.plab, a.out, r), runs))
    print(f"{'run':<28} {'D/d':>5} {'phi':>6} {'W (g/s)':>9} {'Beverloo':>9} {'ratio':>6} {'halves (g/s)':>14} {'CPU (s)':>8}")
    ds, ys = [], []
    for r, folder in zip(runs, folders):
        s = json.load(open(os.path.join(folder, "summary.json")))
        D = r["set"]["variables.D_over_d"] * d
        w, phi = metric(s, "rate"), metric(s, "phi")
        rho_b = phi * rho_p
        w_ref = C_REF * rho_b * math.sqrt(g) * (D - K_REF * d) ** 2.5
        halves = f"{metric(s, 'rate_first_half') * 1e3:.1f}/{metric(s, 'rate_second_half') * 1e3:.1f}"
        print(f"{r['label']:<28} {D / d:>5g} {phi:>6.3f} {w * 1e3:>9.2f} {w_ref * 1e3:>9.2f} {w / w_ref:>6.3f} {halves:>14} "
              f"{s['cpu_seconds']:>8.0f}")
        ds.append(D)
        ys.append((w / (rho_b * math.sqrt(g))) ** 0.4)
    if len(ds) < 3:
        return
    slope, intercept = line_fit(ds, ys)
    c, k = slope ** 2.5, -intercept / (slope * d)
    rms = math.sqrt(sum((y - (slope * x + intercept)) ** 2 for x, y in zip(ds, ys)) / len(ds)) / (sum(ys) / len(ys))
    print(f"fit of (W / (rho_b sqrt g))^(2/5) = C^(2/5) (D - k d) to the {len(ds)} rates: "
          f"C = {c:.3f} (published 0.55-0.65), k = {k:.2f} (published 1.4-1.6); RMS residual {rms:.2%} of the mean")


if __name__ == "__main__":
    main()
