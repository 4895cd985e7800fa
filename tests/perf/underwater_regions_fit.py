#!/usr/bin/env python3
"""underwater_regions_fit.py — the scan of tests/perf/underwater_regions_fit.sh as a table: for each CSV
(named fit_<mu_down>_<mu_up>.csv) and each g, the judged region cases within 5 % of the path tracer and
the RMS of ratio - 1 (the same judging as underwater_regions_summary.py), then the best pair per g.
Standard library only. Usage: tests/perf/underwater_regions_fit.py DIR/fit_*.csv (also the five-value
names of underwater_regions_fit_two_stream.sh)
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from underwater_regions_summary import REGIONS, judged, rows  # noqa: E402


def score(path):
    by_g = {}
    for r in rows([path]):
        if r["model"] != "improved":
            continue
        for reg in REGIONS:
            if judged(r, reg):
                e = float(r[reg + "_ratio"]) - 1
                s = by_g.setdefault(float(r["g"]), [0, 0, 0.0])
                s[0] += 1
                s[1] += abs(e) <= 0.05
                s[2] += e * e
    return by_g


def main(paths):
    table = {}
    for p in paths:
        # fit_<mu_down>_<mu_up>.csv, or fit_<two_stream>_<mu_down>_<mu_up>_<mu_beam_down>_<mu_beam_up>.csv
        # (underwater_regions_fit_two_stream.sh; "table" for the model's own values)
        table[tuple(os.path.basename(p)[:-4].split("_")[1:])] = score(p)
    gs = sorted({g for s in table.values() for g in s})
    width = max(len(k) for k in table)
    names = (["mu_down", "mu_up"] if width == 2 else
             ["two_stream", "mu_down", "mu_up", "mu_beam_down", "mu_beam_up"][:width])
    table = {k + ("",) * (width - len(k)): v for k, v in table.items()}
    print("| " + " | ".join(names) + " | " + " | ".join(f"g = {g:g}: within 5 %, RMS" for g in gs) + " |")
    print("|" + "---:|" * (len(names) + len(gs)))
    for key, s in sorted(table.items()):
        print("| " + " | ".join(key) + " | " +
              " | ".join(f"{s[g][1]}/{s[g][0]}, {(s[g][2] / s[g][0]) ** 0.5:.3f}" for g in gs) + " |")
    print()
    for g in gs:
        best = max(table.items(), key=lambda kv: (kv[1][g][1], -kv[1][g][2]))
        print(f"best at g = {g:g}: " + ", ".join(f"{n} {v}" for n, v in zip(names, best[0])) +
              f" ({best[1][g][1]}/{best[1][g][0]} within 5 %)")


if __name__ == "__main__":
    main(sys.argv[1:])
