#!/usr/bin/env python3
"""Writes a variant of a bundled scene for the renderer's hard cases, structure paths made absolute:
  derived_scene.py SRC DST [--offset OFFSET] [--mesh COMPARTMENT=FILE]
--offset translates every instance by OFFSET·(1, −0.7, 0.3) Å (far from the origin, no axis special);
--mesh replaces a compartment's mesh by a mesh file (e.g. one with sliver triangles);
--effects JSON sets the scene's "effects" object; --transform JSON sets instance 0's transform
(before --offset); --set PATH=JSON sets one value, PATH dotted keys and list indices
(e.g. compartments.rbc.mesh.diameter=4000), and --set-from FILE each PATH: value of a JSON object,
applied last (before --offset)."""
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
ap.add_argument("--set", action="append", default=[])
ap.add_argument("--set-from")
a = ap.parse_args()


def set_value(node, path, value):
    keys = [int(k) if k.isdigit() else k for k in path.split(".")]
    for k in keys[:-1]:
        node = node[k]
    node[keys[-1]] = value


with open(a.src) as f:
    scene = json.load(f)
scene_files.with_absolute_files(scene, os.path.dirname(os.path.abspath(a.src)))
if a.effects:
    scene["effects"] = json.loads(a.effects)
if a.transform:
    scene["instances"][0]["transform"] = json.loads(a.transform)
for assignment in a.set:
    path, value = assignment.split("=", 1)
    set_value(scene, path, json.loads(value))
if a.set_from:
    with open(a.set_from) as f:
        for path, value in json.load(f).items():
            set_value(scene, path, value)
for inst in scene["instances"] if a.offset else []:
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
