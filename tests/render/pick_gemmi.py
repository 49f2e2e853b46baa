#!/usr/bin/python3
"""Oracle test of `nanoview pick`: the atom a picked pixel names is the atom gemmi reads from the
molecule's source structure file.

A package holds each molecule type's atoms in file order after nanobake's selection policy (first
model, waters removed, one atom per (chain, residue number, insertion code, atom name): highest
occupancy, first in file on ties, kept at the place of the key's first atom), centred on their mean
(docs/scenes.md, "Structure reading policy"); a lipid patch gives one molecule type per residue, each centred
on its own mean. So for a pick naming atom i of a molecule type from file F, some residue group G of
F (the whole selection for a protein) must hold, at its index i, an atom with the same name,
element, chain, residue, insertion code and alternate location, at `position` + mean(G) in the
file's coordinates. The selection is re-implemented here on gemmi's hierarchy, independently of
bake/structure/.

usage: pick_gemmi.py NANOVIEW PACKAGE STRUCTURE_DIR WORK_DIR
Renders the package's view at 64x64 with --ids, picks up to 12 pixels spread over the distinct atoms
hit (membrane and core), and checks each pick.
"""
import json
import os
import struct
import subprocess
import sys

import gemmi

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "structure"))
from compare_with_gemmi import four_character_residue_names, names_as_written  # noqa: E402

WATERS = {"HOH", "WAT", "DOD", "H2O"}
SIZE = 64
TOLERANCE = 2e-3  # Å: float32 storage of centred coordinates of a ~200 Å molecule


def selected_atoms(path):
    """nanobake's selection, in file order: [(chain, resname, seqnum, icode, name, element, altloc, pos)]."""
    # Chain parts unmerged: gemmi otherwise moves a chain's HETATM records (haem, glycans) next to
    # its ATOM records, while nanobake keeps file order.
    model = gemmi.read_structure(path, merge_chain_parts=False)[0]
    four_letters = four_character_residue_names(path)
    order, best = [], {}
    for chain in model:
        for residue in chain:
            chain_name, residue_name = names_as_written(chain, residue, four_letters)
            if residue_name in WATERS:
                continue
            for atom in residue:
                key = (chain_name, residue.seqid.num, residue.seqid.icode.strip(), atom.name)
                element = "H" if atom.element.name == "D" else atom.element.name
                entry = (atom.occ, (chain_name, residue_name, residue.seqid.num, residue.seqid.icode.strip(), atom.name,
                                    element.upper(), atom.altloc.strip("\0 "), (atom.pos.x, atom.pos.y, atom.pos.z)))
                if key not in best:
                    order.append(key)
                    best[key] = entry
                elif atom.occ > best[key][0]:
                    best[key] = entry
    return [best[k][1] for k in order]


def residue_groups(atoms):
    groups, start = [], 0
    for i in range(1, len(atoms) + 1):
        if i == len(atoms) or atoms[i][0] != atoms[start][0] or atoms[i][2:4] != atoms[start][2:4]:
            groups.append(atoms[start:i])
            start = i
    return groups


def mean(group):
    n = len(group)
    return [sum(a[7][k] for a in group) / n for k in range(3)]


def matches(group, index, pick):
    if index >= len(group):
        return False
    chain, resname, num, icode, name, element, altloc, pos = group[index]
    a = pick["atom"]
    if (a["chain"], a["residue_name"], a["residue_number"], a.get("insertion_code", ""), a["name"], a["element"].upper(),
            a.get("alt_location", "")) != (chain, resname, num, icode, name, element, altloc):
        return False
    centre = mean(group)
    return all(abs(a["position"][k] + centre[k] - pos[k]) <= TOLERANCE for k in range(3))


def main():
    nanoview, package, structures, work = sys.argv[1:5]
    os.makedirs(work, exist_ok=True)
    env = dict(os.environ, LP_NUM_THREADS=os.environ.get("LP_NUM_THREADS", "4"))
    ids = os.path.join(work, "pick-gemmi.ids")
    subprocess.run([nanoview, "render", package, "-o", os.path.join(work, "pick-gemmi.png"), "--size", f"{SIZE}x{SIZE}",
                    "--ids", ids], check=True, env=env, stdout=subprocess.DEVNULL)
    data = open(ids, "rb").read()
    assert data[:8] == b"NUIDS001", "not an ids file"
    first_pixel = {}  # atom index -> (x, y, kind)
    for p in range(SIZE * SIZE):
        kind, = struct.unpack_from("<I", data, 16 + 48 * p + 12)
        atom, = struct.unpack_from("<I", data, 16 + 48 * p + 36)
        if atom != 0xFFFFFFFF and atom not in first_pixel:
            first_pixel[atom] = (p % SIZE, p // SIZE, kind)
    atoms = sorted(first_pixel)
    if len(atoms) < 12:
        sys.exit(f"FAIL: only {len(atoms)} distinct atoms hit")
    chosen = {atoms[len(atoms) * k // 12] for k in range(12)}  # spread over the package's molecule types
    chosen |= {next(a for a in atoms if first_pixel[a][2] == kind) for kind in (0, 1) if any(first_pixel[a][2] == kind for a in atoms)}

    # Every chosen pixel in one pick (a line of JSON each, in the order asked).
    chosen = sorted(chosen)
    pixels = [str(v) for atom in chosen for v in first_pixel[atom][:2]]
    lines = subprocess.run([nanoview, "pick", package, "--size", f"{SIZE}x{SIZE}", *pixels], check=True, env=env,
                           stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True).stdout.splitlines()
    if len(lines) != len(chosen):
        sys.exit(f"FAIL: pick printed {len(lines)} lines for {len(chosen)} pixels")
    cache, failures, sources, kinds = {}, 0, set(), set()
    for atom, out in zip(chosen, lines):
        x, y, _ = first_pixel[atom]
        pick = json.loads(out)
        if (pick.get("x"), pick.get("y")) != (x, y):
            print(f"FAIL ({x}, {y}): pick answered for pixel ({pick.get('x')}, {pick.get('y')})")
            failures += 1
            continue
        if pick.get("hit") is not True or "error" in pick or pick["atom"]["index"] != atom:
            print(f"FAIL ({x}, {y}): pick does not name atom {atom} of the ids file: {out.strip()}")
            failures += 1
            continue
        source = pick["molecule"]["source"]
        if source not in cache:
            cache[source] = residue_groups(selected_atoms(os.path.join(structures, source)))
        groups = cache[source]
        candidates = [g for g in ([sum(groups, [])] if len(groups) > 1 else []) + groups
                      if matches(g, pick["atom"]["index_in_molecule"], pick)]
        a = pick["atom"]
        what = (f"({x}, {y}) atom {atom}: {a['name']} {a['residue_name']} {a['residue_number']}{a.get('insertion_code', '')} "
                f"chain {a['chain']} of {pick['molecule']['name']} ({source}), {pick['placement']['kind']}")
        if len(candidates) != 1:
            print(f"FAIL {what}: {len(candidates)} atoms of {source} match (gemmi)")
            failures += 1
        else:
            print(f"ok   {what}")
            sources.add(source)
            kinds.add(pick["placement"]["kind"])
    if failures:
        sys.exit(f"FAIL: {failures} pick(s) disagree with gemmi")
    if len(sources) < 2 or len(kinds) < 2:
        sys.exit(f"FAIL: the picks cover too little: sources {sorted(sources)}, kinds {sorted(kinds)}")
    print(f"all {len(chosen)} picks agree with gemmi ({len(sources)} source files, {sorted(kinds)})")


if __name__ == "__main__":
    main()
