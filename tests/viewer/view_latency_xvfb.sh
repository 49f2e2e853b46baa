#!/bin/bash
# The viewer never blocks on a frame (issue #16): in a real window (Xvfb, X11 swapchain on
# lavapipe) it traces a full frame that takes seconds, a key is sent with xdotool while that frame
# is in progress, and the viewer must handle it within 100 ms and before the frame finishes.
# NANO_VIEW_INPUT_LOG makes the viewer log, in wall-clock seconds, when a full frame begins and
# finishes and when each key is handled.
# usage: view_latency_xvfb.sh NANOVIEW PACKAGE WORKDIR
set -euo pipefail
nanoview=$1 package=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
cd "$work"

cat > inner.sh <<'INNER'
set -euo pipefail
nanoview=$1 package=$2
# One lavapipe thread and a 640×480 window: the full frame of the virion takes seconds.
NANO_VIEW_INPUT_LOG=1 LP_NUM_THREADS=1 "$nanoview" view "$package" --size 640x480 2> view.err &
viewer=$!
trap 'kill $viewer 2>/dev/null || true' EXIT
for _ in $(seq 1 1200); do  # up to 120 s to open and refine up to the full frame
  grep -q "full 640x480 frame begun" view.err && break
  kill -0 $viewer 2>/dev/null || { echo "FAIL: the viewer exited"; cat view.err; exit 1; }
  sleep 0.1
done
grep -q "full 640x480 frame begun" view.err || { echo "FAIL: no full frame began"; cat view.err; exit 1; }
sleep 0.5  # well inside the frame
window=$(xdotool search --name "nanoview")
sent=$(date +%s.%N)
xdotool key --window "$window" k  # K: a keyframe (any key would do)
for _ in $(seq 1 50); do
  grep -q "view: key 75 handled" view.err && break
  sleep 0.05
done
kill $viewer 2>/dev/null || true
wait $viewer 2>/dev/null || true
echo "$sent" > sent.txt
INNER

xvfb-run -a -s "-screen 0 800x600x24" bash inner.sh "$nanoview" "$package"
sent=$(cat sent.txt)
handled=$(sed -n 's/^view: key 75 handled at \([0-9.]*\)$/\1/p' view.err | head -n1)
began=$(sed -n 's/^view: full 640x480 frame begun at \([0-9.]*\).*$/\1/p' view.err | tail -n1)
finished=$(sed -n 's/^view: full frame finished at \([0-9.]*\)$/\1/p' view.err | tail -n1)
[ -n "$handled" ] || { echo "FAIL: the key was not handled within 2.5 s"; cat view.err; exit 1; }
/usr/bin/python3 - "$sent" "$handled" "$began" "$finished" <<'PY'
import sys
sent, handled, began = map(float, sys.argv[1:4])
finished = float(sys.argv[4]) if sys.argv[4] else None
latency = handled - sent
print(f"key handled {1000 * latency:.1f} ms after it was sent; the full frame began {sent - began:.2f} s before the key"
      + (f" and finished {finished - handled:.2f} s after it" if finished and finished > began else " and had not finished"))
if finished and began < finished < handled:
    sys.exit("FAIL: the full frame finished before the key was handled: the test did not send it during the frame")
if latency > 0.1:
    sys.exit(f"FAIL: input waited {1000 * latency:.0f} ms (more than 100 ms) during a long frame")
PY
