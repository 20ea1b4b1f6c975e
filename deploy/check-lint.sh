#!/usr/bin/env bash
# Lints the product's code (core/, proto/, server/, client/) with clang-tidy 14 as .clang-tidy
# says, from the release build's compile database (deploy/build.sh first); any finding fails.
# A translation unit found clean is not linted again until its inputs change: a stamp per hash of
# its compile command, every file of the project it includes (ninja's deps), and clang-tidy's
# version and configuration, in deploy/cache-dir.sh's folder. Tests are not linted.
#   MESHMARK_BUILD_DIR  the build folder (default build)
set -euo pipefail
cd "$(dirname "$0")/.."
dir="${MESHMARK_BUILD_DIR:-build}"
root="$PWD"
# The database is GCC's: clang ignores GCC's warning options, and is told what CMake tells clang
# builds (server/CMakeLists.txt: Asio's coroutines with libstdc++).
tidy=(clang-tidy-14 -p "$dir" --quiet --extra-arg=-Wno-unknown-warning-option --extra-arg=-DBOOST_ASIO_HAS_CO_AWAIT=1)

if [[ "${1:-}" == --one ]]; then  # one unit: lint it, stamp it when clean
  file="$2" stamp="$3"
  if "${tidy[@]}" "$file" >"$stamp.findings" 2>/dev/null; then mv "$stamp.findings" "$stamp"; fi
  exit 0
fi

command -v clang-tidy-14 >/dev/null && command -v jq >/dev/null || deploy/install-deps.sh lint
[[ -f "$dir/compile_commands.json" ]] || { echo "lint: no $dir/compile_commands.json: run deploy/build.sh first" >&2; exit 2; }
stamps="$(deploy/cache-dir.sh)/lint"
mkdir -p "$stamps"
tool="$(clang-tidy-14 --version | sha256sum)"

# What a unit's result depends on: its command, its own and included project files' contents
# (system headers by name), the tool and its configuration; paths relative to the checkout, so
# that a fresh clone elsewhere finds the stamps of the same tree.
unit_key() {
  local command="$1" object dep rel
  local -a sources=()
  object=$(sed -E 's/.* -o ([^ ]+) .*/\1/' <<<"$command")
  {
    echo "$tool" "${tidy[*]}" "${command//$root/.}"
    cat .clang-tidy
    while read -r dep; do  # ninja names a dependency relative to the build folder or absolutely
      case "$dep" in
        "") continue ;;
        "$root"/*) rel="${dep#"$root"/}" ;;
        ../*) rel="${dep#../}" ;;
        /*) echo "$dep" && continue ;;  # the system's headers: by name
        *) rel="$dir/$dep" ;;
      esac
      if [[ "$rel" == "$dir"/* ]]; then echo "$rel" "$(sed "s#$root#.#g" "$rel" | sha256sum)"  # the unity batches
      else sources+=("$rel"); fi
    done < <(ninja -C "$dir" -t deps "$object" | tail -n +2 | sed 's/^ *//')
    (( ${#sources[@]} == 0 )) || sha256sum "${sources[@]}"
  } | sha256sum | cut -c1-40
}

units=0
todo=()
while IFS=$'\t' read -r file command; do
  case "$file" in
    "$root"/build*/tests/* | "$root"/tests/* | */console/console_files.cpp) continue ;;
    "$root"/core/* | "$root"/proto/* | "$root"/server/* | "$root"/client/*) ;;
    "$root/$dir"/core/* | "$root/$dir"/proto/* | "$root/$dir"/server/* | "$root/$dir"/client/*) ;;
    *) continue ;;
  esac
  units=$((units + 1))
  key=$(unit_key "$command")
  [[ -f "$stamps/$key" ]] || todo+=("$file" "$stamps/$key")
done < <(jq -r '.[] | [.file, .command] | @tsv' "$dir/compile_commands.json")

if (( ${#todo[@]} )); then
  printf '%s\0' "${todo[@]}" | xargs -0 -n2 -P"$(deploy/cpus.sh)" deploy/check-lint.sh --one
fi
failed=0
for ((i = 1; i < ${#todo[@]}; i += 2)); do [[ -f "${todo[i]}" ]] || failed=$((failed + 1)); done
for ((i = 1; i < ${#todo[@]}; i += 2)); do
  [[ -f "${todo[i]}.findings" ]] && cat "${todo[i]}.findings" && rm -f "${todo[i]}.findings"
done | grep -E '(warning|error):' | sed "s#^$root/##" | sort -u || true
if (( failed )); then
  echo "lint: $failed of $units units have findings (above; .clang-tidy says which checks)"
  exit 1
fi
echo "lint: $units units clean as .clang-tidy says ($(( ${#todo[@]} / 2 )) linted, the rest unchanged since)"
