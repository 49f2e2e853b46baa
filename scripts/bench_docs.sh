#!/usr/bin/env bash
# Regenerates docs/bench/: every number docs/benchmarks.md quotes, with the commands that
# made them (this file). Run on a quiet machine after scripts/setup.sh (or scripts/test.sh) built
# the project; about an hour on 2 cores with lavapipe. Each step writes JSON, and the matrix also
# Markdown and SVG.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=$(cd "${NANO_BUILD_DIR:-$here/build}" && pwd)
out=${1:-$here/docs/bench}
export LP_NUM_THREADS=${LP_NUM_THREADS:-4}
nanobake=$build/bake/nanobake
nanoview=$build/runtime/nanoview
mkdir -p "$out/packages"
# The reports name the packages they measured as given: relative to the output folder, so that
# nothing written names where the repository was checked out.
cd "$out"
out_abs=$(pwd)
out=.
pkgs=packages

for scene in virion rbc blood blood-large; do
  "$nanobake" "$here/data/$scene.json" -o "$pkgs/$scene.nup" --report "$out/bake-$scene.json" --jobs 2 > /dev/null
  # Load, memory and frames: an orbit of 24 frames about the scene camera's target.
  "$nanoview" bench "$pkgs/$scene.nup" --size 256x256 --frames 24 --json "$out/frames-$scene.json"
  # Every accuracy knob against the default on 4 verify views (the oracle must resolve them).
  "$nanoview" bench "$pkgs/$scene.nup" --matrix --size 96x96 --frames 3 --matrix-cameras 4 \
    --json "$out/matrix-$scene.json" --markdown "$out/matrix-$scene.md" --plot "$out/matrix-$scene.svg"
done
# Every pipeline variant built cold (bench --compile turns Mesa's shader cache and ours off itself).
"$nanoview" bench "$pkgs/virion.nup" --compile --json "$out/compile-virion.json"
for scene in virion rbc; do
  "$nanoview" bench "$pkgs/$scene.nup" --effects --size 192x192 --frames 5 --json "$out/effects-$scene.json"
done
# The plasma on and off at blood's scene camera and a close-up by a red cell: frames and work per pixel.
"$nanoview" bench "$pkgs/blood.nup" --medium --json "$out/medium-blood.json" > "$out/medium-blood.md"
# Explicit instancing needs a TLAS instance per copy: only the virion (12k copies) fits.
"$nanoview" bench "$pkgs/virion.nup" --explicit --size 128x128 --frames 3 --json "$out/explicit-virion.json"
python3 "$here/scripts/bench_scale.py" "$build" "$out" --cells 1,4,20,100,1000 --size 128x128 --frames 8
rm -rf "$pkgs" "$out/scale-work"
# CPU micro-benchmarks (Google Benchmark), medians of 5.
for b in structure_bench tiles_bench shell_bench package_bench; do
  # Run from the build folder: Google Benchmark records the executable as it was called.
  (cd "$build" && "benchmarks/$b" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
    --benchmark_format=json --benchmark_out="$out_abs/micro-$b.json" > /dev/null)
done
python3 "$here/scripts/bench_summary.py" "$out"
echo "docs/bench regenerated in $out_abs"
