#!/bin/sh
# underwater_regions_dim.sh — the underwater models by region against the path tracer in the dim,
# absorbing regime no study grid covered: the camera 12 m down (the grids: 3.8 m), a low sun (75°; the
# grids: 30°), a dim sky (0.005; the grids: 0.05), absorbing, strongly forward-scattering water without
# a bottom. The same scene, views and judging as tests/perf/underwater_regions.sh; 8192 paths per pixel
# through the pixel centre, up to 32768 where a region is noisier than 1.8 %; no constant refitted.
# Usage: tests/perf/underwater_regions_dim.sh [csv, default results/underwater/regions_dim.csv]
B=${B:-build/seasim}
OUT=${1:-results/underwater/regions_dim.csv}
mkdir -p "$(dirname "$OUT")"
$B underwater-regions tests/perf/underwater_regions.toml --waters 0.3:0.2,0.4:0.1 --g 0.9,0.95 --depths 0 \
  --views level,up --models thesis,improved --spp 8192 --target-noise 0.018 --max-spp 32768 \
  --set sun.zenith_deg=75 --set sky.radiance=0.005 --set 'camera.position=[0.0, -12.0, 0.0]' --csv "$OUT"
