#!/bin/sh
# underwater_regions.sh — the fast underwater model by region against the path tracer:
# `seasim underwater-regions` over one-band waters (a:b, Jerlov-like: clear 0.03:0.05, the issue's
# 0.1:0.3, coastal 0.4:1.2), g = 0, 0.5, 0.9, 0.95, bottom at 2, 5, 20 m and none (0), the seabed view
# ("level") and a view 30° up, for underwater.model = "thesis" and the discrete-ordinates model (--models thesis,improved); 64x36 at 2048 paths per
# pixel through each pixel's centre (the ray the fast models shade), traced again at up to 16384
# where a region of >= 40 pixels is noisier than 1.8 % (--target-noise; the CSV's reference_spp says
# which). Region noise is printed beside each ratio. The references are cached in $SEASIM_CACHE_DIR
# (or build/)/underwater_regions, so a second run only renders the fast models.
# Usage: tests/perf/underwater_regions.sh [csv, default results/underwater/regions.csv]
B=${B:-build/seasim}
OUT=${1:-results/underwater/regions.csv}
mkdir -p "$(dirname "$OUT")"
$B underwater-regions tests/perf/underwater_regions.toml --waters 0.03:0.05,0.1:0.3,0.4:1.2 \
  --g 0,0.5,0.9,0.95 --depths 2,5,20,0 --views level,up --models thesis,improved --spp 2048 \
  --target-noise 0.018 --max-spp 16384 --csv "$OUT"
