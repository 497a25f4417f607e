#!/usr/bin/env python3
"""plab against LAMMPS and LIGGGHTS on the issue-8 granular scenes, side by side.

Runs every (scene, code, threads) combination `--reps` times, interleaved so
that a change in machine load hits every code alike, and prints the median
loop throughput (particle-steps per second), the ratio plab/peer, and a
physics check: pair contacts and kinetic energy at the end of each code.
plab's throughput is from its run summary (the solve loop); the peers' from
their "Loop time" line. Threads: plab OpenMP threads, peers MPI ranks.
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


def run_plab(plab, scene, threads, steps, work):
    out = os.path.join(work, "plab_out")
    sc = json.load(open(os.path.join(HERE, scene + ".json")))
    sc["commands"] = [{"cycle": steps}]
    path = os.path.join(work, scene + "_run.json")
    json.dump(sc, open(path, "w"))
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    subprocess.run([plab, "run", path, "--out", out], check=True, env=env,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    s = json.load(open(os.path.join(out, "summary.json")))
    pairs = sum(m["active_contacts"] for m in s["models"][:1])  # first rule: grains-grains
    return s["particle_steps_per_second"], pairs, s["energies"]["kinetic"], s["state_hash"]


def run_peer(exe, infile, dim, data, threads, steps):
    cmd = [exe, "-in", os.path.join(HERE, infile), "-var", "dim", str(dim), "-var", "data", data,
           "-var", "steps", str(steps), "-log", "none"]
    if threads > 1:
        cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(threads)] + cmd
    env = dict(os.environ, OMP_NUM_THREADS="1")
    text = subprocess.run(cmd, check=True, env=env, capture_output=True, text=True).stdout
    loop = float(re.search(r"Loop time of ([0-9.eE+-]+) on \d+ procs for (\d+) steps with (\d+) atoms", text).group(1))
    m = re.search(r"PEER_RESULT contacts ([0-9.eE+-]+) kinetic ([0-9.eE+-]+)", text)
    atoms = int(re.search(r"for \d+ steps with (\d+) atoms", text).group(1))
    return atoms * steps / loop, float(m.group(1)), float(m.group(2)), None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--plab", default=os.path.join(ROOT, "build", "plab"))
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--steps", type=int, default=20000)
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--scenes", default="gran3d,gran2d")
    ap.add_argument("--codes", default="plab,lammps,liggghts")
    a = ap.parse_args()
    work = tempfile.mkdtemp(prefix="plab_peers_")
    subprocess.run([sys.executable, os.path.join(HERE, "make_peer_data.py"), work], check=True)
    threads = [int(t) for t in a.threads.split(",")]
    codes = a.codes.split(",")
    results = {}
    for rep in range(a.reps):
        for scene in a.scenes.split(","):
            dim = 3 if scene.endswith("3d") else 2
            for t in threads:
                for code in codes:
                    if code == "plab":
                        r = run_plab(a.plab, scene, t, a.steps, work)
                    elif code == "lammps":
                        r = run_peer("lmp", "lammps_gran.in", dim, os.path.join(work, scene + ".data"), t, a.steps)
                    else:
                        data = os.path.join(work, scene + ("_liggghts" if dim == 2 else "") + ".data")
                        r = run_peer("liggghts", "liggghts_gran.in", dim, data, t, a.steps)
                    results.setdefault((scene, t, code), []).append(r)
                    print(f"  rep {rep + 1} {scene} {code} x{t}: {r[0] / 1e6:.2f} M particle-steps/s, "
                          f"{r[1]:.0f} pair contacts, kinetic {r[2]:.4g} J" + (f", hash {r[3]}" if r[3] else ""),
                          flush=True)
    print(f"\nmedian of {a.reps} interleaved runs, {a.steps} steps, loop throughput in M particle-steps/s")
    print("| scene | threads | " + " | ".join(codes) + " | " +
          " | ".join(f"plab/{c}" for c in codes if c != "plab") + " | pair contacts | kinetic energy, J |")
    print("|---" * (3 + 2 * len(codes) - 1 + 1) + "|")
    for scene in a.scenes.split(","):
        for t in threads:
            med = {c: statistics.median(x[0] for x in results[(scene, t, c)]) for c in codes}
            last = {c: results[(scene, t, c)][-1] for c in codes}
            ratios = [f"{med['plab'] / med[c]:.2f}" for c in codes if c != "plab" and "plab" in med]
            print(f"| {scene} | {t} | " + " | ".join(f"{med[c] / 1e6:.2f}" for c in codes) + " | " +
                  " | ".join(ratios) + " | " + " / ".join(f"{last[c][1]:.0f}" for c in codes) + " | " +
                  " / ".join(f"{last[c][2]:.3g}" for c in codes) + " |")
    if "plab" in codes and len(threads) > 1:
        for scene in a.scenes.split(","):
            hashes = {t: results[(scene, t, "plab")][-1][3] for t in threads}
            print(f"plab {scene}: state hash by thread count {hashes} -> "
                  f"{'bit-identical' if len(set(hashes.values())) == 1 else 'DIFFERENT'}")


if __name__ == "__main__":
    main()
