#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs, builds (Release) and runs the main job on the bundled input.
# Today: (1) converts the real Velodyne VLP-16 scan that MRPT ships into a LiDAR frame and writes
# its range and intensity images as PNG (native 16 rows, and an 8x taller preview); (2) simulates
# the labelled hall sample and writes a preview with the ground-truth moving people in red;
# (3) runs the detector on the committed sample, scores it against its ground truth and writes
# overlays (true positives red, false positives yellow, misses blue); (4) evaluates it beside
# its baselines and writes the HTML report (dynobj-eval); (5) the main job: filters the sample with
# rawlog-dynobj, maps the raw and the filtered rawlog with stock icp-slam, and compares the two
# maps: label-free (how many map points the sweeps see through, each map with its own icp-slam
# poses) and against the ground truth (how many lie on the moving people; the filter never sees
# it), each with a picture of both maps from above, side by side.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"

ensure_packages
BUILD_DIR="${DYNOBJ_BUILD_DIR:-$DYNOBJ_ROOT/build}"
build_project "$BUILD_DIR"
OUT="${DYNOBJ_DEMO_OUT:-$DYNOBJ_ROOT/out/demo}"
INPUT=/usr/share/mrpt/datasets/test_velodyne_VLP16.rawlog
log "converting ${INPUT}"
"$BUILD_DIR/apps/dynobj-frames" -i "$INPUT" -o "$OUT"
"$BUILD_DIR/apps/dynobj-frames" -i "$INPUT" -o "$OUT/preview-x8" --row-scale 8 -q
log "simulating the hall sample (40 sweeps, OS0-64 512 x 10)"
"$BUILD_DIR/apps/dynobj-sim" -s "$DYNOBJ_ROOT/share/dynobj/scenarios/hall.yaml" -o "$OUT/hall-small" \
  --frames 40 --set sensor=sensors/os0-64-512.ini --set name=hall-small --preview 30 -q
SAMPLE="$DYNOBJ_ROOT/rawlogs/hall-small/hall-small"
log "detecting moving objects in the committed sample"
"$BUILD_DIR/apps/dynobj-detect" -i "$SAMPLE.rawlog" --sensor-label LIDAR --gt "$SAMPLE.gt.labels" \
  -o "$OUT/detect/hall-small.det.labels" --overlay-dir "$OUT/detect" -w
log "evaluating: this detector (own ego-motion, ground-truth ego-motion, drifting odometry) and MRPT's"
log "CPointCloudFilterByDistance on the committed sample"
"$BUILD_DIR/apps/dynobj-eval" --run "$DYNOBJ_ROOT/rawlogs/hall-small" -o "$OUT/eval" -q -w
log "the main job: rawlog-dynobj, then stock icp-slam on the raw and on the filtered sample"
SLAM="$OUT/slam"
rm -rf "$SLAM" && mkdir -p "$SLAM/raw" "$SLAM/filtered"
"$BUILD_DIR/apps/rawlog-dynobj" -i "$SAMPLE.rawlog" -o "$SLAM/filtered.rawlog" -w -q
ICP_INI="$DYNOBJ_ROOT/share/dynobj/config/icp-slam-hall.ini"
(cd "$SLAM/raw" && icp-slam "$ICP_INI" "$SAMPLE.rawlog" > icp-slam.log)
(cd "$SLAM/filtered" && icp-slam "$ICP_INI" ../filtered.rawlog > icp-slam.log)
MAP=icp-slam-out/_finalmaps_.txt_mrpt__maps__CSimplePointsMap_00.txt
SM=icp-slam-out/_finalmap_.simplemap
log "the two maps compared label-free (points the sweeps see through, each map with its own icp-slam poses)"
"$BUILD_DIR/apps/dynobj-mapcompare" -i "$SAMPLE.rawlog" --before "$SLAM/raw/$MAP" \
  --after "$SLAM/filtered/$MAP" --before-poses "$SLAM/raw/$SM" --after-poses "$SLAM/filtered/$SM" \
  -o "$SLAM/maps-label-free.png" -w
log "and against the sample's ground truth (points on the moving people)"
"$BUILD_DIR/apps/dynobj-mapcompare" -i "$SAMPLE.rawlog" --gt "$SAMPLE.gt.labels" \
  --poses "$SAMPLE.gt.tum" --before "$SLAM/raw/$MAP" --after "$SLAM/filtered/$MAP" \
  -o "$SLAM/maps-before-after.png" -w
log "done: images in ${OUT} (and ${OUT}/preview-x8); simulated sample and"
log "      ${OUT}/hall-small/hall-small.preview.png (ground-truth dynamic pixels in red);"
log "      detections and overlays in ${OUT}/detect/"
log "      evaluation report: ${OUT}/eval/report.html (open it in a browser)"
log "      the two icp-slam maps from above (left raw, right filtered): points the sweeps see"
log "      through red: ${SLAM}/maps-label-free.png; points on moving people red:"
log "      ${SLAM}/maps-before-after.png"
