#!/bin/sh
# scenes_identical.sh — every shipped scene rendered by two seasim binaries (e.g. a copy of main's
# and this tree's) at a small size with every output the scene allows (image, spectral.exr, .npy
# and, under water, every ground-truth layer), then each file of A compared with B's: "identical"
# when the bytes agree or, for EXR (whose header holds the time of writing), every channel of every
# part does (idiff -fail 0); else the largest error (idiff) and the RGB image's relative L2 (seasim
# compare). A refactor that must not change an image shows "identical" on every line.
# Usage: tests/perf/scenes_identical.sh BINARY_A BINARY_B   (SIZE="96 54", SCENES="scenes/*.toml")
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
differ=0
for scene in ${SCENES:-scenes/*.toml}; do
  name=$(basename "$scene" .toml)
  for v in A B; do
    if [ $v = A ]; then bin=$A; else bin=$B; fi
    out="$T/$name.$v"
    # Layers are for the camera under water and spectral.exr for the spectral models: a scene that
    # refuses them renders with fewer outputs (the log of the last try is kept).
    set -- "--output exr,spectral_exr,npy --output $LAYERS --set spectral.spectral_exr=true" \
           "--output exr,spectral_exr,npy --set spectral.spectral_exr=true" "--output exr,npy"
    ok=0
    for outputs in "$@"; do
      rm -rf "$out"
      # shellcheck disable=SC2086
      if "$bin" render "$scene" -o "$out" --set camera.width=$W --set camera.height=$H $outputs > "$out.log" 2>&1; then
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
          echo "$name $(basename "$f"): differs: $(grep -i 'max error' "$T/idiff.txt" | head -1)" \
               "rel. L2 $("$B" compare "$g" "$f" 2>/dev/null | grep -io 'rel_l2 [^ ,]*' | head -1)"
        fi ;;
      *) differ=1; echo "$name $(basename "$f"): differs" ;;
    esac
  done
done
exit $differ
