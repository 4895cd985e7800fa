#!/bin/sh
# underwater_regions_screen.sh — every underwater study grid (tests/perf/underwater_regions*.sh: training,
# held-out, sun-facing, dim, skies, widened) re-rendered with the discrete-ordinates model against a cheap
# reference: 16 paths per pixel, no refinement, cached in $RC. Two runs of it (today's kernels, then a
# variant's through SEASIM_KERNEL_DIR or another binary B) share those references, so their ratios' quotient
# is exactly the variant's change to the model, region by region; underwater_regions_screen.py puts it on the
# committed CSVs' ratios against the full references (results/underwater/). The whole 845 judged regions in
# about 35 s on 2 cores, instead of an hour of path tracing.
# Usage: tests/perf/underwater_regions_screen.sh OUT_DIR
#   e.g. tests/perf/underwater_regions_screen.sh build/screen/today
#        SEASIM_KERNEL_DIR=/tmp/variant/kernels tests/perf/underwater_regions_screen.sh build/screen/variant
#        tests/perf/underwater_regions_screen.py build/screen/today build/screen/variant
# Env: B (binary, build/seasim), RC (reference cache, build/screen/references).
# The committed CSVs must be the model of the first run's tree (the script's .py says which differ).
set -eu
if [ "${1:-}" = --wrap ]; then
  # Called by the grid scripts as $B: their path count, noise target and models replaced.
  shift
  args=""
  prev=""
  for a in "$@"; do
    case "$prev" in
      --spp) a=16 ;;
      --target-noise) a=0 ;;
      --models) a=improved ;;
      --cache) prev=""; continue ;;  # the screen's own cache instead
    esac
    if [ "$a" = --cache ]; then prev="$a"; continue; fi
    args="$args '$(printf %s "$a" | sed "s/'/'\\\\''/g")'"
    prev="$a"
  done
  eval "exec \"\$SCREEN_BINARY\" $args --cache \"\$RC\""
fi
OUT=${1:?usage: underwater_regions_screen.sh OUT_DIR}
mkdir -p "$OUT" "$OUT/widened"
export SCREEN_BINARY="${B:-build/seasim}" RC="${RC:-build/screen/references}"
export B="$0 --wrap"
mkdir -p "$RC"
tests/perf/underwater_regions.sh "$OUT/regions.csv" >/dev/null
tests/perf/underwater_regions_heldout.sh "$OUT/regions_heldout.csv" >/dev/null
tests/perf/underwater_regions_sun.sh "$OUT/regions_sun.csv" >/dev/null
tests/perf/underwater_regions_dim.sh "$OUT/regions_dim.csv" >/dev/null
tests/perf/underwater_regions_sky.sh "$OUT" >/dev/null
tests/perf/underwater_regions_widened.sh "$OUT/widened" >/dev/null
echo "underwater_regions_screen: $(find "$OUT" -name '*.csv' | wc -l) grids in $OUT"
