#!/bin/sh
# rov_lights_sweep.sh — spotlights under water: the lamps' sampling planes against the path
# tracer, error and time per setting (results/underwater/rov_lights_*.csv, .svg; BENCHMARKS.md).
# At 96x54, caustics off (the path tracer's surface is flat and still):
#   single   lamps only (sun off, black sky), black surfaces, plain 001 (quality.lamps_delta_m = false),
#            against the tracer's single-scattering mode: the planes' own error (n, then m), with the
#            tracer's noise as the floor
#   lamps    lamps only against all orders, plain and delta-M scaled: the lamps' multiple scattering
#   full     rov_lights as shipped (sun K_d + froxels + lamps) against all orders, plain and delta-M
# Usage: tests/perf/rov_lights_sweep.sh [out folder for the references, default /tmp/rov_lights_refs]
B=${B:-build/seasim}
R=${1:-/tmp/rov_lights_refs}
mkdir -p "$R" results/underwater
S=scenes/rov_lights.toml
BASE="--set camera.width=96 --set camera.height=54 --set underwater.caustics=\"none\""
LAMPS="$BASE --set sun.enabled=false --set sky.radiance=0"
SINGLE="$LAMPS --set quality.lamps_delta_m=false --set underwater.multiple_scattering=false --set bottom.albedo=0 --set objects[0].albedo=0 --set objects[1].albedo=0"
eval $B reference $S $SINGLE --steps 16384 -o "$R/single.exr"
eval $B reference $S $LAMPS --steps 16384 -o "$R/lamps.exr"
eval $B reference $S $BASE --steps 4096 -o "$R/full.exr"
eval $B sweep $S $SINGLE --reference "$R/single.exr" --param quality.shafts_planes=2,4,8,15,30,60,120 \
  --csv results/underwater/rov_lights_single_n.csv --plot results/underwater/rov_lights_single_n.svg
eval $B sweep $S $SINGLE --reference "$R/single.exr" --param quality.shafts_subplanes=1,2,3,6,12 \
  --csv results/underwater/rov_lights_single_m.csv --plot results/underwater/rov_lights_single_m.svg
eval $B sweep $S $LAMPS --reference "$R/lamps.exr" --param quality.lamps_delta_m=false,true \
  --param quality.shafts_planes=8,30,120 --csv results/underwater/rov_lights_lamps_n.csv
eval $B sweep $S $BASE --reference "$R/full.exr" --param quality.lamps_delta_m=false,true \
  --param quality.shafts_planes=8,30,120 --csv results/underwater/rov_lights_full_n.csv
