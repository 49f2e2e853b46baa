#!/usr/bin/env python3
"""Is the membrane closed? Frontal close-ups from outside, as a structural biologist would look.

For each sample point of a bundled surface (analytic: the virion's sphere, the red blood cell's
Evans-Fung surface), `nanoview render --ids` (one process, the views as a camera path) looks at it from DISTANCE Å out along the outward
normal with a FOV-degree field of view; a pixel whose ray meets a membrane copy (hit kind 0) first
shows the membrane, a pixel that meets a soluble copy (kind 1) first sees the lumen through a hole.

  membrane_coverage.py NANOVIEW PKG virion|rbc [--require F] [--size N] [--json OUT]
                      [--density MEMBRANE_DENSITY [--lipids POPC,POPE] [--require-density F]]

Prints one line per sample point (membrane pixels / hit pixels) and exits 1 when --require is given
and any point's coverage is below it. With --density (the membrane_density tool of the build), also
counts the lipid copies whose origins stand within --density-radius Å of the normal through the
point (explicit instancing) against a real bilayer's count in that disc: one molecule per
--area-per-lipid Å² in each leaflet (default 66, POPC's; a cholesterol-rich composition packs closer,
the scene's lipid_patch.leaflets give its outer and inner areas).
"""
import argparse
import json
import math
import os
import struct
import subprocess
import sys
import tempfile

# Evans-Fung red blood cell (bake/mesh/rbc_mesh.cpp, BIOLOGY.md 1.2), Å.
R0, C0, C1, C2 = 39100.0, 0.2072, 2.0026, -1.1228


def rbc_height(rho):
    return 0.5 * R0 * math.sqrt(max(0.0, 1.0 - rho * rho)) * (C0 + C1 * rho ** 2 + C2 * rho ** 4)


def rbc_point(rho, phi, top=True):
    """Surface point and outward normal at radial fraction rho (< 1) and azimuth phi."""
    z = rbc_height(rho)
    h = 1e-6
    dz = (rbc_height(rho + h) - rbc_height(rho - h)) / (2 * h * R0)  # dz/dr
    sign = 1.0 if top else -1.0
    # Outward normal of z = sign·f(r): ±(−f'(r) r̂, 1) for the top, (−f'(r) r̂, −1) for the bottom.
    n_r, n_z = -dz, sign
    length = math.hypot(n_r, n_z)
    c, s = math.cos(phi), math.sin(phi)
    p = (rho * R0 * c, rho * R0 * s, sign * z)
    n = (n_r / length * c, n_r / length * s, n_z / length)
    return p, n


def unit(v):
    length = math.sqrt(sum(x * x for x in v))
    return tuple(x / length for x in v)


def sample_points(scene, radius):
    if scene == "virion":
        # The cube-sphere's charts: face centre, cube-edge seam, cube corner, and points between.
        named = {
            "face centre (+x)": (1, 0, 0),
            "face centre (-z)": (0, 0, -1),
            "seam (cube edge +x+y)": (1, 1, 0),
            "seam (cube edge -y+z)": (0, -1, 1),
            "corner (+x+y+z)": (1, 1, 1),
            "corner (-x+y-z)": (-1, 1, -1),
            "between centre and corner": (1, 0.45, 0.45),
            "near a seam": (1, 0.9, 0.1),
        }
        return [(name, tuple(radius * x for x in unit(d)), unit(d)) for name, d in named.items()]
    points = []
    for name, rho, phi, top in [("top dimple (centre)", 0.0, 0.0, True), ("bottom dimple", 0.05, 1.0, False),
                                ("dimple wall", 0.45, 0.3, True), ("crest", 0.72, 2.0, True),
                                ("towards the rim", 0.9, 4.0, False), ("near the rim", 0.985, 0.7, True),
                                ("bottom near the rim", 0.985, 3.9, False),
                                # Seams of the band charts (bake/mesh/rbc_mesh.hpp) at the default
                                # 3,000 triangles: cap | cone, cone | cone, cone | rim cylinder, and
                                # the radial cut of a cone at azimuth 0.
                                ("seam (cap edge)", 0.157, 1.0, True), ("seam (between cones)", 0.886, 2.5, True),
                                ("seam (rim cylinder edge)", 0.992, 5.0, False), ("seam (radial cut)", 0.5, 0.005, True)]:
        p, n = rbc_point(rho, phi, top)
        points.append((name, p, n))
    # The rim itself: the equator, normal along the radius.
    points.append(("rim", (R0, 0.0, 0.0), (1.0, 0.0, 0.0)))
    return points


def read_ids(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"NUIDS001":
        raise SystemExit(f"{path}: not an ids file")
    width, height = struct.unpack_from("<II", data, 8)
    kinds = []
    for i in range(width * height):
        depth, _inst, _elem, kind = struct.unpack_from("<fIII", data, 16 + 48 * i)
        kinds.append(None if not math.isfinite(depth) else kind)
    return kinds


def protein_footprint(report_path):
    """Mean leaflet area (Å²) one membrane protein copy takes, from the bake report of the first
    compartment with a membrane: its proteins' area in the two leaflets over two, per protein copy."""
    with open(report_path) as f:
        report = json.load(f)
    for compartment in report["compartments"]:
        membrane = compartment.get("membrane")
        if not membrane:
            continue
        lipids = set(membrane["lipids_per_um2"])
        # The membrane's Wang set is the one holding its lipids; its other molecules are its proteins.
        sets = {d["set"] for d in report["densities"] if d["molecule"] in lipids}
        proteins = {d["molecule"] for d in report["densities"] if d["set"] in sets} - lipids
        copies = sum(n for name, n in compartment["copies"].items() if name in proteins)
        area = 0.5 * (membrane["protein_area_um2"]["outer"] + membrane["protein_area_um2"]["inner"]) * 1e8
        return area / copies if copies else 0.0
    return 0.0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("nanoview")
    ap.add_argument("package")
    ap.add_argument("scene", choices=["virion", "rbc"])
    ap.add_argument("--radius", type=float, default=500.0, help="virion membrane radius (Å)")
    ap.add_argument("--distance", type=float, default=2000.0)
    ap.add_argument("--fov", type=float, default=4.0)
    ap.add_argument("--size", type=int, default=96)
    ap.add_argument("--require", type=float, default=None, help="smallest coverage accepted at every point")
    ap.add_argument("--json", default=None)
    ap.add_argument("--density", default=None, help="the membrane_density tool: also count lipids at each point")
    ap.add_argument("--density-radius", type=float, default=100.0)
    ap.add_argument("--lipids", default="POPC,POPE", help="molecule names counted as lipids")
    ap.add_argument("--area-per-lipid", default="66",
                    help="Å² per molecule of a real leaflet: one number for both, or OUTER,INNER")
    ap.add_argument("--report", default=None,
                    help="the bake's JSON report: each protein copy in a disc then takes its mean leaflet footprint "
                         "(the report's protein area over its protein copies) from the area the lipids are judged by")
    ap.add_argument("--require-density", type=float, default=None,
                    help="with --density: smallest share of a real bilayer's lipids accepted at every point")
    args = ap.parse_args()
    lipid_names = set(args.lipids.split(","))
    areas = [float(a) for a in args.area_per_lipid.split(",")]
    if len(areas) not in (1, 2) or min(areas) <= 0:
        ap.error(f"--area-per-lipid: expected one or two positive numbers (Å²), got '{args.area_per_lipid}'")
    real_per_a2 = 1.0 / areas[0] + 1.0 / areas[-1]  # both leaflets

    footprint = protein_footprint(args.report) if args.report else 0.0
    points = sample_points(args.scene, args.radius)
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        # Every view in one process: a camera path whose keyframe k is view k, one second apart at one
        # frame a second, so frame k is keyframe k (starting the renderer costs ~2 s, a 96² view far less).
        keyframes = []
        for k, (name, p, n) in enumerate(points):
            eye = tuple(p[i] + args.distance * n[i] for i in range(3))
            up = (0.0, 0.0, 1.0) if abs(n[2]) < 0.9 else (0.0, 1.0, 0.0)
            keyframes.append({"time": k, "position": list(eye), "look_at": list(p), "up": list(up), "fov_degrees": args.fov})
        path = os.path.join(tmp, "views.json")
        with open(path, "w") as f:
            json.dump({"format": "nanouniverse-camera-path", "version": 1, "fps": 1, "keyframes": keyframes}, f)
        subprocess.run([args.nanoview, "render", args.package, "--path", path, "-o", os.path.join(tmp, "f%05d.png"),
                        "--ids", os.path.join(tmp, "ids%05d.bin"), "--size", f"{args.size}x{args.size}"],
                       check=True, stdout=subprocess.DEVNULL)
        counted = []
        if args.density:
            out = subprocess.run([args.density, args.package, "0", str(args.density_radius), "40",
                                  *(f"{x:.6f}" for _, p, n in points for x in (*p, *n))],
                                 check=True, capture_output=True, text=True)
            counted = [json.loads(line)["copies"] for line in out.stdout.splitlines()[:len(points)]]
        for k, (name, p, n) in enumerate(points):
            kinds = read_ids(os.path.join(tmp, f"ids{k:05d}.bin"))
            hit = sum(1 for kind in kinds if kind is not None)
            membrane = sum(1 for kind in kinds if kind == 0)
            coverage = membrane / hit if hit else 0.0
            result = {"point": name, "surface_point": p, "normal": n, "hit_pixels": hit,
                      "membrane_pixels": membrane, "coverage": coverage}
            line = f"{name:28s} {membrane:6d} / {hit:6d} hit pixels show membrane: {100 * coverage:6.2f} %"
            if args.density:
                copies = counted[k]
                lipids = sum(v for key, v in copies.items() if key in lipid_names)
                proteins = {key: v for key, v in copies.items() if key not in lipid_names}
                disc = math.pi * args.density_radius ** 2
                fraction = lipids / (real_per_a2 * disc)
                beside = lipids / (real_per_a2 * max(1.0, disc - footprint * sum(proteins.values())))
                result.update({"lipids_in_disc": lipids, "proteins_in_disc": proteins, "of_real_bilayer": fraction,
                               "of_real_bilayer_beside_proteins": beside})
                line += f"; {lipids:5d} lipids in the {args.density_radius:.0f} Å disc = {100 * fraction:5.1f} % of a real bilayer"
                if args.report:
                    line += f", {100 * beside:5.1f} % beside the proteins"
                if proteins:
                    line += " (" + ", ".join(f"{key} {v}" for key, v in sorted(proteins.items())) + ")"
            results.append(result)
            print(line)
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"package": os.path.basename(args.package), "scene": args.scene, "points": results}, f, indent=1)
    worst = min(r["coverage"] for r in results)
    print(f"smallest coverage {100 * worst:.2f} %")
    failed = args.require is not None and worst < args.require
    if args.density:
        measure = "of_real_bilayer_beside_proteins" if args.report else "of_real_bilayer"
        thinnest = min(r[measure] for r in results)
        print(f"fewest lipids {100 * thinnest:.1f} % of a real bilayer" + (" beside the proteins" if args.report else ""))
        failed = failed or (args.require_density is not None and thinnest < args.require_density)
    if failed:
        sys.exit(1)


if __name__ == "__main__":
    main()
