"""plasma_contact.py NANOVIEW BOX_CLASHES PKG INSTANCE HALF WORKDIR [--json OUT] [--surface-rind]

Where a compartment instance's membrane meets the scene's medium, read as a structural biologist
would: the box of half-size HALF around the instance's first mesh vertex (box_clashes ... where)
is exported by `nanoview export` as CSV (which copy, of which kind) and as mmCIF; gemmi's CIF reader
reads the mmCIF (every atom of the CSV, at the same place), and an exact binned search over its atoms
finds the pairs of a medium atom and a membrane atom (lipid or membrane protein) whose van der Waals
spheres overlap by 0.4 Å or more: there must be none. Then the rind: for every medium copy in the box, its gap to the
membrane (the least distance between its atoms' and membrane atoms' spheres). The nearest copy must
come within the medium's clearance plus one molecule (the largest medium copy's diameter) of the
membrane: a wider empty rind would be plasma kept away from the cell. Prints the gap distribution.
And the rind along the surface, as one would look at it: the membrane atoms that face the plasma
(the nearest membrane atom of some medium atom, both sampled), binned in 20 Å cells; per cell, the
least gap to a medium atom, counted where the box decides it (no atom outside could be nearer).
With --surface-rind, at least 90 % of those cells must have plasma within the clearance plus one
molecule (a red cell's needs a box of half-size 400 Å: minutes; a virion's 300 Å).

`plasma_contact.py --self-test` checks the searches against brute force on random atoms.
"""
import argparse
import collections
import json
import math
import subprocess
import sys

import gemmi
import numpy

CLASH_OVERLAP = 0.4  # Å, as MolProbity counts a serious clash
FINEST_CELL = 4.0  # Å: the nearest-atom search's smallest cells (its speed depends on it, never its answer)
BOUND_SLACK = 1e-6  # Å: rounding in the search's bounds must never drop the true nearest
QUERY_CHUNK = 4096  # points searched at once: bounds the pair arrays' memory

CellLevel = collections.namedtuple("CellLevel", "start count lo hi rep w_max first_child children")


def morton(key, bits):
    """Interleaved bits of the integer cell keys: sorted by it, every cell of every level is one run."""
    code = numpy.zeros(len(key), dtype=numpy.int64)
    for b in range(bits):
        for axis in range(3):
            code |= ((key[:, axis] >> b) & 1) << (3 * b + 2 - axis)
    return code


def cell_tree(targets, weights, finest):
    """Nested cubic cells over the targets, from one cell halving down to `finest`, coarsest level first.
    Per occupied cell: its run of the targets (in `order`), their bounding box (tighter than the cell),
    the target nearest its centre (an upper bound that is a real distance), the greatest weight, and
    its run of children in the next level. Returns order, the targets and weights in it, the levels."""
    key = numpy.floor((targets - targets.min(axis=0)) / finest).astype(numpy.int64)
    bits = max(1, int(key.max()).bit_length())
    code = morton(key, bits)
    order = numpy.argsort(code, kind="stable")
    code, inside, w = code[order], targets[order], weights[order]
    levels, parent_code = [], None
    for shift in range(bits, -1, -1):
        cell_code = code >> (3 * shift)
        start = numpy.flatnonzero(numpy.r_[True, cell_code[1:] != cell_code[:-1]])
        count = numpy.diff(numpy.r_[start, len(code)])
        lo, hi = numpy.minimum.reduceat(inside, start), numpy.maximum.reduceat(inside, start)
        cell_of = numpy.repeat(numpy.arange(len(start)), count)
        off_centre = ((inside - (lo + hi)[cell_of] / 2) ** 2).sum(axis=1)
        rep = numpy.lexsort((off_centre, cell_of))[start]
        if levels:
            # This level's cells are the previous level's children, in its cells' order.
            first = numpy.searchsorted(cell_code[start] >> 3, parent_code)
            levels[-1] = levels[-1]._replace(first_child=first, children=numpy.diff(numpy.r_[first, len(start)]))
        levels.append(CellLevel(start, count, lo, hi, rep, numpy.maximum.reduceat(w, start), None, None))
        parent_code = cell_code[start]
    return order, inside, w, levels


def runs(lengths):
    """For runs of these lengths laid end to end: each element's run, and its place in the run."""
    run = numpy.repeat(numpy.arange(len(lengths)), lengths)
    return run, numpy.arange(len(run)) - numpy.repeat(numpy.cumsum(lengths) - lengths, lengths)


def least_per_group(values, group):
    """Each element's group's least value (the groups contiguous)."""
    start = numpy.flatnonzero(numpy.r_[True, group[1:] != group[:-1]])
    return numpy.repeat(numpy.minimum.reduceat(values, start), numpy.diff(numpy.r_[start, len(group)]))


def candidates(points, targets, weights=None):
    """Pairs (point index, target index): per point, every target that may minimise
    |point - target| - weights[target]. A breadth-first descent of nested cells drops a cell only when
    its least possible value exceeds the value of a target already seen, so no true minimum is lost
    (a brute-force search's answer at a fraction of its time); callers rank the few pairs left."""
    if weights is None:
        weights = numpy.zeros(len(targets))
    if not len(points) or not len(targets):
        return numpy.empty(0, numpy.int64), numpy.empty(0, numpy.int64)
    order, inside, w, levels = cell_tree(targets, weights, FINEST_CELL)
    found_q, found_t = [], []
    for first in range(0, len(points), QUERY_CHUNK):
        q = numpy.arange(first, min(first + QUERY_CHUNK, len(points)))
        cell = numpy.zeros(len(q), dtype=numpy.int64)
        for parent, level in zip(levels, levels[1:]):
            pair, place = runs(parent.children[cell])
            q, cell = q[pair], parent.first_child[cell[pair]] + place
            p = points[q]
            near = numpy.maximum(numpy.maximum(level.lo[cell] - p, p - level.hi[cell]), 0.0)
            lower = numpy.sqrt((near ** 2).sum(axis=1)) - level.w_max[cell]
            upper = numpy.sqrt(((p - inside[level.rep[cell]]) ** 2).sum(axis=1)) - w[level.rep[cell]]
            keep = lower <= least_per_group(upper, q) + BOUND_SLACK
            q, cell = q[keep], cell[keep]
        pair, place = runs(levels[-1].count[cell])
        q, t = q[pair], levels[-1].start[cell[pair]] + place
        value = numpy.sqrt(((points[q] - inside[t]) ** 2).sum(axis=1)) - w[t]
        keep = value <= least_per_group(value, q) + BOUND_SLACK
        found_q.append(q[keep])
        found_t.append(order[t[keep]])
    return numpy.concatenate(found_q), numpy.concatenate(found_t)


def nearest(points, targets):
    """For each point, the index into targets of its nearest target (of equally near ones the lowest
    index, as an argmin over all targets would pick)."""
    q, t = candidates(points, targets)
    d2 = ((points[q] - targets[t]) ** 2).sum(axis=1)
    ranked = numpy.lexsort((t, d2, q))
    q, t = q[ranked], t[ranked]
    first = numpy.r_[True, q[1:] != q[:-1]]
    found = numpy.empty(len(points), dtype=numpy.int64)
    found[q[first]] = t[first]
    return found


def copy_gaps(xyz, radius, by_copy, wall_sample):
    """Each copy's least gap (centre distance less both radii) from every 8th of its atoms to the
    sampled membrane atoms; infinite when there are none."""
    if not by_copy:
        return {}
    probes = [numpy.array(members)[::8] for members in by_copy.values()]
    probe = numpy.concatenate(probes)
    copy_of = numpy.repeat(numpy.arange(len(probes)), [len(p) for p in probes])
    q, w = candidates(xyz[probe], xyz[wall_sample], radius[wall_sample])
    a, b = probe[q], wall_sample[w]
    # The expression the all-pairs matrix evaluated, so each gap is the same to the last bit.
    gap = numpy.linalg.norm(xyz[a] - xyz[b], axis=1) - radius[a] - radius[b]
    least = numpy.full(len(probes), math.inf)
    numpy.minimum.at(least, copy_of[q], gap)
    return {copy: float(g) for copy, g in zip(by_copy, least)}


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


def read_export_csv(path):
    """The export's CSV (header: copy,type,chain,residue,atom,element,x,y,z,radius,kind) as columns:
    each atom's copy, kind, centre and radius."""
    header = open(path).readline().strip().split(",")
    column = {name: i for i, name in enumerate(header)}
    read = lambda names, dtype: numpy.loadtxt(path, delimiter=",", skiprows=1, dtype=dtype, ndmin=1,
                                              usecols=[column[n] for n in names])
    numbers = read(("x", "y", "z", "radius"), float).reshape(-1, 4)
    return read(("copy",), numpy.int64), read(("kind",), str), numbers[:, :3], numbers[:, 3]


def read_mmcif_atoms(path, csv_xyz):
    """gemmi's CIF reader on the export's mmCIF: each atom's centre in the CSV's order (the mmCIF's
    atom ids are the CSV rows, 1-based, grouped by chain there), and a problem when the two files
    disagree on the atoms or on where they are (beyond the mmCIF's 3 decimals)."""
    table = gemmi.cif.read(path).sole_block().find("_atom_site.", ["id", "Cartn_x", "Cartn_y", "Cartn_z"])
    ids = numpy.array(list(table.column(0)), dtype=numpy.int64)
    cif_xyz = numpy.stack([numpy.array(table.column(c), dtype=float) for c in (1, 2, 3)], axis=1).reshape(-1, 3)
    n = len(csv_xyz)
    if len(ids) != n or len(numpy.unique(ids)) != n or (n and (ids.min() != 1 or ids.max() != n)):
        return csv_xyz, f"gemmi reads {len(ids)} atoms (ids {ids.min() if n else '-'}..{ids.max() if n else '-'}), the CSV holds {n}"
    xyz = numpy.empty_like(cif_xyz)
    xyz[ids - 1] = cif_xyz
    off = numpy.abs(xyz - csv_xyz).max(axis=1)
    if n and off.max() > 2e-3:
        i = int(off.argmax())
        return xyz, f"atom {i + 1} at {tuple(xyz[i])} in the mmCIF, {tuple(csv_xyz[i])} in the CSV"
    return xyz, None


def overlapping_pairs(points, point_radius, targets, target_radius, overlap):
    """Every pair (point index, target index) whose spheres overlap by `overlap` or more, exactly: the
    targets are binned in cubes as wide as the longest such centre distance, so each point's pairs lie
    in the 27 cubes around it."""
    if not len(points) or not len(targets):
        return numpy.empty(0, numpy.int64), numpy.empty(0, numpy.int64)
    reach = float(point_radius.max() + target_radius.max() - overlap)
    if reach <= 0:
        return numpy.empty(0, numpy.int64), numpy.empty(0, numpy.int64)
    lo = numpy.minimum(points.min(axis=0), targets.min(axis=0)) - reach
    span = numpy.floor((numpy.maximum(points.max(axis=0), targets.max(axis=0)) - lo) / reach).astype(numpy.int64) + 3
    key = lambda c: (c[:, 0] * span[1] + c[:, 1]) * span[2] + c[:, 2]
    order = numpy.argsort(key(numpy.floor((targets - lo) / reach).astype(numpy.int64)), kind="stable")
    sorted_keys = key(numpy.floor((targets[order] - lo) / reach).astype(numpy.int64))
    cells = numpy.floor((points - lo) / reach).astype(numpy.int64)
    found_p, found_t = [], []
    for dx in (-1, 0, 1):
        for dy in (-1, 0, 1):
            for dz in (-1, 0, 1):
                k = key(cells + numpy.array([dx, dy, dz]))
                first, last = numpy.searchsorted(sorted_keys, k, "left"), numpy.searchsorted(sorted_keys, k, "right")
                p, place = runs(last - first)
                t = order[first[p] + place]
                gap = numpy.linalg.norm(points[p] - targets[t], axis=1) - point_radius[p] - target_radius[t]
                keep = gap <= -overlap
                found_p.append(p[keep])
                found_t.append(t[keep])
    return numpy.concatenate(found_p), numpy.concatenate(found_t)


def percentiles(values):
    return {p: round(values[min(len(values) - 1, int(p / 100 * len(values)))], 1) for p in (10, 50, 90)} if values else {}


def self_test():
    """The searches against brute force on random atoms: overlapping_pairs finds every overlapping pair
    and no other, nearest the argmin of every distance, candidates every weighted minimum."""
    rng = numpy.random.default_rng(5)
    points, targets = rng.uniform(0, 30, (400, 3)), rng.uniform(0, 30, (900, 3))
    pr, tr = rng.uniform(1.0, 2.0, 400), rng.uniform(1.0, 2.0, 900)
    gap = numpy.linalg.norm(points[:, None] - targets[None], axis=2) - pr[:, None] - tr[None]
    expect = set(zip(*numpy.nonzero(gap <= -CLASH_OVERLAP)))
    got = list(zip(*overlapping_pairs(points, pr, targets, tr, CLASH_OVERLAP)))
    failures = []
    if len(got) != len(set(got)) or set(got) != expect or not expect:
        failures.append(f"overlapping_pairs: {len(got)} pairs ({len(set(got))} distinct), brute force {len(expect)}")
    distance = numpy.linalg.norm(points[:, None] - targets[None], axis=2)
    if not (nearest(points, targets) == distance.argmin(axis=1)).all():
        failures.append("nearest differs from the argmin")
    q, t = candidates(points, targets, tr)
    weighted = distance - tr[None]
    if not numpy.allclose(weighted[q, t], weighted.min(axis=1)[q]) or set(q.tolist()) != set(range(len(points))):
        failures.append("candidates misses a weighted minimum")
    for f in failures:
        print("FAIL:", f)
    print(f"self-test: {len(expect)} overlapping pairs, {len(points)} nearest and weighted minima checked")
    return 1 if failures else 0


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
    for ext in ("csv", "cif"):
        out = f"{args.workdir}/plasma-contact-{args.instance}.{ext}"
        subprocess.run([args.nanoview, "export", args.package, "--box", box, "-o", out], check=True, capture_output=True)
    problems = []
    copy, kinds, csv_xyz, radius = read_export_csv(f"{args.workdir}/plasma-contact-{args.instance}.csv")
    xyz, problem = read_mmcif_atoms(f"{args.workdir}/plasma-contact-{args.instance}.cif", csv_xyz)
    if problem:
        problems.append(problem)
    medium = numpy.flatnonzero(kinds == "medium")
    wall = numpy.flatnonzero(kinds == "membrane")
    if not len(medium) or not len(wall):
        problems.append(f"the box holds {len(medium)} medium and {len(wall)} membrane atoms: it must straddle both")

    # Every pair of a medium atom and a membrane atom whose spheres overlap by CLASH_OVERLAP or more.
    m, w = overlapping_pairs(xyz[medium], radius[medium], xyz[wall], radius[wall], CLASH_OVERLAP)
    gap = numpy.linalg.norm(xyz[medium[m]] - xyz[wall[w]], axis=1) - radius[medium[m]] - radius[wall[w]]
    clashes = [(int(copy[medium[i]]), int(copy[wall[j]]), round(float(g), 3)) for i, j, g in zip(m, w, gap)]
    # Each medium copy's gap to the membrane, from every 8th of its atoms to every 32nd membrane atom
    # (a sampled distance: it overstates the gap by at most a few Å).
    by_copy = {}
    for i in medium.tolist():
        by_copy.setdefault(int(copy[i]), []).append(i)
    diameter = 0.0
    for members in by_copy.values():
        m = numpy.array(members)
        centre = xyz[m].mean(axis=0)
        diameter = max(diameter, 2 * float((numpy.linalg.norm(xyz[m] - centre, axis=1) + radius[m]).max()))
    copy_gap = copy_gaps(xyz, radius, by_copy, wall[::32])
    gaps = sorted(copy_gap.values())
    clearance = args.clearance
    diameter = max(diameter, args.molecule_diameter)
    nearest = gaps[0] if gaps else math.inf
    corners = [float(v) for v in box.replace(",", " ").split()]
    cells = surface_rind(xyz, radius, wall, medium, corners[:3], corners[3:]) if len(medium) and len(wall) else []
    decided = [gap for gap, sure in cells if sure]
    reach = clearance + diameter
    covered = sum(1 for gap in decided if gap <= reach)
    summary = {"box": box, "atoms": len(copy), "medium_atoms": len(medium), "membrane_atoms": len(wall),
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
    elif len(medium) and len(wall) and len(decided) < 20:
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
    sys.exit(self_test() if sys.argv[1:] == ["--self-test"] else main())
