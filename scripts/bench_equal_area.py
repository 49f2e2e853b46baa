#!/usr/bin/env python3
"""Bake time against the red blood cell at equal area (issue #39, item 1).

Each mesh of the CGAL corpus (tests/scene_bake/cgal_corpus.py: meshes exported by other tools, read
from Debian's libcgal-demo) gets data/virion.json's composition at --diameter (default 10,000 Å,
a 1 µm cell) and is baked; then the red blood cell (`nanobake make-mesh rbc`, the bundled cell's
surface) is scaled to the same membrane area, given the same composition and baked too. Both bakes
run on --jobs threads in this one run, one after the other, so the ratios compare like with like:
CPU seconds (user + system of the baker), wall seconds and peak resident memory. A mesh the baker
refuses at that size is listed with its refusal (no ratio: nothing was baked).
Writes OUT/equal-area.json and OUT/equal-area.md.
usage: bench_equal_area.py BUILD_DIR OUT_DIR [--diameter 10000] [--cases a,b,...] [--jobs 2]"""
import argparse
import json
import math
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(ROOT, "tests", "scene_bake"))
import cgal_corpus  # noqa: E402
import scene_files  # noqa: E402  (beside this script)


def timed(cmd):
    """Runs cmd; returns (exit code, output, wall s, CPU s, peak resident bytes) of that process."""
    start = time.monotonic()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    out = proc.stdout.read()
    _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    return proc.returncode, out, time.monotonic() - start, usage.ru_utime + usage.ru_stime, usage.ru_maxrss * 1024


def virion_scene(mesh_keys):
    with open(os.path.join(ROOT, "data", "virion.json")) as f:
        scene = scene_files.with_absolute_files(json.load(f), os.path.join(ROOT, "data"))
    scene.pop("camera", None)
    scene["compartments"]["virion"]["mesh"] = mesh_keys
    return scene


def obj_area_and_side(path):
    """Surface area (Å²) and largest bounding-box side (Å) of a triangle OBJ."""
    points, area = [], 0.0
    with open(path) as f:
        for line in f:
            parts = line.split()
            if parts and parts[0] == "v":
                points.append([float(x) for x in parts[1:4]])
            elif parts and parts[0] == "f":
                a, b, c = (points[int(p.split("/")[0]) - 1] for p in parts[1:4])
                u = [b[k] - a[k] for k in range(3)]
                w = [c[k] - a[k] for k in range(3)]
                n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
                area += 0.5 * math.sqrt(sum(x * x for x in n))
    side = max(max(p[k] for p in points) - min(p[k] for p in points) for k in range(3))
    return area, side


def bake(nanobake, work, name, mesh_keys, jobs):
    scene_file = os.path.join(work, name + ".json")
    with open(scene_file, "w") as f:
        json.dump(virion_scene(mesh_keys), f, indent=1)
    package, report = os.path.join(work, name + ".nup"), os.path.join(work, name + "-report.json")
    code, out, wall, cpu, peak = timed([nanobake, "bake", scene_file, "-o", package, "--report", report,
                                        "--jobs", str(jobs), "--quiet"])
    row = {"wall_s": wall, "cpu_s": cpu, "peak_bytes": peak}
    if code != 0:
        # The mesh as the user named it, not where this run keeps it: the table stays free of machine paths.
        lines = out.strip().splitlines()
        said = [line for line in lines if "error" in line][:1] + lines[-1:]
        row["refused"] = (" / ".join(dict.fromkeys(said)) or "exit %d" % code).replace(work + os.sep, "")
        return row
    with open(report) as f:
        baked = json.load(f)
    cell = baked["compartments"][0]
    # A bake that packs its tiles for a distorted surface thins the bilayer: its time is only comparable
    # beside the lipids it placed (a share of a real bilayer's, as the bake summary gives it).
    row.update({"area_um2": cell["membrane"]["area_um2"], "triangles": cell["triangles"],
                "lipids_of_real_bilayer": cell["membrane"]["fraction_of_real_bilayer"],
                "estimated_cpu_s": baked["estimate"]["cpu_seconds"],
                "stages_cpu_s": baked["stages_cpu"]})
    os.remove(package)
    return row


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("build")
    ap.add_argument("out")
    ap.add_argument("--diameter", type=float, default=10000.0)
    ap.add_argument("--cases", default=",".join(cgal_corpus.CASES))
    ap.add_argument("--jobs", type=int, default=2)
    a = ap.parse_args()
    nanobake = os.path.join(os.path.abspath(a.build), "bake", "nanobake")
    work = os.path.abspath(os.path.join(a.out, "equal-area-work"))
    os.makedirs(work, exist_ok=True)
    rbc_obj = os.path.join(work, "rbc.obj")
    subprocess.run([nanobake, "make-mesh", "rbc", "--triangles", "12000", "-o", rbc_obj], check=True,
                   stdout=subprocess.DEVNULL)
    rbc_area, rbc_side = obj_area_and_side(rbc_obj)

    rows = []
    for case in a.cases.split(","):
        file, keys, _, why = cgal_corpus.CASES[case]
        mesh_keys = dict(keys, file=cgal_corpus.extract(file, work), diameter=a.diameter)
        row = {"case": case, "mesh": file, "what": why, "bake": bake(nanobake, work, case, mesh_keys, a.jobs)}
        if "area_um2" in row["bake"]:
            diameter = rbc_side * math.sqrt(row["bake"]["area_um2"] * 1e8 / rbc_area)
            row["rbc_diameter_A"] = diameter
            row["rbc"] = bake(nanobake, work, case + "-rbc", {"file": rbc_obj, "diameter": diameter}, a.jobs)
            if "cpu_s" in row["rbc"] and "refused" not in row["rbc"]:
                row["cpu_ratio"] = row["bake"]["cpu_s"] / row["rbc"]["cpu_s"]
                row["memory_ratio"] = row["bake"]["peak_bytes"] / row["rbc"]["peak_bytes"]
        rows.append(row)
        print(json.dumps(row), flush=True)

    result = {"diameter_A": a.diameter, "jobs": a.jobs, "composition": "data/virion.json", "rows": rows}
    with open(os.path.join(a.out, "equal-area.json.part"), "w") as f:
        json.dump(result, f, indent=1)
    os.replace(os.path.join(a.out, "equal-area.json.part"), os.path.join(a.out, "equal-area.json"))
    lines = ["# Bake time against the red blood cell at equal area",
             "",
             "Each mesh at %.0f Å with data/virion.json's composition, then the red blood cell's surface scaled to "
             "the same membrane area with the same composition; %d jobs, both bakes in one run." % (a.diameter, a.jobs),
             "",
             "| mesh | area µm² | triangles | lipids (RBC's), % of a real bilayer | CPU s (est.) | RBC CPU s | CPU ratio "
             "| peak MB | RBC peak MB | memory ratio |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        b = r["bake"]
        if "refused" in b:
            lines.append("| %s | refused in %.0f s: %s | | | | | | | | |" % (r["mesh"], b["wall_s"], b["refused"].replace("|", "/")))
            continue
        rbc = r.get("rbc", {})
        lines.append("| %s | %.3f | %d | %.0f (%.0f) | %.0f (%.0f) | %.0f | %.2f | %.0f | %.0f | %.2f |" % (
            r["mesh"], b["area_um2"], b["triangles"], 100 * b["lipids_of_real_bilayer"],
            100 * rbc.get("lipids_of_real_bilayer", float("nan")), b["cpu_s"], b["estimated_cpu_s"], rbc.get("cpu_s", float("nan")),
            r.get("cpu_ratio", float("nan")), b["peak_bytes"] / 1e6, rbc.get("peak_bytes", float("nan")) / 1e6,
            r.get("memory_ratio", float("nan"))))
    with open(os.path.join(a.out, "equal-area.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
