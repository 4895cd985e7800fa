#!/usr/bin/env bash
# The kernel tests whose cases are small enough for Oclgrind (each suite under a minute on it), run on
# Oclgrind's simulated device with API checks and data-race detection; fails on a failed test or on
# any Oclgrind report.
#   tests/runtimes/oclgrind_kernel_tests.sh KERNEL_TEST_BINARY WORK_DIR GTEST_FILTER
# Left out (measured with a 30 s cap per suite): the suites that take longer on Oclgrind; Device.* and
# DeviceCache.*, which test PoCL's own device selection and cache; and all but two cases of the
# discrete-ordinates underwater kernel (its 23 take 285 s on Oclgrind; the ordinary seabed and three bands, 5 s,
# are in; common/underwater_ordinates_bands.h says why its lanes return through out pointers: Oclgrind
# 21.10 cannot run the llvm.experimental.noalias.scope.decl that an inlined struct return brings).
set -uo pipefail
binary=${1:?usage: oclgrind_kernel_tests.sh KERNEL_TEST_BINARY WORK_DIR GTEST_FILTER}
work=${2:?}
filter=${3:?}
command -v oclgrind >/dev/null || { echo "oclgrind_kernel_tests: oclgrind is not installed (apt-get install oclgrind; make test-deps does it)"; exit 1; }
rm -rf "$work"
mkdir -p "$work"
log="$work/oclgrind.log"
SEASIM_TEST_DEVICE=oclgrind SEASIM_CACHE_DIR="$work/seasim-cache" \
  oclgrind --check-api --data-races --num-threads 1 --log "$log" "$binary" --gtest_filter="$filter" >"$work/tests.out" 2>&1
rc=$?
grep -E '^\[ *(PASSED|FAILED) *\]|tests? from .* ran' "$work/tests.out"
reports=0
[ -s "$log" ] && reports=$(grep -c '^[^[:space:]]' "$log")
echo "oclgrind_kernel_tests: exit $rc, $reports Oclgrind report(s)"
if [ "$rc" != 0 ] || [ "$reports" != 0 ]; then
  grep -A12 -E 'Failure|FAILED' "$work/tests.out" | head -60
  head -40 "$log" 2>/dev/null
  exit 1
fi
