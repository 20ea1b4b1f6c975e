# Sourced by the scripts here: the daemon's address and your API key.
#   MESHMARK_SERVER  default http://127.0.0.1:8080
#   MESHMARK_TOKEN   an owner's API key (from create-owner.sh)
set -euo pipefail
SERVER="${MESHMARK_SERVER:-http://127.0.0.1:8080}"
auth() { echo "Authorization: Bearer ${MESHMARK_TOKEN:?set MESHMARK_TOKEN to your API key}"; }
# A missing file would otherwise go out as an empty body.
need_file() { [[ -f "$1" ]] || { echo "no such file: $1" >&2; exit 2; }; }
# TEXT as a JSON string (quotes and backslashes escaped; the API refuses control characters).
json_string() {
  local text="${1//\\/\\\\}"
  printf '"%s"' "${text//\"/\\\"}"
}
# The first string value of KEY in the JSON on stdin (enough for the flat answers used here).
json_field() { grep -o "\"$1\":\"[^\"]*\"" | sed -n 1p | cut -d'"' -f4; }
# The mesh format of a file, from its extension; a ZIP named like asset.gltf.zip carries a
# .gltf (or .obj) with its companion files: the extension before .zip names the format.
format_of() {
  local name="${1,,}"
  [[ "$name" == *.zip ]] && name="${name%.zip}"
  echo "${name##*.}"
}
