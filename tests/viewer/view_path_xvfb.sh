#!/bin/bash
# Camera paths in the viewer (Xvfb, X11 swapchain on lavapipe): a script records three keyframes
# with different cameras, saves the path, and screenshots path frames 1 and 45 (between keyframes,
# camera and effect time interpolated); `nanoview render --path` of the saved file must give
# byte-identical .ids and PNGs for those frames. A second run preloads the file with `view --path`.
# usage: view_path_xvfb.sh NANOVIEW PACKAGE WORKDIR
set -euo pipefail
nanoview=$1 package=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
cd "$work"
export LP_NUM_THREADS=4
size=96x72

cat > record.script <<'SCRIPT'
camera pos=700,450,1150;at=0,0,0;up=0,1,0;fov=35
keyframe 0
camera pos=-600,300,1100;fov=40
keyframe 2
camera pos=100,900,800;at=50,0,0
keyframe 4
path save saved.json
path frame 1
screenshot frame1.png
path frame 45
screenshot frame45.png
# the last frames, one each, as a movie would show them
path play 118 120
quit
SCRIPT

# Under the Khronos validation layer: any error it reports fails the viewer (and this test).
run_view() {
  local script=$1 log=$2
  shift 2
  if ! NANO_VALIDATION=1 xvfb-run -a -s "-screen 0 640x480x24" "$nanoview" view "$package" --script "$script" \
       --size $size "$@" > "$log.out" 2> "$log.err"; then
    echo "FAIL: nanoview view --script $script exited non-zero"; cat "$log.err"; exit 1
  fi
  grep -Eq "frame\(s\) rendered, [1-9][0-9]* presented" "$log.err" || { echo "FAIL: no frame was presented"; exit 1; }
}
run_view record.script record

# The saved path reads back with the three keyframes as recorded.
python3 - saved.json <<'PY'
import json, sys
p = json.load(open(sys.argv[1]))
times = [k["time"] for k in p["keyframes"]]
if p["format"] != "nanouniverse-camera-path" or times != [0, 2, 4]:
    print("FAIL: saved path", json.dumps(p)); sys.exit(1)
if p["keyframes"][2]["position"] != [100, 900, 800] or p["keyframes"][2]["look_at"] != [50, 0, 0]:
    print("FAIL: keyframe 2 is not the third camera:", json.dumps(p["keyframes"][2])); sys.exit(1)
print("ok: the saved path has keyframes at", times)
PY

# render --path accepts the file; its frames 1 and 45 are the viewer's screenshots, byte for byte.
for k in 1 45; do
  "$nanoview" render "$package" --path saved.json --frames $k:$k --size $size --ids 'r%d.ids' -o 'r%d.png' \
    > render$k.out 2> render$k.err || { echo "FAIL: render --path saved.json --frames $k:$k"; cat render$k.err; exit 1; }
  cmp frame$k.ids r$k.ids
  cmp frame$k.png r$k.png
done
if cmp -s frame1.ids frame45.ids; then echo "FAIL: frames 1 and 45 show the same"; exit 1; fi
echo "ok: the viewer's path frames 1 and 45 equal render --path's (ids and PNG)"

# `view --path` preloads the file: its frame 45 is the same picture again.
printf 'path frame 45\nscreenshot preload45.png\nquit\n' > preload.script
run_view preload.script preload --path saved.json
cmp preload45.ids r45.ids
echo "ok: view --path saved.json shows frame 45 as render does"
