#!/bin/sh
# underwater_regions_fit.sh — how the discrete-ordinates underwater model's ("improved" in the study's --models) table of diffuse mean cosines
# (The two-stream's tables: run with underwater.diffuse = "two_stream".)
# (diffuseMeanCosines in host/underwater/underwater_ordinates_setup.cpp) was fitted: on the TRAINING grid
# of tests/perf/underwater_regions.sh (its references, cached), every pair (μ̄_down, μ̄_up) below is set
# on the fast renders only (`--model-set`, the references untouched), and
# tests/perf/underwater_regions_fit.py prints per g how many region cases are within 5 % and the RMS of
# ratio - 1. The table takes, per g, the best pair (more cases within 5 %, then the lower RMS), and is
# then reported on the held-out grid (tests/perf/underwater_regions_heldout.sh), which it never saw.
# Usage: tests/perf/underwater_regions_fit.sh [folder for the scan's CSVs, default build/underwater_regions_fit]
B=${B:-build/seasim}
DIR=${1:-build/underwater_regions_fit}
mkdir -p "$DIR"
for down in 0.45 0.5 0.55 0.577 0.62 0.67 0.72 0.77; do
  for up in 0.46 0.49 0.52 0.55 0.577; do
    [ -f "$DIR/fit_${down}_${up}.csv" ] && continue  # a rerun completes an interrupted scan (delete DIR to redo)
    $B underwater-regions tests/perf/underwater_regions.toml --waters 0.03:0.05,0.1:0.3,0.4:1.2 \
      --g 0,0.5,0.9,0.95 --depths 2,5,20,0 --views level,up --models improved --spp 2048 \
      --target-noise 0.018 --max-spp 16384 \
      --model-set underwater.diffuse='"two_stream"' --model-set underwater.mean_cosine_down=$down --model-set underwater.mean_cosine_up=$up \
      --csv "$DIR/fit_${down}_${up}.csv" > /dev/null || exit 1
  done
done
python3 tests/perf/underwater_regions_fit.py "$DIR"/fit_*.csv
