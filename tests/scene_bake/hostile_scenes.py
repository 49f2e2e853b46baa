#!/usr/bin/env python3
"""hostile_scenes.py NANOBAKE SOURCE_DIR [FILTER]

Hostile scenes: a small base scene (written here, from structures in SOURCE_DIR/data/structures)
mutated in one place per case — absurd or tiny amounts, tiles and cubes of 1e-6 Å to 1e9 Å,
molecules larger than their tile, parameters that would empty a molecule or detach it from its
membrane (a depth of 1e6 Å, a clearance of 1e5 Å, a per_compartment of 0, a lipid_mix share that
rounds to none, cubes wider than the compartment), meshes of 1e12 Å, 10^8 instances, duplicate
keys, names that do not resolve, 1e400, 10^5 nested arrays, a 100 MB string, unicode, path
traversal, a directory or binary garbage as a structure, an empty scene. Each must be refused by
`nanobake bake` within 10 s with exit status 1 (the tool's input error; a signal, 134 or 139 is a
crash), an error line `nanobake: error: FILE:KEY: rule` on stderr naming the expected key path of
the scene (or, for a structure file, that file), and nothing left in the output folder (no package,
report or temporary file). A case still running at 10 s is killed with its whole process group and
fails. The cases of AFTER_BAKE are refused only by the end-of-bake invariant, once the base scene
has been baked: they have the base scene's time.

The base scene itself is baked first (case `base_scene_bakes`): it must bake, so that every
refusal below is the mutation's doing.

Cases run two at a time, each in its own folder under a temporary directory, each bake under a
4 GiB address-space limit (a refusal is arithmetic; it never needs that much). One line per case:
name, seconds, OK/FAIL and the first line of the error. FILTER keeps the cases whose name contains
it (or matches it as a glob). Exit status 1 if any case fails.
"""
import concurrent.futures
import fnmatch
import json
import math
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time

TIMEOUT_S = 10.0  # a refusal
BASE_TIMEOUT_S = 60.0  # the base scene's bake (~2 s alone)
# Refused by the end-of-bake invariant (bake_invariants.hpp), after the base scene's ~2 s of baking.
AFTER_BAKE = {"soluble_clearance_400_emptied"}
MEMORY_LIMIT_KIB = 4 * 1024 * 1024
WORKERS = 2


# ---- JSON text with what Python's json cannot write: repeated keys and raw number text --------

class Raw:
    """Text written into the scene as it is (1e400, 10^5 nested brackets)."""

    def __init__(self, text):
        self.text = text


class Pairs:
    """An object written from a list of (key, value) pairs, so a key may appear twice."""

    def __init__(self, pairs):
        self.pairs = pairs


def to_json(value, out):
    if isinstance(value, Raw):
        out.append(value.text)
    elif isinstance(value, Pairs) or isinstance(value, dict):
        items = value.pairs if isinstance(value, Pairs) else list(value.items())
        out.append("{")
        for i, (k, v) in enumerate(items):
            out.append((", " if i else "") + json.dumps(k, ensure_ascii=False) + ": ")
            to_json(v, out)
        out.append("}")
    elif isinstance(value, list):
        out.append("[")
        for i, v in enumerate(value):
            if i:
                out.append(", ")
            to_json(v, out)
        out.append("]")
    else:
        out.append(json.dumps(value, ensure_ascii=False))


def write_scene(path, scene):
    out = []
    to_json(scene, out)
    with open(path, "w", encoding="utf-8") as f:
        f.writelines(out)


# ---- the base scene ---------------------------------------------------------------------------

def uv_sphere_obj(path, radius=1.0, nu=32, nv=16):
    """A closed, outward triangulated UV sphere as OBJ (the file mesh of compartment "vesicle")."""
    points = [(0.0, 0.0, radius)]
    for j in range(1, nv):
        th = math.pi * j / nv
        for i in range(nu):
            ph = 2 * math.pi * i / nu
            points.append((radius * math.sin(th) * math.cos(ph), radius * math.sin(th) * math.sin(ph),
                           radius * math.cos(th)))
    points.append((0.0, 0.0, -radius))
    south = len(points) - 1
    ring = lambda j, i: 1 + (j - 1) * nu + i % nu
    faces = [(0, ring(1, i), ring(1, i + 1)) for i in range(nu)]
    for j in range(1, nv - 1):
        for i in range(nu):
            faces += [(ring(j, i), ring(j + 1, i), ring(j + 1, i + 1)), (ring(j, i), ring(j + 1, i + 1), ring(j, i + 1))]
    faces += [(ring(nv - 1, i), south, ring(nv - 1, i + 1)) for i in range(nu)]
    with open(path, "w") as f:
        for p in points:
            f.write("v %.6f %.6f %.6f\n" % p)
        for t in faces:
            f.write("f %d %d %d\n" % tuple(i + 1 for i in t))


def base_scene(structures, mesh_file):
    """Two compartments, baked in ~2 s: a virion (generated sphere; membrane "envelope" with three
    proteins on a POPC patch; soluble "lumen" with three haemoglobins) and a vesicle (OBJ file mesh;
    membrane "plain": one protein and a `lipids` fill), the vesicle placed at random."""
    s = lambda name: os.path.join(structures, name)
    return {
        "format": "nanouniverse-scene", "version": 1, "seed": 5,
        "molecules": {
            "aqp": {"file": s("1j4n.pdb")},
            "epent": {"file": s("5x29.pdb"), "up": [-0.54, 0.017, -0.841]},
            "mprot": {"file": s("qhd43419a.pdb")},
            "hb": {"file": s("4hhb.pdb")},
            "hb2": {"file": s("4hhb.pdb")},
            "hb3": {"file": s("4hhb.pdb")},
            "lipid": {"file": s("lipid_306.pdb")},
        },
        "membranes": {
            "envelope": {
                "tile_size": 191.1,
                "proteins": [{"molecule": "aqp", "density_per_um2": 300},
                             {"molecule": "epent", "density_per_um2": 300, "per_compartment": 2},
                             {"molecule": "mprot", "density_per_um2": 200}],
                "lipid_patch": {"file": s("popc_bilayer.pdb.gz"), "name": "POPC"},
            },
            "plain": {
                "tile_size": 150,
                "proteins": [{"molecule": "aqp", "copies_per_tile": 0.5}],
                "lipids": {"molecule": "lipid", "area_per_lipid": 65, "leaflet_offset": 12},
            },
        },
        "solubles": {
            "lumen": {"cube_size": 250, "clearance": 5,
                      "molecules": [{"molecule": "hb", "concentration_mM": 1},
                                    {"molecule": "hb2", "concentration_mM": 1},
                                    {"molecule": "hb3", "concentration_mM": 1}]},
        },
        "compartments": {
            "virion": {"mesh": {"generate": "sphere", "triangles": 1280, "radius": 450},
                       "membrane": "envelope", "soluble": "lumen"},
            "vesicle": {"mesh": {"file": mesh_file, "diameter": 800}, "membrane": "plain"},
        },
        "instances": [
            {"compartment": "virion"},
            {"compartment": "vesicle", "count": 2, "box": [[2000, -2000, -2000], [6000, 2000, 2000]], "min_gap": 50},
        ],
    }


# ---- mutations: each takes (scene, folder) and returns the scene to write ---------------------

def setter(*path_and_value):
    """A mutation that sets scene[p0][p1]...[pn] = value."""
    *path, value = path_and_value

    def mutate(scene, folder):
        node = scene
        for p in path[:-1]:
            node = node[p]
        node[path[-1]] = value(folder) if callable(value) else value
        return scene
    return mutate


def protein(membrane, index, key, value):
    """Sets a key of membranes[membrane].proteins[index]; an amount replaces the entry's amount."""
    def mutate(scene, folder):
        entry = scene["membranes"][membrane]["proteins"][index]
        if key in ("density_per_um2", "copies_per_tile"):
            entry.pop("density_per_um2", None)
            entry.pop("copies_per_tile", None)
        entry[key] = value
        return scene
    return mutate


def soluble(index, value, name="lumen"):
    return lambda scene, folder: (scene["solubles"][name]["molecules"][index].update({"concentration_mM": value}), scene)[1]


def each_soluble(value):
    def mutate(scene, folder):
        for m in scene["solubles"]["lumen"]["molecules"]:
            m["concentration_mM"] = value
        return scene
    return mutate


def lipid_mix(outer, inner):
    """Gives the virion's envelope a second lipid species (POPE) in its patch's places."""
    def mutate(scene, folder):
        pope = os.path.join(os.path.dirname(scene["molecules"]["aqp"]["file"]), "pope_bilayer.pdb.gz")
        scene["membranes"]["envelope"]["lipid_mix"] = [{"file": pope, "name": "POPE", "outer": outer, "inner": inner}]
        return scene
    return mutate


def large_cube_rare_soluble(scene, folder):
    """Cubes of 2000 Å, wider than the 900 Å virion: 2e-5 mM of hb2 is 1.5 copies in the cube set
    but 0.005 in the virion."""
    scene["solubles"]["lumen"]["cube_size"] = 2000
    scene["solubles"]["lumen"]["molecules"][1]["concentration_mM"] = 2e-5
    return scene


def structure(molecule, make_path):
    """Points molecule `molecule` at the file make_path(folder) returns (making it if it wants)."""
    return setter("molecules", molecule, "file", make_path)


def many_placements(entries, count, half):
    def mutate(scene, folder):
        scene["instances"] += [{"compartment": "vesicle", "count": count, "box": [[-half] * 3, [half] * 3]}
                               for _ in range(entries)]
        return scene
    return mutate


def duplicate_molecule(scene, folder):
    molecules = list(scene["molecules"].items())
    molecules.append(("hb", {"file": scene["molecules"]["aqp"]["file"]}))
    scene["molecules"] = Pairs(molecules)
    return scene


def duplicate_protein_key(scene, folder):
    proteins = scene["membranes"]["envelope"]["proteins"]
    proteins[0] = Pairs(list(proteins[0].items()) + [("density_per_um2", 30000)])
    return scene


def deep_description(closed):
    def mutate(scene, folder):
        scene["description"] = Raw("[" * 100_000 + ("]" * 100_000 if closed else ""))
        return scene
    return mutate


def huge_reference(megabytes):
    def mutate(scene, folder):  # the case's folder, with the scene, goes right after the run
        scene["compartments"]["virion"]["membrane"] = "m" * (megabytes * 1_000_000)
        return scene
    return mutate


def unicode_missing(folder):
    return os.path.join(folder, "структура_ü.pdb")


def unicode_prose(folder):
    path = os.path.join(folder, "заметки_é.pdb")
    with open(path, "w", encoding="utf-8") as f:
        f.write("Ceci n'est pas une protéine. これは構造ではありません。\n" * 50)
    return path


def traversal(folder):
    # Relative to the scene's folder, with enough ".." to reach the root from wherever the
    # temporary folder is: the path names /etc/passwd, a text file that is not a structure.
    return "../" * (os.path.abspath(folder).count(os.sep) + 2) + "etc/passwd"


def directory(folder):
    path = os.path.join(folder, "hb.pdb")
    os.mkdir(path)
    return path


def garbage(name, head=b""):
    """64 kB of random bytes after `head` (a gzip header makes the reader inflate them)."""
    def make(folder):
        path = os.path.join(folder, name)
        with open(path, "wb") as f:
            f.write(head + random.Random(27).randbytes(65536))
        return path
    return make


def empty_scene(scene, folder):
    return {}


class FILE:
    """An expectation met by the error naming this file (its path contains the fragment) instead of a key."""

    def __init__(self, fragment):
        self.fragment = fragment

    def __repr__(self):
        return "file " + self.fragment


class WHOLE:
    """An expectation met by the scene file refused as a whole: `SCENE:` and the rule, no key."""

    def __repr__(self):
        return "the scene file as a whole"


class AT_LINE:
    """An expectation met by a JSON reading error at the scene's LINE:COLUMN (docs/scene.md)."""

    def __repr__(self):
        return "a LINE:COLUMN of the scene"


def mol_file(molecule, fragment):
    return ("molecules.%s.file" % molecule, FILE(fragment))


ENVELOPE_P2 = "membranes.envelope.proteins[2]"

# (name, mutation, expected key path (or alternatives: a tuple; FILE(...) for a structure file),
#  optional extra fragment the message must contain)
CASES = [
    # amounts
    ("membrane_density_1e12", protein("envelope", 2, "density_per_um2", 1e12), ENVELOPE_P2 + ".density_per_um2", None),
    ("membrane_density_1e-12", protein("envelope", 2, "density_per_um2", 1e-12), ENVELOPE_P2 + ".density_per_um2", None),
    ("soluble_concentration_1e9", soluble(1, 1e9), "solubles.lumen.molecules[1].concentration_mM", None),
    ("soluble_concentration_1e-12", soluble(1, 1e-12), "solubles.lumen.molecules[1].concentration_mM", None),
    # three haemoglobins at 12 mM: each alone takes ~0.36 of the cube (atoms' volume ~5e4 Å³), together ~1.1
    ("solubles_sum_overfill", each_soluble(12), "solubles.lumen", None),
    ("copies_per_tile_1e9", protein("plain", 0, "copies_per_tile", 1e9), "membranes.plain.proteins[0].copies_per_tile", None),
    ("area_per_lipid_0.001", setter("membranes", "plain", "lipids", "area_per_lipid", 0.001),
     "membranes.plain.lipids.area_per_lipid", None),
    ("per_compartment_1e15", protein("envelope", 1, "per_compartment", 10 ** 15),
     "membranes.envelope.proteins[1].per_compartment", None),
    ("per_compartment_1e8", protein("envelope", 1, "per_compartment", 10 ** 8),
     "membranes.envelope.proteins[1].per_compartment", None),
    # nothing emptied, nothing detached (#39): refused before the heavy stages with the value that works
    ("membrane_protein_depth_1e6", protein("envelope", 2, "depth", 1e6), ENVELOPE_P2 + ".depth", "a depth from"),
    ("membrane_protein_depth_-1e6", protein("envelope", 0, "depth", -1e6), "membranes.envelope.proteins[0].depth",
     "a depth from"),
    ("lipid_leaflet_offset_1e6", setter("membranes", "plain", "lipids", "leaflet_offset", 1e6),
     "membranes.plain.lipids.leaflet_offset", "at most"),
    ("soluble_clearance_1e5", setter("solubles", "lumen", "clearance", 1e5), "solubles.lumen.clearance", "at most"),
    ("per_compartment_0", protein("envelope", 1, "per_compartment", 0), "membranes.envelope.proteins[1].per_compartment",
     "at least 1"),
    ("area_per_lipid_1e9", setter("membranes", "plain", "lipids", "area_per_lipid", 1e9),
     "membranes.plain.lipids.area_per_lipid", "places no lipid"),
    ("lipid_mix_share_1e-9", lipid_mix(1e-9, 0.3), "membranes.envelope.lipid_mix[0].outer", "rounds to none"),
    ("cube_wider_than_compartment", large_cube_rare_soluble, "solubles.lumen.molecules[1].concentration_mM",
     "places no copy in compartment 'virion'"),
    # ... or, where only the bake can tell (the membrane shell's inner reach comes off the room), by
    # the end-of-bake invariant, before anything is written: 400 Å + hb's 37 Å fit the virion's
    # 448 Å, not with the shell's ~30 Å as well
    ("soluble_clearance_400_emptied", setter("solubles", "lumen", "clearance", 400),
     "solubles.lumen.molecules[0].concentration_mM", "no copy survived"),
    # tiles, cubes, molecules against them
    ("tile_size_1e-6", setter("membranes", "envelope", "tile_size", 1e-6), "membranes.envelope.tile_size", None),
    ("tile_size_1e-3", setter("membranes", "envelope", "tile_size", 1e-3), "membranes.envelope.tile_size", None),
    ("tile_size_1e9", setter("membranes", "envelope", "tile_size", 1e9), "membranes.envelope.tile_size", None),
    ("cube_size_1e-6", setter("solubles", "lumen", "cube_size", 1e-6), "solubles.lumen.cube_size", None),
    ("cube_size_1e-3", setter("solubles", "lumen", "cube_size", 1e-3), "solubles.lumen.cube_size", None),
    ("cube_size_1e9", setter("solubles", "lumen", "cube_size", 1e9), "solubles.lumen.cube_size", None),
    ("haemoglobin_in_20A_cube", setter("solubles", "lumen", "cube_size", 20),
     ("solubles.lumen.cube_size", "solubles.lumen.molecules[0]"), None),
    ("membrane_protein_in_30A_tile", setter("membranes", "plain", "tile_size", 30),
     ("membranes.plain.tile_size", "membranes.plain.proteins[0]"), None),
    # meshes
    ("mesh_diameter_1e12", setter("compartments", "vesicle", "mesh", "diameter", 1e12), "compartments.vesicle.mesh.diameter", None),
    ("mesh_diameter_1e-3", setter("compartments", "vesicle", "mesh", "diameter", 1e-3), "compartments.vesicle.mesh.diameter", None),
    ("sphere_radius_1e12", setter("compartments", "virion", "mesh", "radius", 1e12), "compartments.virion.mesh.radius", None),
    ("sphere_radius_1e-3", setter("compartments", "virion", "mesh", "radius", 1e-3), "compartments.virion.mesh.radius", None),
    ("sphere_triangles_1e8", setter("compartments", "virion", "mesh", "triangles", 10 ** 8),
     "compartments.virion.mesh.triangles", None),
    # instances: 10^8 copies; 10^7 in a box that holds ~10^5; a count past the parser's maximum
    ("instances_1e8_in_small_boxes", many_placements(10, 10 ** 7, 20000), "instances", None),
    ("placement_1e7_in_small_box", setter("instances", 1, lambda folder: {
        "compartment": "vesicle", "count": 10 ** 7, "box": [[-20000] * 3, [20000] * 3]}), "instances[1]", None),
    ("placement_count_1e9", setter("instances", 1, "count", 10 ** 9), "instances[1].count", None),
    # names and references
    ("duplicate_molecule_name", duplicate_molecule, "molecules.hb", None),
    ("duplicate_protein_key", duplicate_protein_key, "membranes.envelope.proteins[0].density_per_um2", None),
    ("unknown_membrane", setter("compartments", "virion", "membrane", "envelop"), "compartments.virion.membrane", "envelop"),
    ("unknown_soluble", setter("compartments", "virion", "soluble", "lumen2"), "compartments.virion.soluble", "lumen2"),
    ("unknown_compartment", setter("instances", 0, "compartment", "virus"), "instances[0].compartment", "virus"),
    ("unknown_protein_molecule", setter("membranes", "envelope", "proteins", 1, "molecule", "spike"),
     "membranes.envelope.proteins[1].molecule", "spike"),
    # names referring to their own owner: no membrane is called "vesicle", no molecule "lumen"
    ("self_reference_membrane", setter("compartments", "vesicle", "membrane", "vesicle"), "compartments.vesicle.membrane", None),
    ("self_reference_soluble_molecule", setter("solubles", "lumen", "molecules", 0, "molecule", "lumen"),
     "solubles.lumen.molecules[0].molecule", None),
    # JSON at its limits
    ("number_1e400_density", protein("envelope", 0, "density_per_um2", Raw("1e400")),
     "membranes.envelope.proteins[0].density_per_um2", None),
    ("number_-1e400_translate", setter("instances", 0, "transform", {"translate": [Raw("-1e400"), 0, 0]}),
     "instances[0].transform.translate", None),
    # 10^5 nested arrays as the description: refused where the nesting is found (its key path, or
    # its LINE:COLUMN as for any JSON syntax error), never by overflowing a recursive reader's stack
    ("nesting_1e5_levels", deep_description(True), ("description", AT_LINE()), None),
    ("nesting_1e5_unclosed", deep_description(False), ("description", AT_LINE()), None),
    # a 100 MB name: refused at its key, or the file refused as a whole for its size; 60 MB stays
    # under a 64 MiB document limit and must reach the key
    ("string_100MB_reference", huge_reference(100), ("compartments.virion.membrane", WHOLE()), None),
    ("string_60MB_reference", huge_reference(60), "compartments.virion.membrane", None),
    ("empty_scene", empty_scene, "format", None),
    # structure files
    ("unicode_missing_structure", structure("hb", unicode_missing), mol_file("hb", "структура_ü.pdb"), None),
    ("unicode_prose_structure", structure("hb", unicode_prose), mol_file("hb", "заметки_é.pdb"), None),
    ("path_traversal_etc_passwd", structure("hb", traversal), mol_file("hb", "etc/passwd"), None),
    ("structure_is_directory", structure("hb", directory), mol_file("hb", "hb.pdb"), None),
    ("binary_garbage_structure", structure("aqp", garbage("garbage.pdb")), mol_file("aqp", "garbage.pdb"), None),
    ("binary_garbage_structure_gz", structure("aqp", garbage("garbage.pdb.gz", b"\x1f\x8b\x08\x00\x00\x00\x00\x00\x00\x03")),
     mol_file("aqp", "garbage.pdb.gz"), None),
]


# ---- running a case ---------------------------------------------------------------------------

def bake(nanobake, scene_path, out_dir, timeout):
    """Runs the bake in its own process group, killing the group at the timeout."""
    cmd = ["/bin/sh", "-c", 'ulimit -v %d && exec "$@"' % MEMORY_LIMIT_KIB, "sh", nanobake, "bake", scene_path,
           "-o", os.path.join(out_dir, "out.nup"), "--report", os.path.join(out_dir, "report.json"), "--jobs", "2"]
    start = time.monotonic()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, start_new_session=True)
    try:
        out, err = proc.communicate(timeout=timeout)
        timed_out = False
    except subprocess.TimeoutExpired:
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        out, err = proc.communicate()
        timed_out = True
    seconds = time.monotonic() - start
    return proc.returncode, out.decode("utf-8", "replace"), err.decode("utf-8", "replace"), seconds, timed_out


def error_line(stderr):
    for line in stderr.splitlines():
        if line.startswith("nanobake: error: "):
            return line
    return None


def names(expect, scene_path, message):
    """Whether the error message names the expectation at the FILE:WHERE position."""
    if isinstance(expect, FILE):
        return re.search(re.escape(expect.fragment) + r"[^:]*:", message) is not None
    if isinstance(expect, WHOLE):
        return message.startswith("nanobake: error: " + scene_path + ": ")
    if isinstance(expect, AT_LINE):
        return re.match(r"nanobake: error: " + re.escape(scene_path) + r":\d+:\d+: ", message) is not None
    # FILE:KEY followed by ':' (end of WHERE), '.' or '[' (a deeper key of the one expected).
    return re.search(re.escape(scene_path + ":" + expect) + r"(?=[:.\[])", message) is not None


def shorten(text, n=240):
    return text if len(text) <= n else text[:n - 3] + "..."


def run_case(case, nanobake, structures, mesh_file, work):
    name, mutate, expect, extra = case
    folder = os.path.join(work, name)
    out_dir = os.path.join(folder, "out")
    os.makedirs(out_dir)
    scene_path = os.path.join(folder, "scene.json")
    try:
        scene = base_scene(structures, mesh_file)
        if mutate is not None:
            scene = mutate(scene, folder)
        write_scene(scene_path, scene)
        rc, out, err, seconds, timed_out = bake(nanobake, scene_path, out_dir,
                                                TIMEOUT_S if mutate is not None and name not in AFTER_BAKE
                                                else BASE_TIMEOUT_S)
        left = sorted(os.listdir(out_dir))
    finally:
        shutil.rmtree(folder, ignore_errors=True)  # the 100 MB scene, the garbage, the directory
    problems = []
    message = error_line(err)
    if mutate is None:  # the base scene: must bake
        if timed_out:
            problems.append("still running after %.0f s: killed" % BASE_TIMEOUT_S)
        elif rc != 0:
            problems.append("the base scene did not bake (exit %s)" % rc)
        elif "out.nup" not in left:
            problems.append("no package written")
        first = shorten(out.splitlines()[0] if out.strip() else (message or "(no output)"))
        return name, seconds, problems, first
    if timed_out:
        problems.append("still running after %.0f s: killed (hang)" % (BASE_TIMEOUT_S if name in AFTER_BAKE else TIMEOUT_S))
    elif rc < 0:
        problems.append("killed by signal %d (crash)" % -rc)
    elif rc == 0:
        problems.append("baked: exit 0, not refused")
    elif rc != 1:
        problems.append("exit %d, not 1 (the input-error status)" % rc)
    if not timed_out:
        if message is None:
            problems.append("no 'nanobake: error: FILE:KEY: rule' line on stderr")
        else:
            alternatives = expect if isinstance(expect, tuple) else (expect,)
            if not any(names(e, scene_path, message) for e in alternatives):
                problems.append("the error does not name " + " or ".join(
                    "key " + e if isinstance(e, str) else repr(e) for e in alternatives))
            if extra and extra not in message:
                problems.append("the error does not mention %r" % extra)
            if len(message) > 65536:
                problems.append("an error line of %d bytes: the hostile value echoed whole" % len(message))
        if any(text in err for text in ("Traceback", "terminate called", "Assertion", "Sanitizer", "Segmentation")):
            problems.append("crash text on stderr")
    if "root:x:0:0" in err or "root:x:0:0" in out:
        problems.append("echoed /etc/passwd")
    if left:
        problems.append("left in the output folder: " + ", ".join(left))
    first = shorten(message if message else (err.strip().splitlines()[-1] if err.strip() else "(no message)"))
    return name, seconds, problems, first


def main():
    if len(sys.argv) not in (3, 4):
        print(__doc__)
        return 2
    nanobake, source = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    pattern = sys.argv[3] if len(sys.argv) == 4 else None
    structures = os.path.join(source, "data", "structures")
    cases = [("base_scene_bakes", None, None, None)] + CASES
    if pattern:
        glob = any(ch in pattern for ch in "*?[")
        cases = [c for c in cases if (fnmatch.fnmatch(c[0], pattern) if glob else pattern in c[0])]
        if not cases:
            print("no case matches %r" % pattern)
            return 2
    work = tempfile.mkdtemp(prefix="hostile_scenes-")
    lock = threading.Lock()
    results = []
    try:
        mesh_file = os.path.join(work, "vesicle.obj")
        uv_sphere_obj(mesh_file)
        print("%d case(s), %d at a time, %.0f s each at most; nanobake %s" % (len(cases), WORKERS, TIMEOUT_S, nanobake))
        with concurrent.futures.ThreadPoolExecutor(max_workers=WORKERS) as pool:
            futures = [pool.submit(run_case, c, nanobake, structures, mesh_file, work) for c in cases]
            for future in concurrent.futures.as_completed(futures):
                name, seconds, problems, first = future.result()
                with lock:
                    results.append((name, problems))
                    print("%-34s %5.1f s  %-4s  %s" % (name, seconds, "FAIL" if problems else "OK", first), flush=True)
                    for p in problems:
                        print("%-34s          - %s" % ("", p), flush=True)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    failed = [name for name, problems in results if problems]
    print("%d of %d case(s) failed%s" % (len(failed), len(results), (": " + " ".join(sorted(failed))) if failed else ""))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
