#!/usr/bin/env python3
"""Same speed across the kernel redesign (issue 26, acceptance 2).

Runs an old and a new plab binary side by side on the three scenes of
same_bits.py (derived from bench/peers/: one `cycle`, no histories, no
output), at 1 and 2 OpenMP threads, interleaved (old, new, old, new, ...)
so that a change of machine load falls on both, and prints the median
throughput (particle steps per second, from summary.json) of each and the
ratio new/old. Each binary must find its own plug-ins (built in its own
build tree), and reads the scenes of its own checkout (BINARY/../../bench/
peers, when there is one: a scene's spelling may change with the version,
as the ABI 2 property names did). Nothing is asserted: the table is the
result.

    bench/redesign/same_speed.py OLD_PLAB NEW_PLAB [--runs 3] [--threads 1 2]
"""
import argparse
import json
import os
import pathlib
import platform
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from same_bits import derived_scene  # noqa: E402


# scene, steps: long enough (3-10 s at one thread) that start-up is noise
CASES = [("gran3d", 10000), ("gran2d", 10000), ("sph_double_dam_break", 1200)]


def checkout_of(binary):
    root = pathlib.Path(binary).resolve().parents[1]
    return root if (root / "bench" / "peers").is_dir() else pathlib.Path(__file__).resolve().parents[2]


def cpu_line():
    model, flags = platform.processor() or "unknown CPU", ""
    try:
        for line in pathlib.Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name") and model in ("unknown CPU", platform.processor()):
                model = line.split(":", 1)[1].strip()
            if line.startswith("flags"):
                have = set(line.split(":", 1)[1].split())
                flags = " ".join(f for f in ("sse4_2", "avx", "avx2", "fma", "avx512f", "avx512bw", "avx512vl")
                                 if f in have)
    except OSError:
        pass
    return f"{model}; {os.cpu_count()} logical CPUs; vector extensions: {flags or 'none found'}"


def throughput(plab, scene_path, out, threads):
    env = dict(os.environ, OMP_NUM_THREADS=str(threads), OMP_PROC_BIND="true", OMP_WAIT_POLICY="ACTIVE")
    subprocess.run([plab, "run", str(scene_path), "--out", str(out), "--quiet"], check=True, env=env,
                   stdout=subprocess.DEVNULL)
    summary = json.loads((out / "summary.json").read_text())
    return summary["particle_steps_per_second"], summary["state_hash"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    args = ap.parse_args()
    binaries = {"old": str(pathlib.Path(args.old).resolve()), "new": str(pathlib.Path(args.new).resolve())}
    base = pathlib.Path(tempfile.mkdtemp(prefix="plab_same_speed_"))
    print(cpu_line())
    print(f"{'scene':22s} {'threads':>7s} {'old Mps/s':>10s} {'new Mps/s':>10s} {'new/old':>8s}  hashes")
    for name, steps in CASES:
        scene_paths = {}
        for which, binary in binaries.items():
            scene_paths[which] = base / f"{name}_{which}.json"
            scene_paths[which].write_text(json.dumps(derived_scene(name, steps, checkout_of(binary)), indent=1))
        for threads in args.threads:
            rates = {"old": [], "new": []}
            hashes = {"old": set(), "new": set()}
            for run in range(args.runs):
                for which in ("old", "new"):
                    rate, h = throughput(binaries[which], scene_paths[which], base / f"{name}_{which}_{threads}_{run}",
                                         threads)
                    rates[which].append(rate)
                    hashes[which].add(h)
            old, new = statistics.median(rates["old"]), statistics.median(rates["new"])
            same = "same" if hashes["old"] == hashes["new"] and len(hashes["old"]) == 1 else "DIFFERENT"
            print(f"{name:22s} {threads:7d} {old / 1e6:10.2f} {new / 1e6:10.2f} {new / old:8.3f}  {same}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
