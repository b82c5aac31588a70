#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Regenerates the map-cleaning tables of docs/accuracy.md ("Map cleaning (dynobj-mapclean)"):
# simulates hall (300 sweeps), runs stock icp-slam on it, then dynobj-mapclean with each pose
# source (--level-poses, --gt), and the ablations (not levelled; free-space check off; ratio 2).
# Writes out/accuracy/mapclean.md (override the folder: DYNOBJ_ACCURACY_OUT). Time and peak memory
# come from GNU time (package `time`). Not regenerated: the "ceiling" rows (a map built from the
# ground-truth labels), made by a throwaway program.
#   scripts/mapclean-accuracy.sh
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"

ensure_packages time
BUILD_DIR="${DYNOBJ_BUILD_DIR:-$DYNOBJ_ROOT/build}"
[ "${DYNOBJ_SKIP_BUILD:-0}" = 1 ] || build_project "$BUILD_DIR"  # DYNOBJ_SKIP_BUILD=1: use it as built
BIN="$BUILD_DIR/apps"
OUT="${DYNOBJ_ACCURACY_OUT:-$DYNOBJ_ROOT/out/accuracy}"
DIR="$OUT/mapclean"
SHARE="$DYNOBJ_ROOT/share/dynobj"
MD="$OUT/mapclean.md"
rm -rf "$DIR"
mkdir -p "$DIR/icp"
log "mapclean: simulating hall (300 sweeps)"
"$BIN/dynobj-sim" -s "$SHARE/scenarios/hall.yaml" -o "$DIR/hall" -q > /dev/null
log "mapclean: stock icp-slam"
icp_s=$( { cd "$DIR/icp" && /usr/bin/time -f "%e" icp-slam "$SHARE/config/icp-slam-hall.ini" \
           "$DIR/hall/hall.rawlog" > icp-slam.log; } 2>&1 | tail -n1)

# run <label> <pose source> <out name> [more dynobj-mapclean options]: one table row.
run() {
  local label="$1" poses="$2" name="$3"
  shift 3
  log "mapclean: ${label}"
  local t
  t=$( { /usr/bin/time -f "%e %M" "$BIN/dynobj-mapclean" -i "$DIR/hall/hall.rawlog" \
           -o "$DIR/$name" --poses "$poses" --gt "$DIR/hall/hall.gt.labels" -q "$@" \
           > "$DIR/$name.txt"; } 2>&1 | tail -n1)
  local secs=${t% *} kb=${t#* }
  # "SA 99.58%  DA 96.31%  AA 97.93%  ghost points 2790  (...)", "static map 2362845 points (...)"
  local sa da aa ghost pts
  read -r sa da aa ghost < <(sed -n 's/.*SA \([0-9.n/a]*\)%* *DA \([0-9.n/a]*\)%* *AA \([0-9.n/a]*\)%* *ghost points \([0-9]*\).*/\1 \2 \3 \4/p' "$DIR/$name.txt")
  pts=$(sed -n 's/.*static map \([0-9]*\) points.*/\1/p' "$DIR/$name.txt")
  printf '| %s | %s %% | %s %% | %s %% | %s | %s | %s s%s | %s MB |\n' "$label" "$sa" "$da" "$aa" \
    "$(printf "%'d" "$ghost")" "$(printf "%'d" "$pts")" "$secs" \
    "$([ "$poses" = "$DIR/icp/icp-slam-out/_finalmap_.simplemap" ] && echo " (+ ${icp_s} s icp-slam)")" \
    "$((kb / 1024))" >> "$MD.partial"
}

{
  echo "<!-- made by: scripts/mapclean-accuracy.sh -->"
  echo "\`dynobj-sim -s share/dynobj/scenarios/hall.yaml -o hall\`; \`icp-slam share/dynobj/config/icp-slam-hall.ini hall/hall.rawlog\`;"
  echo "per row \`dynobj-mapclean -i hall/hall.rawlog -o <dir> --poses <source> --gt hall/hall.gt.labels [--level-poses] [-c <ablation.ini>]\`"
  echo
  echo "| pose source | SA | DA | AA | ghost points | static map points | time | peak memory |"
  echo "|---|---|---|---|---|---|---|---|"
} > "$MD.partial"
run "rawlog odometry (noisy SE(2))" odometry odometry --level-poses
run "ground-truth TUM (\`hall.gt.tum\`)" "$DIR/hall/hall.gt.tum" gt --level-poses
run "stock \`icp-slam\` simplemap (+ odometry between keyframes)" \
    "$DIR/icp/icp-slam-out/_finalmap_.simplemap" icp --level-poses
run "detector ego-motion, chained" ego ego --level-poses
{
  echo
  echo "Ablations (same command, one change):"
  echo
  echo "| step (ablation) | SA | DA | AA | ghost points | static map points | time | peak memory |"
  echo "|---|---|---|---|---|---|---|---|"
} >> "$MD.partial"
printf '[mapclean]\nfree_space_check = false\n' > "$DIR/no-free-space.ini"
printf '[mapclean]\nfree_space_ratio = 2\n' > "$DIR/ratio2.ini"
run "ground truth, free-space check off, not levelled" "$DIR/hall/hall.gt.tum" gt-nofs -c "$DIR/no-free-space.ini"
run "ground truth, free-space check, not levelled" "$DIR/hall/hall.gt.tum" gt-notlevel
run "odometry, free-space check, not levelled" odometry odo-notlevel
run "ego-motion, free-space check ratio 2 instead of 4, levelled" ego ego-ratio2 --level-poses -c "$DIR/ratio2.ini"
mv "$MD.partial" "$MD"
log "mapclean: ${MD}"
