#!/usr/bin/env python3
"""Makes a proxy mesh with sliver triangles from a generated one: OBJ IN → OBJ OUT. Interior (non-seam)
edges of the triangle that will sit in the middle of the face list, and of a few others, are split
4% of the way from one endpoint; of the two triangles each split makes per side, the one in place
is a sliver (smallest angle ~1.2–1.5°, just above check-mesh's 1° limit, so the baker accepts it). `nanoview verify` aims its membrane views at the middle
triangle, so they look straight at slivers. Written to a temporary name, then renamed."""
import os, sys

src, dst = sys.argv[1], sys.argv[2]
v, vt, vn, faces, head = [], [], [], [], []
for line in open(src):
    p = line.split()
    if not p:
        continue
    if p[0] == "v": v.append([float(x) for x in p[1:4]])
    elif p[0] == "vt": vt.append([float(x) for x in p[1:3]])
    elif p[0] == "vn": vn.append([float(x) for x in p[1:4]])
    elif p[0] == "f": faces.append([tuple(int(i) - 1 for i in c.split("/")) for c in p[1:4]])
    else: head.append(line)

def lerp(a, b, t): return [x + (y - x) * t for x, y in zip(a, b)]

def split(fi, k, t=0.04):
    """Splits edge k of face fi (corners k, k+1) at fraction t from corner k, in both triangles."""
    a, b = faces[fi][k], faces[fi][(k + 1) % 3]
    other = None
    for fj, f in enumerate(faces):
        if fj != fi:
            for kk in range(3):
                if f[kk][0] == b[0] and f[(kk + 1) % 3][0] == a[0]:
                    other = (fj, kk)
    if other is None: return False
    fj, kk = other
    if faces[fj][kk] != b or faces[fj][(kk + 1) % 3] != a: return False  # a UV seam: leave it
    v.append(lerp(v[a[0]], v[b[0]], t)); vt.append(lerp(vt[a[1]], vt[b[1]], t))
    n = lerp(vn[a[2]], vn[b[2]], t); l = sum(x * x for x in n) ** 0.5; vn.append([x / l for x in n])
    m = (len(v) - 1, len(vt) - 1, len(vn) - 1)
    for f_index, kk_, first, second in ((fi, k, a, b), (fj, kk, b, a)):
        f = faces[f_index]; c = f[(kk_ + 2) % 3]
        faces[f_index] = [first, m, c]
        faces.append([m, second, c])
    return True

# Five splits append ten faces, so the first split face lands at index (count + 10) // 2, where
# `verify` aims; its in-place half is the sliver.
splits = [(len(faces) + 10) // 2 + 5 * s for s in range(5)]
done = 0
for fi in splits:
    for k in range(3):
        if split(fi, k):
            done += 1
            break
tmp = dst + ".tmp"
with open(tmp, "w") as out:
    out.write("# sliver test mesh derived from %s: %d edge splits\n" % (os.path.basename(src), done))
    for x in v: out.write("v %.17g %.17g %.17g\n" % tuple(x))
    for x in vt: out.write("vt %.17g %.17g\n" % tuple(x))
    for x in vn: out.write("vn %.17g %.17g %.17g\n" % tuple(x))
    for f in faces: out.write("f " + " ".join("%d/%d/%d" % (c[0] + 1, c[1] + 1, c[2] + 1) for c in f) + "\n")
os.replace(tmp, dst)
print("%s: %d triangles, %d edge splits" % (dst, len(faces), done))
