#!/usr/bin/env python3
"""The cost of clumps: a pile of N four-pebble clumps against one of 4 N
balls of the pebbles' size, the same box, model and step count, run side by
side; prints particle-steps per second (pebbles counted as particles) and
the ratio. Usage: bench/clumps/cost.py build/plab [N] [steps]"""
import json, os, re, subprocess, sys, tempfile, time

plab = sys.argv[1]
n = int(sys.argv[2]) if len(sys.argv) > 2 else 10000
steps = int(sys.argv[3]) if len(sys.argv) > 3 else 2000
side = 0.004 * (4 * n) ** (1 / 3) * 2.2  # a loose fill of 4 N pebbles of radius 1 mm
model = {"groups": ["*", "*"], "model": "linear", "properties": {"kn": 1e4, "ks": 5e3, "fric": 0.5, "dp_nratio": 0.2}}
common = {"dimension": 3, "plugins": ["linear"], "gravity": [0, -9.81, 0],
          "walls": [{"type": "box", "min": [0, 0, 0], "max": [side, 2 * side, side]}],
          "contact_models": [model], "commands": [{"cycle": steps}]}
box = {"min": [0, 0, 0], "max": [side, 2 * side, side]}
tetra = [[0.001, 0.001, 0.001], [-0.001, -0.001, 0.001], [-0.001, 0.001, -0.001], [0.001, -0.001, -0.001]]
clumps = dict(common, bodies=[{"type": "clump_fill", "count": n, "seed": 3, "box": box,
                               "clump": {"group": "grains", "density": 2500,
                                         "pebbles": [{"position": p, "radius": 0.001} for p in tetra]}}])
balls = dict(common, bodies=[{"type": "random_fill", "count": 4 * n, "seed": 3, "box": box, "group": "grains",
                              "radius": 0.001, "density": 2500}])

def run(scene, name):
    d = tempfile.mkdtemp()
    path = os.path.join(d, name + ".json")
    json.dump(scene, open(path, "w"))
    t0 = time.time()
    out = subprocess.run([plab, "run", path, "--out", os.path.join(d, "out")], capture_output=True, text=True)
    if out.returncode:
        sys.exit(out.stderr)
    m = re.search(r"([0-9.e+]+) particle-steps/s", out.stdout + out.stderr)
    return float(m.group(1)) if m else 4 * n * steps / (time.time() - t0)

cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")
flags = next((l for l in open("/proc/cpuinfo") if l.startswith("flags")), "")
ext = " ".join(x for x in ("avx2", "avx512f") if x in flags.split())
print(f"CPU: {cpu} ({ext}); OMP_NUM_THREADS={os.environ.get('OMP_NUM_THREADS', 'unset')}; {steps} steps")
rates = {}
for name, scene in (("clumps", clumps), ("balls", balls), ("clumps", clumps), ("balls", balls)):
    rates.setdefault(name, []).append(run(scene, name))
for name, r in rates.items():
    print(f"{name:7s} {4 * n:7d} particles: {max(r) / 1e6:.3f} M particle-steps/s (best of {len(r)})")
print(f"clumps / balls: {max(rates['clumps']) / max(rates['balls']):.3f}")
