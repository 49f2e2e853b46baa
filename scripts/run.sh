#!/usr/bin/env bash
# The main job: set up, build, bake the bundled default scene and take it as far as the pipeline
# goes today. Rendering (issue #5) is not implemented yet; until it is, this validates the package
# and exports the atoms of a membrane patch explicitly, and says plainly where the pipeline stops.
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

echo "== Explicit instancing of one membrane patch (the oracle the renderer will be checked against)"
"$nanoview" export "$out_dir/$name.nup" --box="${NANO_EXPORT_BOX:-380,-70,-70,540,70,70}" -o "$out_dir/$name-patch.pdb"

echo
echo "Stopped before rendering: the ray-query renderer (issue #5) does not exist yet."
echo "Package, bake report and the exported patch are in $out_dir."
