#!/usr/bin/env python3
"""Renders docs/effects.md's gallery: each bundled scene at four distances, plain (no effects) above and
with the `illustrative` preset below, into one contact sheet per scene.

The four eyes lie on the line from the package's own camera to the point it looks at, at the fractions
of its distance below, so the first column is the scene camera and the last a close-up of what it
looks at. Standard library only (PNG read and write included): Debian's python3, nothing from PyPI.

    scripts/effects_gallery.py --nanoview build/runtime/nanoview --packages out --out docs/images
"""
import argparse
import os
import re
import struct
import subprocess
import sys
import tempfile
import zlib

# Fractions of the scene camera's distance to its target: whole object, a part, a patch, molecules.
DISTANCES = {
    "virion": [1.0, 0.6, 0.42, 0.34],
    "rbc": [1.0, 0.27, 0.066, 0.029],
    "blood": [1.0, 0.35, 0.14, 0.118],
}
GAP = 4  # white pixels between the panels


def read_png(path):
    """(width, height, rows of RGBA bytes) of an 8-bit RGBA or RGB, non-interlaced PNG."""
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(f"{path}: not a PNG")
    pos, idat, header = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
    width, height, depth, colour, _, _, interlace = header
    if depth != 8 or colour not in (2, 6) or interlace:
        raise ValueError(f"{path}: expected 8-bit RGB(A) without interlace")
    channels = 4 if colour == 6 else 3
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            left = line[i - channels] if i >= channels else 0
            up = previous[i]
            corner = previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + left) & 255
            elif kind == 2:
                line[i] = (line[i] + up) & 255
            elif kind == 3:
                line[i] = (line[i] + (left + up) // 2) & 255
            elif kind == 4:
                p = left + up - corner
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - corner)
                line[i] = (line[i] + (left if pa <= pb and pa <= pc else up if pb <= pc else corner)) & 255
        previous = line
        if channels == 3:
            line = bytearray(b for k in range(width) for b in (*line[3 * k:3 * k + 3], 255))
        rows.append(line)
    return width, height, rows


def write_png(path, width, height, rows):
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)
    raw = b"".join(b"\x00" + bytes(row[:width * 4]) for row in rows)
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    handle, temporary = tempfile.mkstemp(dir=os.path.dirname(path) or ".", suffix=".png.part")
    with os.fdopen(handle, "wb") as f:
        f.write(png)
    os.chmod(temporary, 0o644)
    os.replace(temporary, path)


def scene_camera(nanoview, package, work):
    """The package's camera as `render` prints it: (position, look_at, up, fov)."""
    out = subprocess.run([nanoview, "render", package, "--size", "8x8", "-o", os.path.join(work, "probe.png")],
                         check=True, capture_output=True, text=True).stdout
    m = re.search(r"camera position=([^;]+);look_at=([^;]+);up=([^;]+);fov_degrees=(\S+)", out)
    if not m:
        sys.exit(f"{package}: render printed no camera")
    vec = lambda text: [float(x) for x in text.split(",")]
    return vec(m.group(1)), vec(m.group(2)), vec(m.group(3)), float(m.group(4))


def render(nanoview, package, camera, size, out, extra):
    position, look_at, up, fov = camera
    spec = ";".join([f"position={','.join(map(repr, position))}", f"look_at={','.join(map(repr, look_at))}",
                     f"up={','.join(map(repr, up))}", f"fov_degrees={fov!r}"])
    subprocess.run([nanoview, "render", package, "--size", size, "--no-scene-effects", f"--camera={spec}", "-o", out, *extra],
                   check=True, capture_output=True)


def sheet(panels, columns, path):
    width, height = panels[0][0], panels[0][1]
    rows_out = (len(panels) + columns - 1) // columns
    total_w, total_h = columns * width + (columns - 1) * GAP, rows_out * height + (rows_out - 1) * GAP
    canvas = [bytearray(b"\xff" * (total_w * 4)) for _ in range(total_h)]
    for k, (_, _, rows) in enumerate(panels):
        x0, y0 = (k % columns) * (width + GAP), (k // columns) * (height + GAP)
        for y, row in enumerate(rows):
            canvas[y0 + y][x0 * 4:(x0 + width) * 4] = row
    write_png(path, total_w, total_h, canvas)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--nanoview", required=True)
    parser.add_argument("--packages", required=True, help="folder holding virion.nup, rbc.nup and blood.nup")
    parser.add_argument("--out", required=True, help="folder for illustrative-<scene>.png")
    parser.add_argument("--size", default="200x150")
    parser.add_argument("--scenes", nargs="*", default=list(DISTANCES))
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as work:
        for scene in args.scenes:
            package = os.path.join(args.packages, f"{scene}.nup")
            position, look_at, up, fov = scene_camera(args.nanoview, package, work)
            plain, illustrative = [], []
            for k, fraction in enumerate(DISTANCES[scene]):
                eye = [t + fraction * (p - t) for p, t in zip(position, look_at)]
                for extra, panels, name in (([], plain, "plain"), (["--preset", "illustrative"], illustrative, "illustrative")):
                    out = os.path.join(work, f"{scene}-{k}-{name}.png")
                    render(args.nanoview, package, (eye, look_at, up, fov), args.size, out, extra)
                    panels.append(read_png(out))
                print(f"{scene}: eye at {fraction} of the scene camera's distance ({[round(e) for e in eye]})", flush=True)
            sheet(plain + illustrative, len(DISTANCES[scene]), os.path.join(args.out, f"illustrative-{scene}.png"))


if __name__ == "__main__":
    main()
