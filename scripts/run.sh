#!/usr/bin/env bash
# The main job: set up, build, bake the bundled default scene, validate the package and render it
# with nested ray queries into out/ (PNG, depth PFM, hit ids); then, when a display exists, open the
# interactive viewer on it (NANO_NO_VIEWER=1 skips that).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${NANO_BUILD_DIR:-$here/build}
out_dir=${NANO_OUT_DIR:-$here/out}
scene=${1:-$here/data/virion.json}
bash "$here/scripts/setup.sh"
export LP_NUM_THREADS=${LP_NUM_THREADS:-4}
nanobake=$build_dir/bake/nanobake
nanoview=$build_dir/runtime/nanoview
name=$(basename "$scene" .json)
mkdir -p "$out_dir"

echo "== Vulkan device"
"$nanoview" devices

echo "== Bake $scene"
"$nanobake" "$scene" -o "$out_dir/$name.nup" --report "$out_dir/$name-report.json" --jobs "${NANO_JOBS:-2}"
"$nanoview" validate "$out_dir/$name.nup"

echo "== Render"
"$nanoview" render "$out_dir/$name.nup" -o "$out_dir/$name.png" --size "${NANO_SIZE:-512x512}" \
  --depth "$out_dir/$name-depth.pfm" --ids "$out_dir/$name-ids.bin" ${NANO_CAMERA:+--camera "$NANO_CAMERA"}

echo
echo "Image, depth and ids: $out_dir/$name.png, $name-depth.pfm, $name-ids.bin (package and bake report beside them)."

if [[ -n "${DISPLAY:-}" && -z "${NANO_NO_VIEWER:-}" ]]; then  # GLFW here is built for X11
  echo "== Viewer (a display exists): drag to orbit, Tab for fly mode, click to pick, F12 for a screenshot"
  "$nanoview" view "$out_dir/$name.nup" ${NANO_CAMERA:+--camera "$NANO_CAMERA"}
fi
