#!/usr/bin/env python3
"""underwater_regions_summary.py — summarise `seasim underwater-regions` CSVs as Markdown.

For each model and region: how many (water, g, depth, view) cases, how many are within 5 % of the path
tracer, the median and worst |ratio - 1|, and the worst case; then the same by g. Standard library only.
Usage: tests/perf/underwater_regions_summary.py results/underwater/regions.csv [more.csv ...]
"""
import csv
import sys

REGIONS = ["bottom_near", "bottom_far", "water_up", "water_down", "objects"]
MIN_PIXELS = 40  # regions smaller than this (a few pixels of an object) are too noisy to judge
MAX_NOISE = 0.02  # and regions whose reference has a larger relative standard error (turbid water, far)


def judged(r, reg):
    return (r[reg + "_ratio"] and int(r[reg + "_pixels"]) >= MIN_PIXELS
            and float(r[reg + "_ref_rel_se"]) <= MAX_NOISE)


def rows(paths):
    for p in paths:
        with open(p, newline="") as f:
            yield from csv.DictReader(f)


def main(paths):
    data = list(rows(paths))
    models = sorted({r["model"] for r in data}, key=lambda m: (m != "thesis", m))
    print(f"Cases: regions of at least {MIN_PIXELS} pixels whose reference noise is <= {100 * MAX_NOISE:g} % "
          "(the others are counted as 'not judged').")
    spp = {}
    for r in data:
        if r["model"] == models[0]:
            spp[int(r["reference_spp"])] = spp.get(int(r["reference_spp"]), 0) + 1
    print("Reference paths per pixel: " + ", ".join(f"{n} case{'s' if n != 1 else ''} at {k}" for k, n in sorted(spp.items())) + ".")
    print()
    print("| model | region | cases | within 5 % | median abs(ratio-1) | worst ratio (a:b, g, depth, view) | not judged |")
    print("|---|---|---:|---:|---:|---|---:|")
    for m in models:
        for reg in REGIONS:
            cases = [r for r in data if r["model"] == m and judged(r, reg)]
            noisy = sum(1 for r in data if r["model"] == m and r[reg + "_ratio"] and not judged(r, reg))
            if not cases:
                continue
            errs = sorted(abs(float(r[reg + "_ratio"]) - 1) for r in cases)
            worst = max(cases, key=lambda r: abs(float(r[reg + "_ratio"]) - 1))
            within = sum(e <= 0.05 for e in errs)
            print(f"| {m} | {reg} | {len(cases)} | {within} | {errs[len(errs) // 2]:.3f} | "
                  f"{float(worst[reg + '_ratio']):.3f} ({float(worst['a']):g}:{float(worst['b']):g}, "
                  f"{float(worst['g']):g}, {float(worst['depth_m']):g} m, {worst['view']}) | {noisy} |")
    print()
    print("Within 5 % by g (all regions with enough pixels):")
    print()
    gs = sorted({float(r["g"]) for r in data})
    print("| model | " + " | ".join(f"g = {g:g}" for g in gs) + " |")
    print("|---|" + "---:|" * len(gs))
    for m in models:
        cells = []
        for g in gs:
            n = ok = 0
            for r in data:
                if r["model"] != m or float(r["g"]) != g:
                    continue
                for reg in REGIONS:
                    if judged(r, reg):
                        n += 1
                        ok += abs(float(r[reg + "_ratio"]) - 1) <= 0.05
            cells.append(f"{ok}/{n}")
        print(f"| {m} | " + " | ".join(cells) + " |")
    times = {}
    for r in data:
        times.setdefault(r["model"], []).append(float(r["kd_multiple_ms"]))
    print()
    print("kd_multiple kernel ms at 64x36, one band (median; launch-dominated): " +
          ", ".join(f"{m} {sorted(t)[len(t) // 2]:.2f}" for m, t in times.items()))


if __name__ == "__main__":
    main(sys.argv[1:])
