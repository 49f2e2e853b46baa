#!/usr/bin/env python3
"""A rare molecule in a medium packs at the density asked, not rounded up.

usage: rare_soluble.py NANOBAKE SOURCE_DIR WORK

Blood plasma as cellPACK recipes and the bundled scenes have it: albumin at 0.6 mM and IgG at
67 µM in 64 cubes of 250 Å, 0.63 IgG a cube. The tile packer once rounded IgG up to a whole copy in
a unit every cube holds: 6.4e4 /µm³ where 4.04e4 were asked (+59 %). Each set's achieved density
(the bake report's `densities`) must be within 10 % of the request.
"""
import json
import os
import subprocess
import sys


def main():
    nanobake, source, work = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    structures = os.path.join(os.path.abspath(source), "data", "structures")
    scene = {
        "format": "nanouniverse-scene", "version": 1,
        "molecules": {name: {"file": os.path.join(structures, f)}
                      for name, f in (("albumin", "1ao6_a.pdb"), ("igg", "1igt.pdb"), ("hb", "4hhb.pdb"))},
        "solubles": {
            "plasma": {"cube_size": 250, "cubes": 64, "clearance": 5,
                       "molecules": [{"molecule": "albumin", "concentration_mM": 0.6},
                                     {"molecule": "igg", "concentration_mM": 0.067}]},
            "inside": {"cube_size": 250, "molecules": [{"molecule": "hb", "concentration_mM": 5}]}},
        "compartments": {"box": {"mesh": {"generate": "box", "size": [500, 500, 500]}, "soluble": "inside"}},
        "instances": [{"compartment": "box"}],
        "medium": {"soluble": "plasma", "region": [[-1500, -1500, -1500], [1500, 1500, 1500]]},
    }
    path = os.path.join(work, "rare_soluble.json")
    json.dump(scene, open(path, "w"), indent=1)
    report = os.path.join(work, "rare_soluble_report.json")
    p = subprocess.run([nanobake, path, "-o", os.path.join(work, "rare_soluble.nup"), "--report", report, "-q"],
                       capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"bake failed:\n{p.stdout}\n{p.stderr}")
    bad = []
    for d in json.load(open(report))["densities"]:
        ratio = d["achieved"] / d["requested"]
        print(f"{d['set']}/{d['molecule']}: {d['achieved']:.4g} of {d['requested']:.4g} ({100 * (ratio - 1):+.1f} %)")
        if abs(ratio - 1) > 0.10:
            bad.append(d["molecule"])
    if bad:
        sys.exit(f"more than 10 % off the request: {bad}")


if __name__ == "__main__":
    main()
