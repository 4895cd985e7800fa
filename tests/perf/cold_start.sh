#!/bin/sh
# cold_start.sh — the first frame of every shipped scene on a fresh node: wall seconds of
# `seasim render SCENE --output exr` (a new process) with empty kernel caches (seasim's and PoCL's),
# then again with the caches it left (warm), and their ratio. Prints a Markdown table.
# Usage: tests/perf/cold_start.sh [scene.toml ...]   (default: scenes/*.toml; B=build/seasim)
B=${B:-build/seasim}
T=${T:-/tmp/seasim_cold_start}
[ $# -gt 0 ] || set -- scenes/*.toml
wall() { /usr/bin/time -f "%e" "$@" 2>&1 >/dev/null | tail -1; }
echo "| scene | cold s | warm s | cold / warm |"
echo "|---|---:|---:|---:|"
for S in "$@"; do
  rm -rf "$T" && mkdir -p "$T"
  export SEASIM_CACHE_DIR="$T/seasim" POCL_CACHE_DIR="$T/pocl"
  cold=$(wall $B render "$S" -o "$T/out1" --output exr)
  warm=$(wall $B render "$S" -o "$T/out2" --output exr)
  echo "| $(basename "$S" .toml) | $cold | $warm | $(echo "$cold $warm" | awk '{ if ($2 > 0) printf "%.1f", $1 / $2; else print "-" }') |"
done
rm -rf "$T"
