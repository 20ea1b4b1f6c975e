#!/usr/bin/env bash
# Makes the base image deploy/Dockerfile starts from, debian:bookworm-slim, on a machine that
# cannot pull it from a registry: a minimal Debian bookworm made with debootstrap from Debian's
# own mirror, imported under that name. Does nothing when the image is there. The root file
# system is kept as a tarball in deploy/cache-dir.sh's folder, so that a second machine state
# (dockerd's storage wiped) imports it again in seconds. Needs root, docker and debootstrap.
#   MESHMARK_DEBIAN_MIRROR   the mirror (default http://deb.debian.org/debian)
set -euo pipefail
cd "$(dirname "$0")/.."
image=debian:bookworm-slim
if docker image inspect "$image" >/dev/null 2>&1; then exit 0; fi
tarball="$(deploy/cache-dir.sh)/debian-bookworm-minbase.tar"
if [[ ! -s "$tarball" ]]; then
  deploy/install-deps.sh docker
  root=$(mktemp -d)
  trap 'rm -rf "$root"' EXIT
  echo "docker-base: debootstrap --variant=minbase bookworm (no registry needed: Debian's mirror)"
  debootstrap --variant=minbase bookworm "$root" "${MESHMARK_DEBIAN_MIRROR:-http://deb.debian.org/debian}" >/dev/null
  rm -rf "$root"/var/cache/apt/archives/*.deb "$root"/var/lib/apt/lists/*
  tar -C "$root" -cf "$tarball.part" . && mv "$tarball.part" "$tarball"
fi
docker import "$tarball" "$image" >/dev/null
echo "docker-base: $image imported from $tarball ($(du -h "$tarball" | cut -f1))"
