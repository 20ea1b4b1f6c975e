#!/usr/bin/env bash
# GET /metrics — Prometheus text: requests, jobs by kind and state, queue depth, stage durations.
. "$(dirname "$0")/common.sh"
curl -sS --fail-with-body "$SERVER/metrics"
