#!/usr/bin/python3
"""VTK reads the frames plab writes, in every encoding (CTest vtk_read).

Runs tests/restart/pile.json (400 balls, walls, contacts; its end time is
not a multiple of the frame interval) with output.vtk in ascii, binary,
zlib and float32, and a soft-repulsion scene with and without pair
contacts, then reads every file with VTK's own XML reader (Debian
python3-vtk9) and checks what it finds against the run:
  * one point per ball, ids 0..n-1 (Int64), groups (Int32) and the
    group-name table; the binary and zlib arrays equal the ASCII ones
    to round-off, float32 ones to float precision;
  * the last frame is the final state (summary.json's simulated time);
  * contacts are lines with their force; distance interactions are written
    only when pair_contacts is on.
Prints the bytes per 1000 balls per frame of each encoding.
"""
import json
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

import vtk

plab, source, work = sys.argv[1], sys.argv[2], sys.argv[3]
failures = []
os.makedirs(work, exist_ok=True)


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def run(scene, name, vtk_options):
    scene = json.loads(json.dumps(scene))
    scene.setdefault("output", {}).pop("vtk_interval", None)
    scene["output"]["vtk"] = vtk_options
    out = os.path.join(work, name)
    path = os.path.join(work, name + ".json")
    with open(path, "w") as f:
        json.dump(scene, f)
    subprocess.run([plab, "run", path, "--out", out, "--quiet"], check=True)
    return out


def read(path):
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(path)
    r.Update()
    if r.GetErrorCode() != 0:
        raise RuntimeError("VTK could not read " + path)
    return r.GetOutput()


def frames(out, part):
    series = ET.parse(os.path.join(out, "series.pvd")).getroot()
    sets = [d for d in series.iter("DataSet") if os.path.basename(d.get("file")).startswith(part + "_")]
    return [(float(d.get("timestep")), os.path.join(out, d.get("file"))) for d in sets]


def values(array):
    """Every component of a VTK data array, as Python numbers."""
    return [array.GetComponent(t, c) for t in range(array.GetNumberOfTuples())
            for c in range(array.GetNumberOfComponents())]


def names(poly, array):
    a = poly.GetFieldData().GetAbstractArray(array)
    return [a.GetValue(k) for k in range(a.GetNumberOfValues())] if a else None


pile = json.load(open(os.path.join(source, "tests/restart/pile.json")))
interval = pile["output"]["vtk_interval"]
runs = {e: run(pile, "pile_" + e, {"interval": interval, "encoding": e})
        for e in ("ascii", "binary", "zlib")}
runs["float32"] = run(pile, "pile_float32", {"interval": interval, "precision": "float32"})
summary = json.load(open(os.path.join(runs["binary"], "summary.json")))
n = summary["bodies"]

ascii_last = read(frames(runs["ascii"], "balls")[-1][1])
for name, out in runs.items():
    series = frames(out, "balls")
    t_last, last = series[-1]
    poly = read(last)
    check(poly.GetNumberOfPoints() == n, f"{name}: {poly.GetNumberOfPoints()} points for {n} balls")
    pd = poly.GetPointData()
    ids = pd.GetArray("id")
    check(ids is not None and ids.GetDataType() in (vtk.VTK_LONG, vtk.VTK_LONG_LONG, vtk.VTK_ID_TYPE),
          f"{name}: id is a 64-bit integer array")
    check(sorted(int(v) for v in values(ids)) == list(range(n)), f"{name}: ids 0..{n - 1}")
    check(pd.GetArray("group").GetDataType() == vtk.VTK_INT, f"{name}: group is Int32")
    # the balls' group first; the box's walls have a group of their own
    check(names(poly, "group_names") == ["grains", "walls"] and set(values(pd.GetArray("group"))) == {0},
          f"{name}: group_names {names(poly, 'group_names')}, every ball in group 0")
    check(abs(t_last - summary["simulated_time"]) < 1e-10 * summary["simulated_time"],
          f"{name}: last frame at t = {t_last} s, the run ends at {summary['simulated_time']} s")
    tol = 1e-6 if name == "float32" else 1e-13
    for array in ("radius", "velocity", "force"):
        a = values(pd.GetArray(array))
        b = values(ascii_last.GetPointData().GetArray(array))
        scale = max(max(abs(v) for v in b), 1e-300)
        check(len(a) == len(b) and max(abs(x - y) for x, y in zip(a, b)) <= tol * scale,
              f"{name}: {array} equals the ASCII frame to {tol:g}")
    contacts = read(frames(out, "contacts")[-1][1])
    ascii_lines = read(frames(runs["ascii"], "contacts")[-1][1]).GetNumberOfLines()
    # ball-ball contacts only (the summary counts ball-wall ones too)
    check(0 < contacts.GetNumberOfLines() == ascii_lines <= summary["contacts"],
          f"{name}: {contacts.GetNumberOfLines()} contact lines, {summary['contacts']} contacts in all")
    check(contacts.GetCellData().GetArray("force") is not None, f"{name}: contacts carry their force")
    walls = read(frames(out, "walls")[-1][1])
    check(walls.GetNumberOfLines() == 4, f"{name}: the box is 4 wall segments ({walls.GetNumberOfLines()})")
    size = os.path.getsize(last)
    print(f"     {name}: {size} bytes for {n} balls = {size * 1000 / n / 1e3:.1f} kB per 1000 balls per frame")

bounce = json.load(open(os.path.join(source, "examples/coupled/soft_repulsive_bounce.json")))
bounce["commands"] = [{"solve": {"time": 0.08}}]  # it reaches the floor at about 0.064 s
for pairs in (False, True):
    out = run(bounce, f"bounce_pairs_{pairs}", {"interval": 0.002, "pair_contacts": pairs})
    lines = max(read(f).GetNumberOfLines() for _, f in frames(out, "contacts"))
    check((lines > 0) == pairs, f"pair_contacts {pairs}: {lines} distance interactions written")

print(f"{len(failures)} failed")
sys.exit(1 if failures else 0)
