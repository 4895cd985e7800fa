#!/usr/bin/env bash
# shafts_auto_vs_best.sh — quality.shafts_method = "auto" (host/quality/shafts_method_auto.h) against
# the best fixed setting of the three device methods, at the scene's full size, in one run.
#
# Usage: tests/perf/shafts_auto_vs_best.sh BUILD_DIR SCENE.toml LIGHTS REFERENCE.exr OUT.csv
#   LIGHTS: the scene's spotlight count; REFERENCE.exr: `seasim reference SCENE --steps 16000`.
# The grid: the intervals at their defaults (up to 15 objects), the planes at (n, m) = (8, 1), (10, 1),
# (10, 2), (20, 3), (30, 6), (60, 12), the march at 5 ... 160 steps. "auto" at each budget of BUDGETS
# (default "0.25 0.5 1 2" levels) with n and m "auto" too (the shipped scenes give n = 30, m = 6, which
# the search would otherwise keep), its search in a fresh cache folder (so it runs here, once per budget).
# Time: `bench --repeat 5` kernel ms per frame (median of 5), the least over ROUNDS rounds (default 2)
# that visit every setting and every "auto" in turn; error: `seasim compare` RMS in 8-bit levels of one
# frame against REFERENCE.exr. Summary and plot: tests/perf/shafts_auto_vs_best.py OUT.csv ... --svg PLOT.svg.
set -euo pipefail
build=$1 scene=$2 lights=$3 ref=$4 csv=$5
seasim="$build/seasim"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export POCL_CACHE_DIR=${POCL_CACHE_DIR:-$build/pocl-cache}
export SEASIM_CACHE_DIR="$work/cache"

settings=()
"$seasim" plan "$scene" --set quality.shafts_method=intervals > /dev/null 2>&1 && settings+=("intervals|quality.shafts_method=\"intervals\"")
for nm in "8 1" "10 1" "10 2" "20 3" "30 6" "60 12"; do
  set -- $nm
  settings+=("planes n=$1 m=$2|quality.shafts_method=\"planes\" quality.shafts_planes=$1 quality.shafts_subplanes=$2")
done
for s in 5 10 20 40 80 160; do settings+=("march $s steps|quality.shafts_method=\"march\" quality.shafts_march_steps=$s"); done
for b in ${BUDGETS:-0.25 0.5 1 2}; do
  settings+=("auto $b|quality.shafts_method=\"auto\" quality.shafts_error_budget=$b quality.shafts_planes=\"auto\" quality.shafts_subplanes=\"auto\"")
done

sets() {  # the --set arguments of a setting's second field
  local out=()
  for kv in $1; do out+=(--set "$kv"); done
  printf '%s\n' "${out[@]}"
}

declare -A best err label
for ((round = 1; round <= ${ROUNDS:-2}; round++)); do
  for entry in "${settings[@]}"; do
    name=${entry%%|*}
    mapfile -t args < <(sets "${entry#*|}")
    if [ "$round" = 1 ]; then  # the first visit: the error (and for "auto", the search and its choice)
      "$seasim" render "$scene" -o "$work/img" "${args[@]}" > "$work/log" 2>&1
      err[$name]=$("$seasim" compare "$work/img/image.exr" "$ref" | awk '/^rmse_8bit/ {print $2}')
      label[$name]=""
      if [[ $name == auto* ]]; then
        label[$name]=$("$seasim" plan "$scene" "${args[@]}" | sed -n 's/^shafts method "auto": \(.*\), measured on.*/\1/p' | tr -d ',')
      fi
    fi
    ms=$("$seasim" bench --scene "$scene" --repeat 5 --lights "$lights" "${args[@]}" 2>&1 | awk '/ms per frame/ {print $4}')
    if [ -z "${best[$name]:-}" ] || awk -v a="$ms" -v b="${best[$name]}" 'BEGIN {exit !(a < b)}'; then best[$name]=$ms; fi
    echo "round $round: $name ${label[$name]} ${ms} ms, RMS ${err[$name]}" >&2
  done
done
echo "setting,chosen,kernel_ms,rmse_8bit" > "$csv"
for entry in "${settings[@]}"; do
  name=${entry%%|*}
  echo "$name,${label[$name]},${best[$name]},${err[$name]}" >> "$csv"
done
cat "$csv"
