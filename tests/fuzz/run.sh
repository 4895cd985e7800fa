#!/usr/bin/env bash
# Builds the parser fuzzer with clang (build-fuzz/), makes a seed corpus from scenes/ and jobs/,
# and runs it for SECONDS (default 60). Usage: tests/fuzz/run.sh [SECONDS] [extra libFuzzer flags]
# Needs clang (Debian: clang-14, libclang-rt-14-dev). Not part of `make test`; .ci/run runs it for 60 s.
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds=${1:-60}
shift || true
CXX=${CXX:-clang++-14}
CC=${CC:-clang-14}
cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER="$CXX" -DCMAKE_C_COMPILER="$CC" \
      -DSEASIM_FUZZ=ON -DSEASIM_TESTS=OFF > /dev/null
cmake --build build-fuzz --target seasim_fuzz_parsers -j "$(nproc)" > build-fuzz/build.log
seeds=build-fuzz/seeds
corpus=build-fuzz/corpus
mkdir -p "$seeds" "$corpus"
for f in scenes/*.toml; do { printf '\000'; cat "$f"; } > "$seeds/scene_$(basename "$f")"; done
for f in jobs/*.toml; do { printf '\001'; cat "$f"; } > "$seeds/job_$(basename "$f")"; done
for f in scenes/*.toml; do { printf '\002sun.zenith_deg=40\n'; cat "$f"; } > "$seeds/override_$(basename "$f")"; done
for f in scenes/*.toml; do { printf '\003water.jerlov=IB\n'; cat "$f"; } > "$seeds/set_$(basename "$f")"; done
# Findings (crash-*, leak-*, timeout-*) are written to build-fuzz/.
export SEASIM_CACHE_DIR="$PWD/build-fuzz/cache"
log=build-fuzz/last-run.log
status=0
build-fuzz/seasim_fuzz_parsers "$corpus" "$seeds" -max_total_time="$seconds" -max_len=16384 \
  -artifact_prefix=build-fuzz/ -print_final_stats=1 "$@" 2>&1 | tee "$log" || status=$?
# One line for CI logs: how much was tried, and what was found.
execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -n 1)
findings=$(find build-fuzz -maxdepth 1 \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' \) -newer "$seeds" | wc -l)
echo "fuzz: ${execs:-?} executions in ${seconds} s (${rate:-?}/s), corpus $(ls "$corpus" | wc -l) units, $findings finding(s), exit $status"
exit "$status"
