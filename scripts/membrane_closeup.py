#!/usr/bin/env python3
"""Renders docs/membranes.md's close-ups of a membrane: its leaflets side by side.

Three panels of one patch of membrane, each about 150 Å across: on the red blood cell (a package of
data/rbc.json) at the centre of its upper dimple, on the virion (data/virion.json, --scene virion)
at the centre of its +z cube face:
  1. the outer leaflet, seen from outside (2000 Å out along the normal);
  2. the inner leaflet, seen from inside with the soluble left out (--hide; on the virion the half
     below z = 300 Å is clipped away too, so the eye looks up through the lumen);
  3. the bilayer cut open by the plane x = 0 and seen edge-on: the outer leaflet above the inner one.
Each kind of lipid keeps the colour the scene gives it (cholesterol its own). Standard library only.

    scripts/membrane_closeup.py --nanoview build/runtime/nanoview --package out/rbc.nup \
        --out docs/images/rbc-leaflets.png [--scene rbc|virion] [--size 320x320] [--hide haemoglobin]
"""
import argparse
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import effects_gallery  # noqa: E402  (render, read_png, sheet)
import membrane_coverage  # noqa: E402  (the Evans-Fung surface of the red cell)

DISTANCE = 2000.0  # Å from the membrane's mid-surface to the eye
FOV = 4.3          # degrees: ~150 Å across at that distance


VIRION_RADIUS = 450.0  # data/virion.json's sphere (Å)


def panels(scene, hidden):
    """(camera, extra nanoview options, what it shows) of each panel."""
    if scene == "rbc":
        top, normal = membrane_coverage.rbc_point(0.0, 0.0, top=True)  # dimple centre, normal +z
        z = top[2]
        inside_clip = slab = []
    else:
        z = VIRION_RADIUS  # the +z face centre of the cube-sphere, normal +z
        # Keep z >= 300 Å: from below, the eye then meets the top's inner leaflet, not the bottom's outer one.
        inside_clip = ["--clip-plane", f"0,0,1,{-(VIRION_RADIUS - 150.0):g}", "--effect", "clipping"]
        # A slab 40 Å deep behind the cut: the sphere's far half would otherwise fill the frame below
        # the cut face with its inner leaflet.
        slab = ["--clip-plane", "-1,0,0,40"]
    hide = [option for name in hidden for option in ("--hide", name)]
    outside = ((0.0, 0.0, z + DISTANCE), (0.0, 0.0, z), (0.0, 1.0, 0.0), FOV)
    inside = ((0.0, 0.0, z - DISTANCE), (0.0, 0.0, z), (0.0, 1.0, 0.0), FOV)
    # The red cell's dimple rises away from its centre: from the eye's side the cut face is the lowest
    # membrane in view, the far dimple wall shows above it (the virion's top falls away instead). Aimed
    # 10 Å below the mid-surface so the inner leaflet's heads stay in the frame.
    edge_on = ((-DISTANCE, 0.0, z - 10.0), (0.0, 0.0, z - 10.0), (0.0, 0.0, 1.0), 0.8 * FOV)
    return [
        (outside, [], "outer leaflet from outside"),
        (inside, hide + inside_clip, "inner leaflet from inside"),
        # Keep x >= 0: the eye at x < 0 looks at the cut face.
        (edge_on, ["--clip-plane", "1,0,0,0"] + slab + ["--effect", "clipping"] + hide, "the bilayer cut open at x = 0"),
    ]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--nanoview", required=True)
    parser.add_argument("--package", required=True, help="a package of data/rbc.json (or blood.json), or of data/virion.json")
    parser.add_argument("--scene", choices=["rbc", "virion"], default="rbc", help="whose membrane (default rbc)")
    parser.add_argument("--out", required=True, help="the PNG the three panels are written to")
    parser.add_argument("--size", default="320x320")
    parser.add_argument("--hide", nargs="*", default=None,
                        help="left out of the inside and cut views (default: the scene's soluble, haemoglobin or lumen_standin)")
    args = parser.parse_args()
    rendered = []
    with tempfile.TemporaryDirectory() as work:
        hidden = args.hide if args.hide is not None else [{"rbc": "haemoglobin", "virion": "lumen_standin"}[args.scene]]
        for k, (camera, extra, what) in enumerate(panels(args.scene, hidden)):
            out = os.path.join(work, f"panel-{k}.png")
            effects_gallery.render(args.nanoview, args.package, camera, args.size, out, extra)
            rendered.append(effects_gallery.read_png(out))
            print(f"panel {k + 1}: {what}", flush=True)
        partial = args.out + ".partial.png"
        effects_gallery.sheet(rendered, len(rendered), partial)
        os.replace(partial, args.out)


if __name__ == "__main__":
    main()
