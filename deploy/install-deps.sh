#!/usr/bin/env bash
# Installs the Debian (bookworm) packages meshmark builds and runs with. Idempotent: does
# nothing when everything is present. Runs apt-get through sudo when not root.
set -euo pipefail

BUILD_PACKAGES=(
  build-essential cmake pkg-config git ca-certificates
  libeigen3-dev libopenmesh-dev libsuitesparse-dev libopenblas0-serial
  libcpp-httplib-dev nlohmann-json3-dev libspdlog-dev libcli11-dev
  libsqlite3-dev libssl-dev libgtest-dev libnanoflann-dev libboost-dev libdraco-dev zlib1g-dev curl
)
# Only what the daemon needs at run time (used by the Docker image's final stage).
RUNTIME_PACKAGES=(
  libopenmesh1 libcholmod3 libopenblas0-serial libspdlog1.10 libsqlite3-0 libssl3 libdraco7 zlib1g
  ca-certificates
)

# The HTTP load generator for tests/load/load_test.sh.
LOAD_TOOLS=(wrk curl)

# The sanitizer and fuzzing build (deploy/sanitize.sh): clang with its ASan, UBSan and libFuzzer
# runtimes, and llvm-symbolizer for readable reports.
SANITIZE_TOOLS=(clang libclang-rt-14-dev llvm)

packages=("${BUILD_PACKAGES[@]}")
case "${1:-}" in
  --runtime) packages=("${RUNTIME_PACKAGES[@]}") ;;
  --load-tools) packages=("${LOAD_TOOLS[@]}") ;;
  --sanitize) packages=("${SANITIZE_TOOLS[@]}") ;;
esac

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [[ ${#missing[@]} -eq 0 ]]; then exit 0; fi

SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}"
$SUDO apt-get update -q
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
