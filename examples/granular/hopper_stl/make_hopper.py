#!/usr/bin/env python3
"""Writes hopper.stl, the conical hopper of hopper.json, as a binary STL in
millimetres (as a CAD export would be; the scene scales it by 0.001).

A vertical cylinder (radius R_SILO, from the top of the cone up to
Z_TOP) on a cone that narrows to a circular orifice of diameter D at
z = 0, its wall at CONE_DEG above the horizontal. Each circle is a regular
polygon of SIDES sides whose area equals the circle's (its corners a little
outside the radius), so the orifice has the area of a circle of diameter D.
Every band is SIDES quads, each split into two triangles: 4 * SIDES
triangles in all. Python 3 standard library only; run it again to get the
same bytes:

    python3 make_hopper.py            # writes hopper.stl beside this script
"""
import math
import os
import struct

D = 28.0          # orifice diameter, mm (7 ball diameters of 4 mm)
R_SILO = 35.0     # cylinder radius, mm (its diameter 2.5 D)
CONE_DEG = 30.0   # cone wall above the horizontal, degrees
Z_TOP = 160.0     # top of the cylinder, mm (it is open)
SIDES = 32

# a regular polygon of circumradius rho has area (n/2) rho^2 sin(2 pi/n)
AREA_FACTOR = math.sqrt(2 * math.pi / (SIDES * math.sin(2 * math.pi / SIDES)))


def ring(radius, z):
    rho = radius * AREA_FACTOR
    return [(rho * math.cos(2 * math.pi * k / SIDES), rho * math.sin(2 * math.pi * k / SIDES), z) for k in range(SIDES)]


def band(lower, upper):
    """Two triangles per quad between two rings, wound so the normals
    (right-hand rule) point into the hopper, toward the grains."""
    tris = []
    for k in range(SIDES):
        a, b = lower[k], lower[(k + 1) % SIDES]
        c, d = upper[(k + 1) % SIDES], upper[k]
        tris += [(a, d, c), (a, c, b)]
    return tris


def normal(t):
    u = [t[1][i] - t[0][i] for i in range(3)]
    v = [t[2][i] - t[0][i] for i in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    length = math.sqrt(sum(x * x for x in n))
    return [x / length for x in n]


def main():
    z_cone = (R_SILO - D / 2) * math.tan(math.radians(CONE_DEG))
    orifice, cone_top, silo_top = ring(D / 2, 0.0), ring(R_SILO, z_cone), ring(R_SILO, Z_TOP)
    tris = band(orifice, cone_top) + band(cone_top, silo_top)
    header = f"hopper: orifice D {D:g} mm, silo R {R_SILO:g} mm, cone {CONE_DEG:g} deg, {SIDES} sides, mm".encode()
    out = bytearray(header.ljust(80, b" "))
    out += struct.pack("<I", len(tris))
    for t in tris:
        out += struct.pack("<3f", *normal(t))
        for v in t:
            out += struct.pack("<3f", *v)
        out += b"\0\0"
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "hopper.stl")
    with open(path, "wb") as f:
        f.write(out)
    print(f"{path}: {len(tris)} triangles; cone from z = 0 to {z_cone:.2f} mm, cylinder to {Z_TOP:g} mm")


if __name__ == "__main__":
    main()
