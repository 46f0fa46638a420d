#!/usr/bin/env bash
# Writes tests/ctest_costs/{build,build-asan}.txt from the durations CTest
# measured in this clone's build/ and build-asan/ (after a full run of each),
# keeping only the tests that exist now. scripts/lib/ctest_costs.sh seeds a
# fresh tree with them so that ctest -j starts the longest tests first.
# Usage: scripts/save-ctest-costs.sh
set -euo pipefail
cd "$(dirname "$0")/.."
for dir in build build-asan; do
  data=$dir/Testing/Temporary/CTestCostData.txt
  [ -f "$data" ] || { echo "save-ctest-costs: no $data (run the tests there first)" >&2; continue; }
  ctest --test-dir "$dir" -N | sed -n 's/^ *Test *#[0-9]*: //p' |
    awk 'NR == FNR { want[$1] = 1; next } /^---/ { exit }
         NF == 3 && ($1 in want) { cost[$1] = $3 }
         END { for (t in cost) printf "%s 1 %.1f\n", t, cost[t] }' - "$data" |
    LC_ALL=C sort >"tests/ctest_costs/$dir.txt"
  echo "save-ctest-costs: tests/ctest_costs/$dir.txt ($(wc -l <"tests/ctest_costs/$dir.txt") tests)" >&2
done
