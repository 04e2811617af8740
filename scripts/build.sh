#!/usr/bin/env bash
# Configures and builds the whole stack into build/ (Ninja, ccache when present, warnings as
# errors). Usage: scripts/build.sh [extra cmake -D options]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${ROVER_BUILD_DIR:-build}
JOBS=${ROVER_JOBS:-2}
# -g1 (line tables only): backtraces and perf keep file:line, and the build is about a quarter
# faster than with -g (sim/physics rover_simulation.cpp: 32.8 s -> 24.0 s; apl/mobility's
# manager test: 21.0 s -> 15.5 s). For full debug info pass
# -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g -DNDEBUG".
OPT_FLAGS="-O2 -g1 -DNDEBUG"
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DROVER_WERROR=ON \
      -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$OPT_FLAGS" -DCMAKE_C_FLAGS_RELWITHDEBINFO="$OPT_FLAGS" \
      -DROVER_MODULE_FILTER="" -DROVER_BUILD_BENCHMARKS=ON "$@" > "$BUILD_DIR.configure.log" 2>&1 || {
  cat "$BUILD_DIR.configure.log" >&2
  exit 1
}
ninja -C "$BUILD_DIR" -j"$JOBS"
