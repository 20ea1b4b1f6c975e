#!/usr/bin/env bash
# Prints the folder where the test command keeps what makes its next run cheap (compiler cache,
# fuzzing corpora, the Docker base image), outside the clone so that a fresh clone on the same
# machine finds it: $MESHMARK_CACHE, else /var/cache/meshmark when it can be written (root),
# else ${XDG_CACHE_HOME:-~/.cache}/meshmark. Creates it.
set -euo pipefail
dir="${MESHMARK_CACHE:-}"
if [[ -z "$dir" ]]; then
  if mkdir -p /var/cache/meshmark 2>/dev/null && [[ -w /var/cache/meshmark ]]; then dir=/var/cache/meshmark
  else dir="${XDG_CACHE_HOME:-$HOME/.cache}/meshmark"; fi
fi
mkdir -p "$dir"
echo "$dir"
