#!/usr/bin/env bash
# Checks how fcl_disk is packaged for its users, from this checkout:
#   install   cmake build of the library alone, installed with
#             `cmake --install --prefix <tmp>/prefix` (the prefix chosen at install time)
#   pkgconfig test/consumer_pkgconfig: a plain Makefile using
#             `pkg-config --cflags --libs fcl_disk` against that prefix; builds and runs
#   colcon    a throwaway colcon workspace holding this repository (package.xml,
#             build_type cmake) and test/consumer_colcon (find_package(fcl_disk));
#             `colcon build`, then the consumer runs from install/setup.sh
#   doc       the Doxygen `doc` target (API reference of include/fcl_disk/*.h);
#             any Doxygen warning fails it
# Prints how long each step took; exits non-zero as soon as one fails.
#
# Debian packages, installed if missing (root, or sudo):
# ./scripts/install_deps.sh --packaging (pkg-config, colcon, Doxygen).
#
#   ./scripts/check_packaging.sh
# Environment:
#   FCL_DISK_PACKAGING_DIR   work directory (default: a new temporary directory,
#                            removed on success); a given one is kept and reused,
#                            so a second run only rebuilds what changed
#   FCL_DISK_PACKAGING_JOBS  parallel compile jobs (default: nproc)
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."
ROOT=$PWD
JOBS=${FCL_DISK_PACKAGING_JOBS:-$(nproc)}

# ---- helpers ---------------------------------------------------------------------
CURRENT_STEP="setup"
STEP_START=$SECONDS
SUMMARY=()

on_exit() {
  local rc=$?
  if [ "$rc" -ne 0 ]; then
    echo "==== check_packaging.sh: FAILED in step '$CURRENT_STEP' after $((SECONDS - STEP_START)) s (exit $rc)" >&2
    [ -n "${WORK:-}" ] && echo "==== check_packaging.sh: work directory kept: $WORK" >&2
  fi
}
trap on_exit EXIT

begin() {
  CURRENT_STEP=$1
  STEP_START=$SECONDS
  echo "==== check_packaging.sh: $1"
}

end() {
  local took=$((SECONDS - STEP_START))
  echo "==== check_packaging.sh: $CURRENT_STEP took $took s"
  SUMMARY+=("$(printf '%-10s %5d s' "$CURRENT_STEP" "$took")")
}

fail() {
  echo "check_packaging.sh: $*" >&2
  exit 1
}

# The first path under $1 named $2 (fails if none).
find_one() {
  local found
  found=$(find "$1" -name "$2" -print -quit)
  [ -n "$found" ] || fail "no $2 under $1"
  echo "$found"
}

# Fails unless the libfcl_disk that binary $1 loads (in the current environment)
# lies under directory $2.
check_loads_fcl_disk_from() {
  local loaded
  loaded=$(ldd "$1" | awk '/libfcl_disk\.so/ {print $3}')
  echo "$1 loads $loaded"
  case "$(realpath "$loaded" 2>/dev/null)" in
    "$(realpath "$2")"/*) ;;
    *) fail "$1 loads libfcl_disk from '$loaded', not from under $2" ;;
  esac
}

# ---- packages --------------------------------------------------------------------
begin packages
./scripts/install_deps.sh --packaging
end

if [ -n "${FCL_DISK_PACKAGING_DIR:-}" ]; then
  mkdir -p "$FCL_DISK_PACKAGING_DIR"
  WORK=$(realpath "$FCL_DISK_PACKAGING_DIR")
  REMOVE_WORK=0
else
  WORK=$(mktemp -d "${TMPDIR:-/tmp}/fcl_disk_packaging.XXXXXX")
  REMOVE_WORK=1
fi
BUILD=$WORK/build
PREFIX=$WORK/prefix
WS=$WORK/colcon_ws
echo "check_packaging.sh: work directory $WORK, $JOBS jobs"

# ---- install: build the library and install it into a fresh prefix ----------------
begin install
# Configured for the default prefix and installed elsewhere: fcl_disk.pc must name
# the prefix it was installed into.
cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=OFF \
  -DFCL_DISK_BUILD_EXAMPLES=OFF -DFCL_DISK_BUILD_REPORT=OFF -DFCL_DISK_BUILD_BENCHMARKS=OFF
cmake --build "$BUILD" --parallel "$JOBS"
rm -rf "$PREFIX"
cmake --install "$BUILD" --prefix "$PREFIX"
end

# ---- pkgconfig: a plain Makefile consumer -----------------------------------------
begin pkgconfig
PC_FILE=$(find_one "$PREFIX" fcl_disk.pc)
echo "$PC_FILE:"
grep -v '^#' "$PC_FILE"
PKG_CONFIG_PATH=$(dirname "$PC_FILE")
export PKG_CONFIG_PATH
pkg-config --validate fcl_disk
[ "$(pkg-config --variable=prefix fcl_disk)" = "$PREFIX" ] ||
  fail "fcl_disk.pc: prefix=$(pkg-config --variable=prefix fcl_disk), installed into $PREFIX"
echo "pkg-config --modversion fcl_disk: $(pkg-config --modversion fcl_disk)"
echo "pkg-config --cflags --libs fcl_disk: $(pkg-config --cflags --libs fcl_disk)"
mkdir -p "$WORK/consumer_pkgconfig"
make -C "$ROOT/test/consumer_pkgconfig" BUILD_DIR="$WORK/consumer_pkgconfig" clean all
check_loads_fcl_disk_from "$WORK/consumer_pkgconfig/consumer_pkgconfig" "$PREFIX"
"$WORK/consumer_pkgconfig/consumer_pkgconfig"
unset PKG_CONFIG_PATH
end

# ---- colcon: a workspace with fcl_disk and a consumer package ---------------------
begin colcon
mkdir -p "$WS/src"
ln -sfn "$ROOT" "$WS/src/fcl_disk"
ln -sfn "$ROOT/test/consumer_colcon" "$WS/src/fcl_disk_consumer"
rm -rf "$WS/install"
# colcon passes --cmake-args to every package; the consumer ignores fcl_disk's options.
(
  cd "$WS"
  MAKEFLAGS="-j$JOBS" colcon build --base-paths src \
    --cmake-args -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=OFF \
    -DFCL_DISK_BUILD_EXAMPLES=OFF -DFCL_DISK_BUILD_REPORT=OFF --no-warn-unused-cli
)
for package in fcl_disk fcl_disk_consumer; do
  [ -d "$WS/install/$package" ] || fail "colcon did not install $package"
done
(
  # setup.sh is colcon's, not written for `set -u`.
  set +u
  # shellcheck disable=SC1091
  . "$WS/install/setup.sh"
  set -u
  consumer=$(command -v fcl_disk_consumer) || fail "fcl_disk_consumer is not on PATH after install/setup.sh"
  check_loads_fcl_disk_from "$consumer" "$WS/install/fcl_disk"
  fcl_disk_consumer
)
end

# ---- doc: the API reference, without Doxygen warnings -----------------------------
begin doc
cmake "$BUILD" >/dev/null  # picks up Doxygen if it was installed after the first configure
DOC_LOG=$WORK/doc.log
if ! cmake --build "$BUILD" --target doc 2>&1 | tee "$DOC_LOG"; then
  fail "the doc target failed (Doxygen warnings are errors); log: $DOC_LOG"
fi
if grep -E 'warning:|error:' "$DOC_LOG"; then
  fail "Doxygen reported the lines above"
fi
for page in index.html namespacefcl__disk.html classfcl__disk_1_1Disk.html; do
  [ -s "$BUILD/doc/html/$page" ] || fail "the API reference lacks $page"
done
end

# ---- summary ---------------------------------------------------------------------
echo "==== check_packaging.sh: all steps passed"
printf '  %s\n' "${SUMMARY[@]}"
if [ "$REMOVE_WORK" -eq 1 ]; then
  rm -rf "$WORK"
  WORK=
fi
