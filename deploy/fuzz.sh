#!/usr/bin/env bash
# Runs every libFuzzer target of a sanitizer build for SECONDS each, starting from the committed
# corpus (tests/fuzz/corpus/<target>, never written to) and a working corpus in the build folder.
# Usage: deploy/fuzz.sh BUILD_DIR [SECONDS] [TARGET...]. Prints executions per target; exits 1
# on a finding (crash, sanitizer report, leak, timeout or out-of-memory), kept in
# BUILD_DIR/fuzz-findings/<target>/.
set -euo pipefail
cd "$(dirname "$0")/.."
build="$1"; seconds="${2:-30}"; shift $(( $# >= 2 ? 2 : 1 ))
targets=("$@")
if [[ ${#targets[@]} -eq 0 ]]; then
  targets=(read_obj read_off read_ply read_stl document_write api_requests attack_chain http_target)
fi
failed=0
for t in "${targets[@]}"; do
  fuzzer="$build/tests/fuzz/fuzz_$t"
  work="$build/fuzz-corpus/$t"; findings="$build/fuzz-findings/$t"
  mkdir -p "$work" "$findings"
  log="$findings/fuzz.log"
  if "$fuzzer" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
       -artifact_prefix="$findings/" -print_final_stats=1 "$work" "tests/fuzz/corpus/$t" >"$log" 2>&1; then
    runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo '?')
    echo "fuzz $t: $runs executions in ${seconds} s, no finding"
  else
    echo "fuzz $t: FINDING (see $findings)"; tail -n 40 "$log"; failed=1
  fi
done
exit $failed
