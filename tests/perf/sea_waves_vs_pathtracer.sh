#!/bin/sh
# sea_waves_vs_pathtracer.sh — the sea seen from above through FFT waves: each shipped wave scene as it is
# (its sky, sun, water and waves), and wavy_sea with the sun moved to the side and behind the camera,
# the fast sea models ("multiple", the default, and the paper's) against the path tracer traced through
# the same waves to all orders (`seasim reference --all-orders`: the surface as common/sea_waves.h has it,
# the water's light to all orders, the sun's disk in the facets' mirror). One CSV, a scene column first.
# Foam has no counterpart in the path tracer: every scene is rendered with surface.whitecaps = false
# (ocean_noon, ocean_sunset and stormy_sea ship with it on), and whitecaps.toml is left out.
# Usage: tests/perf/sea_waves_vs_pathtracer.sh [out.csv, default results/sea_allorders/waves_vs_pathtracer.csv]
#   W, H, SPP: the size and paths per pixel (default 96 x 54, 4096); ONLY="name ...": those cases alone.
# Where the sun's glitter is in view the path tracer's estimate of it is a rare event (a path's mirror
# ray must fall in the sun's 0.27° disk): its standard error is the ratio_se column; more paths narrow it.
set -eu
OUT=${1:-results/sea_allorders/waves_vs_pathtracer.csv}
W=${W:-96}
H=${H:-54}
SPP=${SPP:-4096}
TMP=$(mktemp)
trap 'rm -f "$TMP"' EXIT
echo "scene,model,region,model_lum,pt_lum,ratio,ratio_se,rel_l2" > "$TMP"
run() {  # name scene [--set ...]
  name=$1
  scene=$2
  shift 2
  if [ -n "${ONLY:-}" ] && ! echo " $ONLY " | grep -q " $name "; then return 0; fi
  echo "== $name" >&2
  KEY=sea.model MODELS="multiple paper" REFERENCE=--all-orders tests/perf/scene_vs_pathtracer.sh "$scene" "$W" "$H" "$SPP" \
    --set surface.whitecaps=false "$@" |
    tail -n +2 | sed "s/^/$name,/" >> "$TMP"
}
run wavy_sea scenes/wavy_sea.toml
run wavy_sea_sun_side scenes/wavy_sea.toml --set sun.azimuth_deg=90
run wavy_sea_sun_behind scenes/wavy_sea.toml --set sun.azimuth_deg=0
run wavy_sea_image_sky scenes/wavy_sea_image_sky.toml
run ocean_noon scenes/ocean_noon.toml
run ocean_sunset scenes/ocean_sunset.toml
run stormy_sea scenes/stormy_sea.toml
run tropical_lagoon scenes/tropical_lagoon.toml
mv "$TMP" "$OUT"
trap - EXIT
cat "$OUT"
