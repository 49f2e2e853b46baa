#!/usr/bin/env python3
"""Scale study (issue #7): the blood scene with N red blood cells and 5·N virions in data/blood.json's
9 µm slab, with twice its area per cell (blood.json's own density is close to where random
sequential placement of the cells' bounding spheres jams: 94 of 100 cells fit), the slab growing in
x and y as N^(1/2), for each N: bake time, package size, device memory,
load time and frame time (an orbit about cell 0 at a fixed distance, so cell 0 fills the same part of
the image whatever N; from about 100 cells others fill the background around it, so the table also
gives the share of pixels hit and the frame time per pixel hit, the cost at a fixed screen coverage). Each N is baked twice, with blood.json's plasma
(its medium) and without it, and measured side by side. Writes OUT/scale.json, OUT/scale.md and
OUT/scale.svg (through `nanoview plot`).
usage: bench_scale.py BUILD_DIR OUT_DIR [--cells 1,4,20,100,1000] [--size 128x128] [--frames 8] [--plasma both|with|without]"""
import argparse, json, os, subprocess, sys, time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import scene_files  # noqa: E402

ap = argparse.ArgumentParser()
ap.add_argument("build")
ap.add_argument("out")
ap.add_argument("--cells", default="1,4,20,100,1000")
ap.add_argument("--size", default="128x128")
ap.add_argument("--frames", type=int, default=8)
ap.add_argument("--jobs", default="2")
ap.add_argument("--plasma", default="both", choices=["both", "with", "without"])
a = ap.parse_args()
here = os.path.dirname(os.path.abspath(__file__))
data = os.path.join(os.path.dirname(here), "data")
nanobake = os.path.join(a.build, "bake", "nanobake")
nanoview = os.path.join(a.build, "runtime", "nanoview")
work = os.path.join(a.out, "scale-work")
os.makedirs(work, exist_ok=True)

with open(os.path.join(data, "blood.json")) as f:
    blood = json.load(f)
base_cells = blood["instances"][0]["count"]
base_box = blood["instances"][0]["box"]


def scene_for(cells, plasma):
    s = scene_files.with_absolute_files(json.loads(json.dumps(blood)), data)
    if not plasma and "medium" in s:
        s["solubles"].pop(s.pop("medium")["soluble"])
    k = (2 * cells / base_cells) ** 0.5  # twice blood.json's area per cell, same thickness
    box = [[base_box[0][0] * k, base_box[0][1] * k, base_box[0][2]], [base_box[1][0] * k, base_box[1][1] * k, base_box[1][2]]]
    s["instances"][0]["count"] = cells
    s["instances"][0]["box"] = box
    s["instances"][1]["count"] = 5 * cells
    s["instances"][1]["box"] = box
    s.pop("camera", None)
    s["description"] = (f"Scale study: {cells} red blood cells and {5 * cells} virions at half blood.json's density, "
                        + ("in plasma" if plasma else "without plasma"))
    return s


def measure(cells, plasma):
    name = f"blood-{cells}" + ("" if plasma else "-no-plasma")
    scene_path = os.path.join(work, name + ".json")
    pkg = os.path.join(work, name + ".nup")
    report = os.path.join(work, name + "-report.json")
    with open(scene_path, "w") as f:
        json.dump(scene_for(cells, plasma), f, indent=1)
    t0 = time.monotonic()
    subprocess.run([nanobake, scene_path, "-o", pkg, "--report", report, "--jobs", a.jobs], check=True,
                   stdout=subprocess.DEVNULL)
    bake_seconds = time.monotonic() - t0
    with open(report) as f:
        rep = json.load(f)
    lo, hi = rep["instances"][0]["aabb"]
    centre = [(l + h) / 2 for l, h in zip(lo, hi)]
    distance = 150000.0  # Å: an 8 µm cell fills about half the height of a 45° view
    camera = "position={},{},{};look_at={},{},{};up=0,1,0;fov_degrees=45".format(centre[0], centre[1], centre[2] + distance, *centre)
    bench_json = os.path.join(work, name + "-bench.json")
    subprocess.run([nanoview, "bench", pkg, "--size", a.size, "--frames", str(a.frames), "--camera", camera,
                    "--json", bench_json], check=True, stdout=subprocess.DEVNULL)
    with open(bench_json) as f:
        b = json.load(f)
    row = {"cells": cells, "virions": 5 * cells, "plasma": plasma, "instances": len(rep["instances"]),
           "represented_atoms": rep["represented_atoms"], "bake_seconds": bake_seconds,
           "package_bytes": os.path.getsize(pkg), "device_memory_bytes": b["device_memory_bytes"],
           "device_memory": b["device_memory"], "load_seconds": b["load_seconds"],
           "frame_seconds": b["frame_seconds"], "hit_pixel_fraction": b["hit_pixel_fraction"], "device": b["device"]}
    print(f"{cells:5d} cells {'with' if plasma else 'without'} plasma: bake {bake_seconds:.1f} s, package "
          f"{row['package_bytes'] / 1e6:.2f} MB, device {row['device_memory_bytes'] / 1e6:.2f} MB, load "
          f"{row['load_seconds']:.2f} s, frame median {row['frame_seconds']['median']:.3f} s", flush=True)
    os.remove(pkg)  # the packages are reproducible from the scene files and seed
    return row


plasmas = {"both": [True, False], "with": [True], "without": [False]}[a.plasma]
rows = [measure(cells, plasma) for cells in [int(c) for c in a.cells.split(",")] for plasma in plasmas]

with open(os.path.join(a.out, "scale.json"), "w") as f:
    json.dump({"size": a.size, "frames": a.frames, "rows": rows}, f, indent=1)


def per_hit(r):
    return r["frame_seconds"]["median"] / r["hit_pixel_fraction"]


def first_of(plasma):
    return next(r for r in rows if r["plasma"] == plasma)


def partner(r):
    """The same scene with the plasma the other way, when it was measured."""
    return next((o for o in rows if o["cells"] == r["cells"] and o["plasma"] != r["plasma"]), None)


md = [f"Scale study on {rows[0]['device']}, frames {a.size}, orbit of {a.frames} frames about cell 0 at 15 µm "
      "(cell 0 covers the same pixels; from about 100 cells others fill the background: the pixels hit column; "
      "with plasma the eye stands in it, so the near plasma fills the view); ratios to the smallest scene of the "
      "same kind in brackets, and with plasma against without.", "",
      "| cells | virions | plasma | represented atoms | bake | package | device memory | with / without plasma | load | "
      "frame (median) | with / without plasma | pixels hit | frame per pixel hit |",
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
for r in rows:
    f, o = first_of(r["plasma"]), partner(r)
    mem_vs = f"{r['device_memory_bytes'] / o['device_memory_bytes']:.2f}×" if o else "–"
    frame_vs = f"{r['frame_seconds']['median'] / o['frame_seconds']['median']:.2f}×" if o else "–"
    md.append(f"| {r['cells']} | {r['virions']} | {'yes' if r['plasma'] else 'no'} | {r['represented_atoms']:.3g} | "
              f"{r['bake_seconds']:.1f} s | {r['package_bytes'] / 1e6:.2f} MB | {r['device_memory_bytes'] / 1e6:.2f} MB "
              f"({r['device_memory_bytes'] / f['device_memory_bytes']:.2f}×) | {mem_vs} | {r['load_seconds']:.2f} s | "
              f"{r['frame_seconds']['median']:.3f} s ({r['frame_seconds']['median'] / f['frame_seconds']['median']:.2f}×) | "
              f"{frame_vs} | {100 * r['hit_pixel_fraction']:.1f} % | {per_hit(r) / per_hit(f):.2f}× |")
# What one more compartment instance costs in device memory, from the smallest to the largest scene.
for plasma in [p for p in [True, False] if any(r["plasma"] == p for r in rows)]:
    kind = [r for r in rows if r["plasma"] == plasma]
    if len(kind) > 1 and kind[-1]["instances"] > kind[0]["instances"]:
        per_instance = (kind[-1]["device_memory_bytes"] - kind[0]["device_memory_bytes"]) / (kind[-1]["instances"] - kind[0]["instances"])
        md.append(f"\n{'With' if plasma else 'Without'} plasma, each compartment instance beyond the first "
                  f"{kind[0]['instances']} adds {per_instance:.0f} bytes of device memory.")
with open(os.path.join(a.out, "scale.md"), "w") as f:
    f.write("\n".join(md) + "\n")
series = []
for plasma in [p for p in [True, False] if any(r["plasma"] == p for r in rows)]:
    kind = [r for r in rows if r["plasma"] == plasma]
    f, tag = kind[0], " (plasma)" if plasma else ""
    for key, label in [("device_memory_bytes", "device memory"), ("package_bytes", "package size"), ("bake_seconds", "bake time")]:
        series.append({"name": label + tag, "lines": True, "points": [[r["cells"], r[key] / f[key]] for r in kind]})
    series.append({"name": "frame time (median)" + tag, "lines": True,
                   "points": [[r["cells"], r["frame_seconds"]["median"] / f["frame_seconds"]["median"]] for r in kind]})
spec = {"title": "Cost against scene size (blood scene, 5 virions per cell, with and without plasma)",
        "x_label": "red blood cells", "y_label": "ratio to 1 cell", "log_x": True, "log_y": True, "series": series}
spec_path = os.path.join(work, "scale-plot.json")
with open(spec_path, "w") as f:
    json.dump(spec, f)
subprocess.run([nanoview, "plot", spec_path, "-o", os.path.join(a.out, "scale.svg")], check=True)
print("\n".join(md))
