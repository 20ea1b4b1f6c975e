#!/usr/bin/env bash
# Runs ctest in BUILD_DIR, the longest tests first. ctest orders a parallel run by each test's cost
# from its last run (Testing/Temporary/CTestCostData.txt), but a fresh clone has no last run and
# would start the longest ones last, leaving one core idle at the end. So the costs are kept in
# deploy/cache-dir.sh's folder, per NAME, and given back to the next clone.
# Usage: deploy/ctest-longest-first.sh BUILD_DIR NAME [ctest arguments]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
dir="$1" name="$2"
shift 2
kept="$("$here/cache-dir.sh")/ctest/$name-costs.txt"
mkdir -p "$dir/Testing/Temporary" "$(dirname "$kept")"
costs="$dir/Testing/Temporary/CTestCostData.txt"
[[ -f "$kept" && ! -f "$costs" ]] && cp "$kept" "$costs"
status=0
(cd "$dir" && ctest "$@") || status=$?
[[ -f "$costs" ]] && cp "$costs" "$kept.tmp" && mv "$kept.tmp" "$kept"
exit $status
