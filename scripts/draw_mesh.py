#!/usr/bin/env python3
"""draw_mesh.py OUT.png MESH.obj [MESH.obj ...] [--size 360] [--view AZ,EL]

Draws each OBJ mesh flat-shaded with its edges, side by side, in one PNG (for the docs: a user's
mesh before and after the baker remeshed it). Each mesh is centred on its bounding box and scaled
by the first mesh's largest side, so panels of one shape line up. Orthographic, z-buffered; only
numpy and zlib (no imaging library on a fresh Debian machine)."""
import argparse
import math
import struct
import zlib

import numpy as np


def read_obj(path):
    vertices, faces = [], []
    for line in open(path):
        t = line.split()
        if not t:
            continue
        if t[0] == "v":
            vertices.append([float(x) for x in t[1:4]])
        elif t[0] == "f":
            idx = [int(c.split("/")[0]) for c in t[1:]]
            idx = [i - 1 if i > 0 else len(vertices) + i for i in idx]
            faces += [[idx[0], idx[k], idx[k + 1]] for k in range(1, len(idx) - 1)]
    return np.array(vertices), np.array(faces)


def rotation(azimuth, elevation):
    a, e = math.radians(azimuth), math.radians(elevation)
    rz = np.array([[math.cos(a), -math.sin(a), 0], [math.sin(a), math.cos(a), 0], [0, 0, 1]])
    rx = np.array([[1, 0, 0], [0, math.cos(e), -math.sin(e)], [0, math.sin(e), math.cos(e)]])
    return rx @ rz


def draw(vertices, faces, size, scale, turn, edges):
    image = np.full((size, size, 3), 255.0)
    depth = np.full((size, size), -np.inf)
    q = (vertices - (vertices.min(0) + vertices.max(0)) / 2) @ turn.T  # x right, y up, z towards the eye
    k = 0.9 * size / scale
    screen = np.stack([size / 2 + k * q[:, 0], size / 2 - k * q[:, 1], q[:, 2]], axis=1)
    light = np.array([-0.3, 0.5, 0.8]) / np.linalg.norm([-0.3, 0.5, 0.8])
    ys, xs = np.mgrid[0:size, 0:size]
    for f in faces:
        n = np.cross(q[f[1]] - q[f[0]], q[f[2]] - q[f[0]])
        length = np.linalg.norm(n)
        if length == 0 or n[2] <= 0:  # degenerate or facing away
            continue
        a, b, c = screen[f]
        lo = np.maximum(np.floor(np.minimum(np.minimum(a, b), c)[:2]).astype(int), 0)
        hi = np.minimum(np.ceil(np.maximum(np.maximum(a, b), c)[:2]).astype(int) + 1, size)
        if (hi <= lo).any():
            continue
        X, Y = xs[lo[1]:hi[1], lo[0]:hi[0]] + 0.5, ys[lo[1]:hi[1], lo[0]:hi[0]] + 0.5
        d = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])
        if d == 0:
            continue
        w1 = ((X - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (Y - a[1])) / d
        w2 = ((b[0] - a[0]) * (Y - a[1]) - (X - a[0]) * (b[1] - a[1])) / d
        w0 = 1 - w1 - w2
        inside = (w0 >= 0) & (w1 >= 0) & (w2 >= 0)
        z = w0 * a[2] + w1 * b[2] + w2 * c[2]
        region = depth[lo[1]:hi[1], lo[0]:hi[0]]
        nearer = inside & (z > region)
        region[nearer] = z[nearer]
        colour = np.array([217.0, 212.0, 191.0]) * (0.3 + 0.7 * max(0.0, float(n @ light) / length))
        pixels = np.broadcast_to(colour, X.shape + (3,)).copy()
        if edges:  # within about a pixel of an edge: barycentric × height of the triangle in pixels
            heights = abs(d) / np.linalg.norm(np.array([c - b, a - c, b - a])[:, :2], axis=1)
            near_edge = np.minimum(np.minimum(w0 * heights[0], w1 * heights[1]), w2 * heights[2]) < 0.8
            pixels[near_edge] *= 0.4
        image[lo[1]:hi[1], lo[0]:hi[0]][nearer] = pixels[nearer]
    return image


def write_png(path, image):
    rows = b"".join(b"\0" + bytes(row) for row in np.clip(image, 0, 255).astype(np.uint8).reshape(image.shape[0], -1))
    chunk = lambda kind, data: struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", image.shape[1], image.shape[0], 8, 2, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("meshes", nargs="+")
    ap.add_argument("--size", type=int, default=360)
    ap.add_argument("--view", default="30,-55")
    ap.add_argument("--edges", default="", help="comma-separated 0/1 per mesh: draw its triangle edges")
    a = ap.parse_args()
    az, el = (float(x) for x in a.view.split(","))
    turn = rotation(az, el)
    meshes = [read_obj(m) for m in a.meshes]
    scale = (meshes[0][0].max(0) - meshes[0][0].min(0)).max()
    edges = [c == "1" for c in a.edges.split(",")] if a.edges else [True] * len(meshes)
    panels = []
    for (v, f), e in zip(meshes, edges):
        v = v * (scale / (v.max(0) - v.min(0)).max())
        panels.append(draw(v, f, a.size, scale, turn, e))
    write_png(a.out, np.concatenate(panels, axis=1))


if __name__ == "__main__":
    main()
