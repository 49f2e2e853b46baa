"""check_report.py REPORT.json KEY=EXPECTED[:TOLERANCE] ...

Checks a nanobake --report against expectations written from the biology (BIOLOGY.md), not from
the baker: `represented_atoms=1.2e12:0.10` means within 10 % of 1.2e12; `copies.rbc.haemoglobin=2.7e8:0.10`
reads compartment rbc's copies of haemoglobin; `lipids.virion.total` its membrane's lipids in both
leaflets, `lipids.virion.outer` and `.inner` in one; `charts.virion.max_stretch` a field of the UV charts the baker made for its mesh;
`bilayer.virion.beside_proteins` the share of a real bilayer's lipids it holds beside its
proteins. Also checks the report's required keys, that every molecule type has beads, and that the
mesh sections are stored the smaller way (Draco where its streams beat zstd) with consistent sizes.
"""
import json
import sys


def lookup(report, key):
    if key == "represented_atoms":
        return report["represented_atoms"]
    kind, compartment, name = key.split(".", 2)
    entry = next(c for c in report["compartments"] if c["name"] == compartment)
    if kind == "copies":
        return entry["copies"][name]
    if kind == "atoms":
        return entry["represented_atoms"]
    if kind == "lipids" and name == "total":  # both leaflets, every species
        return sum(entry["membrane"]["lipids_by_leaflet"].values())
    if kind == "lipids" and name in ("outer", "inner"):  # one leaflet, every species
        return entry["membrane"]["lipids_by_leaflet"][name]
    if kind == "charts":  # the UV charts the baker made: charts (their count), max_stretch, seam_length
        return entry["charts"][name]
    if kind == "bilayer" and name == "beside_proteins":  # share of a real bilayer's lipids
        return entry["membrane"]["fraction_of_real_bilayer_beside_proteins"]
    raise KeyError(key)


def main():
    report = json.load(open(sys.argv[1]))
    failures = 0
    for key in ("represented_atoms", "compartments", "instances", "level_of_detail", "sections", "stages"):
        if key not in report:
            print(f"missing key {key}")
            failures += 1
    for c in report["compartments"]:
        for key in ("name", "represented_atoms", "copies"):
            if key not in c:
                print(f"compartment without {key}")
                failures += 1
    for i in report["instances"]:
        lo, hi = i["aabb"]
        if not all(a < b for a, b in zip(lo, hi)):
            print(f"empty instance aabb {i}")
            failures += 1
    # Every molecule type has its coarse model, fewer beads than atoms (a type of one atom aside).
    for name, lod in report.get("level_of_detail", {}).items():
        if not 1 <= lod["beads"] <= max(1, lod["atoms"] - 1):
            print(f"level of detail of {name}: {lod['beads']} beads for {lod['atoms']} atoms")
            failures += 1
    # The baker's default stores meshes as Draco exactly when that is smaller than zstd.
    meshes = report.get("mesh_sections")
    if meshes is None:
        print("missing key mesh_sections")
        failures += 1
    else:
        draco_smaller = "draco_bytes" in meshes and meshes["draco_bytes"] < meshes["zstd_bytes"]
        chosen = meshes["draco_bytes"] if meshes["codec"] == "draco" else meshes["zstd_bytes"]
        print(f"mesh sections: {meshes['codec']}, {meshes['stored_bytes']} bytes stored "
              f"(zstd {meshes['zstd_bytes']}, Draco {meshes.get('draco_bytes', meshes.get('draco_unavailable'))})")
        if (meshes["codec"] == "draco") != draco_smaller or meshes["stored_bytes"] != chosen:
            print("mesh sections not stored the smaller way")
            failures += 1
    for spec in sys.argv[2:]:
        key, expectation = spec.split("=")
        expected, tolerance = (float(x) for x in expectation.split(":"))
        value = lookup(report, key)
        ok = abs(value - expected) <= tolerance * expected
        print(f"{key}: {value:.4g} (expected {expected:.4g} ± {tolerance:.0%}) {'ok' if ok else 'FAILED'}")
        failures += not ok
    print(f"{len(sys.argv) - 2 - failures if failures <= len(sys.argv) - 2 else 0} passed, {failures} failed")
    sys.exit(1 if failures else 0)


main()
