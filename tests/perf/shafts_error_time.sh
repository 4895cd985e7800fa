#!/usr/bin/env bash
# shafts_error_time.sh — error–time curves of the spotlight shafts: the intervals method
# (quality.shafts_panel_deg), paper 001's sampling planes (n, m), the device's march
# (quality.shafts_march_steps) and the CPU ray marcher (`seasim reference --steps N`), each against a
# converged ray march, in one run.
#
# Usage: tests/perf/shafts_error_time.sh BUILD_DIR SCENE.toml LIGHTS REFERENCE.exr OUT.csv
#   LIGHTS: the scene's spotlight count (bench --lights).
#   REFERENCE.exr: `seasim reference SCENE --steps 16000 -o REFERENCE.exr` (the converged march).
# Time is process CPU seconds (user + system, PoCL's and oneTBB's threads included) per frame, not
# wall time: the 2-core VM is shared and wall times move by up to 5x between runs. Fixed costs are
# taken out by difference: a fast-method frame is (CPU of `bench --repeat 6` - CPU of `bench
# --repeat 1`) / 5; a ray march is CPU of `reference --steps N` - CPU of `reference --steps 1`.
# Error: `seasim compare` RMS in 8-bit levels of one rendered frame against REFERENCE.exr.
# RM_STEPS (environment): the CPU ray-march step counts, default "10 20 50 100 200 400 800 1600";
# MARCH_STEPS: the device march's, default "5 10 20 40 80 160".
# Plot: tests/perf/shafts_error_time_plot.py OUT.csv OUT.svg
set -euo pipefail
build=$1 scene=$2 lights=$3 ref=$4 csv=$5
seasim="$build/seasim"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export POCL_CACHE_DIR=${POCL_CACHE_DIR:-$build/pocl-cache} SEASIM_CACHE_DIR=${SEASIM_CACHE_DIR:-$build/seasim-cache}

cpu() {  # CPU seconds of a command
  /usr/bin/time -f "%U %S" -o "$work/t" "$@" > "$work/out" 2>&1
  awk '{printf "%.3f", $1 + $2}' "$work/t"
}
rms() { "$seasim" compare "$1" "$ref" | awk '/^rmse_8bit/ {print $2}'; }

echo "method,setting,cpu_ms_per_frame,rmse_8bit" > "$csv"
fast() {  # method setting --set ...
  local method=$1 setting=$2
  shift 2
  local one six err
  "$seasim" bench --scene "$scene" --repeat 1 --lights "$lights" "$@" > /dev/null 2>&1  # builds the program once
  one=$(cpu "$seasim" bench --scene "$scene" --repeat 1 --lights "$lights" "$@")
  six=$(cpu "$seasim" bench --scene "$scene" --repeat 6 --lights "$lights" "$@")
  "$seasim" render "$scene" -o "$work/img" "$@" > /dev/null 2>&1
  err=$(rms "$work/img/image.exr")
  awk -v m="$method" -v s="$setting" -v a="$one" -v b="$six" -v e="$err" \
    'BEGIN {printf "%s,%s,%.1f,%s\n", m, s, (b - a) / 5 * 1000, e}' | tee -a "$csv"
}
# The intervals take at most 15 objects: a scene with more has no intervals rows.
intervals_dt="16 2|8 2|4 2|2 2|4 1|4 4|4 8|16 8"
"$seasim" plan "$scene" --set quality.shafts_method=intervals > /dev/null 2>&1 || intervals_dt=""
IFS='|' read -ra intervals_list <<< "$intervals_dt"
for dt in "${intervals_list[@]}"; do
  set -- $dt
  fast intervals "panel_deg=$1 texels=$2" --set quality.shafts_method=intervals --set quality.shafts_panel_deg=$1 \
    --set quality.shafts_panel_texels=$2
done
for nm in "10 2" "30 6" "60 12"; do
  set -- $nm
  fast planes "n=$1 m=$2" --set quality.shafts_method=planes --set quality.shafts_planes=$1 --set quality.shafts_subplanes=$2
done
for steps in ${MARCH_STEPS:-5 10 20 40 80 160}; do
  fast march "steps=$steps" --set quality.shafts_method=march --set quality.shafts_march_steps=$steps
done
base=$(cpu "$seasim" reference "$scene" --steps 1 -o "$work/r1.exr")
for steps in ${RM_STEPS:-10 20 50 100 200 400 800 1600}; do
  t=$(cpu "$seasim" reference "$scene" --steps $steps -o "$work/r.exr")
  err=$(rms "$work/r.exr")
  awk -v s="$steps" -v a="$base" -v b="$t" -v e="$err" \
    'BEGIN {printf "ray march,steps=%s,%.1f,%s\n", s, (b - a) * 1000, e}' | tee -a "$csv"
done
