#!/usr/bin/env python3
"""underwater_regions_screen.py — a model variant's region ratios on every underwater study grid, from two
runs of tests/perf/underwater_regions_screen.sh (today's model, then the variant's) against the same cheap
references: the committed ratio (results/underwater/, full references) times variant / today, per region.
Judged as tests/perf/underwater_regions_summary.py judges (at least 40 pixels, reference noise <= 2 %).
Prints, per grid, the judged regions within 5 % before and after, and with --list every region the variant
moves by more than 0.3 % that is outside 5 % before or after. Standard library only.
Usage: tests/perf/underwater_regions_screen.py TODAY_DIR VARIANT_DIR [--list] [--committed results/underwater]
"""
import csv
import os
import sys

from underwater_regions_summary import REGIONS, judged  # the summary's regions and its judging rule

WITHIN = 0.05


def load(path):
    with open(path, newline="") as f:
        return {(r["a"], r["b"], r["g"], r["depth_m"], r["view"]): r for r in csv.DictReader(f)
                if r["model"] == "improved"}


def main(argv):
    args = [a for a in argv if not a.startswith("--")]
    committed = "results/underwater"
    if "--committed" in argv:
        committed = argv[argv.index("--committed") + 1]
        args.remove(committed)
    today_dir, variant_dir = args[0], args[1]
    show = "--list" in argv
    total = within_before = within_after = 0
    err_before = err_after = 0.0
    for root, _, files in sorted(os.walk(today_dir)):
        for name in sorted(f for f in files if f.endswith(".csv")):
            rel = os.path.relpath(os.path.join(root, name), today_dir)
            old = load(os.path.join(committed, rel))
            today, variant = load(os.path.join(root, name)), load(os.path.join(variant_dir, rel))
            n = before = after = 0
            for key, r in sorted(old.items()):
                for reg in REGIONS:
                    if not judged(r, reg):
                        continue
                    o = float(r[reg + "_ratio"])
                    change = float(variant[key][reg + "_ratio"]) / float(today[key][reg + "_ratio"])
                    moved = o * change
                    n += 1
                    before += abs(o - 1) <= WITHIN
                    after += abs(moved - 1) <= WITHIN
                    err_before += abs(o - 1)
                    err_after += abs(moved - 1)
                    if show and abs(change - 1) > 0.003 and (abs(moved - 1) > WITHIN or abs(o - 1) > WITHIN):
                        print(f"   {rel} {':'.join(key)} {reg}: {o:.3f} -> {moved:.3f}")
            print(f"{rel}: within 5 % {before} -> {after} of {n}")
            total += n
            within_before += before
            within_after += after
    print(f"all grids: within 5 % {within_before} -> {within_after} of {total}; "
          f"mean |ratio - 1| {err_before / total:.4f} -> {err_after / total:.4f}")


if __name__ == "__main__":
    main(sys.argv[1:])
