#!/usr/bin/env bash
# The sanitizer builds and their tests (clang). Usage: deploy/sanitize.sh KIND STEP
#   KIND address  AddressSanitizer + UndefinedBehaviorSanitizer into build-asan/, fuzzers too.
#                 Its tests: the suite as a user without the real meshes runs it
#                 (MESHMARK_SHARED pointed away) but those labelled heavy: every reader, writer,
#                 HTTP, store and daemon test, the CLI, and the geometry's unit tests on the
#                 shapes the tests make. The heavy ones (the end-to-end contract per mesh, the
#                 thread-count and tracing comparisons) repeat the whole pipeline many times:
#                 at a fifth of the release build's speed they would cost 12 minutes, and run
#                 in the release build only.
#   KIND thread   ThreadSanitizer into build-tsan/: the daemon, and the test programs with the
#                 tests labelled concurrency (queue, runner, store, recovery, parallel loops, the
#                 daemon under concurrent and hostile requests), which are all it runs.
#   STEP build | test
# Any sanitizer report fails the run (the daemon's own reports end the daemon, and its test).
set -euo pipefail
cd "$(dirname "$0")/.."
kind="${1:?usage: deploy/sanitize.sh address|thread build|test}"
step="${2:?usage: deploy/sanitize.sh address|thread build|test}"
case "$kind" in
  address) dir=build-asan ;;
  thread) dir=build-tsan ;;
  *) echo "sanitize: unknown kind '$kind' (address or thread)" >&2; exit 2 ;;
esac
jobs=$(deploy/cpus.sh)

if [[ "$step" == build ]]; then
  deploy/install-deps.sh build sanitize
  targets="meshmark meshmarkd meshmark_util_tests meshmark_core_tests meshmark_io_tests meshmark_server_tests"
  targets+=" meshmark_cli_tests fuzzers"
  [[ "$kind" == thread ]] && targets="meshmarkd meshmark_util_tests meshmark_server_tests"
  # The real meshes are left out at configure time: their entries are the release build's.
  CC=clang CXX=clang++ MESHMARK_BUILD_DIR="$dir" MESHMARK_TARGETS="$targets" MESHMARK_SHARED=/nonexistent \
    deploy/build.sh -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBUILD_TESTING=ON -DMESHMARK_SANITIZE="$kind" \
    -DMESHMARK_SHARED=/nonexistent "${@:3}"
  exit 0
fi

[[ "$step" == test ]] || { echo "sanitize: unknown step '$step' (build or test)" >&2; exit 2; }
export MESHMARK_SHARED=/nonexistent
export MESHMARK_THREADS="${MESHMARK_THREADS:-$jobs}"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$PWD/tests/fuzz/lsan.supp"
export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$PWD/tests/tsan.supp"
label=(-LE heavy)
[[ "$kind" == thread ]] && label=(-L concurrency)
deploy/ctest-longest-first.sh "$dir" "$kind" --output-on-failure --no-tests=error -j"$jobs" --timeout 1500 "${label[@]}"
