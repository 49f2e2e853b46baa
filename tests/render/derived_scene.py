#!/usr/bin/env python3
"""Writes a variant of a bundled scene for the renderer's hard cases, structure paths made absolute:
  derived_scene.py SRC DST [--offset OFFSET] [--mesh COMPARTMENT=FILE]
--offset translates every instance by OFFSET·(1, −0.7, 0.3) Å (far from the origin, no axis special);
--mesh replaces a compartment's mesh by a mesh file (e.g. one with sliver triangles);
--effects JSON sets the scene's "effects" object; --transform JSON sets instance 0's transform
(before --offset)."""
import argparse, json, os, sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
import scene_files  # noqa: E402

ap = argparse.ArgumentParser()
ap.add_argument("src")
ap.add_argument("dst")
ap.add_argument("--offset", type=float, default=0.0)
ap.add_argument("--mesh", action="append", default=[])
ap.add_argument("--effects")
ap.add_argument("--transform")
a = ap.parse_args()
with open(a.src) as f:
    scene = json.load(f)
scene_files.with_absolute_files(scene, os.path.dirname(os.path.abspath(a.src)))
if a.effects:
    scene["effects"] = json.loads(a.effects)
if a.transform:
    scene["instances"][0]["transform"] = json.loads(a.transform)
for inst in scene["instances"]:
    t = inst.setdefault("transform", {})
    x, y, z = t.get("translate", [0, 0, 0])
    t["translate"] = [x + a.offset, y - 0.7 * a.offset, z + 0.3 * a.offset]
for m in a.mesh:
    name, path = m.split("=", 1)
    scene["compartments"][name]["mesh"] = {"file": os.path.abspath(path)}
tmp = a.dst + ".tmp"
with open(tmp, "w") as f:
    json.dump(scene, f, indent=1)
os.replace(tmp, a.dst)
