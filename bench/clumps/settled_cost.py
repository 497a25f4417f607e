#!/usr/bin/env python3
"""The cost of clumps in a settled pile: N four-pebble clumps and 4 N balls
of the pebbles' size poured into the same box (as cost.py), each settled for
T_SETTLE s of simulated time with local damping 0.7 and checkpointed; then
each restarts from its checkpoint for STEPS steps, twice, interleaved, and
the resumed runs' particle-steps per second (pebbles counted as particles)
are compared. Usage: bench/clumps/settled_cost.py build/plab [N] [T_SETTLE] [STEPS] [WORK_DIR]
(a WORK_DIR that holds the settled checkpoints of an earlier call with the
same N and T_SETTLE is reused: the settling is the long part)"""
import json, os, re, subprocess, sys, tempfile

plab = sys.argv[1]
n = int(sys.argv[2]) if len(sys.argv) > 2 else 10000
t_settle = float(sys.argv[3]) if len(sys.argv) > 3 else 0.6
steps = int(sys.argv[4]) if len(sys.argv) > 4 else 2000
side = 0.004 * (4 * n) ** (1 / 3) * 2.2
box = {"min": [0, 0, 0], "max": [side, 2 * side, side]}
model = {"groups": ["*", "*"], "model": "linear", "properties": {"kn": 1e4, "ks": 5e3, "fric": 0.5, "dp_nratio": 0.2}}
common = {"dimension": 3, "plugins": ["linear"], "gravity": [0, -9.81, 0],
          "walls": [{"type": "box", "min": [0, 0, 0], "max": [side, 2 * side, side]}],
          "contact_models": [model], "commands": [{"solve": {"time": t_settle}}, {"cycle": steps}]}
tetra = [[0.001, 0.001, 0.001], [-0.001, -0.001, 0.001], [-0.001, 0.001, -0.001], [0.001, -0.001, -0.001]]
scenes = {
    "clumps": dict(common, bodies=[{"type": "clump_fill", "count": n, "seed": 3, "box": box,
                                    "clump": {"group": "grains", "density": 2500, "local_damping": 0.7,
                                              "pebbles": [{"position": p, "radius": 0.001} for p in tetra]}}]),
    "balls": dict(common, bodies=[{"type": "random_fill", "count": 4 * n, "seed": 3, "box": box, "group": "grains",
                                   "radius": 0.001, "density": 2500, "local_damping": 0.7}]),
}

def rate(out):
    m = re.search(r"([0-9.e+]+) particle-steps/s.*?([0-9]+) contacts", out)
    return float(m.group(1)), int(m.group(2))

work = sys.argv[5] if len(sys.argv) > 5 else tempfile.mkdtemp()
checkpoints = {}
for name, scene in scenes.items():
    if os.path.exists(os.path.join(work, name, "checkpoint.plab")):
        checkpoints[name] = os.path.join(work, name, "checkpoint.plab")
        continue
    path = os.path.join(work, name + ".json")
    json.dump(scene, open(path, "w"))
    out = os.path.join(work, name)
    r = subprocess.run([plab, "run", path, "--out", out, "--checkpoint-every", str(t_settle)], capture_output=True, text=True)
    if r.returncode:
        sys.exit(r.stderr)
    checkpoints[name] = os.path.join(out, "checkpoint.plab")

cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")
flags = next((l for l in open("/proc/cpuinfo") if l.startswith("flags")), "")
ext = " ".join(x for x in ("avx2", "avx512f") if x in flags.split())
print(f"CPU: {cpu} ({ext}); OMP_NUM_THREADS={os.environ.get('OMP_NUM_THREADS', 'unset')}; "
      f"settled {t_settle} s, then {steps} steps from the checkpoint")
rates = {}
for k in range(2):
    for name in scenes:
        r = subprocess.run([plab, "restart", checkpoints[name], "--out", os.path.join(work, f"{name}_{k}")],
                           capture_output=True, text=True)
        if r.returncode:
            sys.exit(r.stderr)
        rates.setdefault(name, []).append(rate(r.stdout + r.stderr))
for name, r in rates.items():
    best = max(x for x, _ in r)
    print(f"{name:7s} {4 * n:7d} particles, {r[0][1]} contacts: {best / 1e6:.3f} M particle-steps/s (best of {len(r)})")
print(f"clumps / balls: {max(x for x, _ in rates['clumps']) / max(x for x, _ in rates['balls']):.3f}")
