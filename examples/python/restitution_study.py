#!/usr/bin/env python3
"""Parameter study: the coefficient of restitution of the linear model against
its normal damping ratio, measured on examples/teaching/bounce.json (a disc
dropped onto a floor) and compared with the closed form of the linear spring–
dashpot, e = exp(-beta pi / sqrt(1 - beta^2)).

    PYTHONPATH=build/python python3 examples/python/restitution_study.py [--plot restitution.png]

Each run is driven from Python: the disc's height is read through a view (no
copy) after every step, and the run stopped from the callback once the disc
has left the floor; gravity is off (the closed form is that of a contact
alone) and the disc thrown at the floor at 1 m/s. The plot needs matplotlib (python3-matplotlib); without it the table
is printed only.
"""
import argparse
import math
import os

import numpy as np

import plab

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(HERE, "..", "teaching", "bounce.json")


def restitution(beta, speed=1.0, model="linear"):
    """Rebound over impact speed of one bounce with damping ratio beta. The
    closed form is that of a contact alone, so gravity is switched off and the
    disc thrown at the floor instead: its speed is constant before and after."""
    sim = plab.load(SCENE, set={"contact_models.0.properties.dp_nratio": beta, "gravity": [0, 0],
                                "bodies.0.velocity": [0, -speed], "contact_models.0.model": model})
    touch = sim.scene["walls"][0]["from"][1] + sim.radii[0]  # the centre's height at gap 0
    y, vy = sim.positions, sim.velocities  # views: read after every step, never copied
    touched = []

    def watch(s):
        if y[0, 1] < touch:
            touched.append(s.step)
        return not touched or y[0, 1] < touch  # on until the disc has left the floor

    sim.cycle(100000, every=1, callback=watch)
    return vy[0, 1] / speed


def closed_form(beta):
    return math.exp(-beta * math.pi / math.sqrt(1 - beta * beta))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--plot", help="a PNG of e against beta (needs matplotlib)")
    args = parser.parse_args()
    betas = np.array([0.0, 0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7])
    measured = np.array([restitution(b) for b in betas])
    exact = np.array([closed_form(b) for b in betas])
    print("%8s %10s %10s %10s" % ("beta", "e plab", "e exact", "rel. diff"))
    for b, m, e in zip(betas, measured, exact):
        print("%8.2f %10.4f %10.4f %10.1e" % (b, m, e, abs(m - e) / e))
    if args.plot:
        try:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
        except ImportError:
            print("matplotlib is not installed (python3-matplotlib): no plot")
            return
        fine = np.linspace(0, 0.75, 100)
        plt.plot(fine, [closed_form(b) for b in fine], label="exp(-βπ/√(1-β²))")
        plt.plot(betas, measured, "o", label="plab, bounce.json")
        plt.xlabel("normal damping ratio β (dp_nratio)")
        plt.ylabel("coefficient of restitution e")
        plt.legend()
        plt.savefig(args.plot, dpi=120)
        print("plot:", args.plot)


if __name__ == "__main__":
    main()
