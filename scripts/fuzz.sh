#!/usr/bin/env bash
# Fuzzes the tile decoders and package opening with libFuzzer under ASan +
# UBSan: builds the targets of tests/fuzz/ with clang into build-fuzz/, writes
# the seed corpus (valid blobs and packages), then runs each target for
# SECONDS (default 60), as many at once as there are cores. Inputs that crash
# are saved under build-fuzz/crashes/<target>/ and the script fails; copy each into
# tests/data/fuzz/<target>/ and fix the decoder: the regression test
# (FuzzRegression, label unit) replays every file there.
# --build-only builds and stops; --no-build runs what build-fuzz/ holds;
# --jobs N runs N targets at once (default: the cores; .ci/run runs one at a
# time beside the slow tests, which leave the cores partly idle: docs/ci.md).
# Usage: scripts/fuzz.sh [--build-only|--no-build] [--jobs N] [SECONDS] [TARGET...]
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/lib/stage.sh
. scripts/lib/ccache.sh
do_build=1 do_run=1 jobs=$(nproc)
while [ $# -gt 0 ]; do
  case $1 in
    --build-only) do_run=0 ;;
    --no-build) do_build=0 ;;
    --jobs) jobs=$2; shift ;;
    *) break ;;
  esac
  shift
done
seconds=${1:-60}
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(mblock image_tile line_tile point_tile area_tile analysis_block package url_route)

# (Both stages run as functions under `stage`, where `set -e` does not
# apply: each step's failure is returned explicitly.)
build_fuzz() {
  CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DGLOBE_FUZZ=ON -DGLOBE_BUILD_TESTS=OFF -DGLOBE_SANITIZE=address,undefined \
    "${GLOBE_CCACHE_ARGS[@]}" >/dev/null || return
  cmake --build build-fuzz --target make_fuzz_seeds "${targets[@]/#/fuzz_}"
}

# One target per core at a time; each writes its own log.
fuzz_one() {
  local t=$1
  mkdir -p "build-fuzz/corpus/$t" "build-fuzz/crashes/$t" "build-fuzz/seeds/$t"
  local dirs=("build-fuzz/corpus/$t" "build-fuzz/seeds/$t")
  [ -d "tests/data/fuzz/$t" ] && dirs+=("tests/data/fuzz/$t")
  UBSAN_OPTIONS=print_stacktrace=1 "build-fuzz/tests/fuzz/fuzz_$t" \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="build-fuzz/crashes/$t/" "${dirs[@]}" 2> "build-fuzz/fuzz_$t.log"
}

fuzz_all() {
  rm -rf build-fuzz/seeds
  build-fuzz/tests/fuzz/make_fuzz_seeds build-fuzz/seeds || return
  local t failed=()
  local -A pid_of
  for t in "${targets[@]}"; do
    while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
    echo "fuzz: $t for ${seconds}s" >&2
    fuzz_one "$t" &
    pid_of[$t]=$!
  done
  for t in "${targets[@]}"; do
    if ! wait "${pid_of[$t]}"; then
      tail -40 "build-fuzz/fuzz_$t.log" >&2
      failed+=("$t")
    else
      grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "build-fuzz/fuzz_$t.log" |
        sed "s/^/fuzz: $t /" >&2
    fi
  done
  if [ ${#failed[@]} -gt 0 ]; then
    echo "fuzz: crashes in ${failed[*]}; inputs under build-fuzz/crashes/" >&2
    return 1
  fi
  echo "fuzz: no crash in ${targets[*]}" >&2
}

if [ $do_build = 1 ]; then stage "build (build-fuzz/)" build_fuzz; fi
if [ $do_run = 1 ]; then stage "fuzz (${#targets[@]} x ${seconds}s, $jobs at once)" fuzz_all; fi
