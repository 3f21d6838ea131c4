#!/usr/bin/env bash
# Installs the Debian 12 packages fcl_disk needs to build, test, benchmark and plot.
# The one place the package list lives: scripts/test.sh and .ci/run use this.
# Idempotent: does nothing when every package is already installed.
set -euo pipefail

PACKAGES=(
  cmake
  make
  g++
  libfcl-dev
  libccd-dev
  libeigen3-dev
  libgtest-dev
  libbenchmark-dev
  python3-matplotlib
)

missing=()
for package in "${PACKAGES[@]}"; do
  if ! dpkg -s "$package" 2>/dev/null | grep -q '^Status: install ok installed$'; then
    missing+=("$package")
  fi
done

if [ "${#missing[@]}" -eq 0 ]; then
  echo "install_deps.sh: all ${#PACKAGES[@]} packages already installed"
  exit 0
fi

if [ "$(id -u)" -eq 0 ]; then
  SUDO=()
elif command -v sudo >/dev/null 2>&1; then
  SUDO=(sudo)
else
  echo "install_deps.sh: missing packages (${missing[*]}) and not root, and sudo is not available" >&2
  exit 1
fi

echo "install_deps.sh: installing ${missing[*]}"
"${SUDO[@]}" apt-get update
"${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive \
  apt-get install -y --no-install-recommends "${missing[@]}"
