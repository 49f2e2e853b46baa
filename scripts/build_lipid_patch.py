#!/usr/bin/python3
"""Build a periodic, mixed, asymmetric lipid bilayer patch (heavy atoms, CHARMM36 names) from Debian packages only.

  build_lipid_patch.py --outer CHL1=43,POPC=27,PSM=24,POPE=6 --inner CHL1=43,POPE=26,POPS=17,POPC=8,PSM=6
                       --out data/structures/rbc_bilayer.pdb.gz [--per-leaflet 100] [--seed 1]
                       [--area-per-molecule A] [--target-dpp D] [--md-ps 9] [--threads 1] [--reference auto|rbc|popc|none]
  build_lipid_patch.py --measure FILE.pdb[.gz] [--reference ...]

--outer is the leaflet at larger z (chain A), --inner the one at smaller z (chain B); each is a list of
CHARMM36 residue names with mole percentages adding up to 100 (± 0.5). Known residues: see SPECIES below
(run --help). Both leaflets get --per-leaflet molecules, whole numbers whose fractions must stay within
2 percentage points of the request (the error names sizes that work).

How a patch is made (Debian: python3-rdkit, packmol, python3-simtk + libopenmm-plugins = OpenMM 7.7,
python3-networkx; run with the Debian python3):
  1. each species from its SMILES (stereo included): RDKit ETKDG conformers (fixed seed), tails set all-trans
     (double bonds untouched, so cis stays cis), linker torsions searched so the tails lie side by side,
     MMFF-relaxed with the tail torsions held; the slimmest ones that can stand upright are kept;
  2. atom names from the charmm36.xml residue template by graph matching (elements + bonds, networkx);
  3. packmol packs each leaflet upright at 1.25 x the target area (heads in a height band, tail ends below
     a plane; packmol 20.14 has no periodic boxes, so atoms keep 1 A off the box faces), TIP3P water above
     and below, Na+ beside each leaflet to neutralise its anionic lipids; its best try is taken as it is;
  4. OpenMM CHARMM36 on the CPU: minimise; squeeze the box to the target area in steps while a restraint
     pulls the heads to the target P-P thickness (all-trans lipids start too thick); Langevin MD at 310 K
     under a membrane barostat (tension 0), steered, then free for the last --release-ps; minimise again;
  5. heavy lipid atoms written as PDB (CRYST1 = the box, residues wrapped by centroid into [0,a)x[0,b),
     chain A outer, chain B inner), REMARKs with the provenance and measurements, gzip -n -9, written under
     a temporary name and renamed.
The build writes nothing and exits 1 when the patch has any clash at 0.6 x (r1 + r2), a lipid whose R/S or
cis/trans configuration changed, a stretched bond, a bond through a ring or a lipid on the wrong side.
--measure only measures an existing patch (area per lipid, D_PP, clashes at 0.6/0.8/1.0 x).
Exit status: 0 fine, 1 failed check, 2 bad arguments or missing packages.
"""
import argparse
import collections
import gzip
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time

APT_PACKAGES = "python3-rdkit packmol python3-simtk libopenmm-plugins python3-networkx python3-numpy"

# Bondi radii (Å), the baker's clash rule; unknown elements get carbon's.
VDW_RADIUS = {"C": 1.70, "N": 1.55, "O": 1.52, "P": 1.80, "S": 1.80}
CLASH_FACTORS = (0.6, 0.8, 1.0)
TEMPERATURE_K = 310.0

PALMITOYL = "CCCCCCCCCCCCCCCC(=O)"
OLEOYL = "CCCCCCCC/C=C\\CCCCCCCC(=O)"
OLEOYL_FROM_CARBONYL = "C(=O)CCCCCCC/C=C\\CCCCCCCC"


def palmitoyl_oleoyl_glycerophospho(head):
    """1-palmitoyl-2-oleoyl-sn-glycero-3-phospho-<head>; the [C@H] makes glycerol C2 R (sn-3 phosphate)."""
    return f"{PALMITOYL}OC[C@H](COP(=O)([O-])O{head})O{OLEOYL_FROM_CARBONYL}"


def dioleoyl_glycerophospho_arm():
    """1,2-dioleoyl-sn-glycero-3-phospho, written from its phosphate; glycerol C2 is R as in the PC above."""
    return f"P(=O)([O-])OC[C@H](O{OLEOYL_FROM_CARBONYL})CO{OLEOYL_FROM_CARBONYL}"


Species = collections.namedtuple("Species", "smiles pdb_name area description")

# area: Å² per molecule in one leaflet, used only to size the box before the barostat (fluid single-lipid
# bilayers near 30 °C; cholesterol by its partial area in PC bilayers). pdb_name: the PDB residue-name
# field holds 4 characters, so TOCL2 is written as TOCL.
SPECIES = {
    "POPC": Species(palmitoyl_oleoyl_glycerophospho("CC[N+](C)(C)C"), "POPC", 64.0, "POPC (PC 16:0/18:1)"),
    "POPE": Species(palmitoyl_oleoyl_glycerophospho("CC[NH3+]"), "POPE", 58.0, "POPE (PE 16:0/18:1)"),
    "POPS": Species(palmitoyl_oleoyl_glycerophospho("C[C@H]([NH3+])C(=O)[O-]"), "POPS", 62.0,
                    "POPS (PS 16:0/18:1, L-serine, charge -1)"),
    "POPI": Species(palmitoyl_oleoyl_glycerophospho("[C@H]1[C@H](O)[C@@H](O)[C@H](O)[C@@H](O)[C@H]1O"), "POPI",
                    66.0, "POPI (PI 16:0/18:1, 1D-myo-inositol, charge -1)"),
    "PSM": Species("CCCCCCCCCCCCC/C=C/[C@@H](O)[C@H](COP(=O)([O-])OCC[N+](C)(C)C)NC(=O)CCCCCCCCCCCCCCC", "PSM",
                   55.0, "PSM (N-palmitoyl-D-erythro-sphingomyelin, 2S,3R,4E)"),
    "CHL1": Species("C[C@H](CCCC(C)C)[C@H]1CC[C@@H]2[C@@]1(CC[C@H]3[C@H]2CC=C4[C@@]3(CC[C@@H](C4)O)C)C", "CHL1",
                    27.0, "cholesterol"),
    "TOCL2": Species(f"{OLEOYL}OC[C@H](COP(=O)([O-])OCC(O)CO{dioleoyl_glycerophospho_arm()})O{OLEOYL_FROM_CARBONYL}",
                     "TOCL", 130.0, "tetraoleoyl cardiolipin (CL 4x18:1, charge -2)"),
}

# Published values the measurements are compared with; [verified] = read in the cited page here.
Reference = collections.namedtuple("Reference", "area_low area_high dpp_low dpp_high sources")
REFERENCES = {
    "rbc": Reference(40.0, 50.0, 44.0, 47.0, [
        "area 40-50 A2 per molecule: 'each lipid molecule in average occupies 0.4-0.5 nm2', BioNumbers "
        "BNID 114186, from atomistic simulations of cholesterol/PSM/POPC raft mixtures (Niemela et al. 2007 "
        "PLoS Comput Biol 3:e34) [verified, BioNumbers page]",
        "D_PP 44-47 A for a cholesterol-rich PC/SM bilayer [unverified: the range the task gave]; lipids "
        "extracted from human red cells form lamellae with a 45 A thick lipid layer (Rand 1968 J Gen "
        "Physiol 52:173, abstract) [verified]"]),
    "popc": Reference(64.0, 64.0, 37.0, 39.1, [
        "POPC bilayer: area 0.64 nm2 per lipid and D_HH 3.7 nm from experiment (Kucerka et al.), D_HH 3.91 nm "
        "with CHARMM36 (ACS Omega 2020 5:18080, Table 1, PMC7391366) [verified]; the virion envelope is "
        "59 % POPC, so POPC stands in for the mixture"]),
}


def fail_usage(message):
    print(f"build_lipid_patch: {message}", file=sys.stderr)
    sys.exit(2)


# ---------------------------------------------------------------------------------------------- composition

def parse_composition(text, option):
    """'CHL1=43,POPC=27' -> {'CHL1': 43.0, 'POPC': 27.0}; any mistake is a usage error naming the option."""
    fractions = {}
    for item in filter(None, (part.strip() for part in text.split(","))):
        name, equals, value = item.partition("=")
        name = name.strip().upper()
        if not equals:
            fail_usage(f"{option}: '{item}' is not NAME=PERCENT")
        if name not in SPECIES:
            fail_usage(f"{option}: unknown residue '{name}' (known: {', '.join(sorted(SPECIES))})")
        if name in fractions:
            fail_usage(f"{option}: '{name}' is given twice")
        try:
            percent = float(value)
        except ValueError:
            fail_usage(f"{option}: '{value}' after {name}= is not a number")
        if not percent > 0 or not math.isfinite(percent):
            fail_usage(f"{option}: {name}={value} must be a positive percentage")
        fractions[name] = percent
    total = sum(fractions.values())
    if not fractions or abs(total - 100.0) > 0.5:
        fail_usage(f"{option}: the percentages add up to {total:g}, not 100 (± 0.5)")
    return fractions


def whole_counts(percentages, total):
    """Largest-remainder rounding of percentages to `total` molecules (ties broken by name: reproducible)."""
    exact = {name: p * total / 100.0 for name, p in percentages.items()}
    counts = {name: int(math.floor(x)) for name, x in exact.items()}
    by_remainder = sorted(exact, key=lambda name: (-(exact[name] - counts[name]), name))
    for name in by_remainder[:total - sum(counts.values())]:
        counts[name] += 1
    return counts


def worst_deviation_pp(percentages, counts):
    total = sum(counts.values())
    return max(abs(100.0 * counts[name] / total - p) for name, p in percentages.items())


def leaflet_counts(percentages, total, option):
    """Whole counts within 2 pp of the request, or a usage error naming sizes (90-130) that would work."""
    counts = whole_counts(percentages, total)
    if worst_deviation_pp(percentages, counts) <= 2.0 and all(counts.values()):
        return counts
    working = [n for n in range(90, 131)
               if worst_deviation_pp(percentages, whole_counts(percentages, n)) <= 2.0
               and all(whole_counts(percentages, n).values())]
    fail_usage(f"{option}: {total} molecules cannot hold these fractions within 2 percentage points "
               f"(sizes that can: {', '.join(map(str, working)) or 'none in 90-130'})")


# ---------------------------------------------------------------------------------------------- packages

def import_build_packages():
    """The heavy modules, imported only to build; a missing one is exit 2 naming the apt packages."""
    try:
        import networkx  # noqa: F401
        import numpy  # noqa: F401
        import openmm
        import rdkit  # noqa: F401
    except ImportError as error:
        fail_usage(f"missing Python package ({error.name}); install with: apt-get install -y {APT_PACKAGES} "
                   f"(and run with the Debian python3, /usr/bin/python3)")
    platforms = [openmm.Platform.getPlatform(i).getName() for i in range(openmm.Platform.getNumPlatforms())]
    if "CPU" not in platforms:
        fail_usage(f"OpenMM has no CPU platform (only {', '.join(platforms)}); install with: "
                   f"apt-get install -y libopenmm-plugins")
    if shutil.which("packmol") is None:
        fail_usage(f"packmol not found on PATH; install with: apt-get install -y {APT_PACKAGES}")


def debian_version(package):
    try:
        out = subprocess.run(["dpkg-query", "-W", "-f=${Version}", package], capture_output=True, text=True)
        return out.stdout.strip() or "unknown"
    except OSError:
        return "unknown"


def package_versions():
    return {p: debian_version(p) for p in ("python3-rdkit", "packmol", "python3-simtk", "libopenmm-plugins",
                                           "python3-networkx")}


# ---------------------------------------------------------------------------------------------- templates

Template = collections.namedtuple("Template", "names elements types bonds charge")


def charmm36_path():
    import openmm.app
    return os.path.join(os.path.dirname(openmm.app.__file__), "data", "charmm36.xml")


def read_templates(residue_names):
    """The charmm36.xml residue templates asked for: atom names, elements (from the atom types), bonds."""
    import xml.etree.ElementTree as ElementTree
    element_of_type, templates = {}, {}
    for _, node in ElementTree.iterparse(charmm36_path()):
        if node.tag == "Type":
            element_of_type[node.get("name")] = node.get("element")
        elif node.tag == "Residue" and node.get("name") in residue_names:
            atoms = node.findall("Atom")
            names = [a.get("name") for a in atoms]
            index = {name: i for i, name in enumerate(names)}
            bonds = [(index[b.get("atomName1")], index[b.get("atomName2")]) for b in node.findall("Bond")]
            types = [a.get("type") for a in atoms]
            templates[node.get("name")] = Template(names, [element_of_type[t] for t in types], types, bonds,
                                                   round(sum(float(a.get("charge")) for a in atoms)))
        if node.tag == "Residue":
            node.clear()
    missing = sorted(set(residue_names) - set(templates))
    if missing:
        fail_usage(f"charmm36.xml has no residue template for {', '.join(missing)}")
    return templates


def read_lennard_jones():
    """{atom type: (sigma nm, epsilon kJ/mol)} from the LennardJonesForce sections of charmm36.xml and
    charmm36/water.xml."""
    import xml.etree.ElementTree as ElementTree
    parameters = {}
    for path in (charmm36_path(), os.path.join(os.path.dirname(charmm36_path()), "charmm36", "water.xml")):
        inside = False
        for event, node in ElementTree.iterparse(path, events=("start", "end")):
            if node.tag == "LennardJonesForce":
                inside = event == "start"
            elif inside and event == "start" and node.tag == "Atom":
                parameters[node.get("type")] = (float(node.get("sigma")), float(node.get("epsilon")))
    return parameters


def template_atom_names(mol, template, residue):
    """CHARMM36 atom name and type of each RDKit atom: a graph isomorphism on elements and bonds (symmetric atoms such
    as the two free phosphate oxygens or the methyl hydrogens get either of their equivalent names)."""
    import networkx
    from networkx.algorithms import isomorphism
    ours, theirs = networkx.Graph(), networkx.Graph()
    ours.add_nodes_from((a.GetIdx(), {"element": a.GetSymbol()}) for a in mol.GetAtoms())
    ours.add_edges_from((b.GetBeginAtomIdx(), b.GetEndAtomIdx()) for b in mol.GetBonds())
    theirs.add_nodes_from((i, {"element": e}) for i, e in enumerate(template.elements))
    theirs.add_edges_from(template.bonds)
    matcher = isomorphism.GraphMatcher(ours, theirs, node_match=lambda x, y: x["element"] == y["element"])
    if not matcher.is_isomorphic():
        sys.exit(f"build_lipid_patch: the SMILES of {residue} does not match the charmm36.xml template "
                 f"({mol.GetNumAtoms()} vs {len(template.names)} atoms)")
    order = [matcher.mapping[i] for i in range(mol.GetNumAtoms())]
    return [template.names[k] for k in order], [template.types[k] for k in order]


# ---------------------------------------------------------------------------------------------- conformers

Conformer = collections.namedtuple("Conformer", "residue elements names types positions heads tail_ends bonds")


def head_atoms(mol):
    """Phosphorus atoms, or for a sterol its oxygen: what packmol holds near the water."""
    phosphorus = [a.GetIdx() for a in mol.GetAtoms() if a.GetSymbol() == "P"]
    return phosphorus or [a.GetIdx() for a in mol.GetAtoms() if a.GetSymbol() == "O"]


def tail_end_atoms(mol, heads):
    """Chain-end methyl carbons: at least 80 % as many bonds from the head as the farthest methyl (so a
    choline's or cholesterol's ring methyls are not ends, the acyl and iso-octyl ends are)."""
    from rdkit import Chem
    distance = Chem.GetDistanceMatrix(mol)
    methyls = [a.GetIdx() for a in mol.GetAtoms()
               if a.GetSymbol() == "C" and sum(n.GetSymbol() != "H" for n in a.GetNeighbors()) == 1]
    reach = {m: min(distance[h][m] for h in heads) for m in methyls}
    farthest = max(reach.values())
    return sorted(m for m in methyls if reach[m] >= 0.8 * farthest)


def path_torsions(mol, heads, tail_ends):
    """Torsions about single, non-ring bonds on each head-to-end path, ordered from the head so that
    setting one moves only the end's side."""
    from rdkit import Chem
    torsions = []
    for end in tail_ends:
        head = min(heads, key=lambda h: len(Chem.GetShortestPath(mol, h, end)))
        path = list(Chem.GetShortestPath(mol, head, end))
        for a, b, c, d in zip(path, path[1:], path[2:], path[3:]):
            bond = mol.GetBondBetweenAtoms(b, c)
            if bond.GetBondType() == Chem.BondType.SINGLE and not bond.IsInRing():
                torsions.append((a, b, c, d))
    return list(dict.fromkeys(torsions))


def is_chain_torsion(mol, torsion):
    """Four carbons whose middle two carry no oxygen or nitrogen: a hydrocarbon tail, set all-trans."""
    atoms = [mol.GetAtomWithIdx(i) for i in torsion]
    middle_hetero = any(n.GetSymbol() not in ("C", "H") for atom in atoms[1:3] for n in atom.GetNeighbors())
    return all(atom.GetSymbol() == "C" for atom in atoms) and not middle_hetero


def is_planar_link(mol, torsion):
    """An ester or amide C(=O)-X bond: left as ETKDG made it (trans), not searched."""
    b, c = (mol.GetAtomWithIdx(i) for i in torsion[1:3])
    def carbonyl(atom):
        return atom.GetSymbol() == "C" and any(bond.GetBondTypeAsDouble() == 2.0 and
                                               bond.GetOtherAtom(atom).GetSymbol() == "O" for bond in atom.GetBonds())
    return (carbonyl(b) and c.GetSymbol() in ("O", "N")) or (carbonyl(c) and b.GetSymbol() in ("O", "N"))


def shape_score(positions, shape):
    """Lateral spread plus a penalty for heavy atoms (4+ bonds apart) closer than 3.2 Å."""
    import numpy
    heavy = positions[shape.heavy]
    distances = numpy.linalg.norm(heavy[:, None] - heavy[None], axis=2)[shape.far_pairs]
    overlap = numpy.clip(3.2 - distances, 0.0, None)
    return lateral_spread(positions, shape) + 10.0 * float((overlap ** 2).sum())


def lateral_spread(positions, shape):
    """RMS distance (Å) of the heavy atoms from the line from the head(s) towards the mean tail end: small
    for a slim lipid whose tails run side by side (a conformer with its tails pointing apart scores badly)."""
    import numpy
    head = positions[shape.heads].mean(axis=0)
    axis = positions[shape.tail_ends].mean(axis=0) - head
    axis /= max(numpy.linalg.norm(axis), 1e-6)
    offsets = positions[shape.heavy] - head
    across = offsets - numpy.outer(offsets @ axis, axis)
    return math.sqrt(float((across ** 2).sum(axis=1).mean()))


Shape = collections.namedtuple("Shape", "heads tail_ends heavy far_pairs chain linker")


def lipid_shape(mol):
    """What the conformer search needs to know of a species: heads, ends, torsions, atom pairs to keep apart."""
    import numpy
    from rdkit import Chem
    heads = head_atoms(mol)
    tail_ends = tail_end_atoms(mol, heads)
    heavy = [a.GetIdx() for a in mol.GetAtoms() if a.GetSymbol() != "H"]
    bonds_apart = Chem.GetDistanceMatrix(mol)[numpy.ix_(heavy, heavy)]
    torsions = path_torsions(mol, heads, tail_ends)
    chain = [t for t in torsions if is_chain_torsion(mol, t)]
    linker = [t for t in torsions if t not in chain and not is_planar_link(mol, t)]
    return Shape(heads, tail_ends, heavy, numpy.triu(bonds_apart >= 4), chain, linker)


def set_chain_torsions(conformer, shape):
    from rdkit.Chem import rdMolTransforms
    for torsion in shape.chain:
        rdMolTransforms.SetDihedralDeg(conformer, *torsion, 180.0)


def fold_tails_together(conformer, shape, sweeps=3):
    """Coordinate descent over the linker torsions (30° steps) towards a slim lipid with parallel tails."""
    import numpy
    from rdkit.Chem import rdMolTransforms
    best = shape_score(numpy.array(conformer.GetPositions()), shape)
    for _ in range(sweeps):
        for torsion in shape.linker:
            kept = rdMolTransforms.GetDihedralDeg(conformer, *torsion)
            for angle in range(-180, 180, 30):
                rdMolTransforms.SetDihedralDeg(conformer, *torsion, float(angle))
                score = shape_score(numpy.array(conformer.GetPositions()), shape)
                if score < best:
                    best, kept = score, float(angle)
            rdMolTransforms.SetDihedralDeg(conformer, *torsion, kept)
    return best


def relax_with_straight_tails(mol, conf_id, shape, mmff_properties):
    """MMFF with the tail torsions held near 180° (double bonds are not tail torsions, so cis stays cis)."""
    from rdkit.Chem import rdForceFieldHelpers
    field = rdForceFieldHelpers.MMFFGetMoleculeForceField(mol, mmff_properties, confId=conf_id)
    for torsion in shape.chain:
        field.MMFFAddTorsionConstraint(*torsion, False, 170.0, 190.0, 100.0)
    field.Minimize(maxIts=1000)


def species_seed(seed, residue):
    import zlib
    return (seed * 7919 + zlib.crc32(residue.encode())) % (2 ** 31)


def fits_upright(positions, shape):
    """Can packmol stand this conformer up: heads level within 3 Å along the lipid's axis (both phosphates
    of a cardiolipin in the head zone) and every tail end at least 15 Å below them?"""
    import numpy
    head = positions[shape.heads].mean(axis=0)
    axis = positions[shape.tail_ends].mean(axis=0) - head
    axis /= max(numpy.linalg.norm(axis), 1e-6)
    head_heights = (positions[shape.heads] - head) @ axis
    end_depths = (positions[shape.tail_ends] - head) @ axis
    return float(numpy.ptp(head_heights)) <= 3.0 and float(end_depths.min()) >= 15.0


def straightened_conformers(mol, shape, properties, seed, count):
    """(score, positions) of `count` ETKDG conformers, tails all-trans and folded side by side, MMFF-relaxed."""
    import numpy
    from rdkit.Chem import AllChem
    params = AllChem.ETKDGv3()
    params.randomSeed, params.useRandomCoords, params.numThreads = seed, True, 1
    scored = []
    for conf_id in AllChem.EmbedMultipleConfs(mol, numConfs=count, params=params):
        set_chain_torsions(mol.GetConformer(conf_id), shape)
        fold_tails_together(mol.GetConformer(conf_id), shape)
        relax_with_straight_tails(mol, conf_id, shape, properties)
        positions = numpy.array(mol.GetConformer(conf_id).GetPositions())
        scored.append((shape_score(positions, shape), conf_id, positions))
    return scored


def build_conformers(residue, template, seed, tried, kept, rounds=4):
    """Up to `kept` of the slimmest conformers that packmol can stand upright, from rounds of `tried` ETKDG
    conformers; CHARMM-named. Also the RDKit molecule, holding the slimmest one."""
    from rdkit import Chem
    from rdkit.Chem import AllChem, rdForceFieldHelpers  # noqa: F401 (AllChem registers the MMFF classes)
    mol = Chem.AddHs(Chem.MolFromSmiles(SPECIES[residue].smiles))
    shape = lipid_shape(mol)
    properties = rdForceFieldHelpers.MMFFGetMoleculeProperties(mol)
    upright_ones = []
    for round_number in range(rounds):
        scored = straightened_conformers(mol, shape, properties, species_seed(seed + round_number, residue), tried)
        upright_ones += [item for item in scored if fits_upright(item[2], shape)]
        if len(upright_ones) >= kept:
            break
    if not upright_ones:
        sys.exit(f"build_lipid_patch: none of {rounds * tried} conformers of {residue} can stand upright; "
                 f"try a larger --conformers-tried")
    upright_ones.sort(key=lambda item: item[0])
    slimmest = upright_ones[:kept]
    mol.RemoveAllConformers()
    conformer = Chem.Conformer(mol.GetNumAtoms())
    for i, position in enumerate(slimmest[0][2]):
        conformer.SetAtomPosition(i, position.tolist())
    mol.AddConformer(conformer, assignId=True)
    names, types = template_atom_names(mol, template, residue)
    elements = [a.GetSymbol() for a in mol.GetAtoms()]
    bonds = [(b.GetBeginAtomIdx(), b.GetEndAtomIdx()) for b in mol.GetBonds()]
    return mol, [Conformer(residue, elements, names, types, positions, shape.heads, shape.tail_ends, bonds)
                 for _, _, positions in slimmest]


# ---------------------------------------------------------------------------------------------- packing

# Heights above the mid-plane (Å) packmol holds atoms to. All-trans tails are longer than a fluid leaflet
# is thick, so the packed bilayer starts upright and too thick (with interpenetrating leaflets packmol gets
# nowhere); OpenMM then pulls the heads down to the target thickness (head_height_restraint).
PHOSPHATE_ZONE = (23.5, 27.5)
HYDROXYL_ZONE = (19.0, 23.0)  # a sterol's OH sits near the phospholipids' ester carbonyls
TAIL_END_BELOW = 8.0
LIPID_REACH = 36.0
PAST_MIDPLANE = 1.0
WATER_FROM = 28.0
WATER_PER_A3 = 0.0334
PACKMOL_TOLERANCE = 2.0
SEAM = PACKMOL_TOLERANCE / 2.0
MAX_TILT_DEG = 10.0
# packmol rarely packs long all-trans lipids perfectly; after this many loops its best try goes to the minimiser.
PACKMOL_LOOPS = 30

Box = collections.namedtuple("Box", "a b c")
Placement = collections.namedtuple("Placement", "kind conformer chain count")  # kind: lipid, water, ion

WATER_NAMES = ("O", "H1", "H2")


def water_conformer():
    """TIP3P geometry (O-H 0.9572 Å, H-O-H 104.52°)."""
    import numpy
    half = math.radians(104.52) / 2
    positions = numpy.array([[0, 0, 0], [0.9572 * math.sin(half), 0.9572 * math.cos(half), 0],
                             [-0.9572 * math.sin(half), 0.9572 * math.cos(half), 0]])
    return Conformer("HOH", ["O", "H", "H"], list(WATER_NAMES), ["OT", "HT", "HT"], positions, [], [], [(0, 1), (0, 2)])


def sodium_conformer():
    import numpy
    return Conformer("SOD", ["Na"], ["SOD"], ["SOD"], numpy.zeros((1, 3)), [], [], [])


def box_for(area, molecules, water_per_lipid):
    """Square lateral box of the given area; z holds the bilayer and two water slabs (plus room for heads)."""
    side = math.sqrt(area)
    slab = water_per_lipid * molecules / 2.0 / (WATER_PER_A3 * area)
    return Box(side, side, 2.0 * (WATER_FROM + slab + 4.0))


def upright(conformer, sign):
    """The conformer turned so its head-to-tail axis runs along -sign·z (head up in the outer leaflet)."""
    import numpy
    positions = conformer.positions
    head = positions[conformer.heads].mean(axis=0)
    axis = positions[conformer.tail_ends].mean(axis=0) - head
    axis /= numpy.linalg.norm(axis)
    target = numpy.array([0.0, 0.0, -sign])
    v, c = numpy.cross(axis, target), float(axis @ target)
    if numpy.linalg.norm(v) < 1e-9:
        rotation = numpy.eye(3) if c > 0 else numpy.diag([1.0, -1.0, -1.0])
    else:
        k = numpy.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
        rotation = numpy.eye(3) + k + k @ k / (1.0 + c)  # Rodrigues: turns axis onto target
    return conformer._replace(positions=(positions - head) @ rotation.T)


def write_xyz(path, conformer):
    with open(path, "w") as out:
        out.write(f"{len(conformer.elements)}\n{conformer.residue}\n")
        for element, (x, y, z) in zip(conformer.elements, conformer.positions):
            out.write(f"{element} {x:.4f} {y:.4f} {z:.4f}\n")


def lateral_box(box, z_low, z_high):
    """packmol 20.14 has no periodic boxes (its `pbc` keyword came later): atoms stay SEAM inside each face,
    so copies across a face are at least the tolerance apart; the MD closes the seams."""
    return f"{SEAM:.3f} {SEAM:.3f} {z_low:.3f} {box.a - SEAM:.3f} {box.b - SEAM:.3f} {z_high:.3f}"


def lipid_block(path, placement, box):
    """A leaflet's copies of one conformer: inside its half of the box, heads in their zone, ends low."""
    sign = 1.0 if placement.chain == "A" else -1.0
    mid, conformer = box.c / 2.0, placement.conformer
    zone = PHOSPHATE_ZONE if conformer.elements[conformer.heads[0]] == "P" else HYDROXYL_ZONE
    low, high = sorted((mid - sign * PAST_MIDPLANE, mid + sign * LIPID_REACH))
    # packmol planes: "over plane a b c d" keeps a*x + b*y + c*z >= d; the inner leaflet is the mirror.
    head_low, head_high = sorted((mid + sign * zone[0], mid + sign * zone[1]))
    ends_limit = mid + sign * TAIL_END_BELOW
    ends_rule = f"below plane 0. 0. 1. {ends_limit:.3f}" if sign > 0 else f"over plane 0. 0. 1. {ends_limit:.3f}"
    heads = " ".join(str(i + 1) for i in conformer.heads)
    ends = " ".join(str(i + 1) for i in conformer.tail_ends)
    # The file holds the lipid upright; packmol may turn it freely about z but tilt it only a little,
    # else its optimiser leaves some copies upside down.
    return (f"structure {path}\n  number {placement.count}\n"
            f"  inside box {lateral_box(box, low, high)}\n"
            f"  constrain_rotation x 0. {MAX_TILT_DEG:.1f}\n  constrain_rotation y 0. {MAX_TILT_DEG:.1f}\n"
            f"  atoms {heads}\n    over plane 0. 0. 1. {head_low:.3f}\n    below plane 0. 0. 1. {head_high:.3f}\n"
            f"  end atoms\n  atoms {ends}\n    {ends_rule}\n  end atoms\nend structure\n")


def solvent_block(path, placement, box):
    """Water in both slabs (split evenly); ions in the slab beside the leaflet whose charge they balance."""
    mid = box.c / 2.0
    top = f"inside box {lateral_box(box, mid + WATER_FROM, box.c - SEAM)}"
    bottom = f"inside box {lateral_box(box, SEAM, mid - WATER_FROM)}"
    if placement.kind == "water":
        upper = placement.count // 2
        return (f"structure {path}\n  number {upper}\n  {top}\nend structure\n"
                f"structure {path}\n  number {placement.count - upper}\n  {bottom}\nend structure\n")
    return f"structure {path}\n  number {placement.count}\n  {top if placement.chain == 'A' else bottom}\nend structure\n"


def packmol_input(placements, box, seed, workdir):
    text = (f"tolerance {PACKMOL_TOLERANCE}\nseed {seed}\nfiletype xyz\noutput packed.xyz\n"
            f"nloop {PACKMOL_LOOPS}\nmovebadrandom\n\n")
    for number, placement in enumerate(placements):
        path = f"m{number}.xyz"
        sign = -1.0 if placement.chain == "B" else 1.0
        conformer = upright(placement.conformer, sign) if placement.kind == "lipid" else placement.conformer
        write_xyz(os.path.join(workdir, path), conformer)
        block = lipid_block if placement.kind == "lipid" else solvent_block
        text += block(path, placement, box) + "\n"
    return text


def run_packmol(placements, box, seed, workdir):
    """Packed coordinates in placement order; whether packmol reached its tolerance everywhere."""
    import numpy
    text = packmol_input(placements, box, seed, workdir)
    with open(os.path.join(workdir, "pack.inp"), "w") as f:
        f.write(text)
    with open(os.path.join(workdir, "pack.inp")) as stdin, open(os.path.join(workdir, "packmol.log"), "w") as log:
        status = subprocess.run(["packmol"], stdin=stdin, stdout=log, stderr=subprocess.STDOUT, cwd=workdir)
    with open(os.path.join(workdir, "packmol.log")) as f:
        log_text = f.read()
    # Without a perfect packing packmol leaves its best try as packed.xyz_FORCED; the minimiser takes it on.
    output = next((os.path.join(workdir, name) for name in ("packed.xyz", "packed.xyz_FORCED")
                   if os.path.exists(os.path.join(workdir, name))), None)
    if output is None:
        sys.exit(f"build_lipid_patch: packmol failed (status {status.returncode}); its log ends:\n{log_text[-2000:]}")
    with open(output) as f:
        lines = f.read().splitlines()
    positions = numpy.array([[float(v) for v in line.split()[1:4]] for line in lines[2:2 + int(lines[0])]])
    return positions, "Success!" in log_text


def split_over(count, parts):
    return [count // parts + (1 if i < count % parts else 0) for i in range(parts)]


def plan_placements(leaflets, conformers, templates, water_per_lipid):
    """Packmol's blocks in order: each leaflet's species (copies spread over the kept conformers), water,
    then Na+ per side for that leaflet's negative charge."""
    placements = []
    for chain, counts in leaflets:
        for residue, count in counts.items():
            kinds = conformers[residue]
            placements += [Placement("lipid", c, chain, n) for c, n in zip(kinds, split_over(count, len(kinds))) if n]
    molecules = sum(sum(counts.values()) for _, counts in leaflets)
    placements.append(Placement("water", water_conformer(), "W", int(round(water_per_lipid * molecules))))
    for chain, counts in leaflets:
        charge = sum(templates[r].charge * n for r, n in counts.items())
        if charge > 0:
            sys.exit(f"build_lipid_patch: leaflet {chain} is positive ({charge}); only Na+ counter-ions are placed")
        if charge < 0:
            placements.append(Placement("ion", sodium_conformer(), chain, -charge))
    return placements


# ---------------------------------------------------------------------------------------------- OpenMM

Molecule = collections.namedtuple("Molecule", "kind residue chain first count")  # atoms first..first+count-1


def build_topology(placements, box):
    """OpenMM topology in packmol's order; lipids carry their charmm36.xml residue and atom names, and are
    tied to their template by name (CHL1 and CLOL, say, have the same graph)."""
    from openmm import Vec3, unit
    from openmm.app import Element, Topology
    topology, molecules, chains, templates, atom_types = Topology(), [], {}, {}, []
    for placement in placements:
        chain_id = placement.chain if placement.kind == "lipid" else placement.kind[0].upper()  # W water, I ions
        if chain_id not in chains:
            chains[chain_id] = topology.addChain(chain_id)
        chain = chains[chain_id]
        conformer = placement.conformer
        for _ in range(placement.count):
            residue = topology.addResidue(conformer.residue, chain)
            if placement.kind == "lipid":
                templates[residue] = conformer.residue
            atoms = [topology.addAtom(name, Element.getBySymbol(element), residue)
                     for name, element in zip(conformer.names, conformer.elements)]
            for i, j in conformer.bonds:
                topology.addBond(atoms[i], atoms[j])
            atom_types += conformer.types
            molecules.append(Molecule(placement.kind, conformer.residue, placement.chain, atoms[0].index, len(atoms)))
    topology.setPeriodicBoxVectors([Vec3(box.a, 0, 0), Vec3(0, box.b, 0), Vec3(0, 0, box.c)] * unit.angstrom)
    return topology, molecules, templates, atom_types


def plain_lennard_jones(system, atom_types, lennard_jones):
    """CHARMM36's tabulated LJ (a CustomNonbondedForce) moved into the NonbondedForce with Lorentz-Berthelot
    mixing: about 20 x faster on this OpenMM CPU build. NBFIX pairs (Na+ with lipid oxygens; some sugar-like
    ring types) fall back to the mixing rule during this relaxation only."""
    import openmm
    from openmm import unit
    nonbonded = next(f for f in system.getForces() if isinstance(f, openmm.NonbondedForce))
    for index, atom_type in enumerate(atom_types):
        charge = nonbonded.getParticleParameters(index)[0]
        sigma, epsilon = lennard_jones[atom_type]
        nonbonded.setParticleParameters(index, charge, sigma, epsilon)
    nonbonded.setUseSwitchingFunction(True)
    nonbonded.setSwitchingDistance(0.8 * unit.nanometer)
    nonbonded.setUseDispersionCorrection(False)
    custom = [i for i, f in enumerate(system.getForces()) if isinstance(f, openmm.CustomNonbondedForce)]
    for index in reversed(custom):
        system.removeForce(index)


def create_simulation(topology, templates, atom_types, restraints, positions_a, seed, threads):
    """CHARMM36 + CHARMM TIP3P, H bonds constrained, on the CPU. Electrostatics by reaction field (1.0 nm)
    and plain LJ: PME and the tabulated LJ took ~0.6 s per force evaluation on this OpenMM build, too slow
    for a build; a few ps of relaxation does not need them."""
    import openmm
    from openmm import app, unit
    forcefield = app.ForceField("charmm36.xml", "charmm36/water.xml")
    system = forcefield.createSystem(topology, nonbondedMethod=app.CutoffPeriodic, nonbondedCutoff=1.0 * unit.nanometer,
                                     switchDistance=0.8 * unit.nanometer, constraints=app.HBonds, rigidWater=True,
                                     residueTemplates=templates)
    plain_lennard_jones(system, atom_types, read_lennard_jones())
    for restraint in restraints:
        system.addForce(restraint)
    barostat = openmm.MonteCarloMembraneBarostat(1.0 * unit.bar, 0.0 * unit.bar * unit.nanometer,
                                                 TEMPERATURE_K * unit.kelvin, openmm.MonteCarloMembraneBarostat.XYIsotropic,
                                                 openmm.MonteCarloMembraneBarostat.ZFree, 25)
    barostat.setRandomNumberSeed(seed)
    system.addForce(barostat)
    integrator = openmm.LangevinMiddleIntegrator(TEMPERATURE_K * unit.kelvin, 1.0 / unit.picosecond,
                                                 0.002 * unit.picoseconds)
    integrator.setRandomNumberSeed(seed)
    platform = openmm.Platform.getPlatformByName("CPU")
    simulation = app.Simulation(topology, system, integrator, platform, {"Threads": str(threads)})
    simulation.context.setPositions(positions_a * unit.angstrom)
    return simulation


def head_height_restraint(molecules, heads_of, elements_of, target_dpp):
    """Flat-bottomed pull of each head atom (P; a sterol's O) towards its height above the bilayer's mid-plane
    (the centroid of all lipid atoms): P at target_dpp / 2, sterol O 4 Å lower. The all-trans lipids
    are packed upright and too thick; this steers the thinning that a short MD would not finish."""
    import openmm
    force = openmm.CustomCentroidBondForce(2, "0.5*k_head*max(0, abs(abs(z2 - z1) - height) - 0.05)^2")
    force.addGlobalParameter("k_head", 0.0)
    force.addPerBondParameter("height")
    lipids = [m for m in molecules if m.kind == "lipid"]
    force.addGroup([i for m in lipids for i in range(m.first, m.first + m.count)])
    for m in lipids:
        for head in heads_of[m.residue]:
            lowered = 0.0 if elements_of[m.residue][head] == "P" else 4.0
            group = force.addGroup([m.first + head])
            force.addBond([0, group], [(target_dpp / 2.0 - lowered) / 10.0])
    force.setUsesPeriodicBoundaryConditions(False)
    return force


STEREO_HOLD = 1000.0  # kJ/mol/rad², the stereo restraint's spring while it is on


def stereo_restraint(molecules, species_mols):
    """Flat-bottomed (+-30°) restraints on an improper torsion at each R/S centre and on the torsion across
    each cis/trans double bond the SMILES fixes, at the values of the species' conformer: packmol's overlaps
    can otherwise push an atom through its neighbours in the first minimisation (CHARMM-GUI restrains the
    same things while it equilibrates)."""
    import openmm
    force = openmm.CustomTorsionForce("0.5*k_stereo*max(0, abs(d) - 0.5236)^2;"
                                      "d = theta - theta0 - 6.283185307*floor((theta - theta0 + 3.141592654)/6.283185307)")
    force.addGlobalParameter("k_stereo", STEREO_HOLD)
    force.addPerTorsionParameter("theta0")
    torsions = {residue: stereo_torsions(mol) for residue, mol in species_mols.items()}
    for m in (m for m in molecules if m.kind == "lipid"):
        for atoms, value in torsions[m.residue]:
            force.addTorsion(*(m.first + i for i in atoms), [value])
    return force


def stereo_torsions(mol):
    """(four atom indices, radians) for each R/S centre (neighbours 1-3 and the centre) and each fixed
    double bond (a heavy neighbour on each side), measured on the molecule's conformer."""
    from rdkit.Chem import rdMolTransforms
    conformer = mol.GetConformer()
    atoms, bonds = smiles_stereo(mol)
    torsions = []
    for centre in atoms:
        n = sorted(a.GetIdx() for a in mol.GetAtomWithIdx(centre).GetNeighbors())
        torsions.append((n[0], n[1], n[2], centre))
    for index in bonds:
        bond = mol.GetBondWithIdx(index)
        b, c = bond.GetBeginAtom(), bond.GetEndAtom()
        a = next(x.GetIdx() for x in b.GetNeighbors() if x.GetIdx() != c.GetIdx() and x.GetSymbol() != "H")
        d = next(x.GetIdx() for x in c.GetNeighbors() if x.GetIdx() != b.GetIdx() and x.GetSymbol() != "H")
        torsions.append((a, b.GetIdx(), c.GetIdx(), d))
    return [(t, rdMolTransforms.GetDihedralRad(conformer, *t)) for t in torsions]


def positions_and_box(simulation):
    """Unwrapped positions (Å, molecules whole) and the box edges (Å)."""
    import numpy
    from openmm import unit
    state = simulation.context.getState(getPositions=True, enforcePeriodicBox=False)
    positions = state.getPositions(asNumpy=True).value_in_unit(unit.angstrom)
    vectors = state.getPeriodicBoxVectors(asNumpy=True).value_in_unit(unit.angstrom)
    return numpy.array(positions), Box(*numpy.diag(vectors))


def phosphate_thickness(simulation, molecules):
    """Mean z of the P atoms of chain A minus chain B (Å), for the log."""
    import numpy
    positions, _ = positions_and_box(simulation)
    phosphorus = [a.index for a in simulation.topology.atoms() if a.element is not None and a.element.symbol == "P"]
    chain = {a.index: a.residue.chain.id for a in simulation.topology.atoms()}
    z = {c: numpy.mean([positions[i, 2] for i in phosphorus if chain[i] == c]) for c in ("A", "B")}
    return z["A"] - z["B"]


def minimise(simulation, iterations):
    import openmm
    from openmm import unit
    openmm.LocalEnergyMinimizer.minimize(simulation.context, 10.0 * unit.kilojoule_per_mole / unit.nanometer,
                                         iterations)


HEAD_PULL = 5000.0  # kJ/mol/nm², the steering restraint's spring while it is on
SQUEEZE_MIN_ITERATIONS = 100


def squeeze_to_area(simulation, molecules, target_area, steps, mean_per_leaflet, log):
    """Deflate the loosely packed box to the target area in `steps` equal steps: move every molecule's
    centre (not its shape) towards the origin in x and y, minimise, and let the membrane barostat (z free)
    settle the water for 0.2 ps."""
    from openmm import Vec3, unit
    positions, box = positions_and_box(simulation)
    factor = math.sqrt(target_area / (box.a * box.b)) ** (1.0 / steps)
    for step in range(steps):
        for molecule in molecules:
            atoms = slice(molecule.first, molecule.first + molecule.count)
            centre = positions[atoms, :2].mean(axis=0)
            positions[atoms, :2] += (factor - 1.0) * centre
        box = Box(box.a * factor, box.b * factor, box.c)
        simulation.context.setPeriodicBoxVectors(Vec3(box.a, 0, 0) * unit.angstrom, Vec3(0, box.b, 0) * unit.angstrom,
                                                 Vec3(0, 0, box.c) * unit.angstrom)
        simulation.context.setPositions(positions * unit.angstrom)
        minimise(simulation, SQUEEZE_MIN_ITERATIONS)
        simulation.step(100)
        positions, box = positions_and_box(simulation)
        log(f"  squeeze {step + 1}/{steps}: {box.a * box.b / mean_per_leaflet:.1f} A2 per lipid (mean), D_PP "
            f"{phosphate_thickness(simulation, molecules):.1f} A")
    return positions, box


def relax(simulation, molecules, target_area, args, log):
    """Minimise the packed system, squeeze it to the target area with the heads steered towards the target
    thickness, run the MD steered, then free for the last --release-ps, minimise again."""
    from openmm import unit
    started = time.time()
    minimise(simulation, args.min_steps)
    log(f"  minimised ({args.min_steps} iterations at most): D_PP {phosphate_thickness(simulation, molecules):.1f} A;"
        f" {time.time() - started:.0f} s")
    simulation.context.setParameter("k_head", HEAD_PULL)
    squeeze_to_area(simulation, molecules, target_area, args.squeeze_steps, mean_per_leaflet(args), log)
    simulation.context.setVelocitiesToTemperature(TEMPERATURE_K * unit.kelvin, args.seed)
    steered, free = (int(round(ps / 0.002)) for ps in (args.md_ps - args.release_ps, args.release_ps))
    simulation.step(steered)
    log(f"  MD {args.md_ps - args.release_ps:g} ps steered ({steered} steps of 2 fs): D_PP "
        f"{phosphate_thickness(simulation, molecules):.1f} A; {time.time() - started:.0f} s")
    simulation.context.setParameter("k_head", 0.0)
    simulation.context.setParameter("k_stereo", 0.0)
    simulation.step(free)
    log(f"  MD {args.release_ps:g} ps free: D_PP {phosphate_thickness(simulation, molecules):.1f} A; "
        f"{time.time() - started:.0f} s")
    minimise(simulation, args.final_min_steps)
    return positions_and_box(simulation)


# ---------------------------------------------------------------------------------------------- checks

def stereo_labels(mol, atoms, bonds):
    """R/S of the given atoms and E/Z of the given bonds as the coordinates have them."""
    from rdkit import Chem
    Chem.AssignStereochemistryFrom3D(mol)
    return (tuple(mol.GetAtomWithIdx(i).GetProp("_CIPCode") if mol.GetAtomWithIdx(i).HasProp("_CIPCode") else ""
                  for i in atoms) + tuple(str(mol.GetBondWithIdx(i).GetStereo()) for i in bonds))


def smiles_stereo(mol):
    """The atoms and bonds whose configuration the SMILES fixes. Only those are compared: a phosphate P
    also reads as R/S from coordinates (its two free oxygens, alike, are =O and O- only on paper), and so
    does cardiolipin's central carbon, whose arms differ only by those P labels."""
    from rdkit import Chem
    atoms = [a.GetIdx() for a in mol.GetAtoms() if a.GetChiralTag() != Chem.ChiralType.CHI_UNSPECIFIED]
    bonds = [b.GetIdx() for b in mol.GetBonds() if b.GetStereo() != Chem.BondStereo.STEREONONE]
    return atoms, bonds


def changed_stereo(species_mols, conformers_of, molecules, positions):
    """'RESIDUE atom(s)' for each lipid whose R/S centres or cis/trans bonds, read back from the final
    coordinates, differ from its SMILES (a ring pierced or a bond flipped in the packing)."""
    from rdkit import Chem
    from rdkit.Geometry import Point3D
    reference, changed = {}, []
    for molecule in (m for m in molecules if m.kind == "lipid"):
        mol = Chem.Mol(species_mols[molecule.residue])
        atoms, bonds = smiles_stereo(mol)
        if molecule.residue not in reference:
            reference[molecule.residue] = stereo_labels(Chem.Mol(mol), atoms, bonds)
        conformer = mol.GetConformer()
        for i in range(molecule.count):
            conformer.SetAtomPosition(i, Point3D(*positions[molecule.first + i]))
        names = conformers_of[molecule.residue].names
        where = [names[i] for i in atoms] + ["bond " + "-".join(
            names[k] for k in (mol.GetBondWithIdx(i).GetBeginAtomIdx(), mol.GetBondWithIdx(i).GetEndAtomIdx()))
            for i in bonds]
        labels = stereo_labels(mol, atoms, bonds)
        moved = [w for w, new, old in zip(where, labels, reference[molecule.residue]) if new != old]
        if moved:
            changed.append(f"{molecule.residue} {','.join(moved)}")
    return changed


def long_bonds(topology, positions, limit=2.0):
    """Bonds between heavy atoms longer than `limit` Å (a bond stretched through another molecule)."""
    import numpy
    pairs = numpy.array([(b[0].index, b[1].index) for b in topology.bonds()
                         if b[0].element.symbol != "H" and b[1].element.symbol != "H"])
    lengths = numpy.linalg.norm(positions[pairs[:, 0]] - positions[pairs[:, 1]], axis=1)
    return int((lengths > limit).sum())


def ring_threads(topology, molecules, species_mols, positions, box):
    """Bonds of another molecule that pass through a lipid ring (cholesterol's, inositol's): packing
    artefacts that minimisation cannot undo."""
    import numpy
    bonds = numpy.array([(b[0].index, b[1].index) for b in topology.bonds()])
    owner = numpy.zeros(len(positions), dtype=int)
    for number, molecule in enumerate(molecules):
        owner[molecule.first:molecule.first + molecule.count] = number
    middles = (positions[bonds[:, 0]] + positions[bonds[:, 1]]) / 2.0
    period = numpy.array([box.a, box.b, 0.0])
    threads = 0
    for number, molecule in enumerate(molecules):
        if molecule.kind != "lipid":
            continue
        for ring in species_mols[molecule.residue].GetRingInfo().AtomRings():
            ring_xyz = positions[[molecule.first + i for i in ring]]
            threads += threads_through(ring_xyz, bonds, middles, positions, owner != number, period)
    return threads


def threads_through(ring_xyz, bonds, middles, positions, foreign_atoms, period):
    """How many foreign bonds cross the ring's plane inside the ring (nearest periodic image in x, y)."""
    import numpy
    centre = ring_xyz.mean(axis=0)
    normal = numpy.linalg.svd(ring_xyz - centre)[2][2]
    inner_radius = 0.9 * numpy.linalg.norm(ring_xyz - centre, axis=1).min()
    shift = numpy.where(period > 0, numpy.round((middles - centre) / numpy.where(period > 0, period, 1.0)) * period, 0.0)
    near = numpy.linalg.norm(middles - shift - centre, axis=1) < 2.5
    near &= foreign_atoms[bonds[:, 0]]
    count = 0
    for k in numpy.nonzero(near)[0]:
        u, v = positions[bonds[k, 0]] - shift[k] - centre, positions[bonds[k, 1]] - shift[k] - centre
        su, sv = u @ normal, v @ normal
        if su * sv < 0 and numpy.linalg.norm(u + (v - u) * su / (su - sv)) < inner_radius:
            count += 1
    return count


def leaflet_flips(molecules, positions, heads_of):
    """Lipids whose head ended up on the other side of the mid-plane than their leaflet."""
    import numpy
    lipids = [m for m in molecules if m.kind == "lipid"]
    mid = numpy.mean([positions[m.first:m.first + m.count, 2].mean() for m in lipids])
    flips = 0
    for m in lipids:
        heads = [m.first + i for i in heads_of[m.residue]]
        side = positions[heads, 2].mean() > mid
        flips += side != (m.chain == "A")
    return flips


# ---------------------------------------------------------------------------------------------- the patch file

PatchAtom = collections.namedtuple("PatchAtom", "chain residue number name element x y z")
Patch = collections.namedtuple("Patch", "a b c atoms remarks")


def pdb_atom_line(serial, atom):
    """A HETATM record: 4-character residue names fill columns 18-21, the chain is column 22."""
    name = atom.name if len(atom.name) == 4 else f" {atom.name:<3s}"
    return (f"HETATM{serial:5d} {name:4s} {atom.residue:<4s}{atom.chain:1s}{atom.number:4d}    "
            f"{atom.x:8.3f}{atom.y:8.3f}{atom.z:8.3f}{1.0:6.2f}{0.0:6.2f}          {atom.element:>2s}")


def patch_atoms(molecules, conformers_of, positions, box):
    """Heavy lipid atoms, chain A (outer) first, residues numbered from 1 and shifted by whole periods so
    each residue's centroid lies in [0, a) x [0, b)."""
    import numpy
    atoms, number = [], 0
    for chain in ("A", "B"):
        for molecule in (m for m in molecules if m.kind == "lipid" and m.chain == chain):
            number += 1
            conformer = conformers_of[molecule.residue]
            xyz = positions[molecule.first:molecule.first + molecule.count]
            heavy = [i for i, e in enumerate(conformer.elements) if e != "H"]
            centroid = xyz[heavy].mean(axis=0)
            shift = numpy.array([math.floor(centroid[0] / box.a) * box.a, math.floor(centroid[1] / box.b) * box.b, 0.0])
            pdb_name = SPECIES[molecule.residue].pdb_name
            atoms += [PatchAtom(chain, pdb_name, number, conformer.names[i], conformer.elements[i],
                                *(xyz[i] - shift)) for i in heavy]
    return atoms


def patch_body(atoms, box):
    lines = [f"CRYST1{box.a:9.3f}{box.b:9.3f}{box.c:9.3f}{90.0:7.2f}{90.0:7.2f}{90.0:7.2f} P 1           1"]
    lines += [pdb_atom_line(serial, atom) for serial, atom in enumerate(atoms, 1)]
    return lines + ["END"]


def remark_lines(texts):
    """REMARK 999 records of at most 80 columns, long texts wrapped on spaces."""
    import textwrap
    lines = []
    for text in texts:
        for piece in textwrap.wrap(text, 69, subsequent_indent="  ", break_on_hyphens=False) or [""]:
            lines.append(f"REMARK 999 {piece}")
    return lines


def write_gzip_atomically(path, text):
    """gzip -n -9 (no name, no time stamp: the bytes depend only on the text) into a temporary file in the
    same folder, then renamed over PATH, so a reader never sees a partial patch."""
    packed = subprocess.run(["gzip", "-n", "-9", "-c"], input=text.encode(), capture_output=True, check=True).stdout
    folder = os.path.dirname(os.path.abspath(path))
    handle, temporary = tempfile.mkstemp(prefix=".tmp-", suffix=".pdb.gz", dir=folder)
    try:
        with os.fdopen(handle, "wb") as out:
            out.write(packed)
        os.chmod(temporary, 0o644)
        os.replace(temporary, path)
    except BaseException:
        os.unlink(temporary)
        raise


def read_patch(path):
    """CRYST1 a, b, c, the heavy atoms and the REMARK 999 texts of a patch (.pdb or .pdb.gz)."""
    opener = gzip.open if path.endswith(".gz") else open
    try:
        with opener(path, "rt") as f:
            return read_patch_lines(f.read().splitlines(), os.path.basename(path))
    except OSError as error:
        fail_usage(f"cannot read {os.path.basename(path)}: {error.strerror or error}")


def read_patch_lines(lines, name="the patch"):
    box, atoms, remarks = None, [], []
    for line in lines:
        if line.startswith("CRYST1"):
            box = (float(line[6:15]), float(line[15:24]), float(line[24:33]))
        elif line.startswith(("ATOM", "HETATM")):
            element = line[76:78].strip() or line[12:16].strip()[0]
            atoms.append(PatchAtom(line[21], line[17:21].strip(), int(line[22:26]), line[12:16].strip(), element,
                                   float(line[30:38]), float(line[38:46]), float(line[46:54])))
        elif line.startswith("REMARK 999 "):
            remarks.append(line[11:])
    if box is None:
        sys.exit(f"build_lipid_patch: {name} has no CRYST1 record")
    return Patch(*box, atoms, remarks)


# ---------------------------------------------------------------------------------------------- measurements

def close_pairs(xyz, a, b, cutoff):
    """Index pairs (i < j) closer than `cutoff`, periodic in x and y only (a cell list on a cutoff grid)."""
    import numpy
    wrapped = xyz.copy()
    wrapped[:, 0] %= a
    wrapped[:, 1] %= b
    if min(a, b) < 3.0 * cutoff:
        sys.exit(f"build_lipid_patch: a box of {a:.1f} x {b:.1f} A is too small to count contacts")
    cells_x, cells_y = int(a // cutoff), int(b // cutoff)
    ix = numpy.minimum((wrapped[:, 0] / (a / cells_x)).astype(int), cells_x - 1)
    iy = numpy.minimum((wrapped[:, 1] / (b / cells_y)).astype(int), cells_y - 1)
    iz = numpy.floor((wrapped[:, 2] - wrapped[:, 2].min()) / cutoff).astype(int)
    cells = collections.defaultdict(list)
    for atom, key in enumerate(zip(ix, iy, iz)):
        cells[key].append(atom)
    cells = {key: numpy.array(members) for key, members in cells.items()}
    period = numpy.array([a, b, 0.0])
    found_i, found_j, found_d = [], [], []
    for (cx, cy, cz), members in cells.items():
        for dx, dy, dz in ((dx, dy, dz) for dx in (-1, 0, 1) for dy in (-1, 0, 1) for dz in (-1, 0, 1)):
            others = cells.get(((cx + dx) % cells_x, (cy + dy) % cells_y, cz + dz))
            if others is None:
                continue
            delta = wrapped[members][:, None, :] - wrapped[others][None, :, :]
            delta -= numpy.round(delta / numpy.where(period > 0, period, 1.0)) * period
            distance = numpy.linalg.norm(delta, axis=2)
            i, j = numpy.nonzero((distance < cutoff) & (members[:, None] < others[None, :]))
            found_i.append(members[i]), found_j.append(others[j]), found_d.append(distance[i, j])
    if not found_i:
        return numpy.zeros(0, int), numpy.zeros(0, int), numpy.zeros(0)
    return numpy.concatenate(found_i), numpy.concatenate(found_j), numpy.concatenate(found_d)


def clash_counts(patch):
    """Pairs of heavy atoms of different residues closer than f·(r1 + r2), for each f in CLASH_FACTORS."""
    import numpy
    xyz = numpy.array([(t.x, t.y, t.z) for t in patch.atoms])
    radius = numpy.array([VDW_RADIUS.get(t.element.upper(), VDW_RADIUS["C"]) for t in patch.atoms])
    residue = numpy.array([hash((t.chain, t.number)) for t in patch.atoms])
    i, j, d = close_pairs(xyz, patch.a, patch.b, max(CLASH_FACTORS) * 2.0 * max(VDW_RADIUS.values()))
    foreign = residue[i] != residue[j]
    ratio = d[foreign] / (radius[i] + radius[j])[foreign]
    return {f: int((ratio < f).sum()) for f in CLASH_FACTORS}


def leaflet_composition(patch):
    """{chain: Counter(residue name)} counted once per residue."""
    seen, composition = set(), {"A": collections.Counter(), "B": collections.Counter()}
    for atom in patch.atoms:
        if (atom.chain, atom.number) not in seen:
            seen.add((atom.chain, atom.number))
            composition.setdefault(atom.chain, collections.Counter())[atom.residue] += 1
    return composition


def measure_patch(patch):
    import numpy
    composition = leaflet_composition(patch)
    area = patch.a * patch.b
    n_outer, n_inner = sum(composition["A"].values()), sum(composition["B"].values())
    z_p = {c: [t.z for t in patch.atoms if t.element == "P" and t.chain == c] for c in ("A", "B")}
    heavy_z = numpy.array([t.z for t in patch.atoms])
    return {
        "composition": composition,
        "apl_outer": area / n_outer, "apl_inner": area / n_inner, "apl_mean": 2.0 * area / (n_outer + n_inner),
        "dpp": float(numpy.mean(z_p["A"]) - numpy.mean(z_p["B"])),
        "heavy_thickness": float(numpy.percentile(heavy_z, 99) - numpy.percentile(heavy_z, 1)),
        "clashes": clash_counts(patch),
    }


def compared(value, low, high):
    """'within' a published range, or the signed difference to its nearest end (and in per cent)."""
    if low <= value <= high:
        return "within the published range"
    nearest = low if value < low else high
    return f"{value - nearest:+.1f} ({100.0 * (value - nearest) / nearest:+.0f} %) from the published range"


def measurement_texts(result, reference_name):
    clashes = result["clashes"]
    texts = [f"MEASURED AREA PER LIPID: OUTER (A) {result['apl_outer']:.1f} A2, INNER (B) {result['apl_inner']:.1f} A2,"
             f" MEAN PER MOLECULE {result['apl_mean']:.1f} A2 (box a*b / molecules)",
             f"MEASURED D_PP {result['dpp']:.1f} A (mean z of P, chain A minus chain B); heavy-atom thickness "
             f"{result['heavy_thickness']:.1f} A (1st to 99th percentile of z)",
             "MEASURED CLASHES (heavy atoms of different residues, periodic in x and y, closer than f*(r1+r2), "
             "r: C 1.70 N 1.55 O 1.52 P 1.80 S 1.80): "
             + ", ".join(f"{f:.1f}x {clashes[f]}" for f in CLASH_FACTORS)]
    reference = REFERENCES.get(reference_name)
    if reference:
        texts.append(f"LITERATURE ({reference_name}): area per molecule {reference.area_low:g}-{reference.area_high:g} A2,"
                     f" D_PP {reference.dpp_low:g}-{reference.dpp_high:g} A; this patch: area "
                     f"{compared(result['apl_mean'], reference.area_low, reference.area_high)}, D_PP "
                     f"{compared(result['dpp'], reference.dpp_low, reference.dpp_high)}")
        texts += ["SOURCE: " + source for source in reference.sources]
    return texts


def chosen_reference(name, composition):
    if name != "auto":
        return name
    total = sum(sum(c.values()) for c in composition.values())
    cholesterol = sum(c.get("CHL1", 0) for c in composition.values())
    return "rbc" if cholesterol >= 0.25 * total else "popc"


# ---------------------------------------------------------------------------------------------- the build

def mean_per_leaflet(args):
    return (args.per_leaflet[0] + args.per_leaflet[1]) / 2.0


def per_leaflet_text(args):
    outer, inner = args.per_leaflet
    return str(outer) if outer == inner else f"{outer},{inner}"


def nominal_area(counts):
    """Mean area per molecule of a leaflet from the species' areas (only to size the box)."""
    return sum(SPECIES[r].area * n for r, n in counts.items()) / sum(counts.values())


def canonical_arguments(args):
    """The arguments as the REMARKs record them: every option spelt out, --out by its file name only
    (no folder of this machine)."""
    parts = [f"--outer {args.outer}", f"--inner {args.inner}", f"--per-leaflet {per_leaflet_text(args)}",
             f"--seed {args.seed}", f"--area-per-molecule {args.area_per_molecule:g}",
             f"--pack-inflation {args.pack_inflation:g}", f"--water-per-lipid {args.water_per_lipid:g}",
             f"--conformers-tried {args.conformers_tried}", f"--conformers-kept {args.conformers_kept}",
             f"--min-steps {args.min_steps}", f"--squeeze-steps {args.squeeze_steps}", f"--md-ps {args.md_ps:g}",
             f"--release-ps {args.release_ps:g}", f"--target-dpp {args.target_dpp:g}",
             f"--final-min-steps {args.final_min_steps}", f"--threads {args.threads}",
             f"--reference {args.reference}"] + [f"--note '{note}'" for note in args.note]
    return " ".join(parts + [f"--out {os.path.basename(args.out)}"])


def provenance_texts(args, leaflets, requests, versions, checks):
    texts = ["LIPID BILAYER PATCH BUILT BY scripts/build_lipid_patch.py (Nanouniverse), heavy atoms only;"
             " chain A = outer leaflet (+z), chain B = inner leaflet; normal along z",
             f"ARGUMENTS: {canonical_arguments(args)}",
             f"SEED: {args.seed}",
             "PACKAGES (Debian): " + ", ".join(f"{p} {v}" for p, v in versions.items()),
             "FORCE FIELD: CHARMM36 lipids + CHARMM TIP3P water, Na+ counter-ions (OpenMM charmm36.xml, "
             "charmm36/water.xml), H bonds constrained",
             f"STEPS: RDKit ETKDGv3 + MMFF (tails all-trans), packmol tolerance {PACKMOL_TOLERANCE} A at "
             f"{args.pack_inflation:g} x the area, {PACKMOL_LOOPS} loops; OpenMM CPU: minimise <= {args.min_steps} "
             f"iterations, squeeze to the area in {args.squeeze_steps} steps (each: minimise <= "
             f"{SQUEEZE_MIN_ITERATIONS}, MD 0.2 ps), "
             f"Langevin MD {args.md_ps:g} ps at {TEMPERATURE_K:g} K (2 fs, 1/ps) with a membrane barostat "
             f"(1 bar, tension 0, xy isotropic, z free), minimise <= {args.final_min_steps} iterations. "
             f"During the squeeze and the first {args.md_ps - args.release_ps:g} ps a flat-bottomed restraint "
             f"({HEAD_PULL:g} kJ/mol/nm2, flat within +-0.5 A) held P at +-{args.target_dpp / 2:g} A from the mid-plane (sterol O "
             f"4 A lower): D_PP is steered, not predicted. Until then flat-bottomed (+-30 deg, "
             f"{STEREO_HOLD:g} kJ/mol/rad2) torsion restraints also held every R/S centre and cis/trans bond "
             f"the SMILES fixes; the last {args.release_ps:g} ps ran free. "
             "Electrostatics by reaction field (1.0 nm cut-off), LJ switched 0.8-1.0 nm with Lorentz-Berthelot "
             "mixing (CHARMM NBFIX pairs not applied), for speed on this OpenMM CPU build",
             f"TARGET AREA PER LIPID: {args.area_per_molecule:.1f} A2 ("
             f"{'given' if args.area_given else 'mean of the species areas the script lists'})"]
    texts += [f"NOTE: {note}" for note in args.note]
    for chain, counts in leaflets:
        request = " ".join(f"{SPECIES[r].pdb_name}={p:g}" for r, p in requests[chain].items())
        texts.append(f"REQUEST {chain}: {request}")
        texts.append(f"COUNT {chain}: " + " ".join(f"{SPECIES[r].pdb_name}={n}" for r, n in counts.items()))
    texts += species_notes(set().union(*(set(c) for _, c in leaflets)))
    return texts + checks


def species_notes(residues):
    notes = [f"RESIDUE {SPECIES[r].pdb_name} = {SPECIES[r].description}" for r in sorted(residues)]
    if "TOCL2" in residues:
        notes.append("RESIDUE TOCL is CHARMM36 TOCL2 (dianion); the PDB residue-name field holds 4 characters")
    return notes


def build_patch(args, requests, leaflets, log):
    """Conformers -> packmol -> OpenMM: the PDB lines (CRYST1, atoms, END) and (check texts, all sound?)."""
    started = time.time()
    residues = sorted(set().union(*(set(c) for _, c in leaflets)))
    templates = read_templates(set(residues))
    species_mols, conformers = {}, {}
    for residue in residues:
        species_mols[residue], conformers[residue] = build_conformers(
            residue, templates[residue], args.seed, args.conformers_tried, args.conformers_kept)
    log(f"conformers ({', '.join(residues)}): {time.time() - started:.0f} s")
    placements = plan_placements(leaflets, conformers, templates, args.water_per_lipid)
    molecules_total = sum(sum(c.values()) for _, c in leaflets)
    box = box_for(args.area_per_molecule * args.pack_inflation * mean_per_leaflet(args), molecules_total,
                  args.water_per_lipid)
    with tempfile.TemporaryDirectory(prefix="lipid-patch-") as workdir:
        packed, perfect = run_packmol(placements, box, args.seed, args.keep_work or workdir)
    log(f"packmol ({'perfect' if perfect else 'best try, overlaps left to the minimiser'}): {time.time() - started:.0f} s")
    topology, molecules, residue_templates, atom_types = build_topology(placements, box)
    restraint = head_height_restraint(molecules, {r: c[0].heads for r, c in conformers.items()},
                                      {r: c[0].elements for r, c in conformers.items()}, args.target_dpp)
    restraints = [restraint, stereo_restraint(molecules, species_mols)]
    simulation = create_simulation(topology, residue_templates, atom_types, restraints, packed, args.seed, args.threads)
    positions, box = relax(simulation, molecules, args.area_per_molecule * mean_per_leaflet(args), args, log)
    log(f"OpenMM done: {time.time() - started:.0f} s")
    checks = build_checks(topology, molecules, species_mols, conformers, positions, box, perfect)
    first_conformer = {r: c[0] for r, c in conformers.items()}
    body = patch_body(patch_atoms(molecules, first_conformer, positions, box), box)
    return body, checks


def build_checks(topology, molecules, species_mols, conformers, positions, box, perfect):
    """Texts for the REMARKs and whether the structure is sound: stereo kept, no stretched bond, no bond
    through a ring, every lipid on its own side."""
    changed = changed_stereo(species_mols, {r: c[0] for r, c in conformers.items()}, molecules, positions)
    stretched = long_bonds(topology, positions)
    threads = ring_threads(topology, molecules, species_mols, positions, box)
    flips = leaflet_flips(molecules, positions, {r: c[0].heads for r, c in conformers.items()})
    sound = not changed and not stretched and not threads and not flips
    texts = [f"CHECKS: packmol {'perfect' if perfect else 'best try (not perfect)'}; lipids whose R/S or cis/trans "
             f"changed {len(changed)}{' (' + '; '.join(changed) + ')' if changed else ''}; heavy-atom bonds over "
             f"2 A {stretched}; bonds threaded through a ring {threads}; lipids on the wrong side {flips}"]
    return texts, sound


def parse_arguments():
    parser = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0],
        epilog="Known residues: " + "; ".join(f"{name} ({s.description})" for name, s in SPECIES.items())
        + ". Missing packages: apt-get install -y " + APT_PACKAGES + ".",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--outer", help="outer leaflet (chain A, +z): NAME=PERCENT,... adding up to 100")
    parser.add_argument("--inner", help="inner leaflet (chain B, -z): NAME=PERCENT,... adding up to 100")
    parser.add_argument("--out", help="the patch to write (.pdb.gz)")
    parser.add_argument("--measure", metavar="FILE", help="only measure this patch (.pdb or .pdb.gz)")
    parser.add_argument("--per-leaflet", default="100",
                        help="molecules per leaflet: N, or OUTER,INNER for a patch to be laid on a curved surface "
                        "(the shells spread a leaflet lying d out from the mid-surface of radius R by (1 + d/R)^2 in "
                        "area: the outer leaflet of a patch for that sphere holds that many more molecules in the flat "
                        "box, the inner (1 - d/R)^2 fewer; the box's area is the target area per molecule times their "
                        "mean) (default 100)")
    parser.add_argument("--seed", type=int, default=1, help="seed of RDKit, packmol and OpenMM (default 1)")
    parser.add_argument("--area-per-molecule", type=float,
                        help="target Å² per molecule in a leaflet (default: from the species' areas)")
    parser.add_argument("--pack-inflation", type=float, default=1.25,
                        help="packmol packs at this multiple of the area, OpenMM then squeezes (default 1.25)")
    parser.add_argument("--water-per-lipid", type=float, default=25.0, help="waters per molecule (default 25)")
    parser.add_argument("--conformers-tried", type=int, default=8, help="ETKDG conformers per species (default 8)")
    parser.add_argument("--conformers-kept", type=int, default=3, help="slimmest ones packed (default 3)")
    parser.add_argument("--min-steps", type=int, default=600, help="first minimisation, iterations (default 600)")
    parser.add_argument("--squeeze-steps", type=int, default=5, help="steps from packed to target area (default 5)")
    parser.add_argument("--md-ps", type=float, default=9.0, help="MD length in ps (default 9)")
    parser.add_argument("--release-ps", type=float, default=2.0,
                        help="last part of the MD without the head-height restraint, ps (default 2)")
    parser.add_argument("--target-dpp", type=float,
                        help="P-P thickness (Å) the heads are steered to (default: middle of the reference's range)")
    parser.add_argument("--final-min-steps", type=int, default=500, help="last minimisation (default 500)")
    parser.add_argument("--threads", type=int, default=1,
                        help="OpenMM CPU threads (default 1; 2 is ~25 %% faster). Neither gives the same bytes on "
                        "every run: the conformers and packmol's input are, but packmol 20.14's moving of badly placed "
                        "molecules is not (its log prints an unset count, 'Moving *********'), so a rebuild is a patch "
                        "of the same make under the same checks, which one run can fail where another passed")
    parser.add_argument("--reference", default="auto", choices=["auto", "none"] + sorted(REFERENCES),
                        help="published values to compare with and steer D_PP to (auto: rbc when >= 25 %% "
                        "cholesterol, else popc)")
    parser.add_argument("--note", action="append", default=[],
                        help="a sentence for the REMARKs, e.g. where the composition comes from (repeatable)")
    parser.add_argument("--keep-work", metavar="DIR", help="keep packmol's files in DIR (debugging)")
    args = parser.parse_args()
    if not args.measure and not (args.outer and args.inner and args.out):
        parser.error("a build needs --outer, --inner and --out (or use --measure FILE)")
    try:
        args.per_leaflet = [int(n) for n in args.per_leaflet.split(",")]
    except ValueError:
        parser.error(f"--per-leaflet: expected N or OUTER,INNER (whole numbers), got '{args.per_leaflet}'")
    if len(args.per_leaflet) == 1:
        args.per_leaflet *= 2
    if len(args.per_leaflet) != 2 or min(args.per_leaflet) < 10:
        parser.error("--per-leaflet: one or two counts (outer,inner), each at least 10")
    if not 0 <= args.release_ps <= args.md_ps:
        parser.error("--release-ps must lie between 0 and --md-ps")
    return args


def measure_mode(args):
    patch = read_patch(args.measure)
    result = measure_patch(patch)
    reference = chosen_reference(args.reference, result["composition"])
    for chain, counts in sorted(result["composition"].items()):
        print(f"chain {chain}: " + " ".join(f"{r}={n}" for r, n in sorted(counts.items())))
    for text in measurement_texts(result, reference):
        print(text)
    return 0 if result["clashes"][0.6] == 0 else 1


def main():
    args = parse_arguments()
    if args.measure:
        return measure_mode(args)
    requests = {"A": parse_composition(args.outer, "--outer"), "B": parse_composition(args.inner, "--inner")}
    leaflets = [("A", leaflet_counts(requests["A"], args.per_leaflet[0], "--outer")),
                ("B", leaflet_counts(requests["B"], args.per_leaflet[1], "--inner"))]
    args.area_given = args.area_per_molecule is not None
    if args.area_per_molecule is None:
        args.area_per_molecule = round((nominal_area(leaflets[0][1]) + nominal_area(leaflets[1][1])) / 2.0, 1)
    if args.target_dpp is None:
        reference = REFERENCES.get(chosen_reference(args.reference, dict(leaflets)), REFERENCES["popc"])
        args.target_dpp = round((reference.dpp_low + reference.dpp_high) / 2.0, 1)
    import_build_packages()
    if args.keep_work:
        os.makedirs(args.keep_work, exist_ok=True)
    started = time.time()
    log = lambda text: print(f"[{time.time() - started:6.0f} s] {text}", flush=True)  # noqa: E731
    body, (checks, sound) = build_patch(args, requests, leaflets, log)
    result = measure_patch(read_patch_lines(body))
    reference = chosen_reference(args.reference, result["composition"])
    texts = provenance_texts(args, leaflets, requests, package_versions(), checks)
    texts += measurement_texts(result, reference)
    for text in texts:
        print(text)
    print(f"build time: {time.time() - started:.0f} s on {args.threads} threads")
    if result["clashes"][0.6] or not sound:
        print("build_lipid_patch: the patch failed a check (above); nothing written", file=sys.stderr)
        return 1
    write_gzip_atomically(args.out, "\n".join(remark_lines(texts) + body) + "\n")
    print(f"wrote {os.path.basename(args.out)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
