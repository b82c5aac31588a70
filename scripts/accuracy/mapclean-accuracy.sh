#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Regenerates the map-cleaning figures of docs/accuracy.md ("Map cleaning (dynobj-mapclean)") and
# docs/mapclean.md (the cleaned simplemap rebuilt by stock observations2map): simulates hall (300
# sweeps), runs stock icp-slam on it, then dynobj-mapclean with each pose source (--level-poses,
# --gt), the ablations (not levelled; free-space check off; ratio 2), the ceiling rows (the same job
# with the ground-truth labels as the classification: --labels, the detector does not run) and
# stock observations2map on the cleaned simplemap of the icp-slam row and on icp-slam's own.
# Writes out/accuracy/mapclean.md (override the folder: DYNOBJ_ACCURACY_OUT). Time and peak memory
# come from GNU time (package `time`).
#   scripts/accuracy/mapclean-accuracy.sh                     everything
#   scripts/accuracy/mapclean-accuracy.sh --ceiling           only the simulation and the four ceiling rows
#                                                             (they do not depend on the detector)
#   scripts/accuracy/mapclean-accuracy.sh --observations2map  only the observations2map comparison
#   (the two options can be combined)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../common.sh"

WANT_MAIN=1 WANT_CEILING=1 WANT_O2M=1
if [ $# -gt 0 ]; then
  WANT_MAIN=0 WANT_CEILING=0 WANT_O2M=0
  for a in "$@"; do
    case "$a" in
      --ceiling) WANT_CEILING=1 ;;
      --observations2map) WANT_O2M=1 ;;
      *) echo "unknown option $a (see the head of $0)" >&2; exit 2 ;;
    esac
  done
fi
ensure_packages time
use_apps  # BUILD_DIR, BIN, OUT (common.sh; DYNOBJ_SKIP_BUILD=1: use the build as it is)
DIR="$OUT/mapclean"
SHARE="$DYNOBJ_ROOT/share/dynobj"
MD="$OUT/mapclean.md"
rm -rf "$DIR"
mkdir -p "$DIR/icp"
log "mapclean: simulating hall (300 sweeps)"
"$BIN/dynobj-sim" -s "$SHARE/scenarios/hall.yaml" -o "$DIR/hall" -q > /dev/null
icp_s=""
if [ "$WANT_MAIN" = 1 ] || [ "$WANT_O2M" = 1 ]; then
  log "mapclean: stock icp-slam"
  icp_s=$( { cd "$DIR/icp" && /usr/bin/time -f "%e" icp-slam "$SHARE/config/icp-slam-hall.ini" \
             "$DIR/hall/hall.rawlog" > icp-slam.log; } 2>&1 | tail -n1)
fi
ICP_SM="$DIR/icp/icp-slam-out/_finalmap_.simplemap"

# run <label> <pose source> <out name> [more dynobj-mapclean options]: one table row.
run() {
  local label="$1" poses="$2" name="$3"
  shift 3
  log "mapclean: ${label}"
  local t
  t=$( { /usr/bin/time -f "%e %M" "$BIN/dynobj-mapclean" -i "$DIR/hall/hall.rawlog" \
           -o "$DIR/$name" --poses "$poses" --gt "$DIR/hall/hall.gt.labels" -q -w "$@" \
           > "$DIR/$name.txt"; } 2>&1 | tail -n1)
  local secs=${t% *} kb=${t#* }
  # "SA 99.58%  DA 96.31%  AA 97.93%  ghost points 2790  (...)", "static map 2362845 points (...)"
  local sa da aa ghost pts
  read -r sa da aa ghost < <(sed -n 's/.*SA \([0-9.n/a]*\)%* *DA \([0-9.n/a]*\)%* *AA \([0-9.n/a]*\)%* *ghost points \([0-9]*\).*/\1 \2 \3 \4/p' "$DIR/$name.txt")
  pts=$(sed -n 's/.*static map \([0-9]*\) points.*/\1/p' "$DIR/$name.txt")
  local em=""
  [[ "$label" == ceiling* ]] && em="*"  # ceiling rows in italics
  printf "| ${em}%s${em} | ${em}%s %%${em} | ${em}%s %%${em} | ${em}%s %%${em} | ${em}%s${em} | ${em}%s${em} | %s s%s | %s MB |\n" "$label" "$sa" "$da" "$aa" \
    "$(printf "%'d" "$ghost")" "$(printf "%'d" "$pts")" "$secs" \
    "$([ "$poses" = "$ICP_SM" ] && echo " (+ ${icp_s} s icp-slam)")" \
    "$((kb / 1024))" >> "$MD.partial"
}

GT_LABELS="$DIR/hall/hall.gt.labels"
{
  echo "<!-- made by: scripts/accuracy/mapclean-accuracy.sh $* -->"
  echo "\`dynobj-sim -s share/dynobj/scenarios/hall.yaml -o hall\`; \`icp-slam share/dynobj/config/icp-slam-hall.ini hall/hall.rawlog\`;"
  echo "per row \`dynobj-mapclean -i hall/hall.rawlog -o <dir> --poses <source> --gt hall/hall.gt.labels [--level-poses] [-c <ablation.ini>] [--labels hall/hall.gt.labels]\`"
  echo "(ceiling rows: \`--labels hall/hall.gt.labels\`, the ground truth as the classification; the detector does not run)"
  echo
} > "$MD.partial"
if [ "$WANT_MAIN" = 1 ]; then
  {
    echo "| pose source | SA | DA | AA | ghost points | static map points | time | peak memory |"
    echo "|---|---|---|---|---|---|---|---|"
  } >> "$MD.partial"
  run "rawlog odometry (noisy SE(2))" odometry odometry --level-poses
  run "ground-truth TUM (\`hall.gt.tum\`)" "$DIR/hall/hall.gt.tum" gt --level-poses
  run "stock \`icp-slam\` simplemap (+ odometry between keyframes)" "$ICP_SM" icp --level-poses
  run "detector ego-motion, chained" ego ego --level-poses
  run "ceiling: map built from the ground-truth labels, GT poses" "$DIR/hall/hall.gt.tum" \
      ceiling-gt --level-poses --labels "$GT_LABELS"
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
fi
if [ "$WANT_CEILING" = 1 ]; then
  {
    echo
    echo "Ceiling rows (\`--labels hall/hall.gt.labels\`: the ground truth as the classification):"
    echo
    echo "| pose source (ceiling) | SA | DA | AA | ghost points | static map points | time | peak memory |"
    echo "|---|---|---|---|---|---|---|---|"
  } >> "$MD.partial"
  if [ "$WANT_MAIN" = 1 ]; then  # the row of the first table, again
    sed -n '/^| \*ceiling: /p' "$MD.partial" > "$DIR/ceiling-gt.row"
    cat "$DIR/ceiling-gt.row" >> "$MD.partial"
  else
    run "ceiling: map built from the ground-truth labels, GT poses" "$DIR/hall/hall.gt.tum" \
        ceiling-gt --level-poses --labels "$GT_LABELS"
  fi
  run "ceiling: ground-truth labels, GT poses, not levelled" "$DIR/hall/hall.gt.tum" \
      ceiling-gt-notlevel --labels "$GT_LABELS"
  run "ceiling: ground-truth labels, odometry, levelled" odometry ceiling-odo --level-poses \
      --labels "$GT_LABELS"
  run "ceiling: ground-truth labels, odometry, not levelled" odometry ceiling-odo-notlevel \
      --labels "$GT_LABELS"
fi
if [ "$WANT_O2M" = 1 ]; then
  # Stock observations2map (the INI's [MappingApplication]: one CSimplePointsMap) on the cleaned
  # simplemap of the icp-slam row and on icp-slam's own simplemap; map points on the moving
  # actors counted by tests/tools/map_dynamic_points (ground-truth labels and poses).
  if [ ! -f "$DIR/icp/cleaned.simplemap" ] && [ ! -f "$DIR/icp-row/cleaned.simplemap" ]; then
    log "mapclean: the icp-slam row's cleaned simplemap"
    "$BIN/dynobj-mapclean" -i "$DIR/hall/hall.rawlog" -o "$DIR/icp-row" --poses "$ICP_SM" \
      --level-poses -q -w > "$DIR/icp-row.txt"
  fi
  CLEANED="$DIR/icp/cleaned.simplemap"
  [ -f "$CLEANED" ] || CLEANED="$DIR/icp-row/cleaned.simplemap"
  [ -x "$BUILD_DIR/tests/map_dynamic_points" ] || {
    echo "$BUILD_DIR/tests/map_dynamic_points is missing: build with -DDYNOBJ_BUILD_TESTS=ON" >&2
    exit 1
  }
  log "mapclean: observations2map"
  mkdir -p "$DIR/o2m"
  (cd "$DIR/o2m" && observations2map "$SHARE/config/icp-slam-hall.ini" "$CLEANED" cleaned \
     < /dev/null > cleaned.log && observations2map "$SHARE/config/icp-slam-hall.ini" "$ICP_SM" \
     icp < /dev/null > icp.log)
  kf_clean=$(sed -n 's/.*done: \([0-9]*\) observations.*/\1/p' "$DIR/o2m/cleaned.log")
  kf_icp=$(sed -n 's/.*done: \([0-9]*\) observations.*/\1/p' "$DIR/o2m/icp.log")
  counts=$("$BUILD_DIR/tests/map_dynamic_points" "$DIR/hall/hall.rawlog" "$GT_LABELS" \
           "$DIR/hall/hall.gt.tum" "$DIR/o2m/icp_mrpt__maps__CSimplePointsMap_00.txt" \
           "$DIR/o2m/cleaned_mrpt__maps__CSimplePointsMap_00.txt" 1000 | tail -n1)
  # "map points on moving actors: raw map 10354 (of N), filtered map 3294 (of M), ratio ..."
  on_icp=$(sed -E 's/.*raw map ([0-9]+) \(of ([0-9]+)\).*/\1/' <<< "$counts")
  of_icp=$(sed -E 's/.*raw map ([0-9]+) \(of ([0-9]+)\).*/\2/' <<< "$counts")
  on_cl=$(sed -E 's/.*filtered map ([0-9]+) \(of ([0-9]+)\).*/\1/' <<< "$counts")
  of_cl=$(sed -E 's/.*filtered map ([0-9]+) \(of ([0-9]+)\).*/\2/' <<< "$counts")
  {
    echo
    echo "Stock \`observations2map share/dynobj/config/icp-slam-hall.ini <simplemap> <prefix>\` (one"
    echo "\`CSimplePointsMap\`), points on the moving actors (\`tests/tools/map_dynamic_points\`):"
    echo "the cleaned simplemap of the icp-slam row (${kf_clean} keyframes): $(printf "%'d" "$on_cl") of $(printf "%'d" "$of_cl") map points;"
    echo "icp-slam's own simplemap (${kf_icp} keyframes): $(printf "%'d" "$on_icp") of $(printf "%'d" "$of_icp") map points."
  } >> "$MD.partial"
fi
mv "$MD.partial" "$MD"
log "mapclean: ${MD}"
