#!/bin/sh
# cache_warm.sh — the first frame on a fresh render node, with and without `seasim cache warm`:
# wall seconds of `seasim render SCENE` (a new process each time, as a farm job) with empty caches,
# then after `cache warm` into fresh caches, then once more (everything warm).
# Usage: tests/perf/cache_warm.sh [scene.toml]   (default scenes/seabed.toml)
B=${B:-build/seasim}
S=${1:-scenes/seabed.toml}
T=${T:-/tmp/seasim_cache_warm}
rm -rf "$T" && mkdir -p "$T"
wall() { /usr/bin/time -f "%e" "$@" 2>&1 >/dev/null | tail -1; }
export SEASIM_CACHE_DIR="$T/cold/seasim" POCL_CACHE_DIR="$T/cold/pocl"
echo "cold first frame (no warm-up):     $(wall $B render "$S" -o "$T/out1" --output exr) s"
export SEASIM_CACHE_DIR="$T/warm/seasim" POCL_CACHE_DIR="$T/warm/pocl"
echo "seasim cache warm:                 $(wall $B cache warm "$S") s"
echo "first frame after cache warm:      $(wall $B render "$S" -o "$T/out2" --output exr) s"
echo "next frame (new process, warm):    $(wall $B render "$S" -o "$T/out3" --output exr) s"
echo "next frame (new process, warm):    $(wall $B render "$S" -o "$T/out4" --output exr) s"
