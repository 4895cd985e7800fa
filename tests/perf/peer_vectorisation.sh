#!/usr/bin/env bash
# peer_vectorisation.sh — what GCC made of the vectorised C++ peer of the K_d kernels
# (host/underwater/underwater_cpu_simd.cpp): its -fopt-info report per band loop and the instruction
# mix of the object file (ymm/zmm instructions, libmvec's vector expf calls, scalar expf calls).
# Usage: tests/perf/peer_vectorisation.sh [build-folder]   (default build; after a configure)
# Compiles the file again with the flags of its compile_commands.json entry plus the reports; writes
# nothing under the build folder. Prints the summary that results/underwater/peer_vectorisation.txt holds.
set -euo pipefail
BUILD=${1:-build}
SRC=host/underwater/underwater_cpu_simd.cpp
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
# The compile command as a bash array (the entry quotes its -D values).
eval "CMD=($(python3 - "$BUILD/compile_commands.json" "$SRC" <<'PY'
import json, shlex, sys
for e in json.load(open(sys.argv[1])):
    if e["file"].endswith(sys.argv[2]):
        args, out, skip = shlex.split(e["command"]), [], False
        for a in args:
            if skip: skip = False; continue
            if a in ("-o", "-c"): skip = True; continue
            if a.endswith("ccache"): continue
            out.append(a)
        print(shlex.join(out))
PY
))"
cd "$BUILD"
# One report per run: GCC writes only the last -fopt-info file when given two.
"${CMD[@]}" -fopt-info-vec-optimized="$TMP/optimized.txt" -c "../$SRC" -o "$TMP/peer.o"
"${CMD[@]}" -fopt-info-vec-missed="$TMP/missed.txt" -c "../$SRC" -o "$TMP/peer_missed.o"
echo "compiler: $("${CMD[0]}" --version | head -1)"
echo "this file's own flags (CMakeLists.txt): $(printf '%s\n' "${CMD[@]}" | grep -E '^-(O3|ffast-math|fopenmp-simd)$' | tr '\n' ' ')"
echo
echo "band loops (source line: what -fopt-info-vec says, count over target clones and template variants):"
grep -E "underwater_cpu_simd.cpp:[0-9]+:[0-9]+: optimized: loop vectorized" "$TMP/optimized.txt" |
  sed -E 's|.*underwater_cpu_simd.cpp:([0-9]+):[0-9]+: optimized: |line \1: |' | sort | uniq -c || echo "  none"
echo "loops -fopt-info-vec-missed reports as not vectorised in this file:"
grep -E "underwater_cpu_simd.cpp:[0-9]+:[0-9]+: missed: couldn't vectorize loop" "$TMP/missed.txt" |
  sed -E 's|.*underwater_cpu_simd.cpp:([0-9]+):.*|line \1|' | sort | uniq -c || echo "  none"
echo "(line numbers: sed -n '<line>p' $SRC)"
echo
echo "instruction mix of the object file (objdump -d):"
DIS=$(objdump -dr "$TMP/peer.o")
echo "  instructions on ymm registers: $(grep -c '%ymm' <<<"$DIS")"
echo "  instructions on zmm registers: $(grep -c '%zmm' <<<"$DIS")"
echo "  calls to libmvec's expf: $(grep -cE 'R_X86_64_PLT32\s+_ZGV.N[0-9]+v_expf' <<<"$DIS")" \
  "($(grep -oE '_ZGV.N[0-9]+v_expf' <<<"$DIS" | sort | uniq -c | tr '\n' ' '))"
echo "  calls to scalar expf: $(grep -cE 'R_X86_64_PLT32\s+expf-' <<<"$DIS")"
