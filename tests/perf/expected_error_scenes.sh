#!/bin/sh
# expected_error_scenes.sh — the expected error every shipped scene states about itself (`seasim plan`'s
# last lines, report.json's expected_error; host/quality/expected_error.h), as a Markdown table.
# Usage: tests/perf/expected_error_scenes.sh [seasim, default build/seasim] > results/expected_error_scenes.md
B=${1:-build/seasim}
echo "# The expected error each shipped scene states"
echo
echo "\`$B plan scenes/<scene>.toml\`, its \"expected error\" lines (the same figures as report.json's"
echo "\`expected_error\`; docs/error_vs_time.md says how they are found). Scenes of models without measured"
echo "tables (shallow water, shafts in air) state none."
echo
echo "| scene | expected error |"
echo "|---|---|"
for s in scenes/*.toml; do
  line=$("$B" plan "$s" 2>&1 | grep "^expected error" | sed 's/|/\\|/g' | paste -sd ';' -)
  echo "| $(basename "$s" .toml) | ${line:-none (no measured table for its models)} |"
done
