#!/usr/bin/env bash
# Sanitizer builds (docs/robustness.md, "Sanitizers"):
#   asan  build-asan/: everything, GCC, -fsanitize=address,undefined; the whole
#         ctest suite with leak checking; any report fails its test.
#   tsan  build-tsan/: the library and the concurrency tests (test_concurrency,
#         test_hook), -fsanitize=thread; any report fails.
# Usage (from anywhere):
#   ./scripts/sanitize.sh            # both stages
#   ./scripts/sanitize.sh asan       # one stage
#   ./scripts/sanitize.sh tsan
# Build directories are kept, so a second run only rebuilds what changed.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."
ROOT=$PWD
JOBS=${FCL_DISK_SANITIZE_JOBS:-$(nproc)}

stages=("$@")
[ "${#stages[@]}" -eq 0 ] && stages=(asan tsan)
for stage in "${stages[@]}"; do
  case "$stage" in
    asan | tsan) ;;
    *) echo "sanitize.sh: unknown stage '$stage' (expected asan or tsan)" >&2; exit 2 ;;
  esac
done

./scripts/install_deps.sh

# Prints how long the command took, labelled, and keeps its exit status.
timed() {
  local label=$1
  shift
  local start=$SECONDS
  echo "==== sanitize.sh: $label"
  "$@"
  echo "==== sanitize.sh: $label took $((SECONDS - start)) s"
}

# Both builds use -O1 -g1: line tables are all the reports' stack traces need,
# and -O1 runs the suite several times faster than -O0 while keeping every
# access the sanitizers check (the sanitizer documentation's recommendation).
run_asan() {
  # Exported, not only passed to cmake: the consumer test (test/consumer) configures
  # a nested project, which takes its initial flags from CXXFLAGS / LDFLAGS; its
  # programs load the instrumented libfcl_disk and need the runtime linked in.
  export CXXFLAGS="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
  export LDFLAGS="-fsanitize=address,undefined"
  timed "asan: configure" cmake -S . -B build-asan \
    -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" \
    -DCMAKE_CXX_COMPILER=g++ \
    -DCMAKE_CXX_FLAGS="$CXXFLAGS" \
    -DCMAKE_EXE_LINKER_FLAGS="$LDFLAGS" \
    -DCMAKE_SHARED_LINKER_FLAGS="$LDFLAGS" \
    -DCMAKE_MODULE_LINKER_FLAGS="$LDFLAGS" \
    -DFCL_DISK_BUILD_REPORT=OFF -DFCL_DISK_BUILD_EXAMPLES=OFF
  timed "asan: build" cmake --build build-asan --parallel "$JOBS"
  (
    export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1"
    export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
    cd build-asan
    # consumer_packages is left to the Release run (scripts/test.sh): it installs
    # the package and builds a separate project against it (one file of which
    # instantiates FCL's float dispatch on purpose), 511 s under ASan in CI,
    # testing packaging rather than fcl_disk's code, which the other tests cover.
    timed "asan: ctest" ctest --output-on-failure --timeout 1800 --parallel "$JOBS" \
      -E '^consumer_packages$'
  )
}

run_tsan() {
  timed "tsan: configure" cmake -S . -B build-tsan \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
    -DCMAKE_CXX_COMPILER=g++ \
    -DCMAKE_CXX_FLAGS="-fsanitize=thread" \
    -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=thread" \
    -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=thread" \
    -DFCL_DISK_BUILD_REPORT=OFF -DFCL_DISK_BUILD_EXAMPLES=OFF
  timed "tsan: build" cmake --build build-tsan --parallel "$JOBS" \
    --target fcl_disk test_concurrency test_hook
  # The binaries are run directly: only these two are built, and in one process
  # TSan sees every test's threads (test_concurrency's first test is then still
  # the process's first registration).
  (
    export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1"
    for test in test_concurrency test_hook; do
      timed "tsan: $test" "build-tsan/test/$test"
    done
  )
}

total_start=$SECONDS
for stage in "${stages[@]}"; do
  "run_$stage"
done
echo "==== sanitize.sh: all stages passed in $((SECONDS - total_start)) s"
