#!/usr/bin/env bash
# Sets up (packages), builds, and runs the main job: for now the smoke service set, one service
# per layer (ddl -> dl -> apl), for 15 s, then shows what each service saw.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
BIN=${ROVER_BUILD_DIR:-build}/bin
export ROVER_STATE_DIR=${ROVER_STATE_DIR:-$PWD/runs/state}
"$BIN/roverctl" up deploy/smoke.compose.yaml --for "${ROVER_MAIN_SECONDS:-15}"
"$BIN/roverctl" ps smoke
echo "--- last apl/mobility_status reports (smoke-apl log) ---"
"$BIN/roverctl" logs smoke-apl -p smoke -n 5
