"""check_estimate.py REPORT.json [--factor 2]

The baker's estimate, made before its heavy stages (bake/scene_bake/bake_estimate.hpp), against
what the same bake then took, as its --report records both: CPU seconds of every stage after the
estimate (contention from other tests stretches wall time, not CPU time), the process's peak
resident memory, and the copies of each compartment (each protein and soluble, and the lipids
together: how a patch's species share its places is the tiles' business) within the factor.
When the bake cache served some compartments' shells, the time and memory are held against the
report's estimate_with_cache: the same model without the checking those shells did not need.
"""
import argparse
import json
import sys


def within(label, estimated, measured, factor, problems):
    ratio = estimated / measured if measured > 0 else float("inf")
    ok = 1.0 / factor <= ratio <= factor
    print(f"{label}: estimated {estimated:.4g}, measured {measured:.4g}, ratio {ratio:.2f} {'ok' if ok else 'OUTSIDE'}")
    if not ok:
        problems.append(label)


def main(argv=None):
    parser = argparse.ArgumentParser()
    parser.add_argument("report")
    parser.add_argument("--factor", type=float, default=2.0)
    args = parser.parse_args(argv)
    report = json.load(open(args.report))
    estimate, measured = report["estimate"], report["measured"]
    costs = report.get("estimate_with_cache", estimate)
    cached = [c["name"] for c in report["compartments"] if c.get("shells_from_cache")]
    if cached:
        print(f"shells of {', '.join(cached)} from the bake cache: time and memory against estimate_with_cache")
    problems = []
    within("CPU seconds after the estimate", costs["cpu_seconds"], measured["cpu_seconds_after_estimate"], args.factor,
           problems)
    within("peak memory (bytes)", costs["peak_memory_bytes"], measured["peak_memory_bytes"], args.factor, problems)
    for compartment in report["compartments"]:
        name = compartment["name"]
        guessed = estimate["copies"][name]
        lipid_names = set(compartment.get("membrane", {}).get("lipids_per_um2", {}))
        lipids_guessed = sum(n for molecule, n in guessed.items() if molecule in lipid_names)
        lipids_baked = sum(n for molecule, n in compartment["copies"].items() if molecule in lipid_names)
        if lipid_names:
            within(f"{name} lipids", lipids_guessed, lipids_baked, args.factor, problems)
        for molecule, n in compartment["copies"].items():
            if molecule in lipid_names:
                continue
            if molecule not in guessed:
                print(f"{name} {molecule}: baked {n}, not in the estimate")
                problems.append(f"{name} {molecule}")
                continue
            within(f"{name} {molecule}", guessed[molecule], n, args.factor, problems)
    if problems:
        print("outside a factor of %g: %s" % (args.factor, ", ".join(problems)))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
