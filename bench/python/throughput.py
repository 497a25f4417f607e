#!/usr/bin/env python3
"""Throughput of a run cycled from Python against `plab run` on the same scene.

The scene is bench/peers/gran3d.json scaled to --lateral x --lateral x 25
spheres (63: 99 225 balls, bench/peers/memory.py's scaling), packed touching
(a cubic lattice of spacing d, no jitter) so that every step has the contacts
of a pile (about three per ball) rather than a lattice in free fall; cycled
--steps steps from its start, one thread.
Modes, run in turn --reps times (the minimum of each is reported, since a
loaded machine only adds time):

  cli        build/plab run SCENE --quiet --out DIR: summary.json's cpu and wall seconds,
             less those of the same run of --base steps (the CLI's run includes
             the world's preparation, one neighbour search and force pass, which
             the module does at load: the difference is the cost of the steps)
             Python: --base steps untimed, then the others timed; so every mode
             times the same steps
  py         sim.cycle(steps)
  py_every10 sim.cycle(steps, every=10, callback): the callback reads views
  py_every1  the same after every step
  py_bare1   after every step a callback that reads one value through a view:
             what the module and the Python call cost per call

Figures are per step, as particle-steps per CPU second. The callback takes the positions and velocities views (no copy) and computes
the pile's top and its kinetic energy with NumPy, a realistic monitor; that
NumPy work (O(N) per call) is part of the Python figure. The Python figures
time the cycles only.

    PYTHONPATH=build/python OMP_NUM_THREADS=1 OMP_WAIT_POLICY=PASSIVE python3 bench/python/throughput.py \
        [--steps 500] [--reps 3] [--modes cli,py]
"""
import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "bench", "peers"))
import memory  # noqa: E402  (bench/peers: the scaled gran3d scene)

import plab  # noqa: E402


def dense_scene(lateral, steps):
    """memory.py's scaled gran3d with the balls touching from the start."""
    sc = memory.plab_scene(lateral, steps)
    lattice = sc["bodies"][0]
    d = 2 * lattice["radius"]
    lattice["spacing"] = d
    del lattice["jitter"]
    lo = lattice["box"]["min"]
    lattice["box"]["max"] = [lo[0] + lateral * d, lo[1] + lateral * d, lo[2] + 25 * d]
    return sc


def run_cli(exe, scene_path, work, steps, base):
    def once(n):
        out = os.path.join(work, "cli_out")
        subprocess.run([exe, "run", scene_path, "--quiet", "--out", out, "--set", f"commands.0.cycle={n}"], check=True)
        return json.load(open(os.path.join(out, "summary.json")))
    small, whole = once(base), once(steps)
    share = steps / (steps - base)  # the steps' cost, scaled to `steps` steps
    return ((whole["cpu_seconds"] - small["cpu_seconds"]) * share,
            (whole["wall_seconds"] - small["wall_seconds"]) * share, whole["state_hash"], whole["contacts"])


def run_python(scene_path, steps, base, every, bare=False):
    sim = plab.load(scene_path)
    sim.cycle(base)  # the steps the CLI figure leaves out
    x, v, m = sim.positions, sim.velocities, sim.masses
    seen = []

    def monitor(s):
        seen.append((float(np.max(x[:, 2])), 0.5 * float(np.dot(m, np.einsum("ij,ij->i", v, v)))))

    def glance(s):
        seen.append(s.positions[0, 2])

    cpu0, wall0 = time.process_time(), time.perf_counter()
    if bare:
        sim.cycle(steps - base, every=every, callback=glance)
    elif every:
        sim.cycle(steps - base, every=every, callback=monitor)
    else:
        sim.cycle(steps - base)
    share = steps / (steps - base)
    cpu, wall = (time.process_time() - cpu0) * share, (time.perf_counter() - wall0) * share
    summary = sim.summary()
    return cpu, wall, summary["state_hash"], summary["contacts"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--plab", default=os.path.join(ROOT, "build", "plab"))
    ap.add_argument("--lateral", type=int, default=63)
    ap.add_argument("--steps", type=int, default=500)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--base", type=int, default=10, help="steps of the CLI run subtracted")
    ap.add_argument("--modes", default="cli,py,py_every10,py_every1,py_bare1",
                    help="comma-separated, cli first (the reference)")
    a = ap.parse_args()
    if os.environ.get("OMP_NUM_THREADS") != "1":
        sys.exit("set OMP_NUM_THREADS=1: the figures are for one thread")
    work = tempfile.mkdtemp(prefix="plab_py_throughput_")
    scene_path = os.path.join(work, "gran3d_scaled.json")
    json.dump(dense_scene(a.lateral, a.steps), open(scene_path, "w"))
    n = len(plab.load(scene_path))
    modes = {"cli": lambda: run_cli(a.plab, scene_path, work, a.steps, a.base),
             "py": lambda: run_python(scene_path, a.steps, a.base, 0),
             "py_every10": lambda: run_python(scene_path, a.steps, a.base, 10),
             "py_every1": lambda: run_python(scene_path, a.steps, a.base, 1),
             "py_bare1": lambda: run_python(scene_path, a.steps, a.base, 1, bare=True)}
    chosen = a.modes.split(",")
    if chosen[0] != "cli" or not set(chosen) <= set(modes):
        sys.exit(f"--modes: cli first, then any of {', '.join(modes)}")
    modes = {k: modes[k] for k in chosen}
    best = {k: (float("inf"), float("inf")) for k in modes}
    hashes = {}
    for rep in range(a.reps):
        for name, run in modes.items():
            cpu, wall, h, contacts = run()
            best[name] = (min(best[name][0], cpu), min(best[name][1], wall))
            hashes.setdefault(h, []).append(name)
            print(f"  rep {rep} {name:11s} cpu {cpu:7.2f} s  wall {wall:7.2f} s", flush=True)
    load = os.getloadavg()[0]
    print(f"{n} balls, {contacts} contacts at the end, {a.steps} steps, 1 thread, {platform.node()}, "
          f"load {load:.1f}; minimum of {a.reps}:")
    cli_cpu, cli_wall = best["cli"]
    for name, (cpu, wall) in best.items():
        print(f"  {name:11s} {n * a.steps / cpu:10.4g} particle-steps per cpu s ({cpu / cli_cpu - 1:+6.1%} cpu), "
              f"wall {wall:7.2f} s ({wall / cli_wall - 1:+6.1%})")
    print(f"each: steps {a.base} to {a.steps} timed, scaled to {a.steps} steps")
    print("final state hashes:", "all equal" if len(hashes) == 1 else hashes)


if __name__ == "__main__":
    main()
