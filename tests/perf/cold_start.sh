#!/bin/sh
# cold_start.sh — the first frame of every shipped scene on a fresh node: wall seconds of
# `seasim render SCENE --output exr` (a new process) with empty kernel caches (seasim's and PoCL's),
# first without a kernel store (a device the store was not made for), then with the store beside the
# binary (`make kernel-store`: a node whose device and driver match it), then again with the caches
# the store-fed run left (warm); and the ratios to warm. Prints a Markdown table.
# Usage: tests/perf/cold_start.sh [scene.toml ...]   (default: scenes/*.toml; B=build/seasim,
#        STORE=build/kernel-store)
B=${B:-build/seasim}
STORE=${STORE:-$(dirname "$B")/kernel-store}
T=${T:-/tmp/seasim_cold_start}
[ -d "$STORE" ] || { echo "cold_start.sh: no kernel store at $STORE (make kernel-store)" >&2; exit 2; }
[ $# -gt 0 ] || set -- scenes/*.toml
wall() { /usr/bin/time -f "%e" "$@" 2>&1 >/dev/null | tail -1; }
ratio() { echo "$1 $2" | awk '{ if ($2 > 0) printf "%.1f", $1 / $2; else print "-" }'; }
echo "| scene | cold s, no store | cold s, store | warm s | no store / warm | store / warm |"
echo "|---|---:|---:|---:|---:|---:|"
for S in "$@"; do
  rm -rf "$T" && mkdir -p "$T"
  export SEASIM_CACHE_DIR="$T/seasim" POCL_CACHE_DIR="$T/pocl"
  cold=$(SEASIM_KERNEL_STORE= wall $B render "$S" -o "$T/out0" --output exr)
  rm -rf "$T/seasim" "$T/pocl"
  stored=$(SEASIM_KERNEL_STORE="$STORE" wall $B render "$S" -o "$T/out1" --output exr)
  warm=$(SEASIM_KERNEL_STORE="$STORE" wall $B render "$S" -o "$T/out2" --output exr)
  echo "| $(basename "$S" .toml) | $cold | $stored | $warm | $(ratio "$cold" "$warm") | $(ratio "$stored" "$warm") |"
done
rm -rf "$T"
