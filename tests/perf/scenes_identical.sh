#!/bin/sh
# scenes_identical.sh — every shipped scene rendered by two seasim binaries (e.g. a copy of main's
# and this tree's) at a small size with every output the scene allows (image, spectral.exr, .npy
# and, under water, every ground-truth layer), then each file of A compared with B's: "identical"
# when the bytes agree or, for EXR (whose header holds the time of writing), every channel of every
# part does (idiff -fail 0); else the largest relative L2 over its channels. A refactor that must not change an image shows "identical" on every line.
# Usage: tests/perf/scenes_identical.sh BINARY_A BINARY_B   (SIZE="96 54", SCENES="scenes/*.toml";
# KERNELS_B=DIR: B reads its kernels from DIR, as SEASIM_KERNEL_DIR; DATA_A=DIR: A reads its data
# files from DIR, as SEASIM_DATA_DIR (an older binary with the data folder of its own tree); SET="key=value ...": more --set
# for both, e.g. SET=quality.fast_math=false: kernels built without relaxed maths, whose compiler may
# contract and reorder differently once a kernel's code is moved between functions)
set -eu
A=$1
B=$2
shift 2
SIZE=${SIZE:-96 54}
W=${SIZE% *}
H=${SIZE#* }
T=${T:-/tmp/seasim_scenes_identical}
LAYERS=range,depth,normal,object_id,albedo,clear,direct,backscatter,forward,lamps,transmission,veiling,beta_d,beta_b
rm -rf "$T"
mkdir -p "$T"
# The largest over the channels of ||a - b|| / ||b||, and its channel (oiiotool --dumpdata: 9 decimals).
rel_l2() {
  python3 - "$1" "$2" <<'PY'
import subprocess, sys
def channels(path):
    out = subprocess.run(["oiiotool", "--dumpdata", path], capture_output=True, text=True, check=True).stdout
    rows = [line.split(":", 1)[1].split() for line in out.splitlines() if line.strip().startswith("Pixel (")]
    return list(zip(*[[float(v) for v in r] for r in rows]))
a, b = channels(sys.argv[1]), channels(sys.argv[2])
worst, at = 0.0, -1
for k, (ca, cb) in enumerate(zip(a, b)):
    num = sum((x - y) ** 2 for x, y in zip(ca, cb)) ** 0.5
    den = sum(y * y for y in cb) ** 0.5
    r = num / den if den > 0 else (0.0 if num == 0 else float("inf"))
    if r > worst:
        worst, at = r, k
print(f"{worst:.2e} (channel {at})")
PY
}
differ=0
for scene in ${SCENES:-scenes/*.toml}; do
  name=$(basename "$scene" .toml)
  for v in A B; do
    unset SEASIM_KERNEL_DIR SEASIM_DATA_DIR
    if [ $v = A ]; then
      bin=$A
      [ -n "${DATA_A:-}" ] && export SEASIM_DATA_DIR=$DATA_A
    else
      bin=$B
      [ -n "${KERNELS_B:-}" ] && export SEASIM_KERNEL_DIR=$KERNELS_B
    fi
    out="$T/$name.$v"
    # Layers are for the camera under water and spectral.exr for the spectral models: a scene that
    # refuses them renders with fewer outputs (the log of the last try is kept).
    set -- "--output exr,spectral_exr,npy --output $LAYERS --set spectral.spectral_exr=true" \
           "--output exr,spectral_exr,npy --set spectral.spectral_exr=true" "--output exr,npy"
    ok=0
    for outputs in "$@"; do
      rm -rf "$out"
      # shellcheck disable=SC2086
      sets=""
      for kv in ${SET:-}; do sets="$sets --set $kv"; done
      if "$bin" render "$scene" -o "$out" --set camera.width=$W --set camera.height=$H $sets $outputs > "$out.log" 2>&1; then
        ok=1
        break
      fi
    done
    [ $ok = 1 ] || { echo "$name: $v failed (log $out.log)"; exit 1; }
  done
  for f in "$T/$name.A"/*.exr "$T/$name.A"/*.npy; do
    [ -e "$f" ] || continue
    g="$T/$name.B/$(basename "$f")"
    if [ ! -e "$g" ]; then echo "$name $(basename "$f"): only in A"; differ=1; continue; fi
    if cmp -s "$f" "$g"; then echo "$name $(basename "$f"): identical"; continue; fi
    case "$f" in
      *.exr)  # the headers hold the time of writing: compare every channel of every part
        if idiff -a -fail 0 -warn 0 "$f" "$g" > "$T/idiff.txt" 2>&1; then
          echo "$name $(basename "$f"): identical pixels"
        else
          differ=1
          echo "$name $(basename "$f"): differs, largest rel. L2 over its channels $(rel_l2 "$f" "$g")"
        fi ;;
      *) differ=1; echo "$name $(basename "$f"): differs" ;;
    esac
  done
done
exit $differ
