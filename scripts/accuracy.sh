#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Regenerates every accuracy figure of docs/accuracy.md: simulates each shipped scenario (300
# sweeps, fixed seeds), runs this detector (own intensity ego-motion, ground-truth ego-motion,
# drifting odometry) and MRPT's CPointCloudFilterByDistance, and writes one report per scenario
# plus out/accuracy/accuracy.md (all tables). Usage: scripts/accuracy.sh [scenario ...]
# scripts/accuracy.sh --matrix [options] runs the evaluation matrix instead (every scenario x
# seeds x every sensor preset x motion distortion): scripts/accuracy-matrix.sh --help.
set -euo pipefail
if [ "${1:-}" = "--matrix" ]; then
  shift
  exec "$(dirname "${BASH_SOURCE[0]}")/accuracy-matrix.sh" "$@"
fi
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"

ensure_packages
BUILD_DIR="${DYNOBJ_BUILD_DIR:-$DYNOBJ_ROOT/build}"
build_project "$BUILD_DIR"
OUT="${DYNOBJ_ACCURACY_OUT:-$DYNOBJ_ROOT/out/accuracy}"
mkdir -p "$OUT"
SCENARIOS=("$@")
[ ${#SCENARIOS[@]} -gt 0 ] || SCENARIOS=(hall corridor crossing street static)
SUMMARY="$OUT/accuracy.md"
: > "$SUMMARY.partial"
for s in "${SCENARIOS[@]}"; do
  log "scenario ${s}"
  "$BUILD_DIR/apps/dynobj-eval" --run "$DYNOBJ_ROOT/share/dynobj/scenarios/${s}.yaml" -o "$OUT/${s}" -q
  { echo "### ${s}"; echo; cat "$OUT/${s}/summary.md"; echo; } >> "$SUMMARY.partial"
done
mv "$SUMMARY.partial" "$SUMMARY"
log "done: ${SUMMARY} (tables) and ${OUT}/<scenario>/report.html"
