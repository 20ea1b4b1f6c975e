#!/usr/bin/env bash
# Installs the Debian (bookworm) packages of the named groups (default: build). Idempotent: does
# nothing when everything is present. Runs apt-get through sudo when not root.
#   build     what meshmark builds with (the README's two commands, the Docker image's build stage)
#   test      build, plus what the test command uses: Ninja, ccache, clang-format, clang-tidy, the sanitizer
#             toolchain, Docker, docker-compose and debootstrap (the image test), curl
#   sanitize  clang with its ASan, UBSan, TSan and libFuzzer runtimes, llvm-symbolizer
#   format    clang-format
#   lint      clang-tidy and jq (deploy/check-lint.sh)
#   load      wrk and curl, for tests/load/load_test.sh
#   servers   PostgreSQL (and python3, to find it a free port) and nginx: the cluster tests' servers
#   browser   chromium (headless) and a font: the web console's browser tests
# Usage: deploy/install-deps.sh [GROUP...]   (--runtime and the old --GROUP spellings are accepted)
set -euo pipefail

group_packages() {
  case "$1" in
    build)
      echo build-essential cmake ninja-build pkg-config git ca-certificates \
        libeigen3-dev libopenmesh-dev libsuitesparse-dev libopenblas0-serial \
        libcpp-httplib-dev nlohmann-json3-dev libspdlog-dev libcli11-dev \
        libsqlite3-dev libpq-dev libssl-dev libcurl4-openssl-dev libgtest-dev libnanoflann-dev libboost-dev libdraco-dev zlib1g-dev curl ;;
    sanitize) echo clang libclang-rt-14-dev llvm ;;
    format) echo clang-format ;;
    lint) echo clang-tidy jq ;;
    load) echo wrk curl ;;
    docker) echo docker.io docker-compose debootstrap ;;
    servers) echo postgresql python3 nginx-light ;;
    browser) echo chromium fonts-dejavu-core ;;
    test)
      group_packages build; group_packages sanitize; group_packages format; group_packages lint; group_packages docker
      group_packages servers; group_packages browser
      echo ccache ;;
    *) echo "install-deps: unknown group '$1' (build, test, sanitize, format, lint, load, docker, servers, browser)" >&2; return 2 ;;
  esac
}

groups=("$@")
[[ ${#groups[@]} -eq 0 ]] && groups=(build)
packages=()
for g in "${groups[@]}"; do
  g="${g#--}"
  [[ "$g" == load-tools ]] && g=load
  list=$(group_packages "$g")
  # shellcheck disable=SC2206  # package names: split on whitespace on purpose
  packages+=($list)
done

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep "install ok installed" >/dev/null || missing+=("$p")
done
if [[ ${#missing[@]} -eq 0 ]]; then exit 0; fi

SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}"
$SUDO apt-get update -q
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
