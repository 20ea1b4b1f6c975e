#!/usr/bin/env bash
# Builds everything again with clang, AddressSanitizer and UndefinedBehaviorSanitizer into
# build-sanitize/, runs tests there, then fuzzes every target for FUZZ_SECONDS each (default 30)
# from the committed corpus. Any sanitizer report or fuzzer finding fails the run; findings are
# kept in build-sanitize/fuzz-findings/<target>/.
#
# Which tests: by default (CI) those where outside input arrives — every reader, writer and
# document test, the HTTP layer, the store, the daemon suites that take hostile and ordinary
# requests, the fuzz corpora — and one mesh end to end per basis (kitten: bumps; Duck: an asset
# on the sphere; the filled sphere runs on spot with holes in the CLI and store tests). The
# geometry-heavy rest repeats the release build's arithmetic at a fifth of its speed;
# `deploy/sanitize.sh --full` runs the whole suite (~20 min on 2 cores).
set -euo pipefail
cd "$(dirname "$0")/.."
full=0
[[ "${1:-}" == --full ]] && full=1
deploy/install-deps.sh
deploy/install-deps.sh --sanitize
jobs=$(deploy/cpus.sh)
CC=clang CXX=clang++ cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBUILD_TESTING=ON \
  -DMESHMARK_SANITIZE=ON >/dev/null
cmake --build build-sanitize -j"$jobs"

export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$PWD/tests/fuzz/lsan.supp"
export MESHMARK_THREADS="${MESHMARK_THREADS:-$jobs}"
heavy='^(eval_quick|EndToEnd\.(bunny|bunny_holes|armadillo|mannequin|spot|human_man|scorpion_lowres|sword|arm|spot_cow|sphere_logo|WaterBottle|sword_uv|frag_115|cow_nonmanifold|fertility|rocker_arm|face|tower_holes|human_neutral|mite|beetle|ogre)'
heavy+='|DaemonConcurrency|DaemonCli|curl_walkthrough|ThreadCount\..*|ValidMeshes/.*|GenusZero/.*|HardGenusZero/.*|SphereParam\..*|ProgressiveSphereMap\..*'
heavy+='|Wavelets/PaperScheme\..*|Watermark\..*|EmbedAndDetectCommands\..*|AlignMeshes\..*|Simplify\..*|Remesh\..*)$'
if (( full )); then heavy='^(eval_quick|EndToEnd\.(bunny|bunny_holes|armadillo|mannequin))$'; fi
(cd build-sanitize && ctest --output-on-failure --no-tests=error -j"$jobs" --timeout 1200 -E "$heavy")

exec deploy/fuzz.sh build-sanitize "${FUZZ_SECONDS:-30}"
