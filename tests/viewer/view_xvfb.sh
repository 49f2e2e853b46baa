#!/bin/bash
# `nanoview view --script` in a real window (Xvfb, X11 swapchain on lavapipe): set a camera, render
# two frames, take a screenshot and pick a pixel; the screenshot's .ids (and PNG) must be
# byte-identical to `nanoview render` with the same camera and size.
# usage: view_xvfb.sh NANOVIEW PACKAGE WORKDIR
set -euo pipefail
nanoview=$1 package=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
cd "$work"
export LP_NUM_THREADS=4

camera="pos=700,450,1150;at=0,0,0;up=0,1,0;fov=35"
size=96x72
pick_x=48 pick_y=36
clip_plane="0,0,-1,0"  # removes the half facing the camera: the lumen shows

cat > view.script <<SCRIPT
# the same view render makes below
camera $camera
wait 2
screenshot view.png
pick $pick_x $pick_y
# clipping: one plane, another screenshot (checked with verify below)
clip plane $clip_plane
wait 1
screenshot clip.png
# a new size re-creates the swapchain; frames follow it
size 80x60
wait 1
quit
SCRIPT

# Under the Khronos validation layer: any error it reports fails the viewer (and this test).
run_view() {
  NANO_VALIDATION=1 xvfb-run -a -s "-screen 0 640x480x24" "$nanoview" view "$package" --script view.script --size $size "$@" \
    > view.out 2> view.err
}
if ! run_view; then
  echo "FAIL: nanoview view exited non-zero"; cat view.err; exit 1
fi
cat view.err

# The window really presented (swapchain + overlay), not only rendered.
if ! grep -Eq "frame\(s\) rendered, [1-9][0-9]* presented" view.err; then
  echo "FAIL: no frame was presented"; exit 1
fi

"$nanoview" render "$package" --camera "$camera" --size $size --ids r.ids -o r.png > render.out 2> render.err
cmp view.ids r.ids
cmp view.png r.png
echo "ok: the viewer's screenshot ids and PNG equal render's"

# The pick: one line of JSON with the pixel and describe_hit's keys.
if [ "$(wc -l < view.out)" -ne 1 ]; then echo "FAIL: expected one pick line"; cat view.out; exit 1; fi
grep -q "\"x\":$pick_x" view.out && grep -q "\"y\":$pick_y" view.out && grep -q '"hit":' view.out || {
  echo "FAIL: pick line lacks x, y or hit"; cat view.out; exit 1; }

if cmp -s view.ids clip.ids; then echo "FAIL: 'clip plane $clip_plane' changed nothing"; exit 1; fi

# The clipped screenshot against the CPU oracle with the same plane: what the plane removes (atoms
# whole, by centre) must be what explicit instancing removes.
"$nanoview" verify "$package" --camera "$camera" --size $size --clip-plane "$clip_plane" --ids clip.ids --require 0.999
echo "ok: the clipped screenshot agrees with the oracle"

# The viewer's pick against the CPU oracle's atom under the same pixel (describe_hit of both; the
# viewer's line has "x" and "y" added).
"$nanoview" pick "$package" --camera "$camera" --size $size --oracle $pick_x $pick_y > oracle.json
python3 - view.out oracle.json <<'PY'
import json, sys
viewer = json.loads(open(sys.argv[1]).readline())
oracle = json.loads(open(sys.argv[2]).read())
if not viewer.get("hit"):
    print("FAIL: the picked pixel shows no atom; choose a pixel on the virion"); sys.exit(1)
for d in (viewer, oracle):
    d.pop("x", None); d.pop("y", None)
# Depth is float on the device and double in the oracle: compare it within verify's tolerance.
dv, do = viewer.pop("depth"), oracle.pop("depth")
if abs(dv - do) > max(1e-3, 1e-5 * do):
    print("FAIL: depth", dv, "vs oracle", do); sys.exit(1)
if viewer != oracle:
    print("FAIL: viewer pick", json.dumps(viewer), "!= oracle", json.dumps(oracle)); sys.exit(1)
print("ok: the viewer's pick equals the oracle's:", json.dumps(viewer["atom"]))
PY
