#!/usr/bin/env python3
"""Writes the periodic_shear scenes: one per solid fraction, each a square
periodic cell of N polydisperse discs (radii uniform within +-20 % of r0)
sheared by Lees-Edwards boundaries at constant volume.

plab's random_fill places balls without overlap and so stops near a solid
fraction of 0.55 in 2D; a sheared cell has no walls to compress it. The
packings are therefore made here: discs at random places in the cell, then
overlaps removed by pushing each overlapping pair apart by its overlap
(minimum image), until the largest overlap is below 1e-6 r0. The shear
rate of each scene is chosen from a guess of its inertial number so that
the pressure is near P_target, i.e. the grains stay stiff: kn / (P 1 m)
~ 1e4 (da Cruz et al. 2005 used >= 1e4).

    python3 validation/periodic_shear/make_scenes.py   # rewrites scene_phi*.json and the example

The output is deterministic (seeded)."""
import json
import math
import os
import random

HERE = os.path.dirname(os.path.abspath(__file__))
N = 400
R0 = 0.0005  # m, mean radius
SPREAD = 0.2  # radii uniform in [1 - SPREAD, 1 + SPREAD] r0
# solid fraction -> a guess of the inertial number (da Cruz et al. 2005:
# phi ~ phi_max - a I with phi_max ~ 0.82, a ~ 0.3 for 2D discs), which
# only sets the shear rate (the measured I is what is reported)
EXAMPLE = 0.80  # the scene examples/granular/periodic_shear/ shows
EXAMPLE_FILE = os.path.join(HERE, "..", "..", "examples", "granular", "periodic_shear", "shear_cell.json")
FRACTIONS = {0.74: 0.3, 0.76: 0.2, 0.78: 0.13, 0.79: 0.1, 0.80: 0.055, 0.81: 0.028, 0.815: 0.014, 0.82: 0.005}


def packing(phi, seed):
    rng = random.Random(seed)
    radii = [R0 * (1 - SPREAD + 2 * SPREAD * rng.random()) for _ in range(N)]
    L = math.sqrt(sum(math.pi * r * r for r in radii) / phi)
    x = [[rng.random() * L, rng.random() * L] for _ in range(N)]
    cell = 2 * R0 * (1 + SPREAD)
    n_cells = max(3, int(L / cell))
    size = L / n_cells
    for sweep in range(200000):
        grid = {}
        for i, p in enumerate(x):
            p[0] %= L
            p[1] %= L
            grid.setdefault((int(p[0] / size) % n_cells, int(p[1] / size) % n_cells), []).append(i)
        move = [[0.0, 0.0] for _ in range(N)]
        worst = 0.0
        for (cx, cy), members in grid.items():
            for ox in (-1, 0, 1):
                for oy in (-1, 0, 1):
                    others = grid.get(((cx + ox) % n_cells, (cy + oy) % n_cells), ())
                    for i in members:
                        for j in others:
                            if j <= i:
                                continue
                            dx = x[j][0] - x[i][0]
                            dy = x[j][1] - x[i][1]
                            dx -= L * round(dx / L)
                            dy -= L * round(dy / L)
                            d2 = dx * dx + dy * dy
                            reach = radii[i] + radii[j]
                            if d2 >= reach * reach:
                                continue
                            d = math.sqrt(d2) or 1e-12
                            overlap = reach - d
                            worst = max(worst, overlap)
                            push = 0.5 * 1.01 * overlap / d  # (1 % more: the pushes of neighbours partly cancel)
                            move[i][0] -= push * dx
                            move[i][1] -= push * dy
                            move[j][0] += push * dx
                            move[j][1] += push * dy
        if worst < 1e-6 * R0:
            break
        for p, m in zip(x, move):
            p[0] += m[0]
            p[1] += m[1]
    else:
        raise SystemExit(f"phi {phi}: overlaps not removed (worst {worst / R0:.2e} r0)")
    print(f"phi {phi}: L = {L:.6g} m, {sweep} sweeps")
    return L, radii, [[p[0] % L, p[1] % L] for p in x]


def scene(phi, I_guess, seed):
    L, radii, x = packing(phi, seed)
    inside = lambda v: round(v, 10) if round(v, 10) < L else 0.0  # (a centre must lie in [0, L))
    balls = [{"type": "ball", "group": "grains", "position": [inside(p[0]), inside(p[1])], "radius": round(r, 10),
              "density": "$(rho)"} for p, r in zip(x, radii)]
    return {
        "description": f"Simple shear of a periodic cell (Lees-Edwards) of {N} polydisperse discs at solid fraction {phi}: "
                       "effective friction mu = tau / P from the contacts against the inertial number",
        "dimension": 2,
        "variables": {
            "phi": phi, "L": L, "r0": R0, "d": 2 * R0, "rho": 2500, "kn": 1e7,
            "P_target": 1000, "I_guess": I_guess,
            "rate": "I_guess * sqrt(P_target / rho) / d",
            "strain": 6, "strain_steady": 2,
            "mu_min": 0.275, "b": 1.0
        },
        "domain": {"min": [0, 0], "max": ["$(L)", "$(L)"], "periodic": ["x", "y"], "shear": {"rate": "$(rate)"}},
        "plugins": ["linear"],
        "bodies": balls,
        "contact_models": [{"groups": ["grains", "grains"], "model": "linear",
                            "properties": {"kn": "$(kn)", "ks": "$(0.5 * kn)", "fric": 0.4, "dp_nratio": 0.3}}],
        "timestep": {"safety_factor": 0.5},
        "histories": {"every": 400, "record": [
            {"quantity": "time"},
            {"name": "gamma", "expression": "rate * time"},
            {"name": "p", "quantity": "measure.contact_stress", "with": {"min": [0, 0], "max": ["$(L)", "$(L)"], "component": "pressure"}},
            {"name": "sxy", "quantity": "measure.contact_stress", "with": {"min": [0, 0], "max": ["$(L)", "$(L)"], "component": "xy"}},
            {"name": "pk", "quantity": "measure.kinetic_stress", "with": {"min": [0, 0], "max": ["$(L)", "$(L)"], "component": "pressure"}},
            {"name": "sxyk", "quantity": "measure.kinetic_stress", "with": {"min": [0, 0], "max": ["$(L)", "$(L)"], "component": "xy"}},
            {"name": "mu", "expression": "p > 0 ? sxy / p : 0"},
            {"name": "mu_total", "expression": "p + pk > 0 ? (sxy + sxyk) / (p + pk) : 0"},
            {"name": "kinetic_share", "expression": "p + pk > 0 ? pk / (p + pk) : 0"},
            {"name": "I", "expression": "p > 0 ? rate * d / sqrt(p / rho) : 0"},
            {"name": "mu_trend", "expression": "mu_min + b * I"},
            {"name": "flow_rate", "quantity": "measure.velocity_gradient", "with": {"group": "grains"}},
            {"name": "flow_over_imposed", "expression": "flow_rate / rate"}
        ]},
        "metrics": [
            {"name": "mu", "history": "mu", "reduce": "time_mean", "from": "$(strain_steady / rate)"},
            {"name": "I", "history": "I", "reduce": "time_mean", "from": "$(strain_steady / rate)"},
            {"name": "pressure", "history": "p", "reduce": "time_mean", "from": "$(strain_steady / rate)"},
            {"name": "mu_with_kinetic", "history": "mu_total", "reduce": "time_mean", "from": "$(strain_steady / rate)"},
            {"name": "kinetic_share", "history": "kinetic_share", "reduce": "time_mean", "from": "$(strain_steady / rate)"},
            {"name": "mu_against_trend", "history": "mu", "reduce": "time_mean", "from": "$(strain_steady / rate)", "against": "mu_trend"},
            {"name": "linear_profile", "history": "flow_over_imposed", "reduce": "time_mean", "from": "$(strain_steady / rate)", "analytical": 1}
        ],
        "commands": [{"solve": {"time": "$(strain / rate)"}}]
    }


def main():
    for phi, I_guess in sorted(FRACTIONS.items()):
        s = scene(phi, I_guess, seed=int(round(phi * 1000)))
        name = os.path.join(HERE, f"scene_phi{int(round(phi * 1000))}.json")
        with open(name, "w") as f:
            # one ball a line: the file stays readable and diffable
            balls = s["bodies"]
            s["bodies"] = "BALLS"
            text = json.dumps(s, indent=2)
            text = text.replace('"BALLS"', "[\n    " + ",\n    ".join(json.dumps(b) for b in balls) + "\n  ]")
            f.write(text + "\n")
        if phi == EXAMPLE:
            os.makedirs(os.path.dirname(EXAMPLE_FILE), exist_ok=True)
            with open(EXAMPLE_FILE, "w") as f:
                f.write(text + "\n")


if __name__ == "__main__":
    main()
