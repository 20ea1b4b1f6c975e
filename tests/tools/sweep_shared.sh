#!/usr/bin/env bash
# Every shared mesh and asset kept whole: embed (self-check and record included), then the copy
# moved by a random similarity and mirrored + moved, each read back by `detect --record`.
# Prints one Markdown row per file; a refusal prints the first line of what it said.
#   tests/tools/sweep_shared.sh [MESHMARK_BINARY] > sweep.md
# MESHMARK_SHARED (default ../shared) names the folder holding meshes/ and assets/.
set -u
bin=${1:-build/client/meshmark}
shared=${MESHMARK_SHARED:-../shared}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export MESHMARK_CACHE=${MESHMARK_CACHE:-$work/cache}
key=sweep-key-2026
payload=0123456789abcdef
seed=${SWEEP_SEED:-7}  # the attacks' random similarity and mirror plane

reading() {  # suspect record -> "BER b, detected d, log10 p x"
  local json
  if ! json=$("$bin" detect "$1" --record "$2" --key "$key" --expect "$payload" --json 2>"$work/err"); then
    echo "failed: $(head -c 160 "$work/err")"
    return
  fi
  jq -r '"BER \(.ber), detected \(if .detected then "True" else "False" end), log10 p \(.log10_p_value | floor)"' <<<"$json"
}

sweep_one() {
  local file=$1 name out record started seconds
  name=$(basename "$file")
  out="$work/out/$name"
  record="$work/$name.record.json"
  rm -rf "$work/out" && mkdir -p "$work/out"
  started=$(date +%s.%N)
  if ! "$bin" embed "$file" "$out" --key "$key" --payload "$payload" --records "$work/records" \
      --record "$record" >/dev/null 2>"$work/err"; then
    echo "| $name | refused: $(head -n 1 "$work/err" | head -c 200) |"
    return
  fi
  seconds=$(echo "$(date +%s.%N) - $started" | bc)
  # Attacks write the copy's surface as PLY, whatever its format.
  "$bin" attack similarity "$out" "$work/moved.ply" --seed "$seed" >/dev/null 2>&1
  "$bin" attack chain "$out" "$work/mirrored.ply" --seed "$seed" --steps "mirror | similarity" >/dev/null 2>&1
  printf '| %s | embed %.1f s | %s | %s |\n' "$name" "$seconds" \
    "$(reading "$work/moved.ply" "$record")" "$(reading "$work/mirrored.ply" "$record")"
}

echo "| file | embed | moved + similarity | mirrored + similarity |"
echo "|---|---|---|---|"
for file in "$shared"/meshes/*.obj "$shared"/meshes/*.off "$shared"/meshes/corpus/*.obj \
    "$shared"/meshes/corpus/*.off $(find "$shared/assets" -type f \
    \( -iname '*.gltf' -o -iname '*.glb' -o -iname '*.obj' -o -iname '*.ply' -o -iname '*.stl' \
    -o -iname '*.3mf' \) | sort); do
  sweep_one "$file"
done
