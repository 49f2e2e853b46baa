#!/usr/bin/env python3
"""Writes a copy of a bundled scene with every instance translated by OFFSET Å (and rotated, so no
axis is special), structure paths made absolute: the far-from-origin hard case of the renderer."""
import json, os, sys

src, dst, offset = sys.argv[1], sys.argv[2], float(sys.argv[3])
with open(src) as f:
    scene = json.load(f)
base = os.path.dirname(os.path.abspath(src))
for mol in scene["molecules"].values():
    mol["file"] = os.path.join(base, mol["file"])
for inst in scene["instances"]:
    t = inst.setdefault("transform", {})
    x, y, z = t.get("translate", [0, 0, 0])
    t["translate"] = [x + offset, y - 0.7 * offset, z + 0.3 * offset]
tmp = dst + ".tmp"
with open(tmp, "w") as f:
    json.dump(scene, f, indent=1)
os.replace(tmp, dst)
