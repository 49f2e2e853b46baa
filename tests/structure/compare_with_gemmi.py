#!/usr/bin/python3
"""Oracle test: `nanobake inspect --json` against gemmi with the same selection policy,
implemented here independently on gemmi's hierarchy.

Policy (bake/structure/selection.hpp): first model; waters (HOH WAT DOD H2O) removed by residue
name; hydrogens kept; then one atom per (chain, residue number, insertion code, atom name), the
highest occupancy winning and the first in the file winning ties. Deuterium counts as H.

usage: compare_with_gemmi.py NANOBAKE DIR_OR_GLOB...
A DIR_OR_GLOB that matches nothing is reported as skipped.

Every plain PDB file is also compared a second time with columns 77-80 (element, charge) cut
off, so that both programs must infer elements from atom names (gemmi's inference is the oracle).
"""
import glob
import json
import os
import subprocess
import sys
import gzip
import tempfile

import gemmi

WATERS = {"HOH", "WAT", "DOD", "H2O"}
TOLERANCE = 1e-3
EXTENSIONS = (".pdb", ".cif", ".ent", ".pdb.gz", ".cif.gz", ".ent.gz")


def four_character_residue_names(path):
    """True when ATOM/HETATM lines use column 21 (CHARMM's four-character residue names, as
    scripts/build_lipid_patch.py writes CHL1, POPC): gemmi then reads that column as the first of a
    two-character chain ID, nanobake as the residue name's last letter."""
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "rt", errors="replace") as f:
        return any(line.startswith(("ATOM  ", "HETATM")) and len(line) > 21 and line[20] != " " for line in f)


def names_as_written(chain, residue, four_letters):
    """(chain ID, residue name) as the file means them: in a file of four-character residue names
    (four_character_residue_names), gemmi's two-character chain is the name's 4th letter + the chain."""
    if four_letters and len(chain.name) == 2:
        return chain.name[1], residue.name + chain.name[0]
    return chain.name, residue.name


def expected_from_gemmi(path):
    st = gemmi.read_structure(path)
    four_letters = four_character_residue_names(path)
    if len(st) == 0:
        raise ValueError("gemmi reads no model from it")
    model = st[0]
    kept = {}  # key -> [occupancy, position, element, chain]
    for chain in model:
        for residue in chain:
            chain_name, residue_name = names_as_written(chain, residue, four_letters)
            if residue_name in WATERS:
                continue
            for atom in residue:  # gemmi keeps every altloc as its own atom
                key = (chain_name, residue.seqid.num, residue.seqid.icode.strip(), atom.name)
                element = "H" if atom.element.name == "D" else atom.element.name
                entry = [atom.occ, atom.pos, element, chain_name, atom.serial]
                if key not in kept:
                    kept[key] = entry
                elif atom.occ > kept[key][0]:
                    kept[key] = entry
    atoms = list(kept.values())
    n = len(atoms)
    if n == 0:
        return {"atoms": 0, "models": len(st)}
    xs = [a[1].x for a in atoms]
    ys = [a[1].y for a in atoms]
    zs = [a[1].z for a in atoms]
    elements = {}
    chains = []
    for a in atoms:
        elements[a[2]] = elements.get(a[2], 0) + 1
        if a[3] not in chains:
            chains.append(a[3])
    return {
        "atoms": n,
        "models": len(st),
        "chains": chains,
        "elements": elements,
        "centroid": [sum(xs) / n, sum(ys) / n, sum(zs) / n],
        "aabb": [[min(xs), min(ys), min(zs)], [max(xs), max(ys), max(zs)]],
    }


def differences(got, want):
    out = []
    for key in ("atoms", "models", "chains", "elements"):
        if got.get(key) != want[key]:
            out.append(f"{key}: nanobake {got.get(key)!r} vs gemmi {want[key]!r}")
    for key, values_got, values_want in (
        ("centroid", [got["centroid"]], [want["centroid"]]),
        ("aabb", got["aabb"], want["aabb"]),
    ):
        worst = max(abs(a - b) for vg, vw in zip(values_got, values_want) for a, b in zip(vg, vw))
        if worst > TOLERANCE:
            out.append(f"{key}: off by {worst:.6f} A: nanobake {values_got} vs gemmi {values_want}")
    return out


def structure_files(sources):
    files = []
    for source in sources:
        if os.path.isdir(source):
            found = sorted(os.path.join(source, f) for f in os.listdir(source) if f.lower().endswith(EXTENSIONS))
        else:
            found = sorted(glob.glob(source))
        if not found:
            print(f"SKIP {source}: no structure files there (folder absent?)")
        files.extend(found)
    return files


def without_element_columns(index, path, folder):
    stripped = os.path.join(folder, f"no_element_columns_{index}_" + os.path.basename(path))
    with open(path, errors="surrogateescape") as src, open(stripped, "w", errors="surrogateescape") as dst:
        for line in src:
            dst.write(line.rstrip("\n")[:76] + "\n" if line.startswith(("ATOM", "HETATM")) else line)
    return stripped


def main():
    nanobake, sources = sys.argv[1], sys.argv[2:]
    passed = failed = 0
    unreadable = []
    scratch = tempfile.TemporaryDirectory()
    files = structure_files(sources)
    plain_pdb = [f for f in files if f.lower().endswith((".pdb", ".ent"))]
    files += [without_element_columns(i, f, scratch.name) for i, f in enumerate(plain_pdb)]
    for path in files:
        try:
            want = expected_from_gemmi(path)
        except Exception as e:  # gemmi cannot read it: not a usable oracle for this file
            unreadable.append(f"{path} ({e or type(e).__name__})")
            continue
        run = subprocess.run([nanobake, "inspect", "--json", path], capture_output=True, text=True)
        if want["atoms"] == 0:  # nothing to inspect: nanobake must refuse with an error, not crash
            if run.returncode == 1 and run.stderr.startswith("nanobake: error: "):
                print(f"ok   {path}: no atoms, rejected: {run.stderr.strip()}")
                passed += 1
            else:
                print(f"FAIL {path}: gemmi finds no atoms but nanobake exit {run.returncode}: {run.stderr.strip()}")
                failed += 1
            continue
        if run.returncode != 0:
            print(f"FAIL {path}: nanobake exit {run.returncode}: {run.stderr.strip()}")
            failed += 1
            continue
        diffs = differences(json.loads(run.stdout), want)
        if diffs:
            print(f"FAIL {path}:\n    " + "\n    ".join(diffs))
            failed += 1
        else:
            print(f"ok   {path}: {want['atoms']} atoms, {want['models']} model(s), chains {''.join(want['chains']) or '(blank)'}")
            passed += 1
    for entry in unreadable:
        print(f"SKIP {entry}: gemmi cannot read it")
    print(f"{passed} passed, {failed} failed")
    return 1 if failed or passed == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
