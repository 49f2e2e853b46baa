#!/bin/bash
# No stall when an effect is switched on (issue #26): in a real window (Xvfb, X11 swapchain on
# lavapipe) with every cache cold (Mesa's shader cache off, no pipeline cache of ours), O switches
# ambient occlusion on, whose pipeline is not built; it is built on a worker thread, and a key sent
# during that build must be handled within 100 ms, before the build ends. Once built, a full frame
# with AO must be made. NANO_VIEW_INPUT_LOG makes the viewer log, in wall-clock seconds, frames
# begun (with their pipeline) and finished, keys handled and the build's start and end.
# usage: view_compile_xvfb.sh NANOVIEW PACKAGE WORKDIR
set -euo pipefail
nanoview=$1 package=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
cd "$work"

cat > inner.sh <<'INNER'
set -euo pipefail
nanoview=$1 package=$2
wait_for() {  # PATTERN SECONDS
  for _ in $(seq 1 $((10 * $2))); do
    grep -q "$1" view.err && return 0
    kill -0 $viewer 2>/dev/null || { echo "FAIL: the viewer exited"; cat view.err; exit 1; }
    sleep 0.1
  done
  echo "FAIL: no '$1' within $2 s"; cat view.err; exit 1
}
MESA_SHADER_CACHE_DISABLE=true NANO_VIEW_INPUT_LOG=1 "$nanoview" view "$package" --size 160x120 --no-pipeline-cache \
  --no-scene-effects 2> view.err &
viewer=$!
trap 'kill $viewer 2>/dev/null || true' EXIT
wait_for "view: full frame finished" 300
window=$(xdotool search --name "nanoview")
xdotool key --window "$window" o  # ambient occlusion on: a pipeline not built yet
wait_for "view: compiling the pipeline .* ao" 30
sleep 0.3  # inside the build (it takes seconds cold on lavapipe)
date +%s.%N > sent.txt
xdotool key --window "$window" k  # K: a keyframe (any key would do)
wait_for "view: key 75 handled" 10
wait_for "view: pipeline .* ao.* ready" 300
wait_for "frame begun at .*(.* ao.*)" 60
# The AO frame's full-resolution pass must finish too (its begun line precedes this finished line).
for _ in $(seq 1 1200); do
  awk '/frame begun at .*\(.* ao/ {b = 1} b && /view: full frame finished/ {f = 1} END {exit !f}' view.err && break
  sleep 0.1
done
kill $viewer 2>/dev/null || true
wait $viewer 2>/dev/null || true
INNER

xvfb-run -a -s "-screen 0 800x600x24" bash inner.sh "$nanoview" "$package"
sent=$(cat sent.txt)
handled=$(sed -n 's/^view: key 75 handled at \([0-9.]*\)$/\1/p' view.err | head -n1)
started=$(sed -n 's/^view: compiling the pipeline .* ao.* at \([0-9.]*\)$/\1/p' view.err | head -n1)
ready=$(sed -n 's/^view: pipeline .* ao.* ready at \([0-9.]*\)$/\1/p' view.err | head -n1)
awk '/frame begun at .*\(.* ao/ {b = 1} b && /view: full frame finished/ {f = 1} END {exit !f}' view.err ||
  { echo "FAIL: no full frame with ambient occlusion after the build"; cat view.err; exit 1; }
/usr/bin/python3 - "$sent" "$handled" "$started" "$ready" <<'PY'
import sys
sent, handled, started, ready = map(float, sys.argv[1:5])
latency = handled - sent
print(f"pipeline built in {ready - started:.2f} s on a worker thread; a key sent {sent - started:.2f} s into the build "
      f"was handled {1000 * latency:.1f} ms later, {ready - handled:.2f} s before the build ended")
if not started < sent < ready:
    sys.exit("FAIL: the key was not sent during the build: the test proves nothing")
if latency > 0.1:
    sys.exit(f"FAIL: input waited {1000 * latency:.0f} ms (more than 100 ms) during a pipeline build")
PY
