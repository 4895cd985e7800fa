#!/bin/sh
# fast_math_scenes.sh — quality.fast_math on every shipped scene: the exact-maths image, then
# `seasim sweep` over fast_math = false, true against it (kernel ms of both, and the fast image's
# RMSE / max |Δ| from the exact one in 8-bit levels). Writes $OUT/<scene>/sweep.csv; summary on stdout.
# Usage: tests/perf/fast_math_scenes.sh [scene.toml ...]   (default: scenes/*.toml)
set -e
B=${B:-build/seasim}
OUT=${OUT:-/tmp/seasim_fast_math}
[ $# -gt 0 ] || set -- scenes/*.toml
for s in "$@"; do
  n=$(basename "$s" .toml)
  mkdir -p "$OUT/$n"
  "$B" render "$s" -o "$OUT/$n/exact" --set quality.fast_math=false --output exr > /dev/null
  echo "== $n"
  "$B" sweep "$s" --param quality.fast_math=false,true --reference "$OUT/$n/exact/image.exr" \
      --csv "$OUT/$n/sweep.csv" | grep -v "^device"
done
