#!/usr/bin/env bash
# Sets up (packages), builds, and runs the main job: a return to the lander from 30 m end to end
# (deploy/scenarios/lander_return_30m.yaml: the simulator with the lander, the device drivers,
# locomotion, the pose EKF, stereo, the mast, the mobility manager and apl-rendezvous on their own
# DDS domain; the rover finds the lander, drives to it, servos to the base of its ramp on the
# coded stripes and climbs onto the deck; the judge measures the placement against ground truth),
# then prints where the report, plots, detection images and recording are. ROVER_MAIN_SCENARIO and
# ROVER_MAIN_SEEDS choose another scenario or seeds.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
BIN=${ROVER_BUILD_DIR:-build}/bin
export CYCLONEDDS_URI="file://$PWD/deploy/cyclonedds/loopback.xml"
SCENARIO=${ROVER_MAIN_SCENARIO:-deploy/scenarios/lander_return_30m.yaml}
OUT=runs/main-$(date +%Y%m%d-%H%M%S)
status=0
"$BIN/roverctl" run "$SCENARIO" --seeds "${ROVER_MAIN_SEEDS:-1}" --out "$OUT" || status=$?
echo
echo "campaign folder: $OUT"
for f in "$OUT"/summary.txt "$OUT"/junit.xml "$OUT"/*/result.json "$OUT"/*/map.png \
         "$OUT"/*/estimate_error.png "$OUT"/*/detections "$OUT"/*/run.mcap "$OUT"/*/logs; do
  [ -e "$f" ] && echo "  $f"
done
echo "again: $BIN/roverctl report $OUT"
exit $status
