#!/usr/bin/env bash
# The main job: set up, build, and run the pipeline as far as it exists today.
# Scene baking (issue #4) and rendering (issue #5) are not implemented yet; until they are, this
# generates and checks the bundled proxy meshes, inspects the bundled structures, shows the
# Vulkan device that rendering will use, and says plainly where the pipeline stops.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${NANO_BUILD_DIR:-$here/build}
out_dir=${NANO_OUT_DIR:-$here/out}
bash "$here/scripts/setup.sh"
export LP_NUM_THREADS=${LP_NUM_THREADS:-4}
nanobake=$build_dir/bake/nanobake
nanoview=$build_dir/runtime/nanoview
mkdir -p "$out_dir"

echo "== Vulkan device"
"$nanoview" devices

echo "== Proxy meshes"
"$nanobake" make-mesh rbc -o "$out_dir/rbc.obj"
"$nanobake" check-mesh "$out_dir/rbc.obj"
"$nanobake" make-mesh sphere -o "$out_dir/virion.obj"
"$nanobake" check-mesh "$out_dir/virion.obj"

echo "== Molecules"
for f in "$here"/data/structures/*.pdb*; do
  "$nanobake" inspect "$f"
done

echo
echo "Stopped after the baker's inputs: baking a scene into a package (issue #4) and rendering it"
echo "(issue #5) do not exist yet. Outputs so far are in $out_dir."
