#!/usr/bin/env python3
"""Writes data/meshes/rod-cell.obj: a closed capsule (a cylinder between two hemispheres) in
nanometres, with neither UVs nor normals, as a modelling tool would export it. The baker makes its
UV charts and normals (scene "uv": "auto") and scales it from nm ("units": "nm").

Size: 150 nm across and 400 nm long, the rod of Candidatus Pelagibacter ubique (SAR11), among
the smallest free-living cells (0.12-0.20 x 0.37-0.89 um; Rappe et al. 2002, Nature 418:630).
"""
import math
import sys

RADIUS_NM, LENGTH_NM = 75.0, 400.0
AROUND, CAP_RINGS = 48, 12  # vertices per ring; rings per hemisphere, pole excluded


def capsule():
    half_cylinder = (LENGTH_NM - 2 * RADIUS_NM) / 2
    ring_spacing = 2 * math.pi * RADIUS_NM / AROUND
    cylinder_rings = max(1, round(2 * half_cylinder / ring_spacing))
    rings = []  # (z, radius) from the north pole's neighbour to the south pole's
    for k in range(1, CAP_RINGS + 1):
        polar = (math.pi / 2) * k / CAP_RINGS
        rings.append((half_cylinder + RADIUS_NM * math.cos(polar), RADIUS_NM * math.sin(polar)))
    for k in range(1, cylinder_rings):
        rings.append((half_cylinder - 2 * half_cylinder * k / cylinder_rings, RADIUS_NM))
    for k in range(CAP_RINGS, 0, -1):
        polar = (math.pi / 2) * k / CAP_RINGS
        rings.append((-half_cylinder - RADIUS_NM * math.cos(polar), RADIUS_NM * math.sin(polar)))
    vertices = [(0.0, 0.0, half_cylinder + RADIUS_NM)]
    for i, (z, r) in enumerate(rings):
        twist = 0.5 * (i % 2)  # alternate rings turn half a step: better-shaped triangles
        for j in range(AROUND):
            a = 2 * math.pi * (j + twist) / AROUND
            vertices.append((r * math.cos(a), r * math.sin(a), z))
    vertices.append((0.0, 0.0, -half_cylinder - RADIUS_NM))
    south = len(vertices) - 1

    def at(i, j):
        return 1 + i * AROUND + j % AROUND

    faces = [(0, at(0, j), at(0, j + 1)) for j in range(AROUND)]
    for i in range(len(rings) - 1):
        for j in range(AROUND):
            if i % 2 == 0:  # ring i+1 is turned half a step ahead
                faces.append((at(i, j), at(i + 1, j), at(i + 1, j + 1)))
                faces.append((at(i, j), at(i + 1, j + 1), at(i, j + 1)))
            else:
                faces.append((at(i, j), at(i + 1, j + 1), at(i, j + 1)))
                faces.append((at(i, j), at(i + 1, j), at(i + 1, j + 1)))
    last = len(rings) - 1
    faces += [(south, at(last, j + 1), at(last, j)) for j in range(AROUND)]
    return vertices, faces


def main(path):
    vertices, faces = capsule()
    with open(path, "w") as out:
        out.write("# rod-shaped cell, nanometres: 150 nm across, 400 nm long (scripts/make_rod_cell_mesh.py)\n")
        out.write("# no texture coordinates, no normals: the baker makes both\n")
        for v in vertices:
            out.write("v %.4f %.4f %.4f\n" % v)
        for f in faces:
            out.write("f %d %d %d\n" % tuple(i + 1 for i in f))


main(sys.argv[1] if len(sys.argv) > 1 else "data/meshes/rod-cell.obj")
