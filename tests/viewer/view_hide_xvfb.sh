#!/bin/bash
# `hide NAME` in a viewer script, in a real window (Xvfb, X11 swapchain on lavapipe): blood's
# cut-away screenshotted, then again with its red cells and albumin hidden. check_hidden holds the
# pair to the package's records (both names were in the first, neither is in the second, no other
# pixel changed), and the second's ids are byte-identical to `nanoview render --hide` of that view.
# usage: view_hide_xvfb.sh NANOVIEW CHECK_HIDDEN PACKAGE WORKDIR
set -euo pipefail
nanoview=$1 check_hidden=$2 package=$3 work=$4
rm -rf "$work"
mkdir -p "$work"
cd "$work"
export LP_NUM_THREADS=4

camera="position=41159,42886,60000;look_at=41159,42886,0;up=0,1,0;fov_degrees=40"
size=48x48
clip_plane="0,0,-1,5300"

cat > view.script <<SCRIPT
camera $camera
clip plane $clip_plane
wait 1
screenshot shown.png
hide rbc
hide albumin
wait 1
screenshot hidden.png
quit
SCRIPT

if ! xvfb-run -a -s "-screen 0 640x480x24" "$nanoview" view "$package" --script view.script --size $size > view.out 2> view.err; then
  echo "FAIL: nanoview view exited non-zero"; cat view.err; exit 1
fi
"$check_hidden" "$package" shown.ids hidden.ids rbc albumin
"$nanoview" render "$package" --camera "$camera" --clip-plane "$clip_plane" --hide rbc --hide albumin --size $size \
  --ids r.ids -o r.png > render.out 2> render.err
cmp hidden.ids r.ids
echo "ok: the viewer's hide equals render --hide"
