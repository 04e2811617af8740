#!/usr/bin/env bash
# Configures and builds the whole stack into build/ (Ninja, ccache when present, warnings as
# errors). Usage: scripts/build.sh [extra cmake -D options]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${ROVER_BUILD_DIR:-build}
JOBS=${ROVER_JOBS:-2}
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DROVER_WERROR=ON \
      -DROVER_MODULE_FILTER="" "$@" > "$BUILD_DIR.configure.log" 2>&1 || {
  cat "$BUILD_DIR.configure.log" >&2
  exit 1
}
ninja -C "$BUILD_DIR" -j"$JOBS"
