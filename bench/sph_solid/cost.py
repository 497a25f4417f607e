#!/usr/bin/env python3
"""The cost of an SPH solid against a bonded-DEM structure of the same
resolution: one clamped rubber strip (E 12 MPa, rho 1100, 2D) of NX x NY
particles at spacing D, once as a hypoelastic SPH solid (sph_solid: square
lattice, h 1.3 D, Wendland C2, kernel-gradient correction `all`, artificial
stress 0.3; the elastic_gate_sph gate's settings) and once as bonded balls
(linear_pbond, hexagonal_2d calibration, nu 0.33, balls of radius D/2: the
elastic_gate gate's), the same particle count, gravity and step count, run
back to back and interleaved (sph, dem, sph, dem), one thread each. Prints
CPU seconds per particle-step (the best of the repetitions: a loaded machine
only adds time), the stable step of each model and so the cost per simulated
second, with the CPU name and its vector extensions.

Usage: OMP_NUM_THREADS=1 bench/sph_solid/cost.py build/plab [NX] [NY] [STEPS] [REPS]
"""
import json
import os
import subprocess
import sys
import tempfile

plab = sys.argv[1]
nx = int(sys.argv[2]) if len(sys.argv) > 2 else 200
ny = int(sys.argv[3]) if len(sys.argv) > 3 else 20
steps = int(sys.argv[4]) if len(sys.argv) > 4 else 2000
reps = int(sys.argv[5]) if len(sys.argv) > 5 else 2
D = 0.001
E, rho = 12e6, 1100
clamp = 4  # clamped columns (rows of the strip's section)

common = {"dimension": 2, "gravity": [0, -9.81], "commands": []}

sph = dict(common,
           plugins=["sph_solid"],
           bodies=[{"type": "lattice", "group": "strip", "packing": "square",
                    "box": {"min": [0, 0], "max": [nx * D, ny * D]}, "radius": D / 2, "spacing": D,
                    "mass": rho * D * D, "fix": ["rotation"]}],
           materials={"rubber": {"groups": ["strip"], "rest_density": rho, "youngs_modulus": E, "poissons_ratio": 0.45,
                                 "smoothing_length": 1.3 * D, "particle_spacing": D, "kernel": "wendland_c2"}},
           contact_models=[{"groups": ["strip", "strip"], "model": "sph_solid", "properties": {"alpha": 0.1, "beta": 0}}],
           passes=[{"name": "sph_solid_stress", "material": "rubber",
                    "properties": {"group": "strip", "artificial_stress": 0.3, "kernel_correction": "all"}}])
sph["commands"] = [{"set": {"region": {"min": [-D, -D], "max": [clamp * D, (ny + 1) * D]}, "fix": ["all"]}},
                   {"cycle": steps}]

# hexagonal rows of nx balls, sqrt(3) R apart: ny rows (the same count)
R = D / 2
dem = dict(common,
           plugins=["linear_pbond"],
           bodies=[{"type": "lattice", "group": "strip", "packing": "hexagonal",
                    "solid": {"min": [0, 0], "size": [nx * 2 * R, ny * 3 ** 0.5 * R]}, "radius": R, "density": rho}],
           contact_models=[{"groups": ["strip", "strip"], "model": "linear_pbond",
                            "calibrate": {"method": "hexagonal_2d", "E": E, "nu": 0.33, "sigma_ult": 1e9, "radius": R}}])
dem["commands"] = [{"bond": {"groups": ["strip", "strip"], "gap": 1e-9}},
                   {"set": {"region": {"min": [-D, -D], "max": [clamp * D, ny * D + D]}, "fix": ["all"]}},
                   {"cycle": steps}]


def run(scene, name):
    d = tempfile.mkdtemp(prefix="plab_bench_sph_solid_")
    path = os.path.join(d, name + ".json")
    with open(path, "w") as f:
        json.dump(scene, f)
    out = subprocess.run([plab, "run", path, "--quiet", "--out", os.path.join(d, "out")], capture_output=True, text=True)
    if out.returncode:
        sys.exit(f"{name}: {out.stderr}")
    s = json.load(open(os.path.join(d, "out", "summary.json")))
    return s


cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")
flags = next((l for l in open("/proc/cpuinfo") if l.startswith("flags")), "").split()
ext = " ".join(x for x in ("sse4_2", "avx", "avx2", "fma", "avx512f") if x in flags)
print(f"CPU: {cpu} ({ext}); OMP_NUM_THREADS={os.environ.get('OMP_NUM_THREADS', 'unset')}; "
      f"strip {nx} x {ny} particles at {D * 1e3:g} mm, {steps} steps, {reps} repetitions")
best = {}
for _ in range(reps):
    for name, scene in (("sph_solid", sph), ("linear_pbond", dem)):
        s = run(scene, name)
        n, cpu_s = s["bodies"], s["cpu_seconds"]
        prev = best.get(name)
        if prev is None or cpu_s < prev["cpu"]:
            best[name] = {"cpu": cpu_s, "n": n, "steps": s["steps"], "time": s["simulated_time"], "contacts": s["contacts"],
                          "limited_by": s["timestep"]["limited_by"]}
print(f"{'model':13s} {'particles':>9s} {'contacts':>9s} {'ns/particle-step':>17s} {'dt (s)':>10s} {'CPU s per simulated ms':>23s}")
for name, b in best.items():
    ns = b["cpu"] / (b["n"] * b["steps"]) * 1e9
    dt = b["time"] / b["steps"]
    print(f"{name:13s} {b['n']:9d} {str(b['contacts']):>9s} {ns:17.1f} {dt:10.3g} {b['cpu'] / (b['time'] * 1e3):23.3g}")
r = best["sph_solid"]["cpu"] / best["sph_solid"]["n"] / best["sph_solid"]["steps"]
r /= best["linear_pbond"]["cpu"] / best["linear_pbond"]["n"] / best["linear_pbond"]["steps"]
print(f"sph_solid / linear_pbond per particle-step: {r:.2f}")
