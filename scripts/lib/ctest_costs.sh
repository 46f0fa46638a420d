# Sourced by scripts/test.sh and scripts/sanitize.sh: `seed_ctest_costs DIR`
# gives a fresh build tree the tests' measured durations
# (tests/ctest_costs/DIR.txt, in CTest's own CTestCostData.txt format), so
# that `ctest -j` starts the longest tests first instead of in declaration
# order: a fresh clone otherwise ends its test stages on a few long tests with
# one core idle (docs/ci.md "Longest first"). A tree that has run its tests
# keeps the durations CTest measured itself. scripts/save-ctest-costs.sh
# refreshes the files from this machine's runs.
seed_ctest_costs() {
  local dir=$1 costs
  costs=$(dirname "${BASH_SOURCE[0]}")/../../tests/ctest_costs/$(basename "$dir").txt
  [ -f "$costs" ] || return 0
  [ -f "$dir/Testing/Temporary/CTestCostData.txt" ] && return 0
  mkdir -p "$dir/Testing/Temporary"
  cp "$costs" "$dir/Testing/Temporary/CTestCostData.txt"
}
