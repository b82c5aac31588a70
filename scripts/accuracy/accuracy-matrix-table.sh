#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Turns the cells of scripts/accuracy/accuracy-matrix.sh (cells.tsv, one line per scenario x sensor x
# seed x distortion) into Markdown: mean and WORST cell overall, per scenario, per sensor, per
# distortion setting, and a scenario x sensor grid of F1.
#   scripts/accuracy/accuracy-matrix-table.sh cells.tsv ["command"] [wall seconds] [cells asked] [config]
#                                    [shipped: 1 = config is the shipped dynobj.ini (default), 0 = not]
set -euo pipefail
TSV="$1" CMD="${2:-}" WALL="${3:-}" ASKED="${4:-}" CONFIG="${5:-dynobj.ini}" SHIPPED="${6:-1}"
awk -F'\t' -v cmd="$CMD" -v wall="$WALL" -v asked="$ASKED" -v config="$CONFIG" -v shipped="$SHIPPED" '
function fmt(v) { return v == "" ? "—" : sprintf("%.3f", v) }
function pct(v) { return v == "" ? "—" : sprintf("%.3f %%", 100 * v) }
# add(group, metric, value, cell): running sum, count, min (and max) with the cell that gave it.
function add(g, m, v, cell,   k) {
  if (v == "NA" || v == "") return
  k = g SUBSEP m
  sum[k] += v; cnt[k]++
  if (!(k in lo) || v < lo[k]) { lo[k] = v; locell[k] = cell }
  if (!(k in hi) || v > hi[k]) { hi[k] = v; hicell[k] = cell }
}
function mean(g, m,   k) { k = g SUBSEP m; return cnt[k] ? sum[k] / cnt[k] : "" }
function min_(g, m,   k) { k = g SUBSEP m; return cnt[k] ? lo[k] : "" }
function max_(g, m,   k) { k = g SUBSEP m; return cnt[k] ? hi[k] : "" }
function row(label, g, what,   k) {
  k = g SUBSEP "f1"
  printf "| %s | %d | %s | **%s** | %s | %s | %s | %s | %s | %s / %s | %s / **%s** | %s |\n", label, n[g],
    fmt(mean(g, "f1")), fmt(min_(g, "f1")), fmt(mean(g, "iou")), fmt(min_(g, "iou")),
    fmt(mean(g, "precision")), fmt(mean(g, "recall")), fmt(min_(g, "recall")),
    fmt(mean(g, "or")), fmt(min_(g, "or")), pct(mean(g, "sf")), pct(max_(g, "sf")),
    (k in locell) ? locell[k] : "—"
}
function header(first) {
  print "| " first " | cells | F1 mean | F1 worst | IoU mean | IoU worst | precision mean | recall mean | recall worst | object recall mean / worst | static flagged mean / worst | worst F1 cell |"
  print "|---|---|---|---|---|---|---|---|---|---|---|---|"
}
NR == 1 { next }
{
  scen = $1; sensor = $2; seed = $3; md = $4
  cell = scen " · " sensor " · s" seed " · " (md == "md" ? "distorted" : "undistorted")
  groups[1] = "all"; groups[2] = "scen:" scen; groups[3] = "sensor:" sensor; groups[4] = "md:" md
  groups[5] = "grid:" scen ":" sensor
  for (i = 1; i <= 5; i++) {
    g = groups[i]; n[g]++
    if ($6 + $8 > 0) {  # the cell has moving points: detection scores apply
      add(g, "f1", $11, cell); add(g, "iou", $12, cell); add(g, "precision", $9, cell)
      add(g, "recall", $10, cell); add(g, "or", $13, cell)
    }
    add(g, "sf", $14, cell)
    add(g, "ms", $15, cell); add(g, "secs", $17, cell)
  }
  if (!(scen in seen_scen)) { seen_scen[scen] = 1; scens[++ns] = scen }
  if (!(sensor in seen_sensor)) { seen_sensor[sensor] = 1; sensors[++nz] = sensor }
  ego_failed += $16; cells++
}
END {
  print "# Evaluation matrix"
  print ""
  if (cmd != "") print "Command: `" cmd "` (detector configuration: `" config "`" (shipped == 1 ? ", the shipped defaults" : "") ")."
  printf "%d cells scored%s", cells, (asked != "" ? " of " asked : "")
  if (wall != "") printf "; wall time %d s (%.1f min)", wall, wall / 60
  printf "; sum of cell times %d s; ego-motion failures: %d sweeps.\n\n", sum["all" SUBSEP "secs"], ego_failed
  print "Per cell: per-point precision / recall / F1 / IoU summed over its sweeps (micro average, as in"
  print "the paper), object recall, share of static points flagged. **mean** = mean over cells, **worst**"
  print "= the lowest cell (the highest for static flagged). Cells without moving points (the `static`"
  print "scenario) count for static flagged only."
  print ""
  print "## Overall"
  print ""
  header("")
  row("all", "all")
  print ""
  print "## Per scenario (over sensors, seeds and distortion)"
  print ""
  header("scenario")
  for (i = 1; i <= ns; i++) row(scens[i], "scen:" scens[i])
  print ""
  print "## Per sensor (over scenarios, seeds and distortion)"
  print ""
  header("sensor")
  for (i = 1; i <= nz; i++) row(sensors[i], "sensor:" sensors[i])
  print ""
  print "## Motion distortion"
  print ""
  header("distortion")
  if (n["md:nomd"]) row("off", "md:nomd")
  if (n["md:md"]) row("on", "md:md")
  print ""
  print "## F1 per scenario and sensor: mean over seeds and distortion (worst cell)"
  print ""
  line = "| scenario |"; sep = "|---|"
  for (j = 1; j <= nz; j++) { line = line " " sensors[j] " |"; sep = sep "---|" }
  print line; print sep
  for (i = 1; i <= ns; i++) {
    line = "| " scens[i] " |"
    for (j = 1; j <= nz; j++) {
      g = "grid:" scens[i] ":" sensors[j]
      v = mean(g, "f1")
      line = line " " (v == "" ? (n[g] ? "— (sf " pct(max_(g, "sf")) ")" : "") : sprintf("%.2f (%.2f)", v, min_(g, "f1"))) " |"
    }
    print line
  }
}' "$TSV"
