#!/usr/bin/env python3
"""nanobake on cellPACK recipes, as a user meets it: one scenario per CASE.

usage: recipe_cli.py NANOBAKE SOURCE_DIR WORK CASE

Cases:
  copy_numbers REPORT   the bundled example's bake report against copy numbers computed here from
                        the recipe itself (spheres and the box, analytically): every ingredient
                        within 10 % of what cellPACK would place
  import_then_bake      import-cellpack writes a scene whose paths resolve from where it is written;
                        baking it (dry run) works
  missing_structures    every missing structure named with the names tried, --stand-ins suggested,
                        nothing written; with --stand-ins the recipe bakes (dry run), marked STAND-IN
  cytoplasm_alone       a recipe of its cytoplasm alone (BloodPlasma's form) bakes in its box, within
                        10 % of its copies; a fibre is left out, said so
  refusals              a scene given recipe options, a hostile recipe (negative molarity, 10^13
                        molecules, an include cycle): refused in seconds naming file and key,
                        nothing written
"""
import json
import math
import os
import shutil
import subprocess
import sys
import time

AVOGADRO = 6.02214076e23


def run(nanobake, *args, expect_ok=True):
    started = time.monotonic()
    p = subprocess.run([nanobake, *map(str, args)], capture_output=True, text=True)
    seconds = time.monotonic() - started
    if (p.returncode == 0) != expect_ok:
        sys.exit(f"nanobake {' '.join(map(str, args))}: exit {p.returncode}\nstdout:\n{p.stdout}\nstderr:\n{p.stderr}")
    return p, seconds


def expect(text, part):
    if part not in text:
        sys.exit(f"expected {part!r} in:\n{text}")


def copy_numbers(source, report_file):
    recipe = json.load(open(os.path.join(source, "data/recipes/rbc_microvesicle.json")))
    report = json.load(open(report_file))
    radius = recipe["objects"]["microvesicle"]["radius"]
    (x0, y0, z0), (x1, y1, z1) = recipe["bounding_box"]
    sphere = 4 / 3 * math.pi * radius**3
    area = 4 * math.pi * radius**2
    outside = (x1 - x0) * (y1 - y0) * (z1 - z0) - sphere
    regions = recipe["composition"]["vesicle"]["regions"]
    expected = {}  # (region, molecule) -> copies cellPACK asks for
    for item in regions["surface"]:
        expected[("vesicle", item["object"])] = item.get("count", 0) + item.get("molarity", 0) * AVOGADRO * area * 1e-27
    for item in regions["interior"]:
        expected[("vesicle", item["object"])] = item.get("count", 0) + item["molarity"] * AVOGADRO * sphere * 1e-27
    for item in recipe["composition"]["plasma"]["regions"]["interior"]:
        if isinstance(item, dict):
            expected[("medium", item["object"])] = item["molarity"] * AVOGADRO * outside * 1e-27
    (cell,) = report["compartments"]
    held = {("vesicle", name): n for name, n in cell["copies"].items()}
    held.update({("medium", name): e["copies"] for name, e in report["medium"]["estimated"].items()})
    # The importer's own arithmetic, as the bake report carries it, against the copies computed here.
    asked = {(e["scene"]["region"], e["scene"]["molecule"]): e for e in report["cellpack_recipe"] if "scene" in e}
    for key, want in expected.items():
        entry = asked.get(("medium" if key[0] == "medium" else "vesicle", key[1]))
        if entry is None or abs(entry["copies_asked"] / want - 1) > 1e-9 or entry["copies_placed"] != held.get(key, 0):
            sys.exit(f"{key}: the report's recipe entry {entry} disagrees with {want} asked, {held.get(key, 0)} placed")
    bad = []
    for key, want in expected.items():
        got = held.get(key, 0)
        print(f"{key[0]}/{key[1]}: {got:.6g} of {want:.6g} ({100 * (got / want - 1):+.1f} %)")
        if abs(got / want - 1) > 0.10:
            bad.append(key)
    if bad:
        sys.exit(f"more than 10 % off the recipe: {bad}")


def import_then_bake(nanobake, source, work):
    scene = os.path.join(work, "scenes", "microvesicle.json")
    os.makedirs(os.path.dirname(scene))
    p, _ = run(nanobake, "import-cellpack", os.path.join(source, "data/recipes/rbc_microvesicle.json"),
               "--structures", os.path.join(source, "data/structures"),
               "--lipid-patch", os.path.join(source, "data/structures/popc_bilayer.pdb.gz"), "-o", scene,
               "--report", os.path.join(work, "import.txt"))
    expect(p.stdout, "aquaporin1 [vesicle surface]: asked nbMol 300")
    expect(open(os.path.join(work, "import.txt")).read(), "haemoglobin [vesicle interior]: asked molarity 0.005 M")
    written = json.load(open(scene))
    for name, m in written["molecules"].items():
        if os.path.isabs(m["file"]) or not os.path.isfile(os.path.join(os.path.dirname(scene), m["file"])):
            sys.exit(f"molecule {name}: {m['file']} does not resolve from the scene's folder")
    p, _ = run(nanobake, scene, "--dry-run", "-o", os.path.join(work, "never.nup"))
    expect(p.stdout, "estimate")
    if os.path.exists(os.path.join(work, "never.nup")):
        sys.exit("a dry run wrote a package")


def missing_structures(nanobake, source, work):
    structures = os.path.join(work, "structures")
    os.makedirs(structures)
    for f in ("1ao6_a.pdb", "4hhb.pdb"):  # IgG and aquaporin-1 missing
        shutil.copy(os.path.join(source, "data/structures", f), structures)
    recipe = os.path.join(source, "data/recipes/rbc_microvesicle.json")
    patch = os.path.join(source, "data/structures/popc_bilayer.pdb.gz")
    out = os.path.join(work, "out.nup")
    p, _ = run(nanobake, recipe, "--structures", structures, "--lipid-patch", patch, "-o", out, expect_ok=False)
    expect(p.stderr, "2 ingredient structure(s) not found")
    expect(p.stderr, "aquaporin1 (1j4n; tried 1j4n, 1j4n.pdb")
    expect(p.stderr, "igg (1igt; tried")
    expect(p.stderr, "--stand-ins")
    p, _ = run(nanobake, recipe, "--structures", structures, "--lipid-patch", patch, "--stand-ins", "--dry-run", "-o", out)
    expect(p.stdout, "STAND-IN (structure missing): drawn as its encapsulating radius, 1 sphere")
    if os.listdir(work) != ["structures"]:
        sys.exit(f"files left behind: {os.listdir(work)}")


def cytoplasm_alone(nanobake, source, work):
    """A v1 recipe of plasma alone (as cellPACK's BloodPlasma is): it fills its bounding box."""
    recipe = os.path.join(work, "plasma.json")
    json.dump({"recipe": {"name": "plasma", "version": "1.0"},
               "options": {"boundingBox": [[-1500, -1000, -1200], [1500, 1000, 1200]]},
               "cytoplasme": {"ingredients": {
                   "albumin": {"molarity": 0.0006, "pdb": "1ao6_a.pdb", "encapsulatingRadius": 45},
                   "igg": {"molarity": 0.000067, "pdb": "1IGT", "encapsulatingRadius": 80},
                   "snake": {"Type": "Grow", "molarity": 1e-6, "radii": [[25]], "encapsulatingRadius": 75}}}},
              open(recipe, "w"))
    p, _ = run(nanobake, recipe, "--structures", os.path.join(source, "data/structures"), "-o", os.path.join(work, "plasma.nup"))
    expect(p.stdout, "snake [cytoplasm (the recipe's box)]: asked molarity 1e-06 M; holds nothing: a fibre is not placed")
    expect(p.stdout, "cytoplasm: ")
    for name in ("albumin", "igg"):
        line = next((l for l in p.stdout.splitlines() if l.startswith(f"  {name} [cytoplasm")), "")
        if not line.endswith(" ok"):
            sys.exit(f"{name} not within 10 % of the recipe:\n{p.stdout}")


def refusals(nanobake, source, work):
    out = os.path.join(work, "out.nup")
    p, _ = run(nanobake, os.path.join(source, "data/virion.json"), "--stand-ins", "-o", out, expect_ok=False)
    expect(p.stderr, "are for cellPACK recipes; this is a scene")
    base = json.load(open(os.path.join(source, "data/recipes/rbc_microvesicle.json")))
    cases = [
        ("negative", lambda r: r["composition"]["plasma"]["regions"]["interior"][1].update(molarity=-1),
         ["composition.plasma.regions.interior[1]", "molarity"]),
        ("huge", lambda r: r["composition"]["vesicle"]["regions"]["surface"][0].update(count=1e13),
         ["composition.vesicle.regions.surface[0]", "count"]),
        ("version", lambda r: r.update(format_version="3.0"), [":format_version"]),
    ]
    for name, change, keys in cases:
        recipe = json.loads(json.dumps(base))
        change(recipe)
        path = os.path.join(work, name + ".json")
        json.dump(recipe, open(path, "w"))
        p, seconds = run(nanobake, path, "--structures", os.path.join(source, "data/structures"), "-o", out, expect_ok=False)
        expect(p.stderr, path)
        for key in keys:
            expect(p.stderr, key)
        if seconds > 5:
            sys.exit(f"{name}: refused after {seconds:.1f} s")
    cycle = os.path.join(work, "cycle.json")
    json.dump({"recipe": {"name": "cycle", "version": "1.0"},
               "cytoplasme": {"ingredients": {"self": {"include": "cycle.json"}}}}, open(cycle, "w"))
    p, _ = run(nanobake, cycle, "-o", out, expect_ok=False)
    expect(p.stderr, "cycle.json")
    expect(p.stderr, "includes itself")
    if os.path.exists(out):
        sys.exit("a refused recipe left a package")


def main():
    nanobake, source, work, case = sys.argv[1:5]
    if case == "copy_numbers":
        copy_numbers(source, sys.argv[5])
        return
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    {"import_then_bake": import_then_bake, "missing_structures": missing_structures, "cytoplasm_alone": cytoplasm_alone,
     "refusals": refusals}[case](nanobake, source, work)


if __name__ == "__main__":
    main()
