#!/usr/bin/env python3
"""Initial state of the granular peer scenes (issue 8) for LAMMPS and LIGGGHTS.

Same recipe as gran3d.json / gran2d.json (plab's own generator makes those):
a lattice of spacing 1.1 d starting one radius inside the box, each
coordinate jittered uniformly within +-0.25 mm and each velocity component
within +-0.05 m/s, fixed seed. The random numbers differ from plab's, the
distribution does not. Writes a LAMMPS `read_data` file for atom_style
sphere (LAMMPS) and granular (LIGGGHTS): id type diameter density x y z.
"""
import random
import sys

D, RHO, SPACING, JIT_X, JIT_V = 0.01, 2500.0, 0.011, 0.00025, 0.05


def lattice(dim, lateral=20):
    r = D / 2
    if dim == 3:
        counts, lo = (lateral, lateral, 25), (0.0005 + r,) * 3
    else:
        counts, lo = (100, 100), (0.0005 + r,) * 2
    pts = []
    if dim == 3:
        for k in range(counts[2]):
            for j in range(counts[1]):
                for i in range(counts[0]):
                    pts.append((lo[0] + i * SPACING, lo[1] + j * SPACING, lo[2] + k * SPACING))
    else:
        for j in range(counts[1]):
            for i in range(counts[0]):
                pts.append((lo[0] + i * SPACING, lo[1] + j * SPACING, 0.0))
    return pts


def write(dim, path, seed=1, density=RHO, lateral=20):
    """lateral: balls along x and y (3D); the box side grows with it (0.22 m for 20)."""
    rnd = random.Random(seed)
    pts = lattice(dim, lateral)
    side = lateral * SPACING
    hi = (side, side, 0.40) if dim == 3 else (1.1, 2.0, 0.0)
    with open(path, "w") as f:
        f.write(f"granular settling, {dim}D, {len(pts)} balls\n\n{len(pts)} atoms\n1 atom types\n\n")
        f.write(f"0 {hi[0]} xlo xhi\n0 {hi[1]} ylo yhi\n")
        f.write("0 0.4 zlo zhi\n" if dim == 3 else "-0.005 0.005 zlo zhi\n")
        f.write("\nAtoms # sphere\n\n")
        vel = []
        for n, p in enumerate(pts, 1):
            q = [p[c] + rnd.uniform(-JIT_X, JIT_X) for c in range(dim)] + ([0.0] if dim == 2 else [])
            f.write(f"{n} 1 {D} {density:.9g} {q[0]:.9g} {q[1]:.9g} {q[2]:.9g}\n")
            v = [rnd.uniform(-JIT_V, JIT_V) for _ in range(dim)] + ([0.0] if dim == 2 else [])
            vel.append(v)
        f.write("\nVelocities\n\n")
        for n, v in enumerate(vel, 1):
            f.write(f"{n} {v[0]:.9g} {v[1]:.9g} {v[2]:.9g} 0 0 0\n")


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    write(3, f"{out}/gran3d.data")
    # 2D: LAMMPS gives a 2D sphere the mass 4/3 pi r^3 rho; LIGGGHTS gives it
    # the mass of a disc 1 m thick, pi r^2 rho, so its density is scaled to
    # the same mass (gran2d.json states that mass)
    write(2, f"{out}/gran2d.data")
    write(2, f"{out}/gran2d_liggghts.data", density=RHO * (4 / 3 * D / 2))
