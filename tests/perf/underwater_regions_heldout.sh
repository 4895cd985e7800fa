#!/bin/sh
# underwater_regions_heldout.sh — the underwater models by region against the path tracer on a grid
# held out from the fit of tests/perf/underwater_regions_fit.sh: other waters (a:b = 0.05:0.15 and
# 0.2:0.5), other g (0.3, 0.7, 0.8), other bottom depths (3 and 10 m, and none), the same two views and
# scene as tests/perf/underwater_regions.sh (2048 paths per pixel; 36 references, cached).
# Usage: tests/perf/underwater_regions_heldout.sh [csv, default results/underwater/regions_heldout.csv]
B=${B:-build/seasim}
OUT=${1:-results/underwater/regions_heldout.csv}
mkdir -p "$(dirname "$OUT")"
$B underwater-regions tests/perf/underwater_regions.toml --waters 0.05:0.15,0.2:0.5 \
  --g 0.3,0.7,0.8 --depths 3,10,0 --views level,up --models thesis,improved --spp 2048 --csv "$OUT"
