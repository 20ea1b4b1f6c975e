# Stages of a long script, timed: `stage NAME COMMAND...` runs the command, records its wall time
# and the machine's CPU steal over it, and a table of every stage is printed when the script
# exits (passed or not), with the total. Source it; bash only.
#   STAGES_SKIP   space-separated stage names to leave out (each is listed as skipped)
#   STAGES_ONLY   space-separated stage names to run alone

_stage_names=()
_stage_seconds=()
_stage_steal=()
_stage_status=()
_stages_start=$(date +%s.%N)

# The steal and total jiffies of all CPUs so far (/proc/stat's first line).
_cpu_jiffies() {
  local cpu user nice system idle iowait irq softirq steal rest
  read -r cpu user nice system idle iowait irq softirq steal rest </proc/stat
  echo "$steal $((user + nice + system + idle + iowait + irq + softirq + steal))"
}
_stages_cpu_start=$(_cpu_jiffies)

# Percent of CPU time stolen by the hypervisor between two _cpu_jiffies readings.
_steal_percent() {
  local s0 t0 s1 t1
  read -r s0 t0 <<<"$1"
  read -r s1 t1 <<<"$2"
  awk -v s=$((s1 - s0)) -v t=$((t1 - t0)) 'BEGIN { printf "%.1f", (t > 0 ? 100 * s / t : 0) }'
}

_stage_wanted() {
  local name="$1"
  [[ " ${STAGES_SKIP:-} " == *" $name "* ]] && return 1
  [[ -z "${STAGES_ONLY:-}" || " ${STAGES_ONLY} " == *" $name "* ]]
}

stage() {
  local name="$1"; shift
  if ! _stage_wanted "$name"; then
    _stage_names+=("$name"); _stage_seconds+=(0); _stage_steal+=(-); _stage_status+=(skipped)
    return 0
  fi
  echo "=== stage $name: $*"
  local t0 c0 status=0
  t0=$(date +%s.%N); c0=$(_cpu_jiffies)
  "$@" || status=$?
  _stage_names+=("$name")
  _stage_seconds+=("$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')")
  _stage_steal+=("$(_steal_percent "$c0" "$(_cpu_jiffies)")")
  _stage_status+=("$([[ $status -eq 0 ]] && echo ok || echo "FAILED ($status)")")
  return $status
}

# A stage that could not run here, with the reason: listed in the table, never silent.
stage_not_run() {
  local name="$1" reason="$2"
  echo "=== stage $name: not run: $reason"
  _stage_names+=("$name"); _stage_seconds+=(0); _stage_steal+=(-); _stage_status+=("not run: $reason")
}

print_stage_table() {
  local total steal i
  total=$(awk -v a="$_stages_start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')
  steal=$(_steal_percent "$_stages_cpu_start" "$(_cpu_jiffies)")
  echo
  echo "=== what each stage cost ($(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'))"
  printf '%-16s %9s %7s  %s\n' stage seconds steal result
  for i in "${!_stage_names[@]}"; do
    local percent="${_stage_steal[$i]}%"
    [[ "${_stage_steal[$i]}" == - ]] && percent=-
    printf '%-16s %9s %7s  %s\n' "${_stage_names[$i]}" "${_stage_seconds[$i]}" "$percent" "${_stage_status[$i]}"
  done
  printf '%-16s %9s %7s  %s\n' total "$total" "$steal%" "$(awk -v t="$total" 'BEGIN { printf "%.1f min", t / 60 }')"
}
trap print_stage_table EXIT
