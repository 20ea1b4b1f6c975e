#!/usr/bin/env bash
# Configures and builds meshmark (Release, Ninja) into ./build, through ccache when it is
# installed (its cache in deploy/cache-dir.sh's folder). Usage: deploy/build.sh [cmake args]
#   MESHMARK_BUILD_DIR  the build folder (default build)
#   MESHMARK_TARGETS    what to build (default: everything the configuration has)
set -euo pipefail
cd "$(dirname "$0")/.."
dir="${MESHMARK_BUILD_DIR:-build}"
# A folder configured by an older version of this script with Makefiles cannot switch generator.
if [[ -f "$dir/CMakeCache.txt" ]] && ! grep -q '^CMAKE_GENERATOR:INTERNAL=Ninja$' "$dir/CMakeCache.txt"; then
  echo "build: $dir was configured with another generator; configuring it again with Ninja"
  rm -rf "$dir/CMakeCache.txt" "$dir/CMakeFiles"
fi
launcher=()
if command -v ccache >/dev/null; then
  CCACHE_DIR="${CCACHE_DIR:-$(deploy/cache-dir.sh)/ccache}"
  # Paths below the checkout are hashed relative to it: a clone elsewhere hits the same entries.
  export CCACHE_DIR CCACHE_MAXSIZE="${CCACHE_MAXSIZE:-6G}" CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=true
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
deploy/build-console.sh  # three.js for the web console, which the daemon compiles in
cmake -G Ninja -S . -B "$dir" -DCMAKE_BUILD_TYPE="${CMAKE_BUILD_TYPE:-Release}" "${launcher[@]}" "$@" >/dev/null
read -r -a targets <<<"${MESHMARK_TARGETS:-}"
cmake --build "$dir" -j"$(deploy/cpus.sh)" ${targets[@]:+--target "${targets[@]}"}
