#!/usr/bin/env bash
# FCL 0.7.0's own tests (test/fcl_upstream/) as a guard: loading fcl_disk must not
# change any answer they check. Builds and installs fcl_disk (Release) into a
# temporary prefix, builds the tests against Debian's libfcl and that prefix, and
# runs every test file twice: plainly, and linked with libfcl_disk. Prints each
# step's time and per-file pass counts; exits non-zero on any failure.
#   ./scripts/fcl_upstream_tests.sh
# Environment: FCL_UPSTREAM_BUILD_DIR (default build-upstream/ in the repository),
#              FCL_UPSTREAM_JOBS (default: nproc),
#              FCL_UPSTREAM_FCL_DISK_BUILD: an existing Release build folder of this
#                repository to bring up to date and install fcl_disk from, instead of
#                configuring and building it again (CI: build, after scripts/test.sh).
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."
repo=$(pwd)

build_root=${FCL_UPSTREAM_BUILD_DIR:-$repo/build-upstream}
mkdir -p "$build_root"
build_root=$(cd "$build_root" && pwd)
jobs=${FCL_UPSTREAM_JOBS:-$(nproc)}
prefix=$build_root/prefix
lib_build=${FCL_UPSTREAM_FCL_DISK_BUILD:-$build_root/fcl_disk}
test_build=$build_root/tests
logs=$build_root/logs

now_ms() { echo $(($(date +%s%N) / 1000000)); }
seconds_since() {  # seconds_since start_ms: "12.3"
  local ms=$(($(now_ms) - $1))
  echo "$((ms / 1000)).$((ms % 1000 / 100))"
}

timings=()
step() {  # step "name" command...: runs the command, records how long it took
  local name=$1 start
  shift
  echo "== $name"
  start=$(now_ms)
  "$@"
  timings+=("$(printf '%-30s %7s s' "$name" "$(seconds_since "$start")")")
}

./scripts/install_deps.sh

rm -rf "$prefix" "$logs"
mkdir -p "$logs"

if [ -n "${FCL_UPSTREAM_FCL_DISK_BUILD:-}" ]; then
  if ! grep -q '^CMAKE_BUILD_TYPE:STRING=Release$' "$lib_build/CMakeCache.txt" 2>/dev/null; then
    echo "FCL_UPSTREAM_FCL_DISK_BUILD=$lib_build is not a Release build folder" >&2
    exit 1
  fi
else
  step "fcl_disk: configure" cmake -S . -B "$lib_build" -DCMAKE_BUILD_TYPE=Release \
    -DBUILD_TESTING=OFF -DFCL_DISK_BUILD_EXAMPLES=OFF -DFCL_DISK_BUILD_REPORT=OFF \
    -DFCL_DISK_BUILD_BENCHMARKS=OFF -DFCL_DISK_BUILD_FUZZERS=OFF
fi
step "fcl_disk: build" cmake --build "$lib_build" --target fcl_disk --parallel "$jobs"
step "fcl_disk: install" cmake --install "$lib_build" --prefix "$prefix"
step "FCL tests: configure" cmake -S test/fcl_upstream -B "$test_build" \
  -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix"
step "FCL tests: build" cmake --build "$test_build" --parallel "$jobs"

# The "with" executables must load libfcl_disk, the plain ones must not.
check_linkage() {
  local failed=0 exe needed
  for exe in "${tests[@]}"; do
    needed=$(readelf -d "$test_build/$exe" | grep NEEDED || true)
    if grep -q 'libfcl_disk\.so' <<<"$needed"; then
      echo "FAIL: $exe (plain) has libfcl_disk as NEEDED"
      failed=1
    fi
    needed=$(readelf -d "$test_build/${exe}_with_fcl_disk" | grep NEEDED || true)
    if ! grep -q 'libfcl_disk\.so' <<<"$needed"; then
      echo "FAIL: ${exe}_with_fcl_disk lacks libfcl_disk as NEEDED"
      failed=1
    fi
  done
  [ "$failed" -eq 0 ] && echo "linkage: ${#tests[@]} plain executables without libfcl_disk," \
    "${#tests[@]} with libfcl_disk NEEDED"
  return "$failed"
}

tests=()
for source in test/fcl_upstream/test_fcl_*.cpp; do
  name=$(basename "$source" .cpp)
  [ "$name" = test_fcl_utility ] || tests+=("$name")
done
step "linkage check" check_linkage

# Runs one executable and sets `counts` to "passed/ran"; counts a failure unless
# all passed (and, for the "with" variant, fcl_disk_is_loaded.cpp's checks are
# among them), printing the failing tests and where the log is.
results=()
failures=0
run_one() {
  local exe=$1 log=$logs/$1.log rc=0 ran passed ok=1
  (cd "$test_build" && "./$exe") >"$log" 2>&1 || rc=$?
  ran=$(sed -n 's/^\[==========\] \([0-9]*\) tests\? from .* ran\..*/\1/p' "$log" | tail -1)
  passed=$(sed -n 's/^\[  PASSED  \] \([0-9]*\) tests\?\..*/\1/p' "$log" | tail -1)
  ran=${ran:-?}
  passed=${passed:-0}
  counts=$passed/$ran
  if [ "$rc" -ne 0 ] || [ "$passed" != "$ran" ]; then ok=0; fi
  if [[ $exe == *_with_fcl_disk ]] &&
    [ "$(grep -c '^\[       OK \] FclDiskLoaded\.' "$log")" -ne 2 ]; then
    echo "  FAIL: $exe did not pass fcl_disk_is_loaded.cpp's checks"
    ok=0
  fi
  if [ "$ok" -eq 0 ]; then
    echo "  FAIL: $exe (exit $rc, $passed of $ran passed):"
    grep -E '^\[  FAILED  \]|Failure|rror|Assertion|Segmentation|Abort' "$log" | head -40 |
      sed 's/^/    /' || true
    echo "    full log: $log"
    failures=$((failures + 1))
  fi
}

run_all() {  # run_all suffix: every test file, with the given executable suffix
  local suffix=$1 exe start
  for t in "${tests[@]}"; do
    exe=$t$suffix
    start=$(now_ms)
    run_one "$exe"
    printf '  %-46s %-7s %6s s\n' "$exe" "$counts" "$(seconds_since "$start")"
    results+=("$exe $counts")
  done
}

# Failures are counted, not fatal, so both runs always complete and report.
step "FCL tests: run plain" run_all ""
step "FCL tests: run with fcl_disk" run_all "_with_fcl_disk"

echo
echo "== per file (passed/ran; the 'with' runs include fcl_disk_is_loaded.cpp's 2 checks)"
for t in "${tests[@]}"; do
  plain='' with=''
  for r in "${results[@]}"; do
    [ "${r% *}" = "$t" ] && plain=${r##* }
    [ "${r% *}" = "${t}_with_fcl_disk" ] && with=${r##* }
  done
  printf '  %-34s plain %-7s with fcl_disk %s\n' "$t" "$plain" "$with"
done
echo
echo "== time per step"
printf '  %s\n' "${timings[@]}"

if [ "$failures" -ne 0 ]; then
  echo "fcl_upstream_tests.sh: $failures executable(s) failed (logs in $logs)" >&2
  exit 1
fi
echo "fcl_upstream_tests.sh: all FCL tests pass, plainly and with fcl_disk loaded"
