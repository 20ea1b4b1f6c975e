#!/usr/bin/env bash
# Runs every libFuzzer target of the address-sanitizer build until it stops finding new
# coverage, within one budget of wall time, as many targets at once as there are cores: a target
# ends after FUZZ_PLATEAU seconds (default 5) without a new input, or when it has used its share
# of what is left of TOTAL_SECONDS (default 240: the left budget times the cores over the targets
# left), so that time a target did not need goes to those still growing.
# Inputs come from the committed corpus (tests/fuzz/corpus/<target>, never written to) and a
# working corpus kept between runs outside the clone (deploy/cache-dir.sh), so that a second run
# starts where the first stopped. Prints per target what it ran and why it stopped; exits 1 on a
# finding (crash, sanitizer report, leak, timeout or out-of-memory), kept in
# BUILD_DIR/fuzz-findings/<target>/. Usage: deploy/fuzz.sh BUILD_DIR [TOTAL_SECONDS] [TARGET...]
set -euo pipefail
cd "$(dirname "$0")/.."
build="$1"; total_seconds="${2:-240}"; shift $(( $# >= 2 ? 2 : 1 ))
plateau="${FUZZ_PLATEAU:-5}"
targets=("$@")
if [[ ${#targets[@]} -eq 0 ]]; then
  targets=(read_obj read_off read_ply read_stl document_write api_requests attack_chain http_target zip_archive
    draco_stream packaged_document json_spans xml_tags http_transport)
fi
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}"
export LSAN_OPTIONS="suppressions=$PWD/tests/fuzz/lsan.supp"
cache="$(deploy/cache-dir.sh)/fuzz-corpus"

# Runs one target for at most $2 seconds; prints its line; returns 1 on a finding.
fuzz_one() {
  local t="$1" max_seconds="$2" fuzzer="$build/tests/fuzz/fuzz_$1" work="$cache/$1" findings="$build/fuzz-findings/$1"
  mkdir -p "$work" "$findings"
  local log="$findings/fuzz.log" start now last_new=0 news=0 seen=0 stopped="no new coverage for ${plateau} s"
  start=$(date +%s)
  "$fuzzer" -max_total_time="$max_seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=512 -max_len=65536 \
    -artifact_prefix="$findings/" -print_final_stats=1 "$work" "tests/fuzz/corpus/$t" >"$log" 2>&1 &
  local pid=$! interrupted=0
  while kill -0 "$pid" 2>/dev/null; do
    sleep 1
    now=$(date +%s)
    news=$(grep -c $'\tNEW ' "$log" || true)
    if (( news != seen )); then seen=$news; last_new=$now; fi
    (( last_new == 0 )) && last_new=$now
    if (( now - last_new >= plateau )); then
      kill -INT "$pid" 2>/dev/null || true; interrupted=1; break
    fi
  done
  local status=0 killed=0
  if (( interrupted == 1 )); then
    # libFuzzer's SIGINT handler allocates: landing inside malloc, it can wait on the allocator's
    # lock for ever (seen once in CI, fuzz_xml_tags, its stack in InterruptCallback). A fuzzer
    # still running 10 s after our SIGINT is killed; that is no finding either.
    for _ in $(seq 10); do kill -0 "$pid" 2>/dev/null || break; sleep 1; done
    if kill -0 "$pid" 2>/dev/null; then kill -KILL "$pid" 2>/dev/null || true; killed=1; fi
  fi
  wait "$pid" || status=$?
  # libFuzzer 14 ignores -interrupted_exitcode: our own SIGINT ends it with 72, which is no finding.
  (( interrupted == 1 && (status == 72 || killed == 1) )) && status=0
  if compgen -G "$findings/crash-*" >/dev/null || compgen -G "$findings/leak-*" >/dev/null ||
    compgen -G "$findings/timeout-*" >/dev/null || compgen -G "$findings/oom-*" >/dev/null; then
    (( status == 0 )) && status=1
  fi
  local seconds=$(( $(date +%s) - start ))
  (( seconds >= max_seconds )) && stopped="the ${max_seconds} s cap"
  (( killed == 1 )) && stopped="$stopped; killed 10 s after it hung in its interrupt handler"
  local runs corpus
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo '?')
  corpus=$(find "$work" -type f | wc -l)
  if (( status == 0 )); then
    printf 'fuzz %-15s %9s executions in %3d s (stopped at %s), %d new inputs, working corpus %d: no finding\n' \
      "$t" "$runs" "$seconds" "$stopped" "$news" "$corpus"
  else
    echo "fuzz $t: FINDING (exit $status; see $findings)"; tail -n 40 "$log"; return 1
  fi
}

# As many targets at once as there are cores (each fuzzer is one process on one core); a target's
# share is what is left of the budget times the slots over the targets left.
slots=$(deploy/cpus.sh)
failed=0 started=$(date +%s) left_targets=${#targets[@]} running=0
for t in "${targets[@]}"; do
  if (( running >= slots )); then
    wait -n || failed=1
    running=$(( running - 1 ))
  fi
  left=$(( total_seconds - ($(date +%s) - started) ))
  share=$(( left * slots / left_targets )); (( share < 5 )) && share=5
  fuzz_one "$t" "$share" &
  running=$(( running + 1 )) left_targets=$(( left_targets - 1 ))
done
while (( running > 0 )); do
  wait -n || failed=1
  running=$(( running - 1 ))
done
echo "fuzz: ${#targets[@]} targets in $(( $(date +%s) - started )) s of a ${total_seconds} s budget"
exit $failed
