#!/usr/bin/env bash
# Prints the Debian packages that hold the shared libraries the given binaries load (ldd, then
# dpkg -S), one per line: what a runtime image must install for them, read from the binaries
# themselves so that it cannot drift from what they link. Usage: deploy/runtime-packages.sh BINARY...
set -euo pipefail
if ldd "$@" | grep 'not found' >/dev/null; then
  echo "runtime-packages: a library is missing:" >&2; ldd "$@" | grep 'not found' >&2; exit 1
fi
libraries=$(ldd "$@" | awk '$2 == "=>" && $3 ~ /^\// { print $3 }' | sort -u)
packages=()
for lib in $libraries; do
  owner=""
  # bookworm registers libraries under /lib or /usr/lib; ldd may name either (merged /usr).
  for path in "$lib" "$(readlink -f "$lib")" "/usr$lib" "${lib#/usr}"; do
    owner=$(dpkg-query -S "$path" 2>/dev/null | sed -n 1p) && break
  done
  [[ -n "$owner" ]] || { echo "runtime-packages: no package holds $lib" >&2; exit 1; }
  packages+=("${owner%%:*}")
done
printf '%s\n' "${packages[@]}" | sort -u
