#!/usr/bin/env bash
# Runs the README's studio walkthrough (the sh block after "<!-- studio walkthrough -->") as
# printed, against a real daemon on a free loopback port, with a textured OBJ and twelve partners;
# then checks what it printed: twelve copies, the export, the leak traced to partner-07.
# Usage: studio_walkthrough_test.sh START_SCRIPT MESHMARKD MESHMARK_CLI README
set -euo pipefail
start=$(realpath "$1"); daemon=$(realpath "$2"); cli=$(realpath "$3"); readme=$(realpath "$4")
work=$(mktemp -d); trap 'kill $pid 2>/dev/null; wait $pid 2>/dev/null; rm -rf "$work"' EXIT
MESHMARK_DAEMON="$daemon" "$start" --listen 127.0.0.1:0 --data "$work/data" >"$work/out" 2>"$work/log" &
pid=$!
for _ in $(seq 100); do grep -q "listening on" "$work/out" && break; sleep 0.1; done
export MESHMARK_SERVER=$(grep -o "http://[0-9.:]*" "$work/out")
export MESHMARK_ADMIN_TOKEN=$(cat "$work/data/admin-token") MESHMARK_DATA="$work/data" STUDIO="studio-$RANDOM"
mkdir -p "$work/bin" "$work/studio/backup"
ln -s "$cli" "$work/bin/meshmark"
export PATH="$work/bin:$PATH"
cd "$work/studio"
meshmark example creature chair.obj >/dev/null
sed -i '1i mtllib chair.mtl' chair.obj
printf 'newmtl wood\nmap_Kd wood.png\n' >chair.mtl
printf '\x89PNG\r\n\x1a\n' >wood.png
{ echo "recipient,contact"; for k in $(seq -w 1 12); do echo "partner-$k,studio$k@example.com"; done; } >partners.csv

sed -n '/^<!-- studio walkthrough -->$/,/^```$/p' "$readme" | sed '1,2d;$d' >walkthrough.sh
[[ $(wc -l <walkthrough.sh) -gt 10 ]] || { echo "no walkthrough found in $readme"; exit 1; }
output=$(bash -euo pipefail walkthrough.sh 2>&1)
echo "$output"
grep -q "^wrote 12 of 12 copies into handed-out" <<<"$output"
[[ $(ls handed-out | wc -l) -eq 12 && -f handed-out/chair-partner-07.obj.zip ]]
[[ $(grep -c '^mdl_' handed-out.csv) -eq 12 ]]
grep -q '^found-in-the-wild.obj: a copy of model "chair" (mdl_[0-9a-f]*): the copy given to "partner-07"' <<<"$output"
grep -q "^1 detection(s) against model mdl_" <<<"$output"
cmp backup/master.key "$MESHMARK_DATA/master.key"
echo "studio walkthrough: twelve copies, the export, and the leak traced to partner-07"
