#!/usr/bin/env python3
"""Peak memory per ball of plab and LAMMPS on the gran3d scene scaled up.

The issue-8 acceptance asks for peak memory per particle at or below
LAMMPS's. At 10 000 balls both codes' fixed cost (binary, libraries,
plug-ins) dominates the peak, so this runs gran3d with more balls along x
and y (`--lateral 63`: 63 x 63 x 25 = 99 225 balls in a 0.693 m box) in both
codes, one thread / one rank, and reports each code's peak resident memory
(wait4 maxrss) and bytes per ball, with the pair contacts at the end (the
memory of a granular code grows with its contacts). The default runs the
whole settling (20 000 steps) so that the peak is that of the settled pile.
"""
import argparse
import json
import os
import re
import tempfile

import make_peer_data  # (this script's folder is on the module path)
from run_peers import HERE, ROOT, run_measured


def plab_scene(lateral, steps):
    sc = json.load(open(os.path.join(HERE, "gran3d.json")))
    side = lateral * make_peer_data.SPACING
    box = sc["bodies"][0]["box"]
    box["max"][0] = box["max"][1] = side + 0.0005
    for w in sc["walls"]:
        if w["name"] == "xhi":
            w["point"][0] = side
        if w["name"] == "yhi":
            w["point"][1] = side
    sc["commands"] = [{"cycle": steps}]
    return sc


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--plab", default=os.path.join(ROOT, "build", "plab"))
    ap.add_argument("--lateral", type=int, default=63, help="balls along x and y (gran3d: 20)")
    ap.add_argument("--steps", type=int, default=20000)
    a = ap.parse_args()
    work = tempfile.mkdtemp(prefix="plab_memory_")
    side = a.lateral * make_peer_data.SPACING
    data = os.path.join(work, "gran3d_scaled.data")
    make_peer_data.write(3, data, lateral=a.lateral)
    scene = os.path.join(work, "gran3d_scaled.json")
    json.dump(plab_scene(a.lateral, a.steps), open(scene, "w"))
    env = dict(os.environ, OMP_NUM_THREADS="1")

    out = os.path.join(work, "plab_out")
    _, rss_plab, cpu_plab = run_measured([a.plab, "run", scene, "--out", out], env, False)
    contacts_plab = json.load(open(os.path.join(out, "summary.json")))["models"][0]["active_contacts"]

    text, rss_lmp, cpu_lmp = run_measured(
        ["lmp", "-in", os.path.join(HERE, "lammps_gran.in"), "-var", "steps", str(a.steps), "-log", "none",
         "-var", "dim", "3", "-var", "data", data, "-var", "side", f"{side:.9g}"], env, True)
    atoms = int(re.search(r"for \d+ steps with (\d+) atoms", text).group(1))
    contacts_lmp = float(re.search(r"PEER_RESULT contacts ([0-9.eE+-]+)", text).group(1))
    print(f"gran3d scaled: {a.lateral} x {a.lateral} x 25 = {atoms} balls, box side {side:.3f} m, {a.steps} steps, 1 thread")
    print("| code | peak RSS, MB | bytes per ball | pair contacts at the end | CPU s |")
    print("|---|---|---|---|---|")
    print(f"| plab | {rss_plab:.1f} | {rss_plab * 1048576 / atoms:.0f} | {contacts_plab:.0f} | {cpu_plab:.1f} |")
    print(f"| LAMMPS | {rss_lmp:.1f} | {rss_lmp * 1048576 / atoms:.0f} | {contacts_lmp:.0f} | {cpu_lmp:.1f} |")
    print(f"plab / LAMMPS peak memory: {rss_plab / rss_lmp:.2f}")


if __name__ == "__main__":
    main()
