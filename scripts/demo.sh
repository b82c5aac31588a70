#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs, builds (Release) and runs the main job on the bundled input.
# Today: converts the real Velodyne VLP-16 scan that MRPT ships into a LiDAR frame and writes its
# range and intensity images as PNG (native 16 rows, and an 8x taller preview).
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
log "done: images in ${OUT} (and ${OUT}/preview-x8)"
