#!/usr/bin/env python3
"""The discharge rate of a hopper_stl run against Beverloo's law.

    python3 discharge_rate.py OUT/history.csv [--scene hopper.json]

Reads the run's history (columns time, discharged, core_fraction) and the
scene's variables (count, radius, density, t_settle). The rate is the
least-squares slope of `discharged` over the rows between 20 % and 80 % of
the beads out (the steady part: after the gate has cleared, before the
bed is so low that the flow thins), in beads/s and kg/s. Beverloo's law
for a flat-bottomed silo, W = C rho_b sqrt(g) (D - k d)^(5/2), is evaluated
with its usual constants C = 0.58, k = 1.5 and the bulk density rho_b =
phi rho_s of the settled bed (core_fraction over the last 0.05 s before
the gate opens).
Nothing is fitted to Beverloo. Python 3 standard library only.
"""
import argparse
import csv
import json
import math
import os

D = 0.028   # orifice diameter, m (make_hopper.py: the polygon has the area of this circle)
G = 9.81
C, K = 0.58, 1.5


def slope(xs, ys):
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("history")
    ap.add_argument("--scene", default=os.path.join(here, "hopper.json"))
    a = ap.parse_args()
    var = json.load(open(a.scene))["variables"]
    n, r, rho_s = var["count"], var["radius"], var["density"]
    rows = [{k: float(v) for k, v in row.items()} for row in csv.DictReader(open(a.history))]
    # the core box holds ~300 centres: its fraction is averaged over the last 0.05 s before the gate opens
    settled = [row for row in rows if var["t_settle"] - 0.05 <= row["time"] <= var["t_settle"]]
    phi = sum(row["core_fraction"] for row in settled) / len(settled)
    steady = [row for row in rows if 0.2 * n <= row["discharged"] <= 0.8 * n]
    if len(steady) < 4:
        raise SystemExit(f"only {len(steady)} rows between 20 % and 80 % discharged: did the run finish?")
    t = [row["time"] for row in steady]
    beads = slope(t, [row["discharged"] for row in steady])
    half = len(steady) // 2
    first = slope(t[:half], [row["discharged"] for row in steady[:half]])
    second = slope(t[half:], [row["discharged"] for row in steady[half:]])
    m_bead = rho_s * 4 / 3 * math.pi * r ** 3
    w_run = beads * m_bead
    d = 2 * r
    rho_b = phi * rho_s
    w_beverloo = C * rho_b * math.sqrt(G) * (D - K * d) ** 2.5
    print(f"settled bed: solid fraction {phi:.3f} (core box, mean of {len(settled)} rows), bulk density {rho_b:.0f} kg/m3")
    print(f"steady window: t = {t[0]:.3f} .. {t[-1]:.3f} s, {len(steady)} rows")
    print(f"discharge: {beads:.0f} beads/s (first half {first:.0f}, second half {second:.0f}) = {w_run * 1000:.1f} g/s")
    print(f"Beverloo (C {C}, k {K}, D {D * 1000:g} mm, d {d * 1000:g} mm): {w_beverloo * 1000:.1f} g/s")
    print(f"run / Beverloo: {w_run / w_beverloo:.3f}")
    w_06 = C * 0.6 * rho_s * math.sqrt(G) * (D - K * d) ** 2.5
    print(f"(with the textbook solid fraction 0.6 instead: Beverloo {w_06 * 1000:.1f} g/s, run / Beverloo {w_run / w_06:.3f})")


if __name__ == "__main__":
    main()
