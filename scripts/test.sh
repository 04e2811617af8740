#!/usr/bin/env bash
# Sets up (packages), builds, and runs the whole test suite with ctest. CI runs exactly this.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
start=$(date +%s)
bash scripts/build.sh -DROVER_BUILD_BENCHMARKS=OFF  # benchmarks are run by hand
echo "build: $(( $(date +%s) - start )) s"
BUILD_DIR=${ROVER_BUILD_DIR:-build}
export CYCLONEDDS_URI="file://$PWD/deploy/cyclonedds/loopback.xml"
cd "$BUILD_DIR"
ctest --output-on-failure -j"${ROVER_JOBS:-2}" --timeout 900 "$@"
