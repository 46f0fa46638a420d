#!/usr/bin/env bash
# Builds with AddressSanitizer + UndefinedBehaviorSanitizer (clang) into build-asan/
# and runs the test suite there (every label but web, whose browsers run none
# of the project's binaries, tutorial, whose steps are tested on their own,
# and cluster, whose Slurm jobs run code the real label's shard tests run).
# Leaks are reported, except Mesa's own (scripts/lsan.supp says why).
# Needs the samples (scripts/test.sh fetches them).
# Usage: scripts/sanitize.sh [ctest args]
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/lib/stage.sh
. scripts/lib/ctest_costs.sh
# clang, not GCC: the same sanitizers, built in half the time (GCC 12 spent
# 2.2x clang 14's CPU on ASan-instrumented code; docs/ci.md).
BUILD_DIR=build-asan stage "build (build-asan/)" scripts/build.sh -DCMAKE_C_COMPILER=clang \
  -DCMAKE_CXX_COMPILER=clang++ -DGLOBE_SANITIZE=address,undefined
supp=$(pwd)/scripts/lsan.supp
seed_ctest_costs build-asan
cd build-asan
export LSAN_OPTIONS=suppressions=$supp:print_suppressions=0 UBSAN_OPTIONS=print_stacktrace=1
# The tests that open Mesa through EGL or GLX (a GLFW window under xvfb) run
# without leak detection (ASan and UBSan still on): those drivers leak 112
# bytes and are unloaded (dlclose) before the leak check runs, so their frames
# can no longer be named and suppressed as Mesa's like the others.
egl_test='ViewerRender.OsMesaAndEglGiveTheSameImage|ViewerIdleWindow|ViewerImageryWindow|ViewerGlobe.WindowZooms|ViewerChartsWindow|ViewerBundlesWindow|ViewerShadingWindow'
status=0
# The web label runs browsers, none of the project's binaries: once, in build/.
# The cluster label runs through Slurm the same shard and merge code that the
# real label's ShardedBuild tests run here (docs/ci.md): in build/ only.
# Allocation stacks of 10 frames instead of 30: the sanitized tests run
# about 5 % faster (docs/ci.md), the access itself keeps its whole stack.
ASAN_OPTIONS=detect_leaks=1:malloc_context_size=10 stage "tests (build-asan/)" \
  ctest --output-on-failure -j "$(nproc)" --timeout 1500 -E "$egl_test" -LE "web|tutorial|cluster" \
  "$@" || status=1
ASAN_OPTIONS=detect_leaks=0 stage "tests (build-asan/, EGL/GLX)" ctest --output-on-failure \
  --timeout 1500 -R "$egl_test" || status=1
exit $status
