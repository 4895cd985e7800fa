#!/bin/sh
# path_tracer_lamps.sh — how the path tracer sees spotlights under water: the equiangular sample inside
# each lamp's cone combined with next-event estimation at free-flight vertices (the default) against
# the plain equiangular sample on the whole segment (`reference --plain-lamp-sampling`), on
# tests/perf/lamp_glow.toml for the waters of the lamps' accuracy study (a, b, g) and two cones.
# Both estimators are heavy-tailed, so errors are batch means over K seeds (one image mean per seed),
# the two interleaved seed by seed so the machine's load falls on both alike. Per case: the two means
# and their standard errors, the variance ratio plain/combined of one run's image mean, the kernel-time
# ratio combined/plain, and the efficiency gain (variance ratio / time ratio).
# Usage: tests/perf/path_tracer_lamps.sh [K seeds, default 16] [paths per pixel per seed, default 256]
# Writes results/underwater/path_tracer_lamps.csv and prints a Markdown table.
B=${B:-build/seasim}
K=${1:-16}
SPP=${2:-256}
S=tests/perf/lamp_glow.toml
OUT=results/underwater/path_tracer_lamps.csv
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
mkdir -p results/underwater
echo "a,b,g,cone_deg,seeds,spp,combined_mean,combined_se,plain_mean,plain_se,variance_ratio,time_ratio,efficiency" > "$OUT"
echo "| a | b | g | cone | combined | plain | variance plain/combined | time combined/plain | efficiency |"
echo "|---|---|---|---|---|---|---|---|---|"
for CASE in "0.1 0.3 0.9 20" "0.1 0.8 0.9 20" "0.1 0.3 0.5 20" "0.1 0.3 0.9 10" "0.1 0.3 0.9 60"; do
  set -- $CASE
  A=$1 BB=$2 G=$3 C=$4
  SETS="--set water.a=[$A,$A] --set water.b=[$BB,$BB] --set water.g=$G --set spotlights[0].cone_deg=$C"
  : > "$T/runs"
  i=1
  while [ $i -le "$K" ]; do
    for MODE in combined plain; do
      FLAG=""
      [ $MODE = plain ] && FLAG="--plain-lamp-sampling"
      LINE=$($B reference $S $SETS $FLAG --steps "$SPP" --seed $i -o "$T/r.exr" 2>"$T/err" | grep "image mean")
      if [ -z "$LINE" ]; then
        echo "seasim reference failed ($CASE $MODE seed $i):" >&2
        cat "$T/err" >&2
        exit 1
      fi
      MEAN=$(echo "$LINE" | sed 's/.*image mean \([^)]*\)).*/\1/')
      MS=$(echo "$LINE" | sed 's/.*, \([0-9.]*\) ms on.*/\1/')
      echo "$MODE $MEAN $MS" >> "$T/runs"
    done
    i=$((i + 1))
  done
  awk -v a=$A -v b=$BB -v g=$G -v c=$C -v k=$K -v spp=$SPP -v out="$OUT" '
    { n[$1]++; s[$1] += $2; s2[$1] += $2 * $2; t[$1] += $3 }
    END {
      for (m in n) { mu[m] = s[m] / n[m]; v[m] = (s2[m] - n[m] * mu[m] * mu[m]) / (n[m] - 1); se[m] = sqrt(v[m] / n[m]) }
      vr = v["plain"] / v["combined"]; tr = t["combined"] / t["plain"]
      printf "%s,%s,%s,%s,%d,%d,%.6g,%.3g,%.6g,%.3g,%.4g,%.4g,%.4g\n", a, b, g, c, k, spp, mu["combined"], se["combined"], mu["plain"], se["plain"], vr, tr, vr / tr >> out
      printf "| %s | %s | %s | %s° | %.5g ± %.2g | %.5g ± %.2g | %.3g | %.3g | %.3g |\n", a, b, g, c, mu["combined"], se["combined"], mu["plain"], se["plain"], vr, tr, vr / tr
    }' "$T/runs"
done
