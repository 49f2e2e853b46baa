#!/usr/bin/env bash
# Configures and builds the clang/libFuzzer build (NANO_FUZZ_ONLY) in BUILD_DIR, and fuzzes for a
# bounded time, starting from the checked-in seeds (docs/tests.md, "Fuzzing"):
#   package  the package reader + validator       (seeds tests/fuzz/corpus/, 15 s by default)
#   scene    the scene reader + feasibility       (seeds tests/fuzz/scene_corpus/, 12 s)
#   recipe   the cellPACK recipe reader           (seeds tests/fuzz/recipe_corpus/ and the
#            recipes of tests/cellpack/data/, 6 s)
#   obj off ply stl draco collada
#            one mesh reader each (parse_proxy_mesh; seeds tests/fuzz/mesh_corpus/FORMAT/, 6 s;
#            Collada's Assimp runs in a process of its own, started once per input that passes
#            collada_reader.cpp's checks: far fewer inputs a second)
#   pdb mmcif
#            parse_pdb / parse_mmcif and molecule_from_text (seeds tests/fuzz/structure_corpus/, 6 s)
#   gzip     structure_text_from_bytes (gzip, binary rejection), then molecule_from_text (6 s)
# All sessions run one executable, BUILD_DIR/tests/fuzz/nano_fuzzer, NANO_FUZZ_READER=SESSION naming
# the reader (a finding replays with NANO_FUZZ_READER=SESSION BUILD_DIR/tests/fuzz/nano_fuzzer FILE).
# New corpus entries and crash artifacts go to BUILD_DIR (scratch: BUILD_DIR/{corpus,findings} for
# the package reader, BUILD_DIR/NAME-{corpus,findings} for the others), never into the repository.
# usage: run_fuzz.sh SOURCE_DIR BUILD_DIR [build|SESSION...|all]   (default all: build, then every session)
# NANO_FUZZ_SECONDS overrides the time of each session; arguments after `--` go to libFuzzer.
set -euo pipefail
src=$1
build=$2
shift 2
sessions=(package scene recipe obj off ply stl draco collada pdb mmcif gzip)

# A build type of its own, since the top CMakeLists.txt fixes Release's flags. -O1 with line tables
# only: a tenth less compile time than RelWithDebInfo's -O2 -g (clang's front end and the
# instrumentation take most of it), for much the same speed per input (docs/tests.md, "Fuzzing").
# The line tables (some 7 % of the compile) and the frame pointers are kept so that a finding's
# stack traces, the allocation's from ASan's fast unwinder included, still name file and line.
fuzz_flags="-O1 -DNDEBUG -gline-tables-only -fno-omit-frame-pointer"
build_fuzzers() {
  CC=clang-14 CXX=clang++-14 cmake -S "$src" -B "$build" -G Ninja -DNANO_FUZZ_ONLY=ON \
    -DCMAKE_BUILD_TYPE=Fuzz -DCMAKE_C_FLAGS_FUZZ="$fuzz_flags" -DCMAKE_CXX_FLAGS_FUZZ="$fuzz_flags" \
    -DCMAKE_UNITY_BUILD="${NANO_UNITY_BUILD:-ON}" >/dev/null
  cmake --build "$build" --target nano_fuzzer -j2
}

# fuzz NAME SECONDS MAX_LEN SEEDS [libFuzzer options...]   (SEEDS: folders joined by ':')
fuzz() {
  local name=$1 seconds=${NANO_FUZZ_SECONDS:-$2} max_len=$3
  local -a seeds
  IFS=: read -r -a seeds <<< "$4"
  shift 4
  local prefix=$([ "$name" = package ] || echo "$name-")
  local work=$build/${prefix}corpus findings=$build/${prefix}findings
  mkdir -p "$work" "$findings"
  # libFuzzer adds new inputs to the first corpus directory; the checked-in seeds are only read.
  NANO_FUZZ_READER=$name "$build/tests/fuzz/nano_fuzzer" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
    -max_len="$max_len" -artifact_prefix="$findings/" -print_final_stats=1 "$@" "${extra[@]}" "$work" "${seeds[@]}"
}

session() {
  local fuzz_dir=$src/tests/fuzz
  case $1 in
    package) fuzz package 15 16384 "$fuzz_dir/corpus" ;;
    scene) fuzz scene 12 65536 "$fuzz_dir/scene_corpus" -dict="$fuzz_dir/scene.dict" ;;
    recipe) fuzz recipe 6 65536 "$fuzz_dir/recipe_corpus:$src/tests/cellpack/data" -dict="$fuzz_dir/recipe.dict" ;;
    obj | off | ply | stl | collada) fuzz "$1" 6 16384 "$fuzz_dir/mesh_corpus/$1" -dict="$fuzz_dir/$1.dict" ;;
    draco) fuzz draco 6 16384 "$fuzz_dir/mesh_corpus/draco" ;;
    pdb | mmcif) fuzz "$1" 6 32768 "$fuzz_dir/structure_corpus/$1" -dict="$fuzz_dir/$1.dict" ;;
    gzip) fuzz gzip 6 32768 "$fuzz_dir/structure_corpus/gzip" ;;
    *) echo "run_fuzz.sh: unknown session '$1' (build, ${sessions[*]} or all)" >&2; exit 2 ;;
  esac
}

what=()
extra=()
while [ $# -gt 0 ]; do
  if [ "$1" = -- ]; then
    shift
    extra=("$@")
    break
  fi
  what+=("$1")
  shift
done
[ ${#what[@]} -gt 0 ] || what=(all)
for w in "${what[@]}"; do
  case $w in
    build) build_fuzzers ;;
    all)
      build_fuzzers
      for s in "${sessions[@]}"; do session "$s"; done
      ;;
    *) session "$w" ;;
  esac
done
