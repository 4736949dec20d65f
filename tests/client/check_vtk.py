#!/usr/bin/env python3
"""Checks a ParaView series as felt watch --format vtk writes it, with Python's own XML parser:
the .pvd and every .vtp it lists are well-formed, the listed files exist with increasing times,
and each piece's counts match its data. Prints one line per piece ("name points polys"); exits 1
with the reason on the first fault."""

import os
import sys
import xml.etree.ElementTree as ET


def fail(why):
    print(why, file=sys.stderr)
    sys.exit(1)


def numbers(array, kind):
    return [kind(v) for v in (array.text or "").split()]


def check_vtp(path):
    root = ET.parse(path).getroot()
    if root.tag != "VTKFile" or root.get("type") != "PolyData":
        fail(f"{path}: not a VTK PolyData file")
    for piece in root.iter("Piece"):
        points = int(piece.get("NumberOfPoints"))
        polys = int(piece.get("NumberOfPolys"))
        xyz = numbers(piece.find("Points/DataArray"), float)
        arrays = {a.get("Name"): a for a in piece.iter("DataArray")}
        connectivity = numbers(arrays["connectivity"], int)
        offsets = numbers(arrays["offsets"], int)
        if len(xyz) != 3 * points:
            fail(f"{path}: {len(xyz)} coordinates for {points} points")
        if len(offsets) != polys or (offsets and offsets[-1] != len(connectivity)):
            fail(f"{path}: {polys} polys, {len(offsets)} offsets, {len(connectivity)} indices")
        if any(i < 0 or i >= points for i in connectivity):
            fail(f"{path}: an index outside the {points} points")
        if "Normals" in arrays and len(numbers(arrays["Normals"], float)) != 3 * points:
            fail(f"{path}: normals do not match the points")
        print(piece.get("Name"), points, polys)


def check_pvd(path):
    root = ET.parse(path).getroot()
    if root.tag != "VTKFile" or root.get("type") != "Collection":
        fail(f"{path}: not a VTK collection")
    times = []
    for data_set in root.iter("DataSet"):
        times.append(float(data_set.get("timestep")))
        listed = os.path.join(os.path.dirname(path), data_set.get("file"))
        if not os.path.isfile(listed):
            fail(f"{path}: lists {listed}, which does not exist")
        check_vtp(listed)
    if any(b <= a for a, b in zip(times, times[1:])):
        fail(f"{path}: times that do not increase: {times}")


for name in sys.argv[1:]:
    try:
        (check_pvd if name.endswith(".pvd") else check_vtp)(name)
    except ET.ParseError as e:
        fail(f"{name}: {e}")
