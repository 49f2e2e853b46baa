#!/usr/bin/env python3
"""cgal_corpus.py CASE WORK NANOBAKE NANOVIEW BOX_CLASHES DATA_DIR

Meshes exported by other tools (issue #39): CGAL's own sample data, as Debian's libcgal-demo package
ships it (usr/share/doc/libcgal-dev/data.tar.gz, folder data/meshes/; CGAL's licences, read from the
installed package at test time, never copied into this repository). Each CASE takes one of them as a
user would — a CAD part with sharp creases, a trefoil-knot tube, a 75k-triangle scan, a genus-2
model of 4-7-sided polygons, a genus-3 model with open borders, a cube of 6 quads, a 966-vertex
sphere, an animal with a non-manifold vertex, a mushroom with an open border, a bone whose surfaces
nearly touch — wraps it in mesh_corpus.py's scene (a POPC bilayer and four spikes) at a plausible
diameter, and expects what the mesh honestly allows:
  bakes:   as mesh_corpus.py checks it (validate, a clash-free membrane box, verify against explicit
           instancing), and the bake's own estimate within 2x of its CPU time, peak memory and copies
           (check_estimate.py);
  refused: nanobake exits 1 naming the mesh file and the rule (substrings), no package left; a
           refusal that names a size must name one that then works (checked by check-mesh at it).
Either way `nanobake check-mesh --scene` gives the same verdict and numbers as the bake (not run
again after a refusal that judged the mesh at growing sizes: minutes of the same remeshing), and the
bake time and the estimate are printed side by side.
"""
import json
import os
import re
import subprocess
import sys
import tarfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import check_estimate  # noqa: E402
import mesh_corpus  # noqa: E402

CGAL_DATA = "usr/share/doc/libcgal-dev/data.tar.gz"

# How a refusal says the mesh was judged again at growing sizes (bake/mesh/membrane_fit.cpp).
LADDER_TEXT = "prepared and judged again at up to"

# Each diameter is a small one at which the case's verdict is its own (the bakes scale with the area):
# fandisk and the bunny bake at 3000 Å as at 4500 and 4000, the mushroom is refused at 2000 Å as at
# 3000 (its size ladder then reaches 8,562 Å in a minute, not 7,719 Å in two and a half: the ladder
# starts from the rim's growth, not from the diameter). At 1500 Å the mushroom crashes inside CGAL
# 5.5's tangential relaxation during isotropic remeshing: when every face around a moved vertex is
# degenerate, its check_normals keeps a null halfedge and reads that edge through the remesher's
# constraint map (SIGSEGV). Relaxing outside CGAL's remesher (no edge constraint map) avoids it, but
# as tried it coarsened and rounded worse (a graded box, fandisk, a jittered scan no longer baked):
# not yet worked around.
CASES = {
    # name: (file in data/meshes, mesh keys, expectation, why)
    "cad_fandisk_creases": ("fandisk.off", {"diameter": 3000}, ("bakes",),
                            "a CAD part of 12,946 triangles with 90° creases: remeshed, creases rounded, flat faces coarser"),
    "knot_tube": ("knot1.off", {"diameter": 3000}, ("bakes",),
                  "a trefoil-knot tube of 6,400 triangles whose facets turn by 26°: remeshed, checked everywhere"),
    "scanned_bunny": ("bunny00.off", {"diameter": 3000}, ("bakes",), "a 75,408-triangle scan, creased by its noise"),
    "genus2_polygons": ("double-torus-example.off", {"diameter": 3000}, ("bakes",),
                        "a genus-2 model of 4- to 7-sided faces, cut inside themselves"),
    "genus3_open_repaired": ("double-torus-3-holes.off", {"diameter": 3000, "repair": True}, ("bakes",),
                             "a genus-3 model of polygons with three open borders, closed by \"repair\""),
    "cube_six_quads": ("cube_quad.off", {"diameter": 1500}, ("bakes",), "a cube of 6 quads: rounded corners"),
    "sphere_966": ("sphere966.off", {"diameter": 3000}, ("bakes",), "a 966-vertex sphere"),
    "cow_non_manifold_vertex": ("cow.off", {"diameter": 3000, "repair": True},
                                ("refused", "self-intersection"),
                                "its non-manifold vertex is split by \"repair\"; what stays is a surface crossing itself, face by face"),
    "mushroom_open_border": ("mushroom.off", {"diameter": 2000, "repair": True},
                             ("refused", "places where a bilayer", "still does not take the bilayer"),
                             "its 64-edge border is closed by \"repair\"; its cap's thin rim stays too tight at any size "
                             "tried up to 8 times: the places are named, no size"),
    "bone_near_contact": ("femur.off", {"diameter": 4000}, ("refused", "a defect of the mesh", "no diameter is given"),
                          "two sheets of its surface within 2 Å: a defect no size cures, named where it is"),
}


def cgal_archive():
    """The installed libcgal-demo's data archive (setup.sh installs the package)."""
    listing = subprocess.run(["dpkg", "-L", "libcgal-demo"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    for line in listing.stdout.splitlines():
        if line.endswith("libcgal-dev/data.tar.gz"):
            return line
    sys.exit("FAIL: Debian's libcgal-demo is not installed (scripts/setup.sh installs it): no " + CGAL_DATA)


def extract(name, work):
    target = os.path.join(work, name)
    if not os.path.exists(target):
        with tarfile.open(cgal_archive()) as tar:
            member = tar.getmember("data/meshes/" + name)
            with tar.extractfile(member) as src, open(target + ".part", "wb") as dst:
                dst.write(src.read())
        os.replace(target + ".part", target)
    return target


def check_mesh_scene(nanobake, scene_file, baked, bake_text):
    """check-mesh on the scene's compartment: the bake's verdict and numbers."""
    r = mesh_corpus.run([nanobake, "check-mesh", "--scene", scene_file])
    print("check-mesh --scene:", r.stdout[-1500:])
    if (r.returncode == 0) != baked:
        print("FAIL: check-mesh says %s, the bake %s" % ("fits" if r.returncode == 0 else "refused", "baked" if baked else "refused"))
        return False
    if not baked:
        named = lambda text: re.sub(r"compartment '[^']*'", "", text.split("error: ")[-1]).strip()
        if named(r.stdout) not in named(bake_text):
            print("FAIL: check-mesh and the bake word the refusal differently")
            return False
    return True


def size_works(nanobake, mesh, keys, text):
    """A refusal that names a diameter: the mesh, sized so, must take the bilayer."""
    size = mesh_corpus.smallest_diameter(text)
    if size is None:
        return True
    extra = ["--repair"] if keys.get("repair") else []
    r = mesh_corpus.run([nanobake, "check-mesh", mesh, "--diameter", str(size)] + extra)
    print("check-mesh at the size named:", r.stdout[-600:])
    if r.returncode != 0:
        print("FAIL: the refusal names \"diameter\": %g, at which the mesh is still refused" % size)
        return False
    return True


def main():
    name, work, nanobake, nanoview, box_clashes, data = sys.argv[1:7]
    file, keys, expect, why = CASES[name]
    os.makedirs(work, exist_ok=True)
    work = os.path.abspath(work)
    mesh = extract(file, work)
    scene_file = os.path.join(work, name + ".json")
    with open(scene_file, "w") as f:
        json.dump(mesh_corpus.scene(mesh, keys, data), f, indent=1)
    package = os.path.join(work, name + ".nup")
    report = os.path.join(work, name + "-report.json")
    for stale in (package, report):
        if os.path.exists(stale):
            os.remove(stale)
    print("%s (%s): expect %s: %s" % (name, file, expect[0], why))
    start = time.monotonic()
    # --no-cache: the case is about what the shells stage does on this mesh, which a cache filled by an
    # earlier run (or by mesh_corpus's cube) would skip.
    bake = mesh_corpus.run([nanobake, scene_file, "-o", package, "--report", report, "--jobs", "2", "--no-cache"])
    seconds = time.monotonic() - start
    print(bake.stdout[-3000:])
    if expect[0] == "refused":
        ok = bake.returncode == 1 and file in bake.stdout and all(s in bake.stdout for s in expect[1:])
        ok = ok and not os.path.exists(package)
        print("refused in %.1f s" % seconds if ok else "FAIL: expected a refusal naming %s and %s" % (file, expect[1:]))
        if ok and LADDER_TEXT in bake.stdout:
            # The refusal came after judging the mesh again at growing sizes (minutes of remeshing):
            # check-mesh would repeat all of it through the same fit_membrane. The cow and bone cases
            # hold check-mesh's refusal to the bake's; tests/mesh/membrane_fit_test.cpp the ladder.
            print("check-mesh --scene not run again: the size ladder took %.0f s of the bake" % seconds)
            return 0
        ok = ok and check_mesh_scene(nanobake, scene_file, False, bake.stdout) and size_works(nanobake, mesh, keys, bake.stdout)
        return 0 if ok else 1
    if bake.returncode != 0:
        print("FAIL: the bake failed")
        return 1
    with open(report) as f:
        baked = json.load(f)
    print("bake: %.1f s wall, %.1f CPU s after the estimate (estimated %.1f), peak %.0f MB (estimated %.0f MB)" %
          (seconds, baked["measured"]["cpu_seconds_after_estimate"], baked["estimate"]["cpu_seconds"],
           baked["measured"]["peak_memory_bytes"] / 1e6, baked["estimate"]["peak_memory_bytes"] / 1e6))
    cell = baked["compartments"][0]
    print("remesh:", json.dumps(cell.get("remesh")))
    if not check_mesh_scene(nanobake, scene_file, True, ""):
        return 1
    if check_estimate.main([report]) != 0:
        print("FAIL: the estimate is off by more than 2x")
        return 1
    return mesh_corpus.verify_baked(package, cell, nanoview, box_clashes)


if __name__ == "__main__":
    sys.exit(main())
