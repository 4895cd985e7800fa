#!/usr/bin/env python3
"""underwater_regions_decide.py — the widened underwater study's regions whose verdict its references cannot give,
traced again with more paths.

The study (tests/perf/underwater_regions_widened.sh) judges a region of at least 40 pixels whose reference noise is
at most 2 % (tests/perf/underwater_regions_summary.py) as within 5 % of the path tracer or not. A region whose
ratio lies within two of its reference's standard errors of that band's edge (| |ratio - 1| - 0.05 | < 2 se) is
undecided: the reference's noise, not the model, sets its verdict. This lists every undecided region of one model
in the study's CSVs and, for those chosen (--misses: the judged regions outside 5 % only; --all: every undecided
one), traces its case's reference again at --spp paths per pixel through `seasim underwater-regions` (the same
scene, water, depth, view and axis key as the study) and prints the region's ratio before and after. With
--until-decided, a region still undecided is traced again with four times the paths, up to --cap: the study's
verdicts then rest on references that decide them wherever the cap allows.
The committed CSVs are not changed. Standard library only.
Usage: tests/perf/underwater_regions_decide.py [--misses | --all] [--spp N] [--until-decided [--cap N]]
           [--model improved] [--csv-dir results/underwater/widened] [--cache DIR] [--binary build/seasim]
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from underwater_regions_summary import REGIONS, judged  # the study's regions and its judging rule

HERE = os.path.dirname(os.path.abspath(__file__))


def axes():
    """name -> the scene key the axis moves, from the study's own list."""
    out = {}
    with open(os.path.join(HERE, "underwater_regions_widened.axes")) as f:
        for line in f:
            if line.strip() and not line.startswith("#"):
                name, _, sets = line.rstrip("\n").split("|")
                out[name] = sets
    return out


def undecided(r, reg):
    ratio, se = float(r[reg + "_ratio"]), float(r[reg + "_ref_rel_se"])
    return abs(abs(ratio - 1.0) - 0.05) < 2.0 * se


def trace(args, sets, r, spp):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "case.csv")
        cmd = [args.binary, "underwater-regions", "tests/perf/underwater_regions.toml", "--waters",
               f"{r['a']}:{r['b']}", "--g", r["g"], "--depths", r["depth_m"], "--views", r["view"], "--models",
               args.model, "--spp", str(spp), "--set", sets, "--csv", out]
        if args.cache:
            cmd += ["--cache", args.cache]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
        with open(out, newline="") as f:
            return next(csv.DictReader(f))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    which = p.add_mutually_exclusive_group()
    which.add_argument("--misses", action="store_true", help="trace only the judged regions outside 5 %% (default)")
    which.add_argument("--all", action="store_true", help="trace every undecided region")
    p.add_argument("--spp", type=int, default=131072)
    p.add_argument("--until-decided", action="store_true",
                   help="trace a region still undecided again with four times the paths, up to --cap")
    p.add_argument("--cap", type=int, default=131072)
    p.add_argument("--model", default="improved")
    p.add_argument("--csv-dir", default="results/underwater/widened")
    p.add_argument("--cache", default="")
    p.add_argument("--binary", default="build/seasim")
    args = p.parse_args()
    sets = axes()
    total = open_count = 0
    chosen = []
    for name in sets:
        with open(os.path.join(args.csv_dir, name + ".csv"), newline="") as f:
            for r in csv.DictReader(f):
                if r["model"] != args.model:
                    continue
                for reg in REGIONS:
                    if not judged(r, reg):
                        continue
                    total += 1
                    if not undecided(r, reg):
                        continue
                    open_count += 1
                    miss = abs(float(r[reg + "_ratio"]) - 1.0) > 0.05
                    if args.all or miss:
                        chosen.append((name, r, reg))
    until = f", four times the paths while undecided, up to {args.cap}" if args.until_decided else ""
    print(f"{args.model}: {total} judged regions, {open_count} undecided at 2 standard errors of their references; "
          f"tracing {len(chosen)} again at {args.spp} paths per pixel{until}.")
    print()
    print("| axis | a:b | bottom m | view | region | study: ratio ± se (paths) | again: ratio ± se (paths) | within 5 % |")
    print("|---|---|---:|---|---|---|---|---|")
    counts = {"yes": 0, "no": 0, "undecided": 0}
    for name, r, reg in chosen:
        spp = args.spp
        again = trace(args, sets[name], r, spp)
        while args.until_decided and undecided(again, reg) and spp * 4 <= args.cap:
            spp *= 4
            again = trace(args, sets[name], r, spp)
        ratio, se = float(again[reg + "_ratio"]), float(again[reg + "_ref_rel_se"])
        verdict = "yes" if abs(ratio - 1.0) <= 0.05 else "no"
        counts[verdict] += 1
        if undecided(again, reg):
            verdict += " (still within 2 se of the edge)"
            counts["undecided"] += 1
        print(f"| {name} | {r['a']}:{r['b']} | {r['depth_m']} | {r['view']} | {reg.replace('_', ' ')} | "
              f"{float(r[reg + '_ratio']):.3f} ± {float(r[reg + '_ref_rel_se']):.3f} ({r['reference_spp']}) | "
              f"{ratio:.3f} ± {se:.3f} ({spp}) | {verdict} |", flush=True)
    print()
    print(f"Of the {len(chosen)} traced again: {counts['yes']} within 5 %, {counts['no']} outside; "
          f"{counts['undecided']} of them still within 2 standard errors of the edge.")


if __name__ == "__main__":
    main()
