#!/usr/bin/env python3
"""farm_balance.py — shard imbalance of a job, before (every N-th item) and after (balanced by
estimate, and by an earlier run's timings), measured on the render times of another run.

  tests/perf/farm_balance.py SEASIM JOB PLAN_RUN_DIR EVAL_RUN_DIR N [N ...]

PLAN_RUN_DIR and EVAL_RUN_DIR are output folders of two whole `seasim run JOB -o DIR` runs (their
manifest.json has each item's wall_ms). The "measured" plan is what `seasim farm slurm` computes from
PLAN_RUN_DIR's timings; every plan is then scored on EVAL_RUN_DIR's timings, so the measured plan is
not judged on the times it was made from. Prints Markdown table rows: job, N, then per assignment the
imbalance (largest shard / mean) and the largest shard's render time in s (the farm job's wall time
without scheduling overhead), beside the lower bound max(total / N, largest item).
"""
import json
import os
import subprocess
import sys
import tempfile


def plan(seasim, job, out_dir, n):
    subprocess.run([seasim, "farm", "slurm", job, "--tasks", str(n), "-o", out_dir],
                   check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(out_dir, "farm", f"shard-plan-{n}.json")) as f:
        p = json.load(f)
    return p["cost_source"], {i["name"]: i["shard"] for i in p["items"]}


def score(shard_of, wall_ms, n):
    loads = [0.0] * n
    for name, ms in wall_ms.items():
        loads[shard_of[name]] += ms
    mean = sum(loads) / n
    return max(loads) / mean, max(loads) / 1000.0


def main():
    seasim, job, plan_run, eval_run = sys.argv[1:5]
    counts = [int(a) for a in sys.argv[5:]]
    with open(os.path.join(eval_run, "manifest.json")) as f:
        items = json.load(f)["items"]
    wall_ms = {i["name"]: i["wall_ms"] for i in items}
    names = list(wall_ms)  # job order
    name = os.path.basename(job)
    for n in counts:
        by_count = {nm: k % n for k, nm in enumerate(names)}
        with tempfile.TemporaryDirectory() as empty:
            src_e, by_estimate = plan(seasim, job, empty, n)
        src_m, by_measured = plan(seasim, job, plan_run, n)
        assert src_e == "estimate" and src_m == "measured", (src_e, src_m)
        cells = []
        for assignment in (by_count, by_estimate, by_measured):
            imb, longest = score(assignment, wall_ms, n)
            cells.append(f"{imb:.2f} ({longest:.1f} s)")
        total = sum(wall_ms.values()) / 1000.0
        bound = max(total / n, max(wall_ms.values()) / 1000.0)  # no assignment's largest shard is shorter
        print(f"| {name} | {len(names)} | {n} | {total:.1f} s | {bound:.1f} s | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
