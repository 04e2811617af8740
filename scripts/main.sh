#!/usr/bin/env bash
# Sets up (packages), builds, and runs the main job: the drive-flat scenario end to end (the
# simulator, the device drivers, locomotion and the pose EKF on their own DDS domain; the runner
# drives 20 m and the judge scores the run against ground truth), then prints where the report,
# plots and logs are. ROVER_MAIN_SCENARIO and ROVER_MAIN_SEEDS choose another scenario or seeds.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
BIN=${ROVER_BUILD_DIR:-build}/bin
export CYCLONEDDS_URI="file://$PWD/deploy/cyclonedds/loopback.xml"
SCENARIO=${ROVER_MAIN_SCENARIO:-deploy/scenarios/drive_flat.yaml}
OUT=runs/main-$(date +%Y%m%d-%H%M%S)
status=0
"$BIN/roverctl" run "$SCENARIO" --seeds "${ROVER_MAIN_SEEDS:-1}" --out "$OUT" || status=$?
echo
echo "campaign folder: $OUT"
for f in "$OUT"/*/map.png "$OUT"/*/estimate_error.png "$OUT"/summary.txt "$OUT"/junit.xml; do
  [ -e "$f" ] && echo "  $f"
done
echo "again: $BIN/roverctl report $OUT"
exit $status
