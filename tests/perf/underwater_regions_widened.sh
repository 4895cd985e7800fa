#!/bin/sh
# underwater_regions_widened.sh — the underwater models by region against the path tracer beyond the
# axes every earlier grid held fixed (sun 30° at azimuth 60°, behind the camera's left; sky radiance 0.05;
# bottom albedo 0.35; camera 1.2 m above the bottom): one axis at a time, on three waters the fits never
# used alone (a:b 0.1:0.3, 0.05:0.15, 0.2:0.5), g 0.9, bottoms at 3 and 10 m and none, views level, up
# and down. The camera axes move the camera alone (1 m and 8 m down): the views still aim where they
# aim from 1.2 m above the bottom, so they tilt too (from 1 m down over a 10 m bottom, "level" looks 46°
# down). The same scene and judging as tests/perf/underwater_regions.sh; 2048 paths per pixel
# through the pixel centre, up to 16384 where a region is noisier than 1.8 %; no constant refitted.
# Usage: tests/perf/underwater_regions_widened.sh [folder, default results/underwater/widened]
#   writes <axis>.csv there, one per line of the list below; AXES="name ..." runs a subset.
# CACHE: a folder of traced references to reuse (underwater-regions --cache; its key is the scene and
# the paths, not the path tracer's code: clear it when reference.cl changes).
B=${B:-build/seasim}
OUT=${1:-results/underwater/widened}
mkdir -p "$OUT"
# The axes, one per line of tests/perf/underwater_regions_widened.axes: name | depths | --set arguments.
AXES_ALL=$(grep -v '^#' "$(dirname "$0")/underwater_regions_widened.axes")
echo "$AXES_ALL" | while IFS='|' read -r name depths sets; do
  [ -z "$name" ] && continue
  if [ -n "${AXES:-}" ] && ! echo " $AXES " | grep -q " $name "; then continue; fi
  echo "== $name: $sets (bottoms $depths) =="
  $B underwater-regions tests/perf/underwater_regions.toml --waters 0.1:0.3,0.05:0.15,0.2:0.5 --g 0.9 \
    --depths "$depths" --views level,up,down --models thesis,improved --spp 2048 --target-noise 0.018 \
    --max-spp 16384 ${CACHE:+--cache "$CACHE"} --set "$sets" --csv "$OUT/$name.csv"
done
