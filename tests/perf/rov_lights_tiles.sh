#!/bin/sh
# rov_lights_tiles.sh — the shipped ROV scene's lamps alone (sun off, black sky, caustics off; its rocks
# and sand as they are) at 96x54: each quality.lamps_model against the all-orders path tracer (65536
# paths per pixel, about 5 min on 2 cores), by region: the whole image and a 3 x 3 grid of tiles
# (tests/perf/image_tiles.py). Writes results/underwater/rov_lights_lamps_tiles.csv.
# Usage: tests/perf/rov_lights_tiles.sh [folder for the reference and renders, default /tmp/rov_lights_tiles]
B=${B:-build/seasim}
R=${1:-/tmp/rov_lights_tiles}
S=scenes/rov_lights.toml
mkdir -p "$R" results/underwater
LAMPS='--set camera.width=96 --set camera.height=54 --set underwater.caustics="none" --set sun.enabled=false --set sky.radiance=0'
[ -f "$R/reference.exr" ] || eval $B reference $S $LAMPS --steps 65536 -o "$R/reference.exr" || exit 1
for m in single delta_m orders; do
  eval $B render $S $LAMPS --set "'quality.lamps_model=\"$m\"'" -o "$R/$m" > /dev/null || exit 1
done
python3 tests/perf/image_tiles.py "$R/reference.exr" "$R/single/image.exr" "$R/delta_m/image.exr" "$R/orders/image.exr" \
  > results/underwater/rov_lights_lamps_tiles.csv || exit 1
cat results/underwater/rov_lights_lamps_tiles.csv
