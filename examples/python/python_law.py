#!/usr/bin/env python3
"""A contact law written in NumPy, swapped for `linear` in the teaching
bounce, then changed the way a student would, and timed against the C++ law.

    PYTHONPATH=build/python OMP_NUM_THREADS=1 python3 examples/python/python_law.py [--count 400] [--steps 2000] [--plot law.png]

1. plab.laws.linear (the linear law in NumPy) registered as "py_linear": the
   bounce of examples/teaching/bounce.json gives the same restitution as
   `linear`, to the bit.
2. A change: the dashpot may not pull (the total normal force kept >= 0, as
   linear's dp_mode no_tension): the disc leaves the floor earlier and faster.
3. The cost: a pile of touching discs cycled with `linear` and with `py_linear`.
"""
import argparse
import os
import sys
import time

import numpy as np

import plab

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import restitution_study  # noqa: E402  (the bounce with gravity off, e from the views)


def no_tension(batch):
    """linear, but the normal dashpot never pulls: after the law, a row whose
    normal force points into end 1 (tension) loses it."""
    plab.laws.linear(batch)
    n, f = batch["normal"], batch["force"]
    fn = np.einsum("ij,ij->i", f, n)
    pulling = fn < 0.0
    f[pulling] -= fn[pulling, None] * n[pulling]


def restitution(model, beta):
    return restitution_study.restitution(beta, model=model)


def plot(betas, table, path):
    """e against beta: linear (C++), its NumPy copy, and the student's change."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed (python3-matplotlib): no plot")
        return
    e = np.array(table)
    fine = np.linspace(0, 0.65, 100)
    plt.plot(fine, [restitution_study.closed_form(b) for b in fine], "k-", lw=0.8, label="exp(-βπ/√(1-β²))")
    plt.plot(betas, e[:, 0], "o", ms=9, mfc="none", label="linear (C++ plug-in)")
    plt.plot(betas, e[:, 1], "x", ms=7, label="py_linear (NumPy, same law)")
    plt.plot(betas, e[:, 2], "s", ms=5, label="py_no_tension (the dashpot may not pull)")
    plt.xlabel("normal damping ratio β (dp_nratio)")
    plt.ylabel("coefficient of restitution e")
    plt.title("one bounce, examples/teaching/bounce.json: a law changed in Python")
    plt.legend()
    plt.savefig(path, dpi=110)
    print("plot:", path)


def pile(count, model):
    """About `count` discs in hexagonal stacking, touching from the start (every
    step has about three contacts per disc), under gravity in a box."""
    r = 0.003
    side = 2 * r * (count / 1.15) ** 0.5
    return {
        "dimension": 2, "gravity": [0, -9.81], "plugins": ["linear"],
        "bodies": [{"type": "lattice", "group": "grains", "packing": "hexagonal",
                    "box": {"min": [0, 0], "max": [side, side]}, "radius": r, "density": 2500}],
        "walls": [{"type": "box", "min": [0, 0], "max": [side, 2 * side]}],
        "contact_models": [{"groups": ["*", "*"], "model": model,
                            "properties": {"kn": 1e5, "ks": 5e4, "fric": 0.5, "dp_nratio": 0.2}}],
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--count", type=int, default=400, help="discs in the timed pile")
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--plot", help="a PNG of e against beta for the three laws (needs matplotlib)")
    a = ap.parse_args()
    plab.register_model("py_linear", plab.laws.linear, plab.laws.LINEAR_PROPERTIES, plab.laws.LINEAR_HISTORY,
                        range="rgap")
    plab.register_model("py_no_tension", no_tension, plab.laws.LINEAR_PROPERTIES, plab.laws.LINEAR_HISTORY,
                        range="rgap")
    print("restitution of one bounce (bounce.json, gravity off, thrown at 1 m/s)")
    print("%6s %12s %12s %14s" % ("beta", "linear", "py_linear", "py_no_tension"))
    betas = (0.1, 0.3, 0.5) if not a.plot else (0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6)
    table = []
    for beta in betas:
        e = [restitution(m, beta) for m in ("linear", "py_linear", "py_no_tension")]
        table.append(e)
        print("%6.2f %12.6f %12.6f %14.6f%s" % (beta, *e, "" if e[0] == e[1] else "  (differs!)"))
    if a.plot:
        plot(betas, table, a.plot)

    count, steps = a.count, a.steps
    seconds, forces, hashes = {}, {}, {}
    for model in ("linear", "py_linear"):
        sim = plab.load(pile(count, model))
        discs = len(sim)
        t = time.process_time()
        sim.cycle(steps)
        seconds[model] = time.process_time() - t
        hashes[model] = sim.state_hash()
        forces[model] = sim.summary()["phase_seconds"]["force_displacement"]  # the law's phase, wall s
        contacts = len(sim.contacts()["overlap"])
    print("a pile of touching discs, %d discs, %d steps, %d contacts at the end, 1 thread:\n"
          "  run (cpu s): linear %.2f, py_linear %.2f (%.1fx)\n"
          "  force-displacement phase (wall s): linear %.3f, py_linear %.3f (%.0fx)\n"
          "  same final state: %s" % (discs, steps, contacts, seconds["linear"], seconds["py_linear"],
                                     seconds["py_linear"] / seconds["linear"], forces["linear"], forces["py_linear"],
                                     forces["py_linear"] / forces["linear"], hashes["linear"] == hashes["py_linear"]))


if __name__ == "__main__":
    main()
