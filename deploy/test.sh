#!/usr/bin/env bash
# Sets everything up on a fresh Debian machine and runs every test, in stages, printing at the
# end what each stage cost and the machine's CPU steal (deploy/lib/stages.sh):
#   packages     apt-get install of what the stages use (deploy/install-deps.sh test) and the npm
#                tools (the glTF validator: deploy/install-node-tools.sh)
#   format       every C++ file as .clang-format says (deploy/check-format.sh)
#   build        the release build with warnings as errors, through ccache
#   lint         clang-tidy on core/, proto/, server/ and client/ as .clang-tidy says, each unit
#                linted again only when what it includes changed (deploy/check-lint.sh)
#   tests        its ctest suite: everything, the real meshes too (robustness gate eval_quick); the
#                store and blob store suites also against PostgreSQL and an S3-compatible server
#                started here on loopback (deploy/postgres-test-server.sh, s3rver:
#                deploy/s3-test-server.sh) and stopped at the end
#   console      the web console in headless chromium against a real daemon (deploy/console-test.sh)
#   asan-build   clang with AddressSanitizer + UBSan, and the fuzzers
#   asan-tests   the suite as a user without the real meshes runs it (deploy/sanitize.sh)
#   fuzz         each fuzzer until its coverage stops growing (deploy/fuzz.sh)
#   tsan-build   clang with ThreadSanitizer: the daemon and the concurrency tests
#   tsan-tests   the tests labelled concurrency
#   docker       the image built from deploy/Dockerfile and run (deploy/docker-test.sh)
# Caches outside the clone (deploy/cache-dir.sh) make a second run on the same machine cheap.
# The real meshes are read from $MESHMARK_SHARED (default ../shared); without them the suites on
# them are left out and each absence is printed.
#   STAGES_SKIP="docker fuzz" / STAGES_ONLY="build tests"   run fewer stages
set -euo pipefail
cd "$(dirname "$0")/.."
source deploy/lib/stages.sh
jobs=$(deploy/cpus.sh)
export MESHMARK_THREADS="${MESHMARK_THREADS:-$jobs}"  # the CLI's parallel loops in the tests: the cores we have
export CCACHE_DIR="${CCACHE_DIR:-$(deploy/cache-dir.sh)/ccache}"
shared="${MESHMARK_SHARED:-$(cd .. && pwd)/shared}"
if [[ -d "$shared/meshes" && -d "$shared/assets" ]]; then
  echo "real meshes: $shared"
  export MESHMARK_SHARED="$shared"
else
  echo "real meshes: ABSENT at $shared (set MESHMARK_SHARED; see tests/README.md): the suites on them are left out"
  export MESHMARK_SHARED=/nonexistent
fi

# The glTF validator's node_modules (deploy/install-node-tools.sh puts it there).
export MESHMARK_NODE_MODULES="${MESHMARK_NODE_MODULES:-$(deploy/cache-dir.sh)/node/node_modules}"

packages() { deploy/install-deps.sh test && deploy/install-node-tools.sh >/dev/null; }
release_tests() { deploy/ctest-longest-first.sh build release --output-on-failure --no-tests=error -j"$jobs" --timeout 900; }

stage packages packages
# The servers the store tests run against, for every test stage; stopped however the run ends.
servers=$(mktemp -d)
stop_servers() {
  deploy/postgres-test-server.sh "$servers/postgres" stop
  kill "${s3_pid:-0}" 2>/dev/null || true
  rm -rf "$servers"
}
trap 'stop_servers; print_stage_table' EXIT  # the table too: this replaces stages.sh's trap
read -r s3_endpoint s3_pid < <(deploy/s3-test-server.sh "$servers/s3")
export MESHMARK_TEST_S3_ENDPOINT="$s3_endpoint"
MESHMARK_TEST_POSTGRES=$(deploy/postgres-test-server.sh "$servers/postgres")
export MESHMARK_TEST_POSTGRES
echo "test servers: S3 at $s3_endpoint, PostgreSQL at $MESHMARK_TEST_POSTGRES"
stage format deploy/check-format.sh
stage build deploy/build.sh -DBUILD_TESTING=ON -DMESHMARK_WERROR=ON -DMESHMARK_SHARED="$MESHMARK_SHARED"
stage lint deploy/check-lint.sh
stage tests release_tests
stage console deploy/console-test.sh
stage asan-build deploy/sanitize.sh address build -DMESHMARK_WERROR=ON
stage asan-tests deploy/sanitize.sh address test
stage fuzz deploy/fuzz.sh build-asan "${FUZZ_SECONDS:-40}"
stage tsan-build deploy/sanitize.sh thread build -DMESHMARK_WERROR=ON
stage tsan-tests deploy/sanitize.sh thread test
status=0
stage docker deploy/docker-test.sh || status=$?
if (( status == 77 )); then _stage_status[-1]="not run: see the docker stage's output"; status=0; fi
exit $status
