#!/usr/bin/env bash
# The whole round trip with the scripts in this folder: create an owner, upload an original,
# embed a copy for a recipient, download it, and detect it again. Prints each answer.
# Usage: MESHMARK_ADMIN_TOKEN=... walkthrough.sh MESH [WORKDIR]
here="$(dirname "$0")"
. "$here/common.sh"
need_file "${1:?usage: walkthrough.sh MESH [WORKDIR]}"
mesh="$1"; work="${2:-.}"

echo "# create an owner"
owner=$("$here/create-owner.sh" "studio-$(date +%Y%m%d-%H%M%S)-$RANDOM"); echo "$owner"  # owner names are unique
export MESHMARK_TOKEN=$(json_field api_key <<<"$owner")

echo "# upload the original and wait until it is prepared"
model=$("$here/upload-model.sh" "$mesh"); echo "$model"
model_id=$(json_field id <<<"$model")
"$here/wait-job.sh" "$(json_field job_id <<<"$model")"

echo "# embed a copy for a recipient (the daemon assigns the payload)"
embed=$(MESHMARK_REQUESTED_BY='Ana "A." Licensing' "$here/embed.sh" "$model_id" --recipient "reseller-42"); echo "$embed"
"$here/wait-job.sh" "$(json_field job_id <<<"$embed")"

echo "# download the watermarked copy"
base="$(basename "$mesh")"; marked="$work/marked.${base#*.}"  # a .gltf.zip comes back as one
"$here/get-job-result.sh" "$(json_field job_id <<<"$embed")" "$marked"
ls -l "$marked"

echo "# detect: which copy is this?"
detect=$("$here/detect.sh" "$model_id" "$marked"); echo "$detect"
"$here/wait-job.sh" "$(json_field job_id <<<"$detect")"

echo "# the evidence report, for a takedown notice: it names the recipient"
"$here/get-job-report.sh" "$(json_field job_id <<<"$detect")" "$work/evidence.html"
grep -o "handed out to reseller-42" "$work/evidence.html"

echo "# the detection the report was made of"
"$here/get-job.sh" "$(json_field job_id <<<"$detect")"
