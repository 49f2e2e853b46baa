"""plasma_contact.py NANOVIEW BOX_CLASHES PKG INSTANCE HALF WORKDIR [--json OUT] [--surface-rind]

Where a compartment instance's membrane meets the scene's medium, read as a structural biologist
would: the box of half-size HALF around the instance's first mesh vertex (box_clashes ... where)
is exported by `nanoview export` as CSV (which copy, of which kind) and as mmCIF; gemmi reads the mmCIF
(every atom of the CSV, at the same place) and finds, with its own neighbour search, the pairs of a
medium atom and a membrane atom (lipid or membrane protein) whose van der Waals spheres overlap by
0.4 Å or more: there must be none. Then the rind: for every medium copy in the box, its gap to the
membrane (the least distance between its atoms' and membrane atoms' spheres). The nearest copy must
come within the medium's clearance plus one molecule (the largest medium copy's diameter) of the
membrane: a wider empty rind would be plasma kept away from the cell. Prints the gap distribution.
And the rind along the surface, as one would look at it: the membrane atoms that face the plasma
(the nearest membrane atom of some medium atom, both sampled), binned in 20 Å cells; per cell, the
least gap to a medium atom, counted where the box decides it (no atom outside could be nearer).
With --surface-rind, at least 90 % of those cells must have plasma within the clearance plus one
molecule (a red cell's needs a box of half-size 400 Å: minutes; a virion's 300 Å).
"""
import argparse
import csv
import json
import math
import subprocess
import sys

import gemmi
import numpy

CLASH_OVERLAP = 0.4  # Å, as MolProbity counts a serious clash


def nearest(points, targets, chunk=2048):
    """For each point, the index into targets of its nearest target (numpy, in chunks)."""
    found = numpy.empty(len(points), dtype=numpy.int64)
    t2 = (targets ** 2).sum(axis=1)
    for start in range(0, len(points), chunk):
        p = points[start:start + chunk]
        d2 = t2[None, :] - 2.0 * p @ targets.T
        found[start:start + chunk] = d2.argmin(axis=1)
    return found


def surface_rind(xyz, radius, wall, medium, lo, hi, cell=20.0):
    """Per 20 Å cell of plasma-facing membrane: its least gap to the plasma, and whether the box
    decides it (no atom outside the box could be nearer: the gap is within the cell's atom's
    distance to the box's faces)."""
    wall, medium = numpy.array(wall), numpy.array(medium)
    # The membrane atoms facing the plasma: each the nearest (of every 4th) to some medium atom (of every 8th).
    probe = medium[::8]
    facing = numpy.unique(wall[::4][nearest(xyz[probe], xyz[wall[::4]])])
    m = medium[nearest(xyz[facing], xyz[medium])]
    gaps = numpy.linalg.norm(xyz[facing] - xyz[m], axis=1) - radius[facing] - radius[m]
    room = numpy.minimum(xyz[facing] - numpy.array(lo), numpy.array(hi) - xyz[facing]).min(axis=1)
    per_cell = {}
    for key, gap, inside in zip(map(tuple, numpy.floor(xyz[facing] / cell).astype(int)), gaps, room):
        best = per_cell.get(key)
        if best is None or gap < best[0]:
            per_cell[key] = (float(gap), bool(gap <= inside))
    return sorted(per_cell.values())


def percentiles(values):
    return {p: round(values[min(len(values) - 1, int(p / 100 * len(values)))], 1) for p in (10, 50, 90)} if values else {}


def main(argv=None):
    parser = argparse.ArgumentParser()
    for name in ("nanoview", "box_clashes", "package", "instance", "half", "workdir"):
        parser.add_argument(name)
    parser.add_argument("--json")
    parser.add_argument("--surface-rind", action="store_true",
                        help="require the rind along the surface (the box must hold 20 decided cells)")
    parser.add_argument("--clearance", type=float, default=5.0, help="the medium's clearance (Å)")
    parser.add_argument("--molecule-diameter", type=float, default=0.0,
                        help="one molecule of the medium (Å); default: the largest copy in the box")
    args = parser.parse_args(argv)
    box = subprocess.run([args.box_clashes, args.package, "where", args.instance, args.half], check=True,
                         capture_output=True, text=True).stdout.strip()
    rows, structure = [], None
    for ext in ("csv", "cif"):
        out = f"{args.workdir}/plasma-contact-{args.instance}.{ext}"
        subprocess.run([args.nanoview, "export", args.package, "--box", box, "-o", out], check=True, capture_output=True)
        if ext == "csv":
            rows = list(csv.DictReader(open(out)))
        else:
            structure = gemmi.read_structure(out)
    # mmCIF atoms carry the CSV's order as their serial (1-based): gemmi groups them by chain.
    atoms = [None] * len(rows)
    count = 0
    for chain in structure[0]:
        for res in chain:
            for a in res:
                count += 1
                if 1 <= a.serial <= len(rows):
                    atoms[a.serial - 1] = a
    problems = []
    if count != len(rows) or any(a is None for a in atoms):
        problems.append(f"gemmi reads {count} atoms, the CSV holds {len(rows)}")
        atoms = [a for a in atoms if a is not None]
    for a, r in zip(atoms, rows):
        if max(abs(a.pos.x - float(r["x"])), abs(a.pos.y - float(r["y"])), abs(a.pos.z - float(r["z"]))) > 2e-3:
            problems.append(f"atom {a.serial} at {a.pos} in the mmCIF, ({r['x']}, {r['y']}, {r['z']}) in the CSV")
            break
    kinds = [r["kind"] for r in rows]
    medium = [i for i, k in enumerate(kinds) if k == "medium"]
    wall = [i for i, k in enumerate(kinds) if k == "membrane"]
    if not medium or not wall:
        problems.append(f"the box holds {len(medium)} medium and {len(wall)} membrane atoms: it must straddle both")
    radius = numpy.array([float(r["radius"]) for r in rows])
    xyz = numpy.array([(a.pos.x, a.pos.y, a.pos.z) for a in atoms])

    # gemmi's neighbour search over the membrane atoms, asked about every medium atom.
    wall_model = gemmi.Model("wall")
    chain = gemmi.Chain("W")
    residue = gemmi.Residue()
    residue.name = "WAL"
    for i in wall:
        a = gemmi.Atom()
        a.name, a.element, a.serial = "X", gemmi.Element("C"), i
        a.pos = atoms[i].pos
        residue.add_atom(a)
    chain.add_residue(residue)
    wall_model.add_chain(chain)
    search = gemmi.NeighborSearch(wall_model, gemmi.UnitCell(), 6.0).populate()
    clashes = []
    for i in medium:
        for mark in search.find_atoms(atoms[i].pos, "\0", radius=6.0):
            j = mark.to_cra(wall_model).atom.serial
            gap = atoms[i].pos.dist(atoms[j].pos) - radius[i] - radius[j]
            if gap <= -CLASH_OVERLAP:
                clashes.append((rows[i]["copy"], rows[j]["copy"], round(gap, 3)))
    # Each medium copy's gap to the membrane, from every 8th of its atoms to every 32nd membrane atom
    # (a sampled distance: it overstates the gap by at most a few Å).
    by_copy = {}
    for i in medium:
        by_copy.setdefault(rows[i]["copy"], []).append(i)
    wall_sample = numpy.array(wall[::32])
    copy_gap, diameter = {}, 0.0
    for copy, members in by_copy.items():
        m = numpy.array(members)
        centre = xyz[m].mean(axis=0)
        diameter = max(diameter, 2 * float((numpy.linalg.norm(xyz[m] - centre, axis=1) + radius[m]).max()))
        probe = m[::8]
        best = math.inf
        for start in range(0, len(wall_sample), 20000):
            w = wall_sample[start:start + 20000]
            d = numpy.linalg.norm(xyz[probe][:, None, :] - xyz[w][None, :, :], axis=2) - radius[probe][:, None] - radius[w][None, :]
            best = min(best, float(d.min()))
        copy_gap[copy] = best
    gaps = sorted(copy_gap.values())
    clearance = args.clearance
    diameter = max(diameter, args.molecule_diameter)
    nearest = gaps[0] if gaps else math.inf
    corners = [float(v) for v in box.replace(",", " ").split()]
    cells = surface_rind(xyz, radius, wall, medium, corners[:3], corners[3:]) if medium and wall else []
    decided = [gap for gap, sure in cells if sure]
    reach = clearance + diameter
    covered = sum(1 for gap in decided if gap <= reach)
    summary = {"box": box, "atoms": len(rows), "medium_atoms": len(medium), "membrane_atoms": len(wall),
               "medium_copies": len(by_copy), "clashes": len(clashes), "nearest_gap_A": nearest,
               "copy_gap_percentiles_A": percentiles(gaps),
               "surface_cells": len(cells), "surface_cells_decided": len(decided),
               "surface_rind_percentiles_A": percentiles(decided),
               "surface_within_reach": covered / len(decided) if decided else None,
               "largest_medium_copy_A": diameter}
    print(json.dumps(summary, indent=1))
    if clashes:
        problems.append(f"{len(clashes)} medium–membrane atom pairs overlap by ≥ {CLASH_OVERLAP} Å, e.g. {clashes[:3]}")
    if gaps and nearest > clearance + diameter:
        problems.append(f"the nearest medium copy stands {nearest:.1f} Å from the membrane, more than the clearance "
                        f"plus one molecule ({clearance + diameter:.1f} Å): an empty rind")
    if not args.surface_rind:
        pass
    elif medium and wall and len(decided) < 20:
        problems.append(f"only {len(decided)} cells of plasma-facing membrane are decided within the box: make it larger")
    elif decided and covered < 0.9 * len(decided):
        problems.append(f"along the surface only {covered} of {len(decided)} cells have plasma within the clearance plus "
                        f"one molecule ({reach:.1f} Å; median gap {decided[len(decided) // 2]:.1f} Å): plasma kept away")
    if args.json:
        json.dump(summary, open(args.json, "w"), indent=1)
    for p in problems:
        print("FAIL:", p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
