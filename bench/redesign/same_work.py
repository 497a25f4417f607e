#!/usr/bin/env python3
"""Same work across the kernel redesign, counted rather than timed (issue 26,
acceptance 2): the instructions each binary executes on the same scene, by
valgrind's callgrind, which repeats the count exactly for the same binary
and input where timings on a shared VM spread by +-15 %.

    bench/redesign/same_work.py OLD_PLAB NEW_PLAB [--scenes gran3d gran2d] [--steps 2000]

Build both with -DPLAB_NATIVE_ARCH=OFF (valgrind 3.19 does not run AVX-512
code). Each binary runs the scenes of its own checkout (the build folder's
parent), derived as same_bits.py derives them; the hashes must agree.
"""
import argparse
import json
import os
import pathlib
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import same_bits  # noqa: E402


def instructions(plab, scene, work):
    scene_path = work / "scene.json"
    scene_path.write_text(json.dumps(scene))
    out = work / "out"
    env = dict(os.environ, OMP_NUM_THREADS="1")
    run = subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={work / 'cg.out'}", plab, "run",
                          str(scene_path), "--quiet", "--out", str(out)], env=env, capture_output=True, text=True)
    found = re.search(r"Collected : (\d+)", run.stderr)
    if run.returncode != 0 or not found:
        sys.exit(f"{plab}: callgrind run failed:\n{run.stderr[-2000:]}")
    return int(found.group(1)), json.loads((out / "summary.json").read_text())["state_hash"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--scenes", nargs="+", default=["gran3d", "gran2d"])
    ap.add_argument("--steps", type=int, default=2000)
    a = ap.parse_args()
    print(f"{'scene':10} {'old instructions':>18} {'new instructions':>18} {'new/old':>8}  hashes")
    for name in a.scenes:
        counts, hashes = [], []
        for plab in (a.old, a.new):
            root = pathlib.Path(plab).resolve().parents[1]
            with tempfile.TemporaryDirectory() as tmp:
                n, h = instructions(plab, same_bits.derived_scene(name, a.steps, root), pathlib.Path(tmp))
            counts.append(n)
            hashes.append(h)
        print(f"{name:10} {counts[0]:>18,} {counts[1]:>18,} {counts[1] / counts[0]:>8.4f}  "
              f"{'same' if hashes[0] == hashes[1] else 'DIFFER'} {hashes[1]}")


if __name__ == "__main__":
    main()
