#!/bin/sh
# underwater_regions_fit_two_stream.sh — how the discrete-ordinates underwater model's ("improved" in the study's --models) two-stream closure and
# (The two-stream's tables: run with underwater.diffuse = "two_stream".)
# mean cosines per mode were chosen (docs/journal/underwater_regions_2_*.md): the closure (`underwater.two_stream_closure`,
# quadrature or asymptotic: TwoStreamClosure in host/underwater/underwater_ordinates_setup.h), the mean
# cosines of the two-stream's own modes e^{-k y}, e^{-k (H - y)} (μ̄_down, μ̄_up) and of the sun beam's
# diffuse offspring e^{-m y} (μ̄_beam_down, μ̄_beam_up). On the TRAINING grid of
# tests/perf/underwater_regions.sh only (its references, cached), each combination below is set on the
# fast renders only (`--model-set`, the references untouched); tests/perf/underwater_regions_fit.py
# prints per g the region cases within 5 % and the RMS of ratio - 1. The held-out grid
# (tests/perf/underwater_regions_heldout.sh) reports the result and chooses nothing.
# Usage: tests/perf/underwater_regions_fit_two_stream.sh [folder for the scan's CSVs, default
# build/underwater_regions_fit_two_stream]; COMBOS="closure_down_up_beamdown_beamup ..." to scan others.
B=${B:-build/seasim}
DIR=${1:-build/underwater_regions_fit_two_stream}
mkdir -p "$DIR"
for combo in ${COMBOS:-asymptotic_0.9_0.9_0.9_0.9 asymptotic_0.65_0.65_0.65_0.65 asymptotic_0.72_0.72_0.72_0.72 \
                       asymptotic_0.577_0.52_0.577_0.52 asymptotic_0.85_0.6_0.85_0.6 asymptotic_0.72_0.52_0.72_0.52 \
                       quadrature_0.577_0.52_0.72_0.52 quadrature_0.577_0.52_0.85_0.52}; do
  [ -f "$DIR/fit_$combo.csv" ] && continue  # a rerun completes an interrupted scan (delete DIR to redo)
  set -- $(echo "$combo" | tr _ ' ')
  $B underwater-regions tests/perf/underwater_regions.toml --waters 0.03:0.05,0.1:0.3,0.4:1.2 \
    --g 0,0.5,0.9,0.95 --depths 2,5,20,0 --views level,up --models improved --spp 2048 \
    --target-noise 0.018 --max-spp 16384 \
    --model-set underwater.diffuse='"two_stream"' --model-set underwater.two_stream_closure=$1 \
    --model-set underwater.mean_cosine_down=$2 --model-set underwater.mean_cosine_up=$3 \
    --model-set underwater.beam_mean_cosine_down=$4 --model-set underwater.beam_mean_cosine_up=$5 \
    --csv "$DIR/fit_$combo.csv" > /dev/null || exit 1
done
python3 tests/perf/underwater_regions_fit.py "$DIR"/fit_*.csv
