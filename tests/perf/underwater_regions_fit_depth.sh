#!/bin/sh
# underwater_regions_fit_depth.sh — how the discrete-ordinates underwater model's ("improved" in the study's --models) asymptotic share w was chosen
# (The two-stream's tables: run with underwater.diffuse = "two_stream".)
# (docs/journal/underwater_regions_2_*.md): the diffuse field's k taken as its mean log-slope over the camera's depth, a field
# of the two-stream's fast mode and the asymptotic mode e^{-K∞ y} holding the share w of it at the
# surface (`underwater.asymptotic_share`: depthMeanDiffuseK in
# host/underwater/underwater_ordinates_setup.h; 0 = the two-stream's surface k). On the
# TRAINING grid of tests/perf/underwater_regions.sh only (its references, cached), each w below is set
# on the fast renders only (`--model-set`, the references untouched); tests/perf/underwater_regions_fit.py
# prints per g the region cases within 5 % and the RMS of ratio - 1. The held-out grid
# (tests/perf/underwater_regions_heldout.sh) reports the result and chooses nothing.
# Usage: tests/perf/underwater_regions_fit_depth.sh [folder for the scan's CSVs, default
# build/underwater_regions_fit_depth]; SHARES="0 0.1 ..." to scan others.
B=${B:-build/seasim}
DIR=${1:-build/underwater_regions_fit_depth}
mkdir -p "$DIR"
for w in ${SHARES:-0 0.1 0.2 0.3 0.4}; do
  [ -f "$DIR/fit_$w.csv" ] && continue  # a rerun completes an interrupted scan (delete DIR to redo)
  $B underwater-regions tests/perf/underwater_regions.toml --waters 0.03:0.05,0.1:0.3,0.4:1.2 \
    --g 0,0.5,0.9,0.95 --depths 2,5,20,0 --views level,up --models improved --spp 2048 \
    --target-noise 0.018 --max-spp 16384 \
    --model-set underwater.diffuse='"two_stream"' --model-set underwater.asymptotic_share=$w --csv "$DIR/fit_$w.csv" > /dev/null || exit 1
done
python3 tests/perf/underwater_regions_fit.py "$DIR"/fit_*.csv
