#!/bin/sh
# underwater_sun_aureole.sh — the radiance around the refracted sun (`underwater-regions --views sun`, the
# study's camera turned to the sun over a 5 m bottom) in the issue's and coastal water at g = 0.9 and 0.95,
# the thesis and discrete-ordinates models against the path tracer, binned by the angle to the sun:
# results/underwater/sun_aureole.csv and .svg (tests/perf/underwater_sun_aureole.py). The references are
# those of tests/perf/underwater_regions_sun.sh (cached).
# Usage: tests/perf/underwater_sun_aureole.sh [out prefix, default results/underwater/sun_aureole]
B=${B:-build/seasim}
OUT=${1:-results/underwater/sun_aureole}
DUMP=$(mktemp -d)
trap 'rm -rf "$DUMP"' EXIT
$B underwater-regions tests/perf/underwater_regions.toml --waters 0.1:0.3,0.4:1.2 --g 0.9,0.95 --depths 5 \
  --views sun --models thesis,improved --spp 2048 --target-noise 0.018 --max-spp 16384 --dump "$DUMP" || exit 1
python3 "$(dirname "$0")/underwater_sun_aureole.py" "$OUT.csv" "$OUT.svg" "$DUMP"/a0.1_b0.3_g0.9_d5_sun.csv \
  "$DUMP"/a0.1_b0.3_g0.95_d5_sun.csv "$DUMP"/a0.4_b1.2_g0.9_d5_sun.csv "$DUMP"/a0.4_b1.2_g0.95_d5_sun.csv
