#!/bin/bash
# The viewer never blocks on a frame (issue #16): in a real window (Xvfb, X11 swapchain on
# lavapipe) it traces a full frame that takes seconds, a key is sent with xdotool while that frame
# is in progress, and the viewer must show a frame made after it within 100 ms, before the frame finishes.
# The latency is the viewer's own (issue #29): NANO_VIEW_INPUT_LOG makes it log, per key, the end of
# the poll before the one that delivered it (the key cannot have waited longer), when it was
# received, handled and first presented, and when each full frame begins and finishes; the times
# of this script (a loaded machine delays xdotool and date, not the viewer) only place the key.
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
xdotool key --window "$window" k  # K: a keyframe (any key would do)
for _ in $(seq 1 100); do  # up to 10 s for the key to be presented (the check below bounds the latency)
  grep -q "view: key 75 presented" view.err && break
  sleep 0.1
done
kill $viewer 2>/dev/null || true
wait $viewer 2>/dev/null || true
INNER

xvfb-run -a -s "-screen 0 800x600x24" bash inner.sh "$nanoview" "$package"
grep -q '^view: key 75 presented' view.err || { echo "FAIL: no frame was presented after the key within 10 s"; cat view.err; exit 1; }
python3 - view.err <<'PY'
import re
import sys
log = open(sys.argv[1]).read().splitlines()
# The key's line, the last full frame begun before it and that frame's end, if it came.
k = next(i for i, l in enumerate(log) if l.startswith("view: key 75 presented"))
m = re.search(r"presented ([0-9.]+) ms after .*\((\d+) window frame\(s\) later\): queued after ([0-9.]+), "
              r"received ([0-9.]+), handled ([0-9.]+), presented ([0-9.]+)", log[k])
if not m:
    sys.exit(f"FAIL: cannot read the viewer's key line: {log[k]}")
latency_ms, frames = float(m.group(1)), int(m.group(2))
queued, received, handled, presented = map(float, m.groups()[2:])
begun = [i for i, l in enumerate(log[:k]) if l.startswith("view: full 640x480 frame begun at")]
if not begun:
    sys.exit("FAIL: no full frame began before the key")
began = float(re.search(r"at ([0-9.]+)", log[begun[-1]]).group(1))
ends = [l for l in log[begun[-1]:] if l.startswith("view: full frame finished at")]
finished = float(ends[0].rsplit(" ", 1)[1]) if ends else None
print(f"key queued at the earliest {queued - began:.2f} s into the full frame; received {1000 * (received - queued):.1f} ms, "
      f"handled {1000 * (handled - queued):.1f} ms, presented {latency_ms:.1f} ms after ({frames} window frame(s))"
      + (f"; the full frame finished {finished - presented:.2f} s after" if finished else "; the full frame had not finished"))
if not began < queued:
    sys.exit("FAIL: the key reached the viewer before the full frame began: the test did not send it during the frame")
if finished is not None and finished < presented:
    sys.exit("FAIL: the full frame finished before the key was presented: the viewer waited for the frame")
if latency_ms > 100:
    sys.exit(f"FAIL: the viewer presented the key {latency_ms:.0f} ms (more than 100 ms) after it was queued at the earliest")
PY
