#!/usr/bin/env python3
"""Frame time of two nanoview builds on the same packages, measured alternately in one run.

    bench_against.py OLD_NANOVIEW NEW_NANOVIEW PKG [PKG ...] [--size 256x256] [--frames 4] [--rounds 2]
                     [--camera SPEC] [--json OUT]

Each round runs `nanoview bench PKG --size S --frames F` with the old build, then the new one (the
order flips every round), so drift of a shared machine falls on both alike. Prints per package the
median frame time of each build and the ratio old / new."""
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
a = ap.parse_args()

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
    for package in a.packages:
        seconds = {"old": [], "new": []}
        for r in range(a.rounds):
            order = ["old", "new"] if r % 2 == 0 else ["new", "old"]
            for which in order:
                seconds[which].append(frame_seconds(a.old if which == "old" else a.new, package, out))
        old, new = statistics.median(seconds["old"]), statistics.median(seconds["new"])
        row = {"package": os.path.basename(package), "old_seconds": old, "new_seconds": new, "old_over_new": old / new,
               "rounds": a.rounds, "frames_per_round": a.frames, "size": a.size}
        results.append(row)
        print(f"{row['package']:>20}: old {old:.4f} s, new {new:.4f} s per frame at {a.size}: {old / new:.2f}x faster", flush=True)
if a.json:
    with open(a.json, "w") as f:
        json.dump(results, f, indent=2)
