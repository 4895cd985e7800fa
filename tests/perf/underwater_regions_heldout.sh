#!/bin/sh
# underwater_regions_heldout.sh — the underwater models by region against the path tracer on a grid
# held out from the fit of tests/perf/underwater_regions_fit.sh: other waters (a:b = 0.05:0.15 and
# 0.2:0.5), other g (0.3, 0.7, 0.8), other bottom depths (3 and 10 m, and none), the same two views and
# scene and reference paths as tests/perf/underwater_regions.sh (2048 per pixel through the pixel's
# centre, up to 16384 where a region is noisier than 1.8 %; 36 cases, their references cached).
# Usage: tests/perf/underwater_regions_heldout.sh [csv, default results/underwater/regions_heldout.csv]
B=${B:-build/seasim}
OUT=${1:-results/underwater/regions_heldout.csv}
mkdir -p "$(dirname "$OUT")"
$B underwater-regions tests/perf/underwater_regions.toml --waters 0.05:0.15,0.2:0.5 \
  --g 0.3,0.7,0.8 --depths 3,10,0 --views level,up --models thesis,improved --spp 2048 \
  --target-noise 0.018 --max-spp 16384 --csv "$OUT"
