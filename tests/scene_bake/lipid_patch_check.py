#!/usr/bin/python3
"""Is a lipid patch written by scripts/build_lipid_patch.py what its REMARKs say it is? Read with gemmi.

  lipid_patch_check.py PATCH.pdb[.gz] [PATCH ...]

Reads each patch with python3-gemmi (independent of nanobake's PDB reader and of the builder's own
reader) and checks: a CRYST1 record with positive a, b and right angles; no hydrogens; per chain (A outer,
B inner) the residue names and counts equal the "COUNT A:" / "COUNT B:" REMARKs; each residue's share
of its leaflet is within 2 percentage points of the "REQUEST" REMARK; no two heavy atoms of different
residues closer than 0.6 x (r1 + r2) (C 1.70, N 1.55, O 1.52, P 1.80, S 1.80 Å), periodic images in
x and y included. Needs no OpenMM, RDKit or packmol.
Prints one line per check and exits 0 when every patch passes, 1 when any check fails, 2 on bad
arguments or a missing python3-gemmi.
"""
import collections
import gzip
import os
import re
import sys

DEBIAN_PYTHON = "/usr/bin/python3"  # where Debian's python3-gemmi lives, if the python3 on PATH is another

try:
    import gemmi
except ImportError:
    if os.path.realpath(sys.executable) != os.path.realpath(DEBIAN_PYTHON) and os.path.exists(DEBIAN_PYTHON):
        os.execv(DEBIAN_PYTHON, [DEBIAN_PYTHON] + sys.argv)
    print("lipid_patch_check: needs python3-gemmi (apt-get install -y python3-gemmi)", file=sys.stderr)
    sys.exit(2)

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "structure"))
from compare_with_gemmi import names_as_written  # noqa: E402

RADIUS = {"C": 1.70, "N": 1.55, "O": 1.52, "P": 1.80, "S": 1.80}
CLASH_FACTOR = 0.6
MAX_DEVIATION_PP = 2.0


def patch_text(path):
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "rt") as f:
        return f.read()


def remark_compositions(text, key):
    """{'A': {'CHL1': 43.0, ...}, 'B': {...}} from the 'REMARK 999 <KEY> A: NAME=VALUE ...' lines."""
    found = {}
    for chain, pairs in re.findall(rf"^REMARK 999 {key} ([AB]): (.*)$", text, flags=re.MULTILINE):
        found[chain] = {name: float(value) for name, value in re.findall(r"(\w+)=([\d.]+)", pairs)}
    return found


def residue_counts(model):
    """Residues per leaflet chain and name. gemmi 0.5 reads a residue name from columns 18-20 and a chain id
    from columns 21-22, so a CHARMM name's 4th character (CHL1, POPC: column 21) arrives as the first of a
    two-character chain id ('1A'); names_as_written puts it back."""
    counts = collections.defaultdict(collections.Counter)
    for chain in model:
        for residue in chain:
            chain_name, residue_name = names_as_written(chain, residue, True)
            counts[chain_name][residue_name] += 1
    return counts


def check_cell(structure, text):
    cell = structure.cell
    if not re.search(r"^CRYST1", text, flags=re.MULTILINE):
        return "no CRYST1 record"
    if not (cell.a > 0 and cell.b > 0) or any(abs(angle - 90.0) > 1e-3 for angle in (cell.alpha, cell.beta, cell.gamma)):
        return f"CRYST1 is not an orthogonal box with positive a, b ({cell})"
    return None


def check_hydrogens(model):
    hydrogens = sum(1 for chain in model for residue in chain for atom in residue if atom.element.name in ("H", "D"))
    return f"{hydrogens} hydrogen atoms" if hydrogens else None


def check_counts(counts, text):
    remarked = remark_compositions(text, "COUNT")
    if set(remarked) != {"A", "B"}:
        return "no 'COUNT A:' and 'COUNT B:' REMARKs"
    for chain in ("A", "B"):
        listed = {name: int(n) for name, n in remarked[chain].items()}
        if dict(counts.get(chain, {})) != listed:
            return f"chain {chain} holds {dict(counts.get(chain, {}))}, the REMARK says {listed}"
    if set(counts) - {"A", "B"}:
        return f"chains other than A and B: {sorted(set(counts) - {'A', 'B'})}"
    return None


def check_fractions(counts, text):
    requested = remark_compositions(text, "REQUEST")
    if set(requested) != {"A", "B"}:
        return "no 'REQUEST A:' and 'REQUEST B:' REMARKs"
    for chain in ("A", "B"):
        total = sum(counts[chain].values())
        for name in set(requested[chain]) | set(counts[chain]):
            share = 100.0 * counts[chain].get(name, 0) / total
            asked = requested[chain].get(name, 0.0)
            if abs(share - asked) > MAX_DEVIATION_PP:
                return f"chain {chain}: {name} is {share:.1f} % of the leaflet, {asked:g} % was asked"
    return None


def clashes(structure):
    """Pairs of heavy atoms of different residues closer than CLASH_FACTOR x (r1 + r2); gemmi finds the
    neighbours through the cell's images, the distance is taken with images in x and y only."""
    model, cell = structure[0], structure.cell
    reach = CLASH_FACTOR * 2.0 * max(RADIUS.values())
    search = gemmi.NeighborSearch(model, cell, 5.0).populate()
    found = set()
    for ci, chain in enumerate(model):
        for ri, residue in enumerate(chain):
            for ai, atom in enumerate(residue):
                for mark in search.find_atoms(atom.pos, "\0", radius=reach):
                    key = (mark.chain_idx, mark.residue_idx)
                    if key == (ci, ri):
                        continue
                    other = mark.to_cra(model).atom
                    dx = other.pos.x - atom.pos.x
                    dy = other.pos.y - atom.pos.y
                    dx -= round(dx / cell.a) * cell.a
                    dy -= round(dy / cell.b) * cell.b
                    dz = other.pos.z - atom.pos.z
                    limit = CLASH_FACTOR * (RADIUS.get(atom.element.name, 1.7) + RADIUS.get(other.element.name, 1.7))
                    if (dx * dx + dy * dy + dz * dz) ** 0.5 < limit:
                        found.add(tuple(sorted([(ci, ri, ai), (mark.chain_idx, mark.residue_idx, mark.atom_idx)])))
    return len(found)


def check_patch(path):
    """(check name, problem or None) for each check of one patch."""
    text = patch_text(path)
    structure = gemmi.read_pdb_string(text)
    structure.setup_entities()
    model = structure[0]
    counts = residue_counts(model)
    results = [("CRYST1", check_cell(structure, text)), ("no hydrogens", check_hydrogens(model)),
               ("counts match the REMARKs", check_counts(counts, text))]
    fractions_problem = check_fractions(counts, text) if results[-1][1] is None else "counts unreadable"
    results.append(("fractions within 2 pp of the request", fractions_problem))
    pairs = clashes(structure) if results[0][1] is None else None
    results.append((f"no clash at {CLASH_FACTOR} x (r1 + r2)",
                    None if pairs == 0 else f"{pairs} pairs" if pairs is not None else "no box to look across"))
    return results


def main():
    paths = sys.argv[1:]
    if not paths or any(p.startswith("-") for p in paths):
        print("usage: " + __doc__.strip().splitlines()[2].strip(), file=sys.stderr)
        return 2
    failed = False
    for path in paths:
        if not os.path.isfile(path):
            print(f"lipid_patch_check: {path}: no such file", file=sys.stderr)
            return 2
        for name, problem in check_patch(path):
            print(f"{os.path.basename(path)}: {name}: {'ok' if problem is None else 'FAILED: ' + problem}")
            failed |= problem is not None
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
