#!/usr/bin/env python3
"""underwater_regions_terms.py — the per-pixel CSVs of `seasim underwater-regions --dump DIR` summed by
region, and the water looking up split at Snell's window (d_y above or below cos 48.6°): per part the
reference, the discrete-ordinates model's render and its terms (reference/underwater_ordinates_terms.h), each as a
fraction of the reference, so a miss shows which term it is in; refl_obj: the fraction of the
part's pixels whose reflected ray meets an object (which the model does not trace).
Usage: tests/perf/underwater_regions_terms.py DIR/*.csv"""
import csv
import math
import sys

TERMS = ["inscatter_modes", "inscatter_beam", "inscatter_tms", "froxel_ss", "window", "reflected_inscatter",
         "reflected_bottom", "reflected_froxel_ss", "lambert", "model_total"]
SHORT = ["modes", "beam", "tms", "froxel", "window", "refl_ms", "refl_bot", "refl_ss", "lambert", "total"]
WINDOW_COS = math.sqrt(1.0 - (1.0 / 1.33) ** 2)  # cos of the critical angle from below (n = 1.33)


def part(row):
    r = row["region"]
    if r == "water_up":
        return "water_up, window" if float(row["d_y"]) > WINDOW_COS else "water_up, TIR"
    return r


def main(paths):
    print("| case | part | px | fast/ref | " + " | ".join(SHORT) + " | refl_obj |")
    print("|---|---|---:|---:|" + "---:|" * (len(SHORT) + 1))
    for path in paths:
        with open(path) as f:
            rows = list(csv.DictReader(f))
        if not rows or "inscatter_modes" not in rows[0]:
            continue
        parts = {}
        for row in rows:
            s = parts.setdefault(part(row), {"px": 0, "obj": 0, "reference": 0.0, "fast": 0.0, **{t: 0.0 for t in TERMS}})
            s["px"] += 1
            s["obj"] += float(row.get("reflected_object") or 0) > 0
            s["reference"] += float(row["reference"])
            s["fast"] += float(row["fast_improved"])
            for t in TERMS:
                s[t] += float(row[t])
        name = path.rsplit("/", 1)[-1][:-4]
        for p in sorted(parts):
            s = parts[p]
            ref = s["reference"] or 1.0
            cells = " | ".join("%.3f" % (s[t] / ref) for t in TERMS)
            print("| %s | %s | %d | %.3f | %s | %.2f |" % (name, p, s["px"], s["fast"] / ref, cells, s["obj"] / s["px"]))


if __name__ == "__main__":
    main(sys.argv[1:])
