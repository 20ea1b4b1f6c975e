#!/usr/bin/env bash
# Configures and builds meshmark (Release) into ./build. Usage: deploy/build.sh [extra cmake args]
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build build -j"$(deploy/cpus.sh)"
