#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Regenerates the accuracy tables (docs/accuracy.md). Each option writes one Markdown file in
# out/accuracy/ (override: DYNOBJ_ACCURACY_OUT) headed by the commands that made it:
#   scripts/accuracy/accuracy.sh [scenario ...]  Table I: simulates each shipped scenario (300 sweeps, its own
#                                                seed), runs this detector (own intensity ego-motion,
#                                                ground-truth ego-motion, drifting odometry) and MRPT's
#                                                CPointCloudFilterByDistance: accuracy.md + one report each
#   scripts/accuracy/accuracy.sh --ablations     hall, one key changed at a time
#   scripts/accuracy/accuracy.sh --seeds         the RANSAC seed's effect: [ego_motion] seed 1-3
#   scripts/accuracy/accuracy.sh --os0-128       hall at 128 x 2048, defaults vs the OS0-128 preset INI
#   scripts/accuracy/accuracy.sh --quick-matrix  23 cells of 100 sweeps: seeds the defaults were never tuned on
#   scripts/accuracy/accuracy.sh --held-out      the same on seed 201 (+ six other sensor cells): checked only
#                                                after a change was chosen on the quick matrix
#   scripts/accuracy/accuracy.sh --ego-error     the ego-motion error against the simulator's true
#                                                poses, with and without [ego_refinement]
#   scripts/accuracy/accuracy.sh --realdata      real HDL-64 streets without labels: label-free consistency and
#                                                ICP agreement on ../shared/realdata/kitti-hdl64-city-22 and,
#                                                when DYNOBJ_DATA2 names it, the 154-sweep data_2 folder
#   scripts/accuracy/accuracy.sh --real          real recordings, human labels: data_2 (DYNOBJ_DATA2, the
#                                                154-sweep folder) against KITTI's boxes
#                                                (../shared/realdata/kitti-tracking-0000), online and offline,
#                                                per class; then --realdata. Skips clearly without the data.
#   scripts/accuracy/accuracy.sh --real-ablations the same data_2 score with each switch of the shipped INI
#                                                flipped (REAL_ABLATIONS below), online and offline F1
#   scripts/accuracy/accuracy.sh --mapclean      the map-cleaning tables (scripts/accuracy/mapclean-accuracy.sh)
#   scripts/accuracy/accuracy.sh --all           every section above
#   scripts/accuracy/accuracy.sh --matrix [...]  the full evaluation matrix (scripts/accuracy/accuracy-matrix.sh --help)
set -euo pipefail
HERE="$(dirname "${BASH_SOURCE[0]}")"
if [ "${1:-}" = "--matrix" ]; then
  shift
  exec "$HERE/accuracy-matrix.sh" "$@"
fi
source "$HERE/../common.sh"

ensure_packages jq
use_apps  # BUILD_DIR, BIN, OUT (common.sh; DYNOBJ_SKIP_BUILD=1: use the build as it is)
SCEN="$DYNOBJ_ROOT/share/dynobj/scenarios"
# DYNOBJ_ACCURACY_CONFIG: another detector INI (e.g. one holding "[ego_refinement] enabled = false")
CONFIG="${DYNOBJ_ACCURACY_CONFIG:-$DYNOBJ_ROOT/share/dynobj/config/dynobj.ini}"
mkdir -p "$OUT"

# simulate <scenario> <dir> [dynobj-sim options]: a sequence in <dir> (once per call).
simulate() {
  local s="$1" dir="$2"
  shift 2
  rm -rf "$dir"
  "$BIN/dynobj-sim" -s "$SCEN/$s.yaml" -o "$dir" -q "$@" > /dev/null
}
# evaluate <sequence dir> <out dir> [dynobj-eval options]: this detector, own ego-motion; prints
# "precision recall IoU F1" of the run.
evaluate() {
  local seq="$1" dir="$2"
  shift 2
  "$BIN/dynobj-eval" --run "$seq" -o "$dir" --modes intensity --overlays 0 -q -w "$@" > /dev/null
  jq -r '.runs[0] | [.precision, .recall, .iou, .f1] | map(if . == null then "n/a"
         else (. * 1000 | round / 1000 | tostring) end) | join(" ")' "$dir/summary.json"
}
# static_flagged <eval out dir>: the run's share of static points flagged, in percent (3 decimals).
static_flagged() {
  jq -r '.runs[0].static_flagged | if . == null then "n/a" else (. * 100000 | round / 1000 | tostring) end' \
    "$1/summary.json"
}
# fmt3 "0.9" -> "0.900"
fmt3() { local v; for v in "$@"; do [ "$v" = n/a ] && printf 'n/a ' || printf '%.3f ' "$v"; done; }

table1() {
  local scenarios=("$@") summary="$OUT/accuracy.md"
  [ ${#scenarios[@]} -gt 0 ] || scenarios=(hall corridor crossing street static)
  {
    echo "<!-- made by: scripts/accuracy/accuracy.sh ${scenarios[*]} -->"
    echo "Per scenario: \`dynobj-eval --run share/dynobj/scenarios/<s>.yaml -o $OUT/<s> -q\`"
    echo
  } > "$summary.partial"
  for s in "${scenarios[@]}"; do
    log "Table I: scenario ${s}"
    "$BIN/dynobj-eval" --run "$SCEN/${s}.yaml" -o "$OUT/${s}" -q -w
    { echo "#### ${s}"; echo; cat "$OUT/${s}/summary.md"; echo; } >> "$summary.partial"
  done
  mv "$summary.partial" "$summary"
  log "Table I: ${summary} (and ${OUT}/<scenario>/report.html)"
}

# One row per variant: "label|INI text" (printf escapes), evaluated on hall (300 sweeps).
ABLATIONS=(
  "defaults|"
  "online, no hindsight (\`[hindsight] lag = 0\`: the paper; what the per-observation filters give)|[hindsight]\nlag = 0\n"
  "hindsight trusts a track at its first dynamic sweep (\`min_dynamic = 0\`)|[hindsight]\nmin_dynamic = 0\n"
  "hindsight without the merge test (\`max_growth = 100\`)|[hindsight]\nmax_growth = 100\n"
  "hindsight on the average speed to the confirming sweep (\`speed_window = 0\`)|[hindsight]\nspeed_window = 0\n"
  "hindsight flags the last sweep before a start too (\`start_check = false\`)|[hindsight]\nstart_check = false\n"
  "region growing may take objects at rest (\`[region_growing] keep_out_settled = false\`)|[region_growing]\nkeep_out_settled = false\n"
  "the refinement's own translation in every direction (\`[ego_refinement] degenerate_share = 0\`)|[ego_refinement]\ndegenerate_share = 0\n"
  "paper's one-sided foreground \`B(f − h, θ)\` (\`absolute = false\`)|[foreground]\nabsolute = false\n"
  "no free-space check (\`[free_space] enabled = false\`: the paper's movement decision)|[free_space]\nenabled = false\n"
  "free space from the point's own row only (\`side_rows = 0\`)|[free_space]\nside_rows = 0\n"
  "no hysteresis|[tracking]\nhysteresis = false\n"
  "no Kalman prediction (the paper's Eq. 8 only, no coasting)|[tracking]\nprediction = false\n"
  "Eq. (23) as the paper: every cluster, no rigid-mover, viewpoint or upright exemption (\`rigid_tolerance = 0\`, \`long_object_ego_ratio = 0\`, \`upright_length = 0\`)|[movement]\nrigid_tolerance = 0\nlong_object_ego_ratio = 0\nupright_length = 0\n"
  "Eq. (23) for upright clusters too (\`upright_length = 0\`)|[movement]\nupright_length = 0\n"
  "no cluster area bound (\`max_area = 0\`)|[clustering]\nmax_area = 0\n"
  "Eq. (23) only where the viewpoint moved (\`long_object_ego_ratio = 1.5\`; for a stationary sensor)|[movement]\nlong_object_ego_ratio = 1.5\n"
  "ORB 3 levels, 1500 features|[ego_motion]\nlevels = 3\nfeatures = 1500\n"
  "every feature in the search (no 17 cm voxel reduction)|[clustering]\nvoxel = 0\n"
  "faster ego-motion: 400 ORB features, FAST threshold 20|[ego_motion]\nfeatures = 400\nfast_threshold = 20\n"
  "RANSAC: 200 fixed samples, no refits (the previous default)|[ego_motion]\nconfidence = 1\nrefinements = 0\n"
  "no split of a cluster holding a mover and an object at rest (\`[association] split_radius = 0\`)|[association]\nsplit_radius = 0\n"
  "a sliding rigid cluster needs no more free space than any other (\`[free_space] slide_free_ratio = 0\`)|[free_space]\nslide_free_ratio = 0\n"
  "hindsight's stop check on the quarter rule only (\`[hindsight] rest_speed = 0\`)|[hindsight]\nrest_speed = 0\n"
  "region growing may take what the lookback frame saw (\`[region_growing] past_surface_check = false\`)|[region_growing]\npast_surface_check = false\n"
  "3-D centroid steps, as the paper (\`[movement] planar = false\`)|[movement]\nplanar = false\n"
  "3-D centroid steps and ε_d = 0.25 m (\`planar = false\`, \`min_displacement = 0.25\`)|[movement]\nplanar = false\nmin_displacement = 0.25\n"
  "a track starts from 4 features (\`[clustering] min_points = 4\`)|[clustering]\nmin_points = 4\n"
  "the ground beside a point counts against it however high the point (\`[free_space] clearance = 100\`)|[free_space]\nclearance = 100\n"
  "no older frame for a slow candidate (\`[free_space] max_lookback = 0\`)|[free_space]\nmax_lookback = 0\n"
  "no set-back top for wide objects (\`[region_growing] slope_factor = 0\`)|[region_growing]\nslope_factor = 0\n"
  "earlier sweeps grown over what the newest held frame still sees (\`[hindsight] later_surface_check = false\`)|[hindsight]\nlater_surface_check = false\n"
  "a rigid mover's own past body counted as occupied (\`[free_space] exclude_own_past = false\`)|[free_space]\nexclude_own_past = false\n"
  "a thin surface seen through in the past frame alone is free space (\`[free_space] thin_frames = 0\`)|[free_space]\nthin_frames = 0\n"
  "hindsight counts the whole way from an earlier sweep, sideways too (\`[hindsight] way_along = false\`)|[hindsight]\nway_along = false\n"
  "hindsight asks the newest frame only of grown points, once the object went farther than its extent (\`[hindsight] later_surface_points = false\`)|[hindsight]\nlater_surface_points = false\n"
  "a mover's part under split_min_share is never split off, and a mover's cluster that is mostly one at rest stays the mover's (\`[association] split_match_radius = 0\`, \`split_rest_majority = false\`)|[association]\nsplit_match_radius = 0\nsplit_rest_majority = false\n"
  "a mover's region takes the body of one at rest beside it, all but its features (\`[region_growing] nearer_rest_radius = 0\`)|[region_growing]\nnearer_rest_radius = 0\n"
  "a long cluster is a rigid mover only when its ends moved with its centroid (\`[movement] rigid_ends_length = 0\`)|[movement]\nrigid_ends_length = 0\n"
  "a mover that clearly stopped is at rest only once settled, 10 sweeps later (\`[tracking] stop_at_rest = false\`)|[tracking]\nstop_at_rest = false\n"
  "hindsight fills no sweep where a dynamic track was not seen between two sightings (\`[hindsight] fill_gaps = false\`)|[hindsight]\nfill_gaps = false\n"
  "hindsight fills no sweep before a trusted track was first seen (\`[hindsight] fill_before = false\`)|[hindsight]\nfill_before = false\n"
  "a mover's cluster that is not split keeps the fair part of one at rest in it, flagged (\`[association] split_hold_back = false\`)|[association]\nsplit_hold_back = false\n"
)
ablations() {
  local dir="$OUT/ablations" md="$OUT/ablations.md" i=0 label ini
  mkdir -p "$dir"
  log "ablations: simulating hall (300 sweeps)"
  simulate hall "$dir/sim"
  {
    echo "<!-- made by: scripts/accuracy/accuracy.sh --ablations -->"
    echo "Per variant: \`dynobj-sim -s share/dynobj/scenarios/hall.yaml -o sim\`, then"
    echo "\`dynobj-eval --run sim -o <variant> --modes intensity -c <dynobj.ini + the changed keys>\`"
    echo
    echo "| variant | precision | recall | IoU | F1 |"
    echo "|---|---|---|---|---|"
  } > "$md.partial"
  for v in "${ABLATIONS[@]}"; do
    label="${v%%|*}"
    ini="${v#*|}"
    i=$((i + 1))
    { cat "$CONFIG"; printf '\n%b' "$ini"; } > "$dir/variant-$i.ini"
    log "ablations: ${label}"
    read -r p r iou f1 < <(evaluate "$dir/sim" "$dir/variant-$i" -c "$dir/variant-$i.ini")
    echo "| ${label} | $(fmt3 "$p" "$r" "$iou" "$f1" | xargs | sed 's/ / | /g') |" >> "$md.partial"
  done
  mv "$md.partial" "$md"
  log "ablations: ${md}"
}

seeds() {
  local dir="$OUT/seeds" md="$OUT/seeds.md" s seed
  mkdir -p "$dir"
  {
    echo "<!-- made by: scripts/accuracy/accuracy.sh --seeds -->"
    echo "Per scenario: \`dynobj-sim -s share/dynobj/scenarios/<s>.yaml -o sim\`, then per RANSAC seed"
    echo "\`dynobj-eval --run sim --modes intensity -c <dynobj.ini with [ego_motion] seed = S>\`"
    echo
    echo "| scenario | F1 / IoU, seed 1 | seed 2 | seed 3 |"
    echo "|---|---|---|---|"
  } > "$md.partial"
  for s in hall street crossing; do
    log "seeds: simulating ${s} (300 sweeps)"
    simulate "$s" "$dir/$s"
    local row="| ${s} |"
    for seed in 1 2 3; do
      { cat "$CONFIG"; printf '\n[ego_motion]\nseed = %s\n' "$seed"; } > "$dir/seed-$seed.ini"
      read -r p r iou f1 < <(evaluate "$dir/$s" "$dir/$s-seed$seed" -c "$dir/seed-$seed.ini")
      row="$row $(fmt3 "$f1" | xargs) / $(fmt3 "$iou" | xargs) |"
    done
    echo "$row" >> "$md.partial"
  done
  mv "$md.partial" "$md"
  log "seeds: ${md}"
}

os0_128() {
  local dir="$OUT/os0-128" md="$OUT/os0-128.md"
  mkdir -p "$dir"
  log "os0-128: simulating hall at 128 x 2048 and 64 x 1024 (100 sweeps)"
  simulate hall "$dir/hall-128" --frames 100 --set sensor=sensors/os0-128-2048.ini
  simulate hall "$dir/hall-64" --frames 100
  {
    echo "<!-- made by: scripts/accuracy/accuracy.sh --os0-128 -->"
    echo "\`dynobj-sim -s share/dynobj/scenarios/hall.yaml --frames 100 [--set sensor=sensors/os0-128-2048.ini] -o sim\`,"
    echo "then \`dynobj-eval --run sim --modes intensity -c <config>\`"
    echo
    echo "| sensor | configuration | precision | recall | IoU | F1 |"
    echo "|---|---|---|---|---|---|"
    read -r p r iou f1 < <(evaluate "$dir/hall-128" "$dir/defaults" -c "$CONFIG")
    echo "| OS0-128, 128 × 2048 | defaults (\`dynobj.ini\`, tuned for 64 × 1024) | $(fmt3 "$p" "$r" "$iou" "$f1" | xargs | sed 's/ / | /g') |"
    read -r p r iou f1 < <(evaluate "$dir/hall-128" "$dir/preset" -c "$DYNOBJ_ROOT/share/dynobj/config/dynobj-os0-128-2048.ini")
    echo "| OS0-128, 128 × 2048 | \`dynobj-os0-128-2048.ini\` | $(fmt3 "$p" "$r" "$iou" "$f1" | xargs | sed 's/ / | /g') |"
    read -r p r iou f1 < <(evaluate "$dir/hall-64" "$dir/os0-64" -c "$CONFIG")
    echo "| OS0-64, 64 × 1024 (for comparison) | defaults | $(fmt3 "$p" "$r" "$iou" "$f1" | xargs | sed 's/ / | /g') |"
  } > "$md.partial"
  mv "$md.partial" "$md"
  log "os0-128: ${md}"
}

# The quick matrix: 100 sweeps per cell, seeds the defaults were never tuned on, a few presets.
QUICK=("hall 101" "hall 102" "corridor 101" "corridor 102" "crossing 101" "crossing 102"
       "street 101" "street 102" "static 101" "hall 101 vlp-16" "hall 101 os0-128"
       "crossing 101 vlp-16" "crossing 101 hdl-32" "street 101 hdl-64" "street 101 vlp-16"
       "parking 101" "parking 102" "warehouse 101" "warehouse 102" "plaza 101" "plaza 102"
       "crowd 101" "corner 101")
# HELD_OUT: seed 201 of every scenario and six other sensor cells, looked at only after a change
# was chosen on QUICK (scripts/accuracy/accuracy.sh --held-out).
HELD_OUT=("hall 201" "corridor 201" "crossing 201" "street 201" "parking 201" "warehouse 201"
          "plaza 201" "crowd 201" "corner 201" "static 201" "street 201 vlp-16" "plaza 201 hdl-32"
          "crowd 201 os1-32" "parking 201 vlp-16" "hall 201 os0-64-512" "corner 201 os1-64-2048")
# quick_matrix <name> <cell ...>: one table row per cell ("scenario seed [sensor preset]"), 100
# sweeps each, then the mean and the worst F1 (cells with something moving) and the largest
# static share.
quick_matrix() {
  local name="$1" dir="$OUT/$1" md="$OUT/$1.md" cell s seed sensor sets p r iou f1 st
  shift
  mkdir -p "$dir"
  {
    echo "<!-- made by: scripts/accuracy/accuracy.sh --$name -->"
    echo "Per cell: \`dynobj-sim -s share/dynobj/scenarios/<s>.yaml --seed <S> -n 100 [--set sensor=sensors/<preset>.ini] -o sim\`,"
    echo "then \`dynobj-eval --run sim --modes intensity -c $(basename "$CONFIG")\`"
    echo
    echo "| cell | precision | recall | IoU | F1 | static flagged |"
    echo "|---|---|---|---|---|---|"
  } > "$md.partial"
  : > "$dir/f1.txt"
  for cell in "$@"; do
    read -r s seed sensor <<< "$cell"
    sets=()
    [ -n "${sensor:-}" ] && sets=(--set "sensor=sensors/$sensor.ini")
    log "$name: ${cell}"
    simulate "$s" "$dir/sim" --frames 100 --seed "$seed" "${sets[@]}"
    read -r p r iou f1 < <(evaluate "$dir/sim" "$dir/eval" -c "$CONFIG")
    st=$(static_flagged "$dir/eval")
    echo "| ${s}, seed ${seed}${sensor:+, ${sensor}} | $(fmt3 "$p" "$r" "$iou" "$f1" | xargs | sed 's/ / | /g') | ${st} % |" >> "$md.partial"
    echo "${s}-${seed}${sensor:+@${sensor}} $f1 $st $r" >> "$dir/f1.txt"
  done
  awk '$2 != "n/a" && $4 != "n/a" { n++; m += $2; if (w == "" || $2 < w) { w = $2; wc = $1 } }
       $3 != "n/a" && $3 + 0 > s { s = $3 + 0; sc = $1 }
       END { printf "| **mean / worst F1 (%d cells), largest static share** | | | | **%.3f / %.3f** (%s) | **%.3f %%** (%s) |\n", n, m / n, w, wc, s, sc }' \
    "$dir/f1.txt" >> "$md.partial"
  mv "$md.partial" "$md"
  log "$name: ${md}"
}

# Ego-motion error against the true poses (dynobj-detect --ego-truth: RMS per frame pair), the
# detector with and without the geometric refinement, 100 sweeps per sequence.
# A cell: "scenario seed [sensor preset]" (a preset gets the intensity model of its make, as in the
# matrix).
EGO_CELLS=("parking 102" "warehouse 101" "warehouse 102" "parking 2 os0-64" "parking 2 os1-32"
           "parking 201 vlp-16" "plaza 101" "street 101 vlp-16")
ego_error() {
  local dir="$OUT/ego-error" md="$OUT/ego-error.md" cell s seed without with
  mkdir -p "$dir"
  { cat "$CONFIG"; printf '\n[ego_refinement]\nenabled = false\n'; } > "$dir/no-refinement.ini"
  {
    echo "<!-- made by: scripts/accuracy/accuracy.sh --ego-error -->"
    echo "Per sequence: \`dynobj-sim -s share/dynobj/scenarios/<s>.yaml --seed <S> -n 100 -o sim\`, then"
    echo "\`dynobj-detect -i sim/<name>.rawlog --ego-truth sim/<name>.gt.tum -c <config>\` (translation / rotation RMS per frame pair, max translation)"
    echo
    echo "| sequence (100 sweeps) | without (\`[ego_refinement] enabled = false\`) | with (default) |"
    echo "|---|---|---|"
  } > "$md.partial"
  # "ego-motion error over 99 pairs: translation RMS 0.003 m (max 0.005), rotation RMS 0.048 deg (max 0.096)"
  ego_rms() {
    "$BIN/dynobj-detect" -i "$1" --ego-truth "${1%.rawlog}.gt.tum" -c "$2" |
      sed -n -E 's/.*translation RMS ([0-9.]+) m \(max ([0-9.]+)\), rotation RMS ([0-9.]+) deg.*/\1 m \/ \3° (max \2 m)/p'
  }
  local sensor sets
  for cell in "${EGO_CELLS[@]}"; do
    read -r s seed sensor <<< "$cell"
    sets=()
    [ -z "$sensor" ] ||
      sets=(--set "sensor=sensors/$sensor.ini" --set "intensity.model=$(intensity_model_of "$sensor")")
    log "ego error: ${s} seed ${seed}${sensor:+ on $sensor}"
    simulate "$s" "$dir/sim" --frames 100 --seed "$seed" "${sets[@]}"
    local rawlog
    rawlog=$(ls "$dir"/sim/*.rawlog)
    without=$(ego_rms "$rawlog" "$dir/no-refinement.ini")
    with=$(ego_rms "$rawlog" "$CONFIG")
    echo "| ${s} seed ${seed}${sensor:+ (${sensor})} | ${without} | ${with} |" >> "$md.partial"
  done
  mv "$md.partial" "$md"
  log "ego error: ${md}"
}

# Real recordings without labels (../shared/realdata/README.md): each folder of PCD sweeps or
# Velodyne pcap is imported (dynobj-import), then one dynobj-detect run per recording with the label-free checks:
# --consistency (eval::MapConsistency, top view written next to the rawlog; KITTI-derived, CC
# BY-NC-SA: never commit it; the Velodyne one is Apache-2.0, docs/images/ holds a copy) and --check-ego (agreement with MRPT's 3D ICP).
# A recording whose folder is absent is skipped with a message.
REALDATA_DIR="${DYNOBJ_REALDATA:-$DYNOBJ_ROOT/../shared/realdata}"  # DYNOBJ_REALDATA: elsewhere
realdata() {
  local dir="$OUT/realdata" md="$OUT/realdata.md" name src txt
  mkdir -p "$dir"
  {
    echo "<!-- made by: ${DYNOBJ_ACCURACY_CONFIG:+DYNOBJ_ACCURACY_CONFIG=$(basename "$CONFIG") }scripts/accuracy/accuracy.sh --realdata -->"
    echo "Per recording: \`dynobj-import -i <folder or pcap> -o <name>.rawlog\` (the sample is a rawlog already), then"
    echo "\`dynobj-detect -i <name>.rawlog -c $(basename "$CONFIG") --consistency <name>.png --check-ego\`"
    echo
    echo "| recording | sweeps | flagged | suspicious (of flagged) | transient (of flagged) | unflagged but transient | ICP agreement (pairs) | median difference |"
    echo "|---|---|---|---|---|---|---|---|"
  } > "$md.partial"
  # The committed simulated sample first: the checks' floor on data whose precision is known.
  for rec in "hall-small (simulated sample)|$DYNOBJ_ROOT/rawlogs/hall-small/hall-small.rawlog" \
             "city-22|$REALDATA_DIR/kitti-hdl64-city-22" "data_2|${DYNOBJ_DATA2:-}" \
             "monterey (real HDL-32E pcap, highway)|$REALDATA_DIR/velodyne/monterey-hdl32-first-100-packets.pcap"; do
    name="${rec%%|*}"
    src="${rec#*|}"
    if [ -z "$src" ]; then
      log "realdata: ${name} skipped: set DYNOBJ_DATA2 to the 154-sweep data_2 folder (../shared/realdata/README.md)"
      continue
    fi
    if [ ! -e "$src" ]; then
      log "realdata: ${name} skipped: ${src} does not exist"
      continue
    fi
    log "realdata: ${name} (${src})"
    local base="$dir/${name%% *}" rawlog="$src"
    rm -f "$base.png"
    if [ -d "$src" ] || [[ "$src" == *.pcap ]]; then
      rm -f "$base.rawlog"
      "$BIN/dynobj-import" -i "$src" -o "$base.rawlog" -q > /dev/null
      rawlog="$base.rawlog"
    fi
    txt="$base.txt"
    "$BIN/dynobj-detect" -i "$rawlog" -c "$CONFIG" --consistency "$base.png" --check-ego > "$txt"
    # "consistency: 22 sweeps, 2541212 points, flagged 3.87 %: on static structure (suspicious)
    #  6.4 %, transient 65.6 %, undecided 28.0 %; unflagged but transient ~58000 points (...)"
    local c sweeps flagged susp trans missed
    c=$(grep -m1 '^  consistency: ' "$txt")
    sweeps=$(sed -E 's/.*consistency: ([0-9]+) sweeps.*/\1/' <<< "$c")
    flagged=$(sed -E 's/.*flagged ([0-9.]+) %:.*/\1/' <<< "$c")
    susp=$(sed -E 's/.*\(suspicious\) ([0-9.]+) %.*/\1/' <<< "$c")
    trans=$(sed -E 's/.*transient ([0-9.]+) %, undecided.*/\1/' <<< "$c")
    missed=$(sed -E 's/.*unflagged but transient ~([0-9]+) points.*/\1/' <<< "$c")
    # "ICP check: ... both: 21, agree within 0.10 m / 1.0 deg on 21 (100.0 %); difference
    #  translation median 0.019 m p95 ..., rotation median 0.124 deg p95 ..."
    local i both agree dt dr
    i=$(grep -m1 '^  ICP check: ' "$txt")
    both=$(sed -E 's/.*both: ([0-9]+),.*/\1/' <<< "$i")
    agree=$(sed -E 's/.* on ([0-9]+) \([0-9.]+ %\); difference.*/\1/' <<< "$i")
    dt=$(sed -E 's/.*translation median ([0-9.]+) m.*/\1/' <<< "$i")
    dr=$(sed -E 's/.*rotation median ([0-9.]+) deg.*/\1/' <<< "$i")
    printf '| %s | %s | %s %% | %s %% | %s %% | ~%s | %s of %s | %s m / %s° |\n' "$name" "$sweeps" \
      "$flagged" "$susp" "$trans" "$(printf "%'d" "$missed")" "$agree" "$both" "$dt" "$dr" \
      >> "$md.partial"
  done
  mv "$md.partial" "$md"
  log "realdata: ${md} (top views: ${dir}/<recording>.png, KITTI-derived: do not commit them)"
}

# Real recordings with human labels (../shared/realdata/kitti-tracking-0000: KITTI's 3-D boxes of
# data_2). A development set: the detector never reads it; dynobj-eval scores its output.
KITTI_LABELS="$REALDATA_DIR/kitti-tracking-0000"
# real_ready: 0 when data_2 and its labels are there (else says what is missing).
real_ready() {
  if [ -z "${DYNOBJ_DATA2:-}" ] || [ ! -d "${DYNOBJ_DATA2:-}" ]; then
    log "real: skipped: set DYNOBJ_DATA2 to the 154-sweep data_2 folder (fetch github:udacity/SFND_Lidar_Obstacle_Detection, src/sensors/data/pcd/data_2; ../shared/realdata/README.md)"
    return 1
  fi
  if [ ! -f "$KITTI_LABELS/label_02_0000.txt" ]; then
    log "real: skipped: no KITTI labels in $KITTI_LABELS"
    return 1
  fi
}
# real_eval <out dir> [dynobj-eval options]: data_2 against the KITTI boxes, both modes.
real_eval() {
  local dir="$1"
  shift
  "$BIN/dynobj-eval" --run "$DYNOBJ_DATA2" --truth "$KITTI_LABELS/label_02_0000.txt" \
    --calib "$KITTI_LABELS/calib.txt" -o "$dir" -q "$@" > /dev/null
}
# real_f1 <eval out dir> <mode>: F1 of that mode, 3 decimals.
real_f1() { jq -r --arg m "$2" '.runs[] | select(.mode == $m) | .f1 * 1000 | round / 1000' "$1/summary.json"; }

real() {
  local dir="$OUT/real" md="$OUT/real.md"
  real_ready || return 0
  mkdir -p "$dir"
  log "real: data_2 against KITTI's boxes (online and offline)"
  real_eval "$dir/data_2" -c "$CONFIG"
  {
    echo "<!-- made by: scripts/accuracy/accuracy.sh --real -->"
    echo "\`dynobj-eval --run data_2 --truth kitti-tracking-0000/label_02_0000.txt --calib kitti-tracking-0000/calib.txt -o <dir>\`"
    echo "(points in the front camera's view, 0.2 m band around moving boxes left out; summed over all sweeps)"
    echo
    echo "| mode | precision | recall | IoU | F1 | object recall | car | van | cyclist | pedestrian | static flagged |"
    echo "|---|---|---|---|---|---|---|---|---|---|---|"
    jq -r '.runs[] | . as $r | .object_recall as $o |
      def cls($c): ($o.by_class[$c] // null) | if . == null then "–" else "\(.detected)/\(.present)" end;
      def f3: . * 1000 | round / 1000 | tostring;
      "| \($r.mode) | \($r.precision | f3) | \($r.recall | f3) | \($r.iou | f3) | \($r.f1 | f3) | \($o.recall | f3) (\($o.detected)/\($o.present)) | \(cls("Car")) | \(cls("Van")) | \(cls("Cyclist")) | \(cls("Pedestrian")) | \($r.static_flagged * 100000 | round / 1000) % |"' \
      "$dir/data_2/summary.json"
  } > "$md.partial"
  mv "$md.partial" "$md"
  log "real: ${md} (per object and sweep: ${dir}/data_2/objects.csv; the tracks' motion: truth-tracks.csv)"
  realdata
}

# Each switch of the shipped INI flipped, on data_2's human labels: "label|INI text".
REAL_ABLATIONS=(
  "defaults|"
  "[foreground] absolute = false|[foreground]\nabsolute = false\n"
  "[foreground] exclude_ground = false|[foreground]\nexclude_ground = false\n"
  "[ego_refinement] enabled = false|[ego_refinement]\nenabled = false\n"
  "[association] split_rest_majority = false|[association]\nsplit_rest_majority = false\n"
  "[association] split_hold_back = false|[association]\nsplit_hold_back = false\n"
  "[movement] planar = false|[movement]\nplanar = false\n"
  "[free_space] enabled = false|[free_space]\nenabled = false\n"
  "[free_space] require_proof = false|[free_space]\nrequire_proof = false\n"
  "[free_space] exclude_own_past = false|[free_space]\nexclude_own_past = false\n"
  "[tracking] prediction = false|[tracking]\nprediction = false\n"
  "[tracking] hysteresis = false|[tracking]\nhysteresis = false\n"
  "[tracking] stop_at_rest = false|[tracking]\nstop_at_rest = false\n"
  "[region_growing] keep_out_settled = false|[region_growing]\nkeep_out_settled = false\n"
  "[region_growing] past_surface_check = false|[region_growing]\npast_surface_check = false\n"
  "[hindsight] start_check = false|[hindsight]\nstart_check = false\n"
  "[hindsight] stop_check = false|[hindsight]\nstop_check = false\n"
  "[hindsight] later_surface_check = false|[hindsight]\nlater_surface_check = false\n"
  "[hindsight] later_surface_points = false|[hindsight]\nlater_surface_points = false\n"
  "[hindsight] way_along = false|[hindsight]\nway_along = false\n"
  "[hindsight] fill_gaps = false|[hindsight]\nfill_gaps = false\n"
  "[hindsight] fill_before = false|[hindsight]\nfill_before = false\n"
)
real_ablations() {
  local dir="$OUT/real-ablations" md="$OUT/real-ablations.md" v label ini base_on base_off on off
  real_ready || return 0
  mkdir -p "$dir"
  {
    echo "<!-- made by: scripts/accuracy/accuracy.sh --real-ablations -->"
    echo "Per variant: \`dynobj-eval --run data_2 --truth <KITTI boxes> --calib <calib> -c <dynobj.ini + the changed key>\`"
    echo
    echo "| variant | online F1 | change | offline F1 | change |"
    echo "|---|---|---|---|---|"
  } > "$md.partial"
  local i=0
  for v in "${REAL_ABLATIONS[@]}"; do
    label="${v%%|*}"
    ini="$dir/variant-$i.ini"
    { cat "$CONFIG"; printf '\n%b' "${v#*|}"; } > "$ini"  # the later key wins
    log "real ablations: ${label}"
    real_eval "$dir/variant-$i" -c "$ini"
    on=$(real_f1 "$dir/variant-$i" online)
    off=$(real_f1 "$dir/variant-$i" offline)
    if [ "$i" = 0 ]; then base_on=$on; base_off=$off; fi
    awk -v l="$label" -v a="$on" -v b="$base_on" -v c="$off" -v d="$base_off" \
      'BEGIN { printf "| %s | %.3f | %+.3f | %.3f | %+.3f |\n", l, a, a - b, c, c - d }' >> "$md.partial"
    i=$((i + 1))
  done
  mv "$md.partial" "$md"
  log "real ablations: ${md}"
}

case "${1:-}" in
  --ablations) ablations ;;
  --seeds) seeds ;;
  --os0-128) os0_128 ;;
  --quick-matrix) quick_matrix quick-matrix "${QUICK[@]}" ;;
  --held-out) quick_matrix held-out "${HELD_OUT[@]}" ;;
  --ego-error) ego_error ;;
  --realdata) realdata ;;
  --real) real ;;
  --real-ablations) real_ablations ;;
  --mapclean) exec "$HERE/mapclean-accuracy.sh" ;;
  --all) table1; ablations; seeds; os0_128; quick_matrix quick-matrix "${QUICK[@]}"; quick_matrix held-out "${HELD_OUT[@]}"; ego_error; realdata; "$HERE/mapclean-accuracy.sh" ;;
  -*) echo "unknown option $1 (see the head of $0)" >&2; exit 2 ;;
  *) table1 "$@" ;;
esac
