#!/usr/bin/env bash
# Builds the libFuzzer targets of test/fuzz/ with clang++-14 (build-fuzz/: -O1 -g,
# assertions on, AddressSanitizer + UndefinedBehaviorSanitizer, the library
# instrumented too) and runs each for a bounded time on a copy of the committed
# seed corpus, so the repository is never modified. Prints per target the
# executions and whether anything was found; exits non-zero if any target found
# a crash, a sanitizer report, a violated invariant or a timeout.
#   ./scripts/fuzz.sh                             # every target, 60 s each
#   FCL_DISK_FUZZ_SECONDS=300 ./scripts/fuzz.sh   # longer
#   FCL_DISK_FUZZ_SEED=0 ./scripts/fuzz.sh        # a random seed (default: 1)
#   ./scripts/fuzz.sh fuzz_hook                   # only the named targets
# A finding's input is left in build-fuzz/fuzz-run/<target>/artifacts/; rerun it
# with FCL_DISK_FUZZ_PRINT=1 build-fuzz/test/fuzz/<target> <file> to see it
# decoded (docs/fuzzing.md).
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."

SECONDS_PER_TARGET="${FCL_DISK_FUZZ_SECONDS:-60}"
# libFuzzer's random seed. Fixed by default, so that a CI run repeats (nearly:
# libFuzzer is not bit-for-bit deterministic) an exploration that can be run
# locally before pushing, and a finding fails CI only when code changed; 0 = a fresh random seed
# per run, for longer campaigns hunting new inputs.
SEED="${FCL_DISK_FUZZ_SEED:-1}"
BUILD=build-fuzz
TARGETS=(fuzz_exact_distance fuzz_almohamad_selim fuzz_disk_intersection fuzz_hook fuzz_disk_shapes
         fuzz_disk_environment)
if [ "$#" -gt 0 ]; then TARGETS=("$@"); fi
# The decoder's longest input is 224 bytes (raw mode, every field a raw double,
# one injected value, one perturbed rotation, fuzz_hook's option byte); longer
# inputs only carry ignored bytes.
MAX_LEN=256
# A single query takes microseconds; 10 s means a hang.
TIMEOUT_SECONDS=10

./scripts/install_deps.sh --sanitizers
cmake -S . -B "$BUILD" \
  -DCMAKE_CXX_COMPILER=clang++-14 \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DFCL_DISK_BUILD_FUZZERS=ON \
  -DBUILD_TESTING=OFF -DFCL_DISK_BUILD_EXAMPLES=OFF -DFCL_DISK_BUILD_REPORT=OFF \
  -DFCL_DISK_BUILD_BENCHMARKS=OFF
# Named targets are built one after another (CMake's Makefile generator); the
# default build ("all": the library and the four targets) runs them in parallel.
if [ "$#" -gt 0 ]; then
  cmake --build "$BUILD" --parallel "$(nproc)" --target "${TARGETS[@]}"
else
  cmake --build "$BUILD" --parallel "$(nproc)"
fi

export UBSAN_OPTIONS="print_stacktrace=1:${UBSAN_OPTIONS:-}"
failed=()
for target in "${TARGETS[@]}"; do
  work="$BUILD/fuzz-run/$target"
  rm -rf "$work"
  mkdir -p "$work/corpus" "$work/artifacts"
  cp test/fuzz/corpus/"$target"/* "$work/corpus/"
  log="$work/log.txt"
  status=0
  "$BUILD/test/fuzz/$target" "$work/corpus" \
    -max_total_time="$SECONDS_PER_TARGET" -seed="$SEED" -max_len="$MAX_LEN" \
    -timeout="$TIMEOUT_SECONDS" \
    -print_final_stats=1 -artifact_prefix="$work/artifacts/" >"$log" 2>&1 || status=$?
  # Final stats on a clean exit; the last status line otherwise.
  executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  if [ -z "$executions" ]; then
    executions=$(grep -o '^#[0-9]*' "$log" | tail -1 | tr -d '#')
  fi
  artifacts=$(find "$work/artifacts" -type f | wc -l)
  if [ "$status" -ne 0 ] || [ "$artifacts" -ne 0 ]; then
    echo "$target: ${executions:-?} executions: FOUND a failure (exit $status), input in $work/artifacts/"
    grep -E 'invariant violated|ERROR|SUMMARY|input:|^  ' "$log" | head -20 || true
    failed+=("$target")
  else
    echo "$target: ${executions:-?} executions in ${SECONDS_PER_TARGET} s, nothing found"
  fi
done

if [ "${#failed[@]}" -ne 0 ]; then
  echo "fuzz.sh: failures in ${failed[*]} (full logs: $BUILD/fuzz-run/<target>/log.txt)" >&2
  exit 1
fi
echo "fuzz.sh: ${#TARGETS[@]} targets, nothing found"
