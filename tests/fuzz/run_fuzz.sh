#!/usr/bin/env bash
# Configures and builds the clang/libFuzzer build (NANO_FUZZ_ONLY) in BUILD_DIR, then fuzzes the
# package reader + validator for a bounded time starting from the seeds in tests/fuzz/corpus/.
# New corpus entries and crash artifacts go to BUILD_DIR (scratch), never into the repository.
# usage: run_fuzz.sh SOURCE_DIR BUILD_DIR   (NANO_FUZZ_SECONDS overrides the default 60 s)
set -euo pipefail
src=$1
build=$2
seconds=${NANO_FUZZ_SECONDS:-60}

CC=clang-14 CXX=clang++-14 cmake -S "$src" -B "$build" -G Ninja -DNANO_FUZZ_ONLY=ON \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" --target package_fuzzer -j2

work=$build/corpus
findings=$build/findings
mkdir -p "$work" "$findings"
# libFuzzer adds new inputs to the first corpus directory; the checked-in seeds are only read.
"$build/tests/fuzz/package_fuzzer" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
  -max_len=16384 -artifact_prefix="$findings/" -print_final_stats=1 "$work" "$src/tests/fuzz/corpus"
