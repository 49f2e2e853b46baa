"""compare_mesh_codecs.py DEFAULT.json DEFAULT.nup ZSTD.json ZSTD.nup

The same scene baked twice: by default (meshes on Draco's grids, stored as Draco streams where those
are smaller) and with --mesh-codec zstd (meshes exactly as read). The first must hold Draco mesh
sections, the second none, and the first's mesh sections must be the smaller; snapping the mesh by
at most 1/64 Å per axis must not change what the cell holds: every molecule's copies within 1 %.
(The rest of the two packages differs too, since the membrane is baked on the moved mesh: the
file sizes are printed, not compared.)
"""
import json
import os
import sys


def main():
    draco_report, draco_pkg, zstd_report, zstd_pkg = sys.argv[1:5]
    a, b = json.load(open(draco_report)), json.load(open(zstd_report))
    failures = 0
    ma, mb = a["mesh_sections"], b["mesh_sections"]
    if ma["codec"] != "draco" or mb["codec"] != "zstd":
        print(f"codecs {ma['codec']} / {mb['codec']}, expected draco / zstd")
        failures += 1
    size_a, size_b = os.path.getsize(draco_pkg), os.path.getsize(zstd_pkg)
    saved = mb["stored_bytes"] - ma["stored_bytes"]
    print(f"package {size_a} bytes with Draco mesh sections ({ma['stored_bytes']} bytes of meshes), "
          f"{size_b} with zstd ({mb['stored_bytes']}): {size_b - size_a} bytes smaller, mesh sections x"
          f"{mb['stored_bytes'] / ma['stored_bytes']:.2f}")
    if saved <= 0:
        print(f"Draco mesh sections take {ma['stored_bytes']} bytes, zstd ones {mb['stored_bytes']}")
        failures += 1
    for ca, cb in zip(a["compartments"], b["compartments"]):
        for name, n in ca["copies"].items():
            m = cb["copies"].get(name, 0)
            if abs(n - m) > 0.01 * max(n, m):
                print(f"{ca['name']}/{name}: {n} copies on Draco's grids, {m} exact")
                failures += 1
    print("ok" if not failures else f"{failures} failed")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
