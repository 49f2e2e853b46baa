#!/usr/bin/env python3
"""Smoke test of one Google Benchmark executable (benchmarks/CMakeLists.txt).

    check_benchmark_json.py BENCH_EXE OUT.json [extra benchmark flags...]

Lists the executable's benchmarks, runs them all briefly (--benchmark_min_time=0.01: one or a few
iterations; Google Benchmark 1.7 takes plain seconds) with JSON output to OUT.json, and fails unless
every listed benchmark appears in the JSON without "error_occurred". An error whose message starts
with "skipped:" is an input legitimately absent on this machine (benchmarks/bench_inputs.hpp): it is
reported, not failed.
"""
import json
import subprocess
import sys


def main() -> int:
    if len(sys.argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    exe, out, extra = sys.argv[1], sys.argv[2], sys.argv[3:]
    listed = subprocess.run([exe, "--benchmark_list_tests=true", *extra], check=True, capture_output=True,
                            text=True).stdout.split()
    if not listed:
        print(f"{exe}: lists no benchmarks", file=sys.stderr)
        return 1
    subprocess.run([exe, "--benchmark_min_time=0.01", "--benchmark_format=json", f"--benchmark_out={out}",
                    *extra], check=True, stdout=subprocess.DEVNULL)
    with open(out, encoding="utf-8") as f:
        results = json.load(f)["benchmarks"]

    by_name = {r.get("run_name", r["name"]): r for r in results}
    failures = []
    for name in listed:
        r = by_name.get(name)
        if r is None:
            failures.append(f"{name}: missing from the JSON")
        elif r.get("error_occurred"):
            message = r.get("error_message", "")
            if message.startswith("skipped:"):
                print(f"{name}: {message}")
            else:
                failures.append(f"{name}: error: {message}")
        elif r.get("iterations", 0) < 1:
            failures.append(f"{name}: no iterations")
        else:
            print(f"{name}: {r['real_time']:.4g} {r['time_unit']} real per iteration")
    for failure in failures:
        print(failure, file=sys.stderr)
    print(f"{len(listed)} benchmarks, {len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
