#!/usr/bin/env python3
"""lamp_orders_summary.py — how many of the lamps' regions each model brings within 5 % of the path tracer,
from the `seasim lamp-regions` CSVs of tests/perf/lamp_orders_sweep.sh, judged as the underwater studies judge
(tests/perf/underwater_regions_summary.py: at least 40 pixels and a reference whose relative standard error
is at most 2 %). A region whose reference is noisier cannot say whether a model is within 5 %: with an error
of 5-10 % a perfect model would land outside the band a third of the time. Those regions are counted as
"not judged", and this prints how many regions outside 5 % reference noise alone would give a perfect model
under the looser rule the lamps' study used before (at least 20 pixels, noise at most 10 %).
Then every judged region outside 5 % of the last model in the tables (the sweep's default model comes last),
with its reference's error. Standard library only.
Usage: tests/perf/lamp_orders_summary.py SET=table.csv [SET=table.csv ...]
"""
import csv
import math
import sys

from underwater_regions_summary import MAX_NOISE, MIN_PIXELS, judged

REGIONS = ["whole", "lit_bottom", "beam", "outside"]
LOOSE_PIXELS, LOOSE_NOISE = 20, 0.10


def outside_by_noise(se):
    """P(|ratio - 1| > 5 %) for a perfect model whose reference has relative standard error se."""
    return math.erfc(0.05 / (se * math.sqrt(2.0))) if se > 0 else 0.0


def loose(r, reg):
    return int(r[reg + "_pixels"]) >= LOOSE_PIXELS and float(r[reg + "_ref_rel_se"]) <= LOOSE_NOISE


def main(args):
    sets = []
    for a in args:
        name, path = a.split("=", 1)
        with open(path, newline="") as f:
            sets.append((name, list(csv.DictReader(f))))
    models = []
    for _, rows in sets:
        for r in rows:
            if r["model"] not in models:
                models.append(r["model"])
    print(f"Judged: regions of at least {MIN_PIXELS} pixels whose reference noise is <= {100 * MAX_NOISE:g} %; "
          f"'loose': at least {LOOSE_PIXELS} pixels and noise <= {100 * LOOSE_NOISE:g} %.")
    print()
    print("| model | set | judged | within 5 % | mean abs(ratio-1) | worst ratio | not judged | loose: within 5 % "
          "| loose: outside 5 % by the reference's noise alone (a perfect model) |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|")
    misses = []
    for model in models:
        totals = [0, 0, 0, 0, 0, 0.0]
        for name, rows in sets:
            judged_n = within = not_judged = loose_n = loose_within = 0
            dev_sum, worst, by_noise = 0.0, None, 0.0
            for r in (r for r in rows if r["model"] == model):
                for reg in REGIONS:
                    # A region with light in the reference (lamp-regions writes ratio 0 and noise 0 where the
                    # reference has none; a model without light where the reference has some is judged: ratio 0),
                    # and enough pixels to look at.
                    if (not r[reg + "_ratio"] or int(r[reg + "_pixels"]) < LOOSE_PIXELS
                            or (float(r[reg + "_ratio"]) <= 0 and float(r[reg + "_ref_rel_se"] or 0) == 0)):
                        continue
                    ratio = float(r[reg + "_ratio"])
                    if loose(r, reg):
                        loose_n += 1
                        loose_within += abs(ratio - 1) <= 0.05
                        by_noise += outside_by_noise(float(r[reg + "_ref_rel_se"]))
                    if not judged(r, reg):
                        not_judged += 1
                        continue
                    judged_n += 1
                    within += abs(ratio - 1) <= 0.05
                    dev_sum += abs(ratio - 1)
                    if worst is None or abs(ratio - 1) > abs(worst - 1):
                        worst = ratio
                    if abs(ratio - 1) > 0.05 and model == models[-1]:
                        misses.append((model, name, f"{r['a']}:{r['b']}:{r['g']}:{r['cone_deg']}°:{r['height_m']} m", reg,
                                       ratio, float(r[reg + "_ref_rel_se"])))
            mean = dev_sum / judged_n if judged_n else float("nan")
            print(f"| {model} | {name} | {judged_n} | {within} | {mean:.3f} | "
                  f"{worst if worst is not None else float('nan'):.3f} | {not_judged} | {loose_within} of {loose_n} | "
                  f"{by_noise:.1f} |")
            for k, v in enumerate([judged_n, within, not_judged, loose_n, loose_within, by_noise]):
                totals[k] += v
        print(f"| {model} | all | {totals[0]} | {totals[1]} | | | {totals[2]} | {totals[4]} of {totals[3]} | "
              f"{totals[5]:.1f} |")
    print()
    print(f"Judged regions outside 5 % ({models[-1]}):")
    print()
    print("| model | set | a:b:g:cone:height | region | ratio | reference's rel. se |")
    print("|---|---|---|---|---:|---:|")
    for m in misses:
        print(f"| {m[0]} | {m[1]} | {m[2]} | {m[3].replace('_', ' ')} | {m[4]:.3f} | {m[5]:.3f} |")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
