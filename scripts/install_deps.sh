#!/usr/bin/env bash
# Installs the Debian 12 packages fcl_disk needs to build, test, benchmark and plot.
# The one place the package lists live: scripts/test.sh, scripts/fuzz.sh and .ci/run use this.
# Idempotent: does nothing when every package is already installed.
#   ./scripts/install_deps.sh               # the base list
#   ./scripts/install_deps.sh --sanitizers  # the base list and the fuzzing/sanitizer tools
#   ./scripts/install_deps.sh --packaging   # the base list and pkg-config, colcon, Doxygen
#                                           # (scripts/check_packaging.sh); options combine
set -euo pipefail

PACKAGES=(
  cmake
  make
  g++
  libfcl-dev
  libccd-dev
  libeigen3-dev
  liboctomap-dev   # fcl::OcTree in the tests, fuzz target and benchmarks (libfcl-dev pulls it too)
  libgtest-dev
  libbenchmark-dev
  python3-matplotlib
)

# Clang with libFuzzer and the sanitizer runtimes (scripts/fuzz.sh, docs/fuzzing.md).
SANITIZER_PACKAGES=(
  clang-14
  libclang-rt-14-dev
)

# pkg-config, colcon and Doxygen (scripts/check_packaging.sh).
PACKAGING_PACKAGES=(
  doxygen
  pkg-config
  colcon
  python3-colcon-cmake   # colcon builds CMake packages
  python3-colcon-ros     # colcon reads package.xml (build_type cmake)
)

for option in "$@"; do
  case "$option" in
    --sanitizers) PACKAGES+=("${SANITIZER_PACKAGES[@]}") ;;
    --packaging) PACKAGES+=("${PACKAGING_PACKAGES[@]}") ;;
    *) echo "usage: $0 [--sanitizers] [--packaging]" >&2; exit 2 ;;
  esac
done

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
