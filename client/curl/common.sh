# Sourced by the scripts here: the daemon's address and your API key.
#   MESHMARK_SERVER  default http://127.0.0.1:8080
#   MESHMARK_TOKEN   an owner's API key (from create-owner.sh)
set -euo pipefail
SERVER="${MESHMARK_SERVER:-http://127.0.0.1:8080}"
auth() { echo "Authorization: Bearer ${MESHMARK_TOKEN:?set MESHMARK_TOKEN to your API key}"; }
