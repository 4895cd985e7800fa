#!/bin/sh
# sea_allorders_widened.sh — the sea seen from above, a fast model against all orders of scattering
# beyond the one setting every earlier table used (flat_sea at 96x54, camera 5 m up looking 45° down,
# sun 40° from the zenith, g 0.9): one axis at a time, Jerlov I, IB, II, III, 3C over a bottom at 5 m
# and deep water (the views: steep, 45° below the horizon to 15° past the nadir; grazing, 3° to 63°
# below the horizon). Each line runs tests/perf/sea_allorders.sh with SCENE_SET (the path tracer's images
# kept per axis by SCENE_TAG, so a second model costs its own renders only).
#   tests/perf/sea_allorders_widened.sh [build-dir] [paths-per-pixel] [out-folder] [render --set ...]
# e.g. tests/perf/sea_allorders_widened.sh build 2048 results/sea_allorders/widened
#      tests/perf/sea_allorders_widened.sh build 2048 results/sea_allorders/widened_paper \
#        --set 'sea.model="paper"' --set sea.second_order=true
# writes <axis>.csv (sea_allorders.sh's columns) per axis; AXES="name ..." runs a subset.
set -eu
B=${1:-build}
SPP=${2:-2048}
OUT=${3:-results/sea_allorders/widened}
[ $# -ge 3 ] && shift 3 || shift $#
mkdir -p "$OUT"
# name | --set arguments for both renderers
AXES_ALL="
sun_high|--set sun.zenith_deg=20.0
sun_low|--set sun.zenith_deg=65.0
g_080|--set water.g=0.8
g_095|--set water.g=0.95
view_steep|--set camera.look_at=[0.0,0.0,-1.34]
view_grazing|--set camera.look_at=[0.0,0.0,-7.7]
"
echo "$AXES_ALL" | while IFS='|' read -r name sets; do
  [ -z "$name" ] && continue
  if [ -n "${AXES:-}" ] && ! echo " $AXES " | grep -q " $name "; then continue; fi
  echo "== $name: $sets =="
  DEPTHS="${DEPTHS:-5 1000}" SCENE_SET="$sets" SCENE_TAG="$name" sh tests/perf/sea_allorders.sh "$B" "$SPP" "$OUT/$name.csv" "$@"
done
