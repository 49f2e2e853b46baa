#!/usr/bin/python3
"""`nanoview pick` on the device and with --oracle (CPU explicit instancing) name the same atom.

Both pick pixel (X, Y) of the package's own view; the JSON lines must agree in every key but depth
(equal within verify's tolerance, max(1e-3 Å, 1e-5·t)), and the pixel must show an atom.

usage: pick_agree.py NANOVIEW PACKAGE WxH X Y
"""
import json
import os
import subprocess
import sys


def pick(nanoview, package, size, x, y, extra):
    env = dict(os.environ, LP_NUM_THREADS=os.environ.get("LP_NUM_THREADS", "4"))
    out = subprocess.run([nanoview, "pick", package, "--size", size, x, y] + extra, check=True, env=env,
                         stdout=subprocess.PIPE, text=True).stdout
    lines = out.splitlines()
    if len(lines) != 1:
        sys.exit(f"FAIL: pick {' '.join(extra)} printed {len(lines)} lines, expected one line of JSON:\n{out}")
    return json.loads(lines[0])


def main():
    nanoview, package, size, x, y = sys.argv[1:6]
    gpu = pick(nanoview, package, size, x, y, [])
    oracle = pick(nanoview, package, size, x, y, ["--oracle"])
    print("gpu:   ", json.dumps(gpu, sort_keys=True))
    print("oracle:", json.dumps(oracle, sort_keys=True))
    if gpu.get("hit") is not True or "error" in gpu:
        sys.exit("FAIL: the pixel does not show an atom")
    depth_gpu, depth_oracle = gpu.pop("depth"), oracle.pop("depth")
    if gpu != oracle:
        sys.exit("FAIL: device and oracle name different atoms or copies")
    if abs(depth_gpu - depth_oracle) > max(1e-3, 1e-5 * depth_oracle):
        sys.exit(f"FAIL: depths {depth_gpu} and {depth_oracle} differ")
    print("device and oracle agree")


if __name__ == "__main__":
    main()
