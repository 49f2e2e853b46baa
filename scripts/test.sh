#!/usr/bin/env bash
# The whole test suite: installs what is missing, builds, runs every CTest test on lavapipe.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${NANO_BUILD_DIR:-$here/build}
bash "$here/scripts/setup.sh"
# lavapipe spreads a dispatch over LP_NUM_THREADS threads; more threads than cores still helps it.
export LP_NUM_THREADS=${LP_NUM_THREADS:-4}
# The suite draws tiny images (at most 96x96 for the oracle's sake), so compiling a pipeline (LLVM at
# its first dispatch, ~6 s a variant cold) costs far more than drawing with it. GALLIVM_PERF=nopt
# asks llvmpipe to skip LLVM's optimisation passes: a cold compile takes half as long, a frame runs
# up to twice as long, the pixels are the same (docs/tests.md). run.sh and the benchmarks keep the
# driver's default; `GALLIVM_PERF= bash scripts/test.sh` runs the suite with it.
export GALLIVM_PERF=${GALLIVM_PERF-nopt}
# Caches under the build tree, not the user's ~/.cache: Mesa's shader cache, our pipeline cache and
# the bake cache of the tests that use the default one. A run then neither reads what an earlier
# run (or the user's own work) left there nor leaves its own behind; a fresh build tree is a cold run.
export XDG_CACHE_HOME="$build_dir/test-cache"
cd "$build_dir"
# Name the Vulkan device every rendering test runs on, so the log says what was tested.
"$build_dir/runtime/nanoview" devices
# Tests labelled known-defect document open defects (see the issue notes); run them with
# `ctest -L known-defect`.
ctest --output-on-failure -j "${NANO_TEST_JOBS:-2}" -LE known-defect "$@"
