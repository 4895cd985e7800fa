#!/usr/bin/env python3
"""shafts_auto_vs_best.py — the summary of tests/perf/shafts_auto_vs_best.sh: for each "auto" row, the
fastest fixed setting of the grid at equal or lower error (the issue's criterion: "auto" at most 1.1x
its time) and the fastest whose full-size error is within the budget.

Usage: tests/perf/shafts_auto_vs_best.py OUT.csv [OUT.csv ...]   (prints a Markdown table)
Equal error allows 0.005 levels: the grid's errors are single frames against one reference.
"""
import csv
import sys

TOLERANCE = 0.005


def main():
    print("| scene | budget | auto's choice | ms | RMS | fastest at equal error | ms | ratio "
          "| fastest within the budget (full size) | ms | ratio |")
    print("|---|---:|---|---:|---:|---|---:|---:|---|---:|---:|")
    worst = 0.0
    for path in sys.argv[1:]:
        rows = list(csv.DictReader(open(path)))
        grid = [r for r in rows if not r["setting"].startswith("auto")]
        scene = path.rsplit("/", 1)[-1].removeprefix("auto_vs_best_").removesuffix(".csv")
        for a in (r for r in rows if r["setting"].startswith("auto")):
            budget = float(a["setting"].split()[1])
            ms, err = float(a["kernel_ms"]), float(a["rmse_8bit"])
            equal = [g for g in grid if float(g["rmse_8bit"]) <= err + TOLERANCE]
            within = [g for g in grid if float(g["rmse_8bit"]) <= budget]
            e = min(equal, key=lambda g: float(g["kernel_ms"])) if equal else None
            w = min(within, key=lambda g: float(g["kernel_ms"])) if within else None
            re = ms / float(e["kernel_ms"]) if e else float("nan")
            rw = ms / float(w["kernel_ms"]) if w else float("nan")
            if e:
                worst = max(worst, re)
            print(f"| {scene} | {budget:g} | {a['chosen']} | {ms:.1f} | {err:.3f} | "
                  f"{e['setting'] if e else '-'} | {float(e['kernel_ms']) if e else float('nan'):.1f} | {re:.2f} | "
                  f"{w['setting'] if w else '-'} | {float(w['kernel_ms']) if w else float('nan'):.1f} | {rw:.2f} |")
    print(f"\nworst ratio at equal error: {worst:.2f}")


if __name__ == "__main__":
    main()
