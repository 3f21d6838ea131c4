#!/usr/bin/env bash
# The main job: installs what is needed, builds fcl_disk (Release, build/), runs
# the example scene and then the speed-against-error report, which prints its
# table and writes build/report/report.csv and build/report/report.png.
#   ./scripts/run.sh            # full report (about a minute)
#   ./scripts/run.sh --quick    # a few pairs per family
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."

./scripts/install_deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build --parallel "$(nproc)" --target disk_scene fcl_disk_report
./build/examples/disk_scene
echo
./build/bench/fcl_disk_report "$@"
