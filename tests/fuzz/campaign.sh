#!/usr/bin/env bash
# A long fuzzing campaign: builds the libFuzzer targets in BUILD_DIR (run_fuzz.sh build), then fuzzes
# each target in turn for MINUTES, with the seeds, dictionaries and limits of run_fuzz.sh, and
# prints a Markdown table: executions, executions per second, coverage (edges), features, corpus
# entries and findings per target (docs/tests.md, "Fuzzing").
#   usage: campaign.sh BUILD_DIR MINUTES [TARGET...]
#   TARGET: package scene obj off ply stl draco collada pdb mmcif gzip (default: all of them, in that order)
# Each target's libFuzzer output, ending in its final stats, goes to BUILD_DIR/campaign/TARGET.log;
# the table to BUILD_DIR/campaign/summary.md too. Corpora grow in BUILD_DIR/TARGET-corpus (the
# package reader's in BUILD_DIR/corpus) across campaigns; findings (crash-, leak-, timeout-, oom-
# files) go to BUILD_DIR/TARGET-findings (BUILD_DIR/findings). libFuzzer stops a target at its
# first finding and the campaign goes on with the next one. Exit status 1 when any target had a
# finding, 2 on bad arguments.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
src=$(cd "$here/../.." && pwd)
if [ $# -lt 2 ] || ! [[ $2 =~ ^[0-9]+$ ]] || [ "$2" -lt 1 ]; then
  echo "usage: campaign.sh BUILD_DIR MINUTES [TARGET...]   (MINUTES a whole number, at least 1)" >&2
  exit 2
fi
mkdir -p "$1"
build=$(cd "$1" && pwd)
minutes=$2
shift 2
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(package scene obj off ply stl draco collada pdb mmcif gzip)
for t in "${targets[@]}"; do
  case $t in
    package | scene | obj | off | ply | stl | draco | collada | pdb | mmcif | gzip) ;;
    *) echo "campaign.sh: unknown target '$t' (package scene obj off ply stl draco collada pdb mmcif gzip)" >&2; exit 2 ;;
  esac
done

bash "$here/run_fuzz.sh" "$src" "$build" build >&2  # the table alone on stdout
out=$build/campaign
mkdir -p "$out"

# The last value of libFuzzer's "stat::NAME:" line in LOG, or "?".
final_stat() { sed -n "s/^stat::$2: *\([0-9]*\).*/\1/p" "$1" | tail -1 | grep . || echo "?"; }
# The last status line's cov, ft and corp entries, as "cov ft corp", or "? ? ?".
last_status() {
  grep -o 'cov: [0-9]* ft: [0-9]* corp: [0-9]*' "$1" | tail -1 | sed 's/cov: \([0-9]*\) ft: \([0-9]*\) corp: \([0-9]*\)/\1 \2 \3/' |
    grep . || echo "? ? ?"
}

table="| target | time | executions | exec/s | coverage (edges) | features | corpus entries | findings |
|---|---|---:|---:|---:|---:|---:|---|"
found=0
for t in "${targets[@]}"; do
  log=$out/$t.log
  findings=$build/$([ "$t" = package ] && echo findings || echo "$t-findings")
  mkdir -p "$findings"
  marker=$out/.$t.start
  touch "$marker"
  echo "campaign: $t for $minutes min -> $log" >&2
  start=$SECONDS
  status_code=0
  NANO_FUZZ_SECONDS=$((minutes * 60)) bash "$here/run_fuzz.sh" "$src" "$build" "$t" >"$log" 2>&1 || status_code=$?
  elapsed=$((SECONDS - start))
  read -r cov ft corp < <(last_status "$log")
  artifacts=$(find "$findings" -type f -newer "$marker" -printf '%f\n' | sort)
  rm -f "$marker"
  if [ -n "$artifacts" ]; then
    found=1
    what=$(sed -n 's/^SUMMARY: //p' "$log" | tail -1 | sed 's/|/\\|/g')
    result="$(echo "$artifacts" | wc -l): ${what:-see log} ($(echo "$artifacts" | tr '\n' ' ' | sed 's/ $//'))"
  elif [ "$status_code" -ne 0 ]; then
    found=1
    result="exit status $status_code, no artifact (see $t.log)"
  else
    result="none"
  fi
  table+="
| $t | $((elapsed / 60)) min $((elapsed % 60)) s | $(final_stat "$log" number_of_executed_units) | $(final_stat "$log" average_exec_per_sec) | $cov | $ft | $corp | $result |"
done
echo "$table" | tee "$out/summary.md"
exit $found
