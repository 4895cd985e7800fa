#!/bin/sh
# underwater_regions_sky.sh — the underwater models by region against the path tracer under skies that
# are not uniform: Preetham's daylight (turbidity 3) and the environment image scenes/textures/
# sky_clear.exr, with the sun 30° and 60° from the zenith. The path tracer takes the same sky as the fast
# models (reference.cl: the sky towards each path's direction in air through Snell's window); the fast
# models take its integrals (E_D0's sky part) and, in Snell's window, its radiance. The same scene, views
# and judging as tests/perf/underwater_regions.sh; 2048 paths per pixel through the pixel centre, up to
# 16384 where a region is noisier than 1.8 %; no constant refitted.
# Usage: tests/perf/underwater_regions_sky.sh [folder, default results/underwater]
#   writes regions_sky_<sky>_sun<zenith>.csv there, one per sky and sun.
# CACHE: a folder of traced references to reuse (underwater-regions --cache; its key is the scene and
# the paths, not the path tracer's code: clear it when reference.cl changes).
B=${B:-build/seasim}
OUT=${1:-results/underwater}
mkdir -p "$OUT"
IMAGE="$(pwd)/scenes/textures/sky_clear.exr"
for sky in preetham image; do
  for sun in 30 60; do
    if [ "$sky" = image ]; then set_sky="sky.image=\"$IMAGE\""; else set_sky="sky.turbidity=3.0"; fi
    echo "== sky $sky, sun $sun deg =="
    $B underwater-regions tests/perf/underwater_regions.toml --waters 0.1:0.3,0.05:0.15,0.2:0.5 --g 0.9 \
      --depths 10,0 --views level,up --models thesis,improved --spp 2048 --target-noise 0.018 --max-spp 16384 \
      ${CACHE:+--cache "$CACHE"} --set "sky.model=\"$sky\"" --set "$set_sky" --set sun.zenith_deg=$sun --csv "$OUT/regions_sky_${sky}_sun${sun}.csv"
  done
done
