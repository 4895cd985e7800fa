#!/bin/sh
# underwater_regions_sun.sh — the underwater models against the path tracer looking at the refracted sun
# (`--views sun`: the camera of tests/perf/underwater_regions.sh turned to the sun's direction in the
# water; the whole frame is water looking up, Snell's window and the beam's forward peak), which neither
# grid looks at: the training grid's waters and g, a 5 m bottom and none. Not part of the fit or of the
# training and held-out counts: it shows where the discrete-ordinates model's TMS term counts the forward peak twice
# (docs/journal/underwater_regions_4_*.md). 2048 paths per pixel through the pixel's centre, up to 16384 where a region is noisier
# than 1.8 %; the references cached.
# Usage: tests/perf/underwater_regions_sun.sh [csv, default results/underwater/regions_sun.csv]
B=${B:-build/seasim}
OUT=${1:-results/underwater/regions_sun.csv}
mkdir -p "$(dirname "$OUT")"
$B underwater-regions tests/perf/underwater_regions.toml --waters 0.03:0.05,0.1:0.3,0.4:1.2 \
  --g 0,0.5,0.9,0.95 --depths 5,0 --views sun --models thesis,improved --spp 2048 \
  --target-noise 0.018 --max-spp 16384 --csv "$OUT"
