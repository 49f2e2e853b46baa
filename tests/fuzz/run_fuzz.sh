#!/usr/bin/env bash
# Configures and builds the clang/libFuzzer build (NANO_FUZZ_ONLY) in BUILD_DIR, and fuzzes for a
# bounded time, starting from the checked-in seeds:
#   package  the package reader + validator   (seeds tests/fuzz/corpus/, 35 s by default)
#   scene    the scene reader + feasibility   (seeds tests/fuzz/scene_corpus/, 25 s by default)
# New corpus entries and crash artifacts go to BUILD_DIR (scratch), never into the repository.
# usage: run_fuzz.sh SOURCE_DIR BUILD_DIR [build|package|scene|all]   (default all: build, then both)
# NANO_FUZZ_SECONDS overrides the time of each session.
set -euo pipefail
src=$1
build=$2
what=${3:-all}

build_fuzzers() {
  CC=clang-14 CXX=clang++-14 cmake -S "$src" -B "$build" -G Ninja -DNANO_FUZZ_ONLY=ON \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
  cmake --build "$build" --target package_fuzzer scene_fuzzer -j2
}

# fuzz NAME SECONDS MAX_LEN SEEDS [libFuzzer options...]; scratch in BUILD_DIR/{corpus,findings}
# for the package reader (as before the scene fuzzer came), BUILD_DIR/scene-{corpus,findings}.
fuzz() {
  local name=$1 seconds=${NANO_FUZZ_SECONDS:-$2} max_len=$3 seeds=$4
  shift 4
  local prefix=$([ "$name" = package ] || echo "$name-")
  local work=$build/${prefix}corpus findings=$build/${prefix}findings
  mkdir -p "$work" "$findings"
  # libFuzzer adds new inputs to the first corpus directory; the checked-in seeds are only read.
  "$build/tests/fuzz/${name}_fuzzer" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
    -max_len="$max_len" -artifact_prefix="$findings/" -print_final_stats=1 "$@" "$work" "$seeds"
}

case $what in
  build) build_fuzzers ;;
  package) fuzz package 35 16384 "$src/tests/fuzz/corpus" ;;
  scene) fuzz scene 25 65536 "$src/tests/fuzz/scene_corpus" -dict="$src/tests/fuzz/scene.dict" ;;
  all)
    build_fuzzers
    fuzz package 35 16384 "$src/tests/fuzz/corpus"
    fuzz scene 25 65536 "$src/tests/fuzz/scene_corpus" -dict="$src/tests/fuzz/scene.dict"
    ;;
  *) echo "run_fuzz.sh: unknown session '$what' (build, package, scene or all)" >&2; exit 2 ;;
esac
