#!/usr/bin/env python3
"""Checks a `nanoview bench --json` file holds every key docs/benchmarks.md promises for its mode, with
values of the right kind and in range: check_bench_json.py FILE frames|effects|matrix|explicit|counters|compile|medium
[KNOBS: with matrix, the --matrix-knobs asked for]"""
import json, math, sys

path, mode = sys.argv[1], sys.argv[2]
d = json.load(open(path))
problems = []

def need(obj, key, where, kind=(int, float), positive=False):
    if key not in obj:
        problems.append(f"{where}: missing '{key}'")
        return None
    v = obj[key]
    if kind and not isinstance(v, kind):
        problems.append(f"{where}.{key}: expected {kind}, got {v!r}")
    elif positive and not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
        problems.append(f"{where}.{key}: expected a positive finite number, got {v!r}")
    return v

for k in ("package", "device", "mode"):
    need(d, k, "top", str)
need(d, "package_bytes", "top", int, positive=True)
if d.get("mode") != mode:
    problems.append(f"mode is {d.get('mode')!r}, expected {mode!r}")
if d.get("validation_errors", 1) != 0:
    problems.append("validation_errors must be 0")
if mode == "frames":
    need(d, "load_seconds", "top", positive=True)
    need(d, "open_to_first_image_seconds", "top", positive=True)
    stages = need(d, "load_stages_seconds", "top", dict) or {}
    for k in ("map", "validate", "device", "upload", "nlas_builds", "mlas_builds", "ulas_builds"):
        need(stages, k, "load_stages_seconds")
    fs = need(d, "frame_seconds", "top", dict) or {}
    for k in ("min", "median", "p95"):
        need(fs, k, "frame_seconds", positive=True)
    if fs and not (fs.get("min", 0) <= fs.get("median", 0) <= fs.get("p95", 0)):
        problems.append("frame_seconds: expected min <= median <= p95")
    need(d, "rays_per_second", "top", positive=True)
    need(d, "device_memory_bytes", "top", int, positive=True)
    mem = need(d, "device_memory", "top", dict) or {}
    for k in ("package_data", "derived", "nlas", "mlas", "ulas", "flat"):
        need(mem, k, "device_memory", int)
    total = sum(mem.get(k, 0) for k in ("package_data", "derived", "nlas", "mlas", "ulas", "flat"))
    if total != d.get("device_memory_bytes"):
        problems.append(f"device_memory categories sum to {total}, not device_memory_bytes")
    need(d, "molecules_on_screen", "top", positive=True)
    coverage = need(d, "hit_pixel_fraction", "top", positive=True)
    if isinstance(coverage, (int, float)) and coverage > 1:
        problems.append(f"hit_pixel_fraction {coverage} is more than every pixel")
    flat = need(d, "flat_level", "top", dict) or {}
    for k in ("copies", "triangles", "last_build_seconds"):
        need(flat, k, "flat_level")
    # --flatten auto: the level takes at most half of what the scene itself takes.
    if mem.get("flat", 0) * 2 > total - mem.get("flat", 0):
        problems.append(f"flat level {mem.get('flat')} B is more than half the scene's {total - mem.get('flat', 0)} B")
elif mode == "effects":
    names = [v.get("name") for v in need(d, "variants", "top", list) or []]
    for n in ("no effect code", "all off", "clipping", "animation", "jitter", "ao", "shadows", "all on"):
        if n not in names:
            problems.append(f"variants: missing {n!r}")
    for v in d.get("variants", []):
        need(v, "ratio_to_all_off", v.get("name", "?"), positive=True)
elif mode == "matrix":
    rows = need(d, "matrix", "top", list) or []
    knobs = {r.get("knob") for r in rows}
    # The knobs asked for (bench --matrix-knobs), or every knob of DESIGN.md's table.
    asked = ["default"] + sys.argv[3].replace("-", " ").split(",") if len(sys.argv) > 3 else [
        "default", "hierarchy", "shell", "prism test", "precision", "lod", "flat level", "effect"]
    for k in asked:
        if k not in knobs:
            problems.append(f"matrix: no row for knob {k!r}")
    for k in knobs - set(asked):
        problems.append(f"matrix: a row for knob {k!r}, which was not asked for")
    for r in rows:
        where = f"{r.get('knob')}={r.get('value')}"
        need(r, "time_ratio", where, positive=True)
        w = need(r, "wrong_pixels_percent", where)
        if isinstance(w, (int, float)) and not 0 <= w <= 100:
            problems.append(f"{where}: wrong_pixels_percent {w} outside [0, 100]")
        q = need(r, "queries_per_pixel", where, positive=True)
        c = need(r, "candidates_per_pixel", where, positive=True)
elif mode == "explicit":
    r = need(d, "explicit_vs_virtual", "top", dict) or {}
    for k in ("explicit_seconds_median", "virtual_seconds_median", "explicit_device_bytes", "virtual_device_bytes", "copies"):
        need(r, k, "explicit_vs_virtual", positive=True)
    a = need(r, "agreement", "explicit_vs_virtual")
    if isinstance(a, (int, float)) and a < 0.999:
        problems.append(f"explicit and virtual instancing agree on only {a} of the pixels")
elif mode == "counters":
    work = need(d, "work", "top", dict) or {}
    rows = ("ulas_queries", "ulas_candidates", "prism_tests", "prisms_entered", "replas_queries", "slots_tried",
            "mlas_queries", "mlas_candidates", "ownership_rejects", "listed_rejects", "nlas_queries", "nlas_candidates",
            "sphere_tests", "core_steps", "core_boxes", "mask_rejects", "flat_queries", "flat_candidates",
            "medium_steps", "medium_keep_queries", "medium_rejects", "queries_started", "candidates_met")
    per = {}
    for side in ("virtual", "explicit"):
        s = (need(work, side, "work", dict) or {}).get("per_pixel", {})
        per[side] = {k: s.get(k, {}).get("mean", -1) for k in rows}
        for k in rows:
            st = s.get(k)
            if not isinstance(st, dict) or not (0 <= st.get("mean", -1) <= st.get("max", -1) and st.get("p95", -1) <= st.get("max", -1)):
                problems.append(f"{side}.{k}: expected 0 <= mean <= max and p95 <= max, got {st}")
    v, e = per["virtual"], per["explicit"]
    # Laws of the traversal, not measured values: one top-level query per pixel without effects;
    # explicit instancing has no other level; every nLAS query follows a molecule candidate that
    # survived the rejections; a prism is entered only after its test.
    if e["ulas_queries"] != 1 or v["ulas_queries"] != 1:
        problems.append(f"expected one top-level query per pixel, got virtual {v['ulas_queries']}, explicit {e['ulas_queries']}")
    if any(e[k] != 0 for k in ("prism_tests", "mlas_queries", "nlas_queries", "core_steps", "flat_queries")):
        problems.append("explicit instancing counted work at levels it does not have")
    if not e["sphere_tests"] <= e["ulas_candidates"]:
        problems.append("explicit: more sphere tests than candidates")
    if not v["prisms_entered"] <= v["prism_tests"]:
        problems.append("virtual: more prisms entered than tested")
    if not v["nlas_queries"] <= v["mlas_candidates"] - v["ownership_rejects"] - v["listed_rejects"] - v["mask_rejects"] + 1e-9:
        problems.append("virtual: more nLAS queries than molecule candidates that survived the rejections")
    if not v["flat_queries"] <= 1 or not v["sphere_tests"] <= v["nlas_candidates"] + v["flat_candidates"] + 1e-9:
        problems.append("virtual: at most one flat-level query a ray, and a sphere test only for an atom candidate")
    if not v["sphere_tests"] > 0 or not v["queries_started"] > v["ulas_queries"]:
        problems.append("virtual: a view of the scene should reach atoms")
    if work.get("counting_changes_no_pixel") is not True:
        problems.append("counting changed the virtual image")
    a = need(work, "agreement_virtual_vs_explicit", "work")
    if isinstance(a, (int, float)) and a < 0.999:
        problems.append(f"explicit and virtual instancing agree on only {a} of the pixels")
    fs = need(work, "frame_seconds_median", "work", dict) or {}
    for k in ("virtual_without_counter_code", "virtual", "virtual_counting", "explicit", "explicit_counting"):
        need(fs, k, "frame_seconds_median", positive=True)
elif mode == "compile":
    need(d, "cold", "top", str)
    rows = need(d, "variants", "top", list) or []
    built = {}  # pipeline name -> the row that built it
    for i, v in enumerate(rows):
        where = f"variants[{i}]"
        what = need(v, "selected_by", where, str)
        name = need(v, "pipeline", where, str)
        if "same_pipeline_as" in v:
            if built.get(name) != v["same_pipeline_as"]:
                problems.append(f"{where}: same pipeline as {v['same_pipeline_as']!r}, but that row did not build {name!r}")
        elif "unavailable" not in v:
            if name in built:
                problems.append(f"{where}: pipeline {name!r} built twice")
            built[name] = what
            need(v, "spirv_bytes", where, int, positive=True)
            need(v, "ray_query_loops", where, int, positive=True)
            for k in ("create_seconds", "first_dispatch_seconds", "total_seconds"):
                need(v, k, where, positive=True)
            if "total_seconds" in v and abs(v["total_seconds"] - v.get("create_seconds", 0) - v.get("first_dispatch_seconds", 0)) > 1e-9:
                problems.append(f"{where}: total_seconds is not create + first dispatch")
    by_what = {v.get("selected_by"): v for v in rows}
    for what in ("as render draws it", "no effect code", "every effect off", "ao", "shadows", "clipping", "jitter"):
        if what not in by_what:
            problems.append(f"no row for {what!r}")
    # Animation moves instances on the host: it selects no shader code of its own.
    if "same_pipeline_as" not in by_what.get("animation", {}):
        problems.append("animation built a pipeline of its own")
    if "no_effect_code" not in by_what.get("no effect code", {}).get("pipeline", ""):
        problems.append("'no effect code' is not the build without effect code")
elif mode == "medium":
    for k in ("scene_camera", "close_up"):
        need(d, k, "top", str)
    views = need(d, "views", "top", list) or []
    names = [v.get("name") for v in views]
    if names != ["scene camera, plasma", "scene camera, no plasma", "close-up, plasma", "close-up, no plasma"]:
        problems.append(f"views are {names}, expected each view with and without plasma")
    for i, v in enumerate(views):
        where = f"views[{i}]"
        need(v, "frame_seconds", where, dict)
        need(v, "ratio_to_without_plasma", where, positive=True)
        need(v, "hit_pixel_fraction", where)
        need(v, "work", where, dict)
    # The plasma costs medium steps where it is shown and none where it is hidden.
    steps = [(((v.get("work") or {}).get("per_pixel") or {}).get("medium_steps") or {}).get("mean") for v in views]
    if len(steps) == 4 and not (steps[0] and steps[0] > 0 and steps[1] == 0 and steps[3] == 0):
        problems.append(f"medium_steps means {steps}: expected > 0 with plasma, 0 without")
else:
    problems.append(f"unknown mode {mode}")
if problems:
    print("\n".join(problems))
    sys.exit(1)
print(f"{path}: complete ({mode})")
