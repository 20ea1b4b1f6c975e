#!/usr/bin/env bash
# Builds everything again with clang, AddressSanitizer and UndefinedBehaviorSanitizer into
# build-sanitize/, runs the test suite there (all but the robustness evaluation, which the
# release build runs), then fuzzes every target for FUZZ_SECONDS each (default 30) from the
# committed corpus. Any sanitizer report or fuzzer finding fails the run; findings are kept in
# build-sanitize/fuzz-findings/<target>/.
set -euo pipefail
cd "$(dirname "$0")/.."
deploy/install-deps.sh
deploy/install-deps.sh --sanitize
CC=clang CXX=clang++ cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBUILD_TESTING=ON \
  -DMESHMARK_SANITIZE=ON >/dev/null
cmake --build build-sanitize -j"$(nproc)"

export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$PWD/tests/fuzz/lsan.supp"
# The evaluation and most end-to-end runs repeat the release build's arithmetic at a fifth of
# its speed: here one mesh per path through the code runs end to end (spot: the sphere; kitten:
# bumps; cow_nonmanifold: a pinch; Duck: an asset; the filled sphere runs on spot with holes in
# the CLI, daemon and store tests); the rest (daemon integration tests included) runs in full.
(cd build-sanitize && ctest --output-on-failure --no-tests=error -j"$(nproc)" --timeout 1200 \
   -E '^(eval_quick|EndToEnd\.(bunny|bunny_holes|armadillo|mannequin|human_man|scorpion_lowres|sword|arm|spot_cow|sphere_logo|WaterBottle|sword_uv|frag_115|fertility|rocker_arm|face|tower_holes|human_neutral|mite|beetle|ogre))$')

exec deploy/fuzz.sh build-sanitize "${FUZZ_SECONDS:-30}"
