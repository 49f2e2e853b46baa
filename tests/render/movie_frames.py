#!/usr/bin/python3
"""`nanoview render --path --frames A:B` against single renders.

A 3-keyframe path at 2 fps; frames 1:3 (times 0.5, 1, 1.5: between keys in both segments, and on
the middle key) at 48x48 must give exactly three PNGs
(and ids files) in a directory the command creates, and frame k must be byte for byte the image and
ids of `render --camera C_k --time k/fps`, where C_k is computed here from the path: Catmull–Rom
tangents with time spacing (one-sided at the ends), cubic Hermite on eye and target, lerp on fov
(up is the same at every key). Key coordinates are multiples of 16 so C_k is exact in decimal and
both commands see the same floats. Also: bad patterns and ranges fail before writing anything.

usage: movie_frames.py NANOVIEW PACKAGE WORK_DIR
"""
import filecmp
import json
import os
import shutil
import subprocess
import sys

KEYS = [  # time, eye, target, fov
    (0.0, (896, 704, 1296), (0, 0, 0), 40.0),
    (1.0, (1024, 512, 1152), (16, 0, -16), 50.0),
    (2.0, (768, 768, 1408), (0, 16, 0), 60.0),
]
FPS = 2
FRAMES = range(1, 4)
SIZE = "48x48"


def hermite(t, which):
    """Eye (which=1) or target (which=2) at time t inside the keys' range."""
    i = max(k for k in range(len(KEYS) - 1) if KEYS[k][0] <= t)
    def tangent(j):
        lo, hi = max(j - 1, 0), min(j + 1, len(KEYS) - 1)
        return [(KEYS[hi][which][c] - KEYS[lo][which][c]) / (KEYS[hi][0] - KEYS[lo][0]) for c in range(3)]
    t0, t1 = KEYS[i][0], KEYS[i + 1][0]
    dt, s = t1 - t0, (t - t0) / (t1 - t0)
    h00, h10, h01, h11 = (1 + 2 * s) * (1 - s) ** 2, s * (1 - s) ** 2, s * s * (3 - 2 * s), s * s * (s - 1)
    m0, m1 = tangent(i), tangent(i + 1)
    return [h00 * KEYS[i][which][c] + h10 * dt * m0[c] + h01 * KEYS[i + 1][which][c] + h11 * dt * m1[c] for c in range(3)]


def camera(t):
    i = max(k for k in range(len(KEYS) - 1) if KEYS[k][0] <= t)
    s = (t - KEYS[i][0]) / (KEYS[i + 1][0] - KEYS[i][0])
    fov = (1 - s) * KEYS[i][3] + s * KEYS[i + 1][3]
    fmt = lambda v: ",".join(repr(float(x)) for x in v)
    return f"pos={fmt(hermite(t, 1))};at={fmt(hermite(t, 2))};up=0,1,0;fov={fov!r}"


def run(args, env, expect_ok=True):
    r = subprocess.run(args, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if (r.returncode == 0) != expect_ok:
        sys.exit(f"FAIL: {' '.join(args)} exited {r.returncode}\n{r.stdout}{r.stderr}")
    return r


def main():
    nanoview, package, work = sys.argv[1:4]
    env = dict(os.environ, LP_NUM_THREADS=os.environ.get("LP_NUM_THREADS", "4"))
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    path = os.path.join(work, "path.json")
    keyframes = [{"time": 0, "camera": "pos=896,704,1296;at=0,0,0;up=0,1,0;fov=40"}]
    keyframes += [{"time": t, "position": list(eye), "look_at": list(at), "fov_degrees": fov} for t, eye, at, fov in KEYS[1:]]
    with open(path, "w") as f:
        json.dump({"format": "nanouniverse-camera-path", "version": 1, "fps": FPS, "keyframes": keyframes}, f)

    frames = os.path.join(work, "frames")  # does not exist: the command creates it
    base = [nanoview, "render", package, "--size", SIZE]
    # Rejected before anything is written.
    for bad in (["--path", path, "--frames", "0:2", "-o", os.path.join(frames, "%d_%d.png")],
                ["--path", path, "--frames", "0:5", "-o", os.path.join(frames, "%03d.png")],
                ["--path", path, "--frames", "0:2", "-o", os.path.join(frames, "%03d.png"), "--ids", os.path.join(frames, "x.ids")],
                ["--frames", "0:2", "-o", os.path.join(frames, "%03d.png")]):
        run(base + bad, env, expect_ok=False)
    if os.path.exists(frames):
        sys.exit("FAIL: a rejected command left files behind")

    run(base + ["--path", path, "--frames", "1:3", "-o", os.path.join(frames, "%03d.png"), "--ids",
                os.path.join(frames, "%03d.ids")], env)
    got = sorted(os.listdir(frames))
    want = [f"{k:03d}.{ext}" for k in FRAMES for ext in ("ids", "png")]
    if got != sorted(want):
        sys.exit(f"FAIL: frames directory holds {got}, expected {sorted(want)}")

    for k in FRAMES:
        t = k / FPS
        single = os.path.join(work, f"single{k}")
        run(base + ["--camera", camera(t), "--time", repr(t), "-o", single + ".png", "--ids", single + ".ids"], env)
        for ext in ("ids", "png"):
            if not filecmp.cmp(os.path.join(frames, f"{k:03d}.{ext}"), f"{single}.{ext}", shallow=False):
                sys.exit(f"FAIL: frame {k} ({ext}) differs from `render --camera {camera(t)} --time {t}`")
        print(f"ok   frame {k} = render --camera {camera(t)} --time {t}")
    print("movie frames agree with single renders")


if __name__ == "__main__":
    main()
