#!/usr/bin/env python3
"""Frame time of two nanoview builds on the same packages, measured alternately in one run.

    bench_against.py OLD_NANOVIEW NEW_NANOVIEW PKG [PKG ...] [--size 256x256] [--frames 4] [--rounds 2]
                     [--camera SPEC] [--old-packages DIR] [--counters [--closeup NAME=SPEC ...]]
                     [--json OUT] [--markdown OUT]

Each round runs `nanoview bench PKG --size S --frames F` with the old build, then the new one (the
order flips every round), so drift of a shared machine falls on both alike. Prints per package the
median frame time of each build and the ratio old / new.

--old-packages DIR: the old build reads DIR/<same file name> (a package baked by the old baker, when
the format gained a section). --counters: `bench --counters` instead, at a fixed camera (the scene's,
and for a package named NAME.nup also the --closeup NAME=SPEC view): frame time and the work per pixel
at every level (DDA steps, boxes, queries, candidates), old beside new."""
import argparse, json, os, statistics, subprocess, sys, tempfile

ap = argparse.ArgumentParser()
ap.add_argument("old")
ap.add_argument("new")
ap.add_argument("packages", nargs="+")
ap.add_argument("--size", default="256x256")
ap.add_argument("--frames", type=int, default=4)
ap.add_argument("--rounds", type=int, default=2)
ap.add_argument("--camera")
ap.add_argument("--json")
ap.add_argument("--markdown")
ap.add_argument("--old-packages")
ap.add_argument("--counters", action="store_true")
ap.add_argument("--closeup", action="append", default=[])
a = ap.parse_args()
closeups = dict(c.split("=", 1) for c in a.closeup)
COUNTERS = ["core_steps", "core_boxes", "ulas_candidates", "mlas_queries", "mlas_candidates", "nlas_queries",
            "queries_started", "candidates_met"]


def package_for(which, package):
    if which == "old" and a.old_packages:
        return os.path.join(a.old_packages, os.path.basename(package))
    return package


def counters_run(binary, package, camera, out):
    cmd = [binary, "bench", package, "--counters", "--size", a.size, "--frames", str(a.frames), "--json", out]
    if camera:
        cmd += ["--camera", camera]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    with open(out) as f:
        d = json.load(f)
    per_pixel = d["work"]["virtual"]["per_pixel"]
    return d["work"]["frame_seconds_median"]["virtual"], {k: per_pixel[k]["mean"] for k in COUNTERS if k in per_pixel}, d["camera"]

def frame_seconds(binary, package, out):
    cmd = [binary, "bench", package, "--size", a.size, "--frames", str(a.frames), "--json", out]
    if a.camera:
        cmd += ["--camera", a.camera]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    with open(out) as f:
        return json.load(f)["frame_seconds"]["median"]

results = []
with tempfile.TemporaryDirectory() as work:
    out = os.path.join(work, "bench.json")
    for package in a.packages if a.counters else []:
        name = os.path.splitext(os.path.basename(package))[0]
        for view, camera in [("scene", a.camera)] + ([("close-up", closeups[name])] if name in closeups else []):
            seconds = {"old": [], "new": []}
            work_of = {}
            for r in range(a.rounds):
                for which in (["old", "new"] if r % 2 == 0 else ["new", "old"]):
                    s_, w_, cam = counters_run(a.old if which == "old" else a.new, package_for(which, package), camera, out)
                    seconds[which].append(s_)
                    work_of[which] = w_
            old, new = statistics.median(seconds["old"]), statistics.median(seconds["new"])
            row = {"package": os.path.basename(package), "view": view, "camera": cam, "old_seconds": old, "new_seconds": new,
                   "old_over_new": old / new, "old_per_pixel": work_of["old"], "new_per_pixel": work_of["new"],
                   "rounds": a.rounds, "frames_per_round": a.frames, "size": a.size}
            results.append(row)
            print(f"{row['package']:>14} {view:>8}: old {old:.4f} s, new {new:.4f} s ({old / new:.2f}x); " +
                  ", ".join(f"{k} {work_of['old'].get(k, 0):.1f}->{work_of['new'].get(k, 0):.1f}" for k in COUNTERS[:4]), flush=True)
    for package in [] if a.counters else a.packages:
        seconds = {"old": [], "new": []}
        for r in range(a.rounds):
            order = ["old", "new"] if r % 2 == 0 else ["new", "old"]
            for which in order:
                seconds[which].append(frame_seconds(a.old if which == "old" else a.new, package_for(which, package), out))
        old, new = statistics.median(seconds["old"]), statistics.median(seconds["new"])
        row = {"package": os.path.basename(package), "old_seconds": old, "new_seconds": new, "old_over_new": old / new,
               "rounds": a.rounds, "frames_per_round": a.frames, "size": a.size}
        results.append(row)
        print(f"{row['package']:>20}: old {old:.4f} s, new {new:.4f} s per frame at {a.size}: {old / new:.2f}x faster", flush=True)
if a.json:
    with open(a.json, "w") as f:
        json.dump(results, f, indent=2)
if a.markdown and a.counters:
    with open(a.markdown, "w") as f:
        f.write(f"| scene | view | frame old → new ({a.size}, warm) | old / new | " +
                " | ".join(k.replace("_", " ") + " / pixel" for k in COUNTERS) + " |\n")
        f.write("|---|---|---|---|" + "---|" * len(COUNTERS) + "\n")
        for r in results:
            f.write(f"| {r['package']} | {r['view']} | {r['old_seconds']:.4f} → {r['new_seconds']:.4f} s | {r['old_over_new']:.2f}× | " +
                    " | ".join(f"{r['old_per_pixel'].get(k, 0):.1f} → {r['new_per_pixel'].get(k, 0):.1f}" for k in COUNTERS) + " |\n")
