#!/usr/bin/env python3
"""Same bits across the kernel redesign (issue 26, acceptance 1).

Derives three scenes from bench/peers/ — its `commands` replaced by one
`cycle` and its `histories` and `output` removed — runs each with the plab
binary given, and compares summary.json's `state_hash` with the hash the
kernel gave before the redesign (main f68c133, written into the issue).
Exit status 1 if any hash differs.

    bench/redesign/same_bits.py build/plab [--threads N] [--keep DIR]
"""
import argparse
import json
import os
import pathlib
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]

# scene, steps, state_hash before the redesign
CASES = [
    ("gran3d", 2000, "ffe2917937a9a800"),
    ("gran2d", 2000, "34d1e85601951bb8"),
    ("sph_double_dam_break", 400, "ac66590f4c9b1d98"),
]


def derived_scene(name, steps, root=ROOT):
    scene = json.loads((root / "bench" / "peers" / f"{name}.json").read_text())
    scene["commands"] = [{"cycle": steps}]
    scene.pop("histories", None)
    scene.pop("output", None)
    return scene


def run(plab, scene, work, threads):
    scene_path = work / "scene.json"
    scene_path.write_text(json.dumps(scene, indent=1))
    out = work / "out"
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    start = time.perf_counter()
    subprocess.run([plab, "run", str(scene_path), "--out", str(out), "--quiet"], check=True, env=env,
                   stdout=subprocess.DEVNULL)
    wall = time.perf_counter() - start
    return json.loads((out / "summary.json").read_text())["state_hash"], wall


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("plab")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--keep", help="write the derived scenes and outputs here instead of a temporary folder")
    args = ap.parse_args()
    plab = str(pathlib.Path(args.plab).resolve())
    base = pathlib.Path(args.keep) if args.keep else pathlib.Path(tempfile.mkdtemp(prefix="plab_same_bits_"))
    failed = 0
    print(f"{'scene':24s} {'steps':>6s} {'expected':>18s} {'got':>18s}  wall s")
    for name, steps, expected in CASES:
        work = base / name
        work.mkdir(parents=True, exist_ok=True)
        got, wall = run(plab, derived_scene(name, steps), work, args.threads)
        mark = "same" if got == expected else "DIFFERENT"
        failed += got != expected
        print(f"{name:24s} {steps:6d} {expected:>18s} {got:>18s}  {wall:6.1f}  {mark}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
