#!/usr/bin/env python3
"""A granular column collapse driven step by step from Python: the column of
examples/dry_column_collapse.json released at once (no gate, no settling),
its front, height and kinetic energy read from views every 100 steps, printed
every 0.05 s, and the run stopped from the callback at t = 0.5 s (the
thesis's last frame) or when the heap has come to rest.

    PYTHONPATH=build/python python3 examples/python/column_collapse.py

Prints the front x_f (the rightmost disc: single rolling discs lead it), the
mean x and the height h over time, and the runout (x_f - L0) / L0 against the
initial aspect ratio H0 / L0.
"""
import json
import os

import numpy as np

import plab

HERE = os.path.dirname(os.path.abspath(__file__))


def released_column():
    with open(os.path.join(HERE, "..", "dry_column_collapse.json")) as f:
        scene = json.load(f)
    scene["walls"] = [w for w in scene["walls"] if w.get("name") != "gate"]
    scene["bodies"][0]["local_damping"] = 0.0
    for key in ("commands", "output", "histories"):
        scene.pop(key)
    return scene


def main():
    sim = plab.load(released_column())
    x, v, m, r = sim.positions, sim.velocities, sim.masses, sim.radii  # views, no copies
    L0 = float(np.max(x[:, 0] + r))
    H0 = float(np.max(x[:, 1] + r))
    print("column: %d discs, L0 = %.3f m, H0 = %.3f m" % (len(sim), L0, H0))
    print("%8s %8s %8s %8s %12s" % ("t (s)", "front", "mean x", "height", "kinetic (J)"))
    printed = [-1.0]

    def report(s):
        kinetic = 0.5 * float(np.sum(m * np.sum(np.square(v), axis=1)))
        if s.time >= printed[0] + 0.05:
            printed[0] = s.time
            print("%8.3f %8.4f %8.4f %8.4f %12.3e" %
                  (s.time, np.max(x[:, 0] + r), np.mean(x[:, 0]), np.max(x[:, 1] + r), kinetic))
        return s.time < 0.5 and not (s.time > 0.05 and kinetic < 1e-6)  # on until t = 0.5 s or at rest

    sim.cycle(10**6, every=100, callback=report)
    front = float(np.max(x[:, 0] + r))
    print("runout (x_f - L0) / L0 = %.2f for H0 / L0 = %.2f, after %d steps (%.3f s)" %
          ((front - L0) / L0, H0 / L0, sim.step, sim.time))


if __name__ == "__main__":
    main()
