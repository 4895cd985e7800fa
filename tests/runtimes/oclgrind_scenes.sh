#!/usr/bin/env bash
# Every shipped scene rendered on Oclgrind's simulated OpenCL device with its API checks, memory checks
# (out-of-bounds and invalid accesses, read-only / write-only buffer misuse) and data-race detection;
# fails on any report. Oclgrind runs kernels about 10^3 times slower than PoCL, so each scene is drawn
# at 16 x 9 with its quality knobs at their smallest sensible values: the checks are about how kernels
# touch memory, which does not depend on the grid sizes.
#   tests/runtimes/oclgrind_scenes.sh SEASIM_BINARY SCENES_DIR WORK_DIR [SCENE ...]
# Oclgrind's uninitialised-value plugin is not used: it crashes Oclgrind 21.10 itself.
set -uo pipefail

seasim=${1:?usage: oclgrind_scenes.sh SEASIM_BINARY SCENES_DIR WORK_DIR [SCENE ...]}
scenes_dir=${2:?}
work=${3:?}
shift 3
command -v oclgrind >/dev/null || { echo "oclgrind_scenes: oclgrind is not installed (apt-get install oclgrind; make test-deps does it)"; exit 1; }

if [ $# -gt 0 ]; then scenes=("$@"); else scenes=("$scenes_dir"/*.toml); fi
small=(camera.width=16 camera.height=9
       quality.sea_lut_size=16 quality.sea_nz=2 quality.sea_nd=8 quality.sea_map_size=8
       quality.shafts_planes=4 quality.shafts_subplanes=2 quality.shafts_table_size=32 quality.shadow_map_size=32
       quality.froxel_x=8 quality.froxel_y=6 quality.froxel_z=8 quality.caustic_map_size=16 quality.caustic_layers=2
       quality.fourflow_table_size=8)
# OCLGRIND_EXTRA_SETS: more key=value overrides (space-separated), e.g. the ground-truth layers per band.
read -r -a extra <<<"${OCLGRIND_EXTRA_SETS:-}"
small+=("${extra[@]}")

rm -rf "$work"
mkdir -p "$work"
# A kernel cache of this run's own, so every kernel is built (and checked) by Oclgrind.
export SEASIM_CACHE_DIR="$work/seasim-cache"
failed=0 kernels_total=0
printf '%-22s %6s %8s %7s %s\n' scene exit seconds passes reports
for scene in "${scenes[@]}"; do
  name=$(basename "$scene" .toml)
  args=()
  for kv in "${small[@]}"; do args+=(--set "$kv"); done
  grep -q '^grid *=' "$scene" && args+=(--set surface.grid=16)
  log="$work/$name.oclgrind.log"
  start=$(date +%s%N)
  oclgrind --check-api --data-races --num-threads 1 --log "$log" \
    "$seasim" render "$scene" -o "$work/$name" --device oclgrind "${args[@]}" >"$work/$name.out" 2>&1
  rc=$?
  seconds=$(awk -v a="$start" -v b="$(date +%s%N)" 'BEGIN { printf "%.1f", (b - a) / 1e9 }')
  reports=0
  # Each report starts with an unindented line ("Invalid read from write-only buffer", "Index (4)
  # exceeds static array size (4)", "Read-write data race at ..."); its details are indented.
  [ -s "$log" ] && reports=$(grep -c '^[^[:space:]]' "$log")
  [ -s "$log" ] && [ "$reports" = 0 ] && reports=1   # something was logged, in a form not counted above
  # The passes that ran and their kernel files, from report.json's plan.
  kernels=0
  if [ -f "$work/$name/report.json" ]; then
    kernels=$(grep -c '"kernel": "kernels/' "$work/$name/report.json")
    grep -o '"kernel": "kernels/[a-z_0-9]*.cl"' "$work/$name/report.json" >>"$work/kernel_files.txt"
  fi
  kernels_total=$((kernels_total + kernels))
  printf '%-22s %6s %8s %7s %s\n' "$name" "$rc" "$seconds" "$kernels" "$reports"
  if [ "$rc" != 0 ] || [ "$reports" != 0 ]; then
    failed=$((failed + 1))
    echo "---- $name: exit $rc, $reports Oclgrind report(s); the first lines of $log and of the output:"
    head -n 20 "$log" 2>/dev/null
    tail -n 5 "$work/$name.out"
  fi
done
# A device that allows fewer work-items per group than the passes' 8 x 8 (as a GPU may for a
# register-heavy kernel): the launches must fall back to a size the driver chooses, not fail.
if [ -z "${OCLGRIND_EXTRA_SETS:-}" ] && { [ $# -eq 0 ] || printf '%s\n' "$@" | grep -q seabed; }; then
  small_group_scene="$scenes_dir/seabed.toml"
  args=()
  for kv in "${small[@]}"; do args+=(--set "$kv"); done
  log="$work/seabed_wgsize16.oclgrind.log"
  oclgrind --check-api --max-wgsize 16 --num-threads 1 --log "$log" "$seasim" render "$small_group_scene" \
    -o "$work/seabed_wgsize16" --device oclgrind "${args[@]}" >"$work/seabed_wgsize16.out" 2>&1
  rc=$?
  reports=0
  [ -s "$log" ] && reports=$(grep -c '^[^[:space:]]' "$log")
  printf '%-22s %6s %8s %7s %s\n' "seabed, groups <= 16" "$rc" "-" "-" "$reports"
  if [ "$rc" != 0 ] || [ "$reports" != 0 ]; then
    failed=$((failed + 1))
    echo "---- seabed on a device allowing 16 work-items per group: exit $rc"
    tail -n 5 "$work/seabed_wgsize16.out"
    head -n 20 "$log" 2>/dev/null
  fi
fi
# The lamps' orders model on its lattice (underwater_lamps_lattice and the lattice's reads): at 16x9 a
# pixel is wider than any cell, so rov_lights again at 32x18 (3.3 degrees per pixel) with 10-degree cells,
# every third pixel.
if [ -z "${OCLGRIND_EXTRA_SETS:-}" ] && { [ $# -eq 0 ] || printf '%s\n' "$@" | grep -q rov_lights; }; then
  args=()
  for kv in "${small[@]}"; do args+=(--set "$kv"); done
  args+=(--set camera.width=32 --set camera.height=18 --set quality.lamps_ms_cell_deg=10 --set spectral.count=4)
  log="$work/rov_lights_lattice.oclgrind.log"
  oclgrind --check-api --data-races --num-threads 1 --log "$log" "$seasim" render "$scenes_dir/rov_lights.toml" \
    -o "$work/rov_lights_lattice" --device oclgrind "${args[@]}" >"$work/rov_lights_lattice.out" 2>&1
  rc=$?
  reports=0
  [ -s "$log" ] && reports=$(grep -c '^[^[:space:]]' "$log")
  lattice=$(grep -c '"underwater_lamps_lattice"' "$work/rov_lights_lattice/report.json" 2>/dev/null)
  printf '%-22s %6s %8s %7s %s\n' "rov_lights, lattice" "$rc" "-" "${lattice:-0}" "$reports"
  if [ "$rc" != 0 ] || [ "$reports" != 0 ] || [ "${lattice:-0}" = 0 ]; then
    failed=$((failed + 1))
    echo "---- rov_lights with its lamps' lattice: exit $rc, $reports report(s), lattice kernel timed ${lattice:-0} time(s)"
    tail -n 5 "$work/rov_lights_lattice.out"
    head -n 20 "$log" 2>/dev/null
  fi
fi
files=0
[ -f "$work/kernel_files.txt" ] && files=$(sort -u "$work/kernel_files.txt" | wc -l)
echo "oclgrind_scenes: ${#scenes[@]} scenes, $kernels_total passes ($files kernel files) checked by Oclgrind, $failed with a report or a failure"
[ "$failed" = 0 ]
