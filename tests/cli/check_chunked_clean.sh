#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Test of scripts/batch/chunked-clean.sh (GNU parallel, -j 2) and scripts/batch/chunked-clean.sbatch
# (run as Slurm would run its array tasks, then the merge): the committed sample in chunks of 2 s;
# both give the same merged map, byte for byte; a second run of the script skips every chunk; a
# chunk that fails is named and the exit code is 1, with no merged map.
#   check_chunked_clean.sh <source-dir> <dynobj-mapclean> <sample.rawlog> <work-dir>
set -euo pipefail
SRC="$1" BIN="$2" SAMPLE="$3" W="$4"
fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$W" && mkdir -p "$W"

"$SRC/scripts/batch/chunked-clean.sh" -j 2 -l 2 -O 1 -b "$BIN" -o "$W/par" "$SAMPLE" -- --formats ply \
  > "$W/run1.txt" 2>&1 || { cat "$W/run1.txt"; fail "first run exited non-zero"; }
grep -q "chunked-clean: 2 chunks of about 2 s (+ 1 s overlap)" "$W/run1.txt" || { cat "$W/run1.txt"; fail "run 1 header"; }
grep -q "^dynobj-mapclean --merge: 2 chunks, 40 scans" "$W/run1.txt" || { cat "$W/run1.txt"; fail "run 1 merge"; }
for f in static.ply dynamic.ply poses.tum; do [ -f "$W/par/map/$f" ] || fail "no map/$f"; done
[ ! -e "$W/par/map/static.png" ] || fail "--formats ply did not reach the merge"
[ "$(tail -n +2 "$W/par/logs/joblog.tsv" | awk -F'\t' '$7 == 0' | wc -l)" -eq 2 ] || fail "joblog"

"$SRC/scripts/batch/chunked-clean.sh" -j 2 -l 2 -O 1 -b "$BIN" -o "$W/par" "$SAMPLE" -- --formats ply \
  > "$W/run2.txt" 2>&1 || { cat "$W/run2.txt"; fail "second run exited non-zero"; }
[ "$(cat "$W/par/logs/chunk-1.log" "$W/par/logs/chunk-2.log")" = "$(printf 'skipped\nskipped')" ] ||
  fail "the second run ran the chunks again"

# Slurm: the plan, each array task, then the merge job.
"$BIN" -i "$SAMPLE" --plan-chunks 2 > "$W/chunks.txt"
for task in 1 2; do
  SLURM_ARRAY_TASK_ID=$task DYNOBJ_MAPCLEAN="$BIN" "$SRC/scripts/batch/chunked-clean.sbatch" \
    "$SAMPLE" "$W/chunks.txt" "$W/slurm" --chunk-overlap 1 --formats ply > "$W/task$task.txt" 2>&1 ||
    { cat "$W/task$task.txt"; fail "array task $task"; }
done
"$BIN" -q -w -o "$W/slurm/map" --merge "$W/slurm/chunks/"* --formats ply > /dev/null
cmp "$W/par/map/static.ply" "$W/slurm/map/static.ply" || fail "GNU parallel and Slurm maps differ"
cmp "$W/par/map/poses.tum" "$W/slurm/map/poses.tum" || fail "GNU parallel and Slurm poses differ"

# A chunk that fails (a bad config for every chunk): named, exit 1, no map.
printf '[mapclean]\nvoxel_sise = 1\n' > "$W/bad.ini"
if "$SRC/scripts/batch/chunked-clean.sh" -j 2 -l 2 -b "$BIN" -o "$W/bad" "$SAMPLE" -- -c "$W/bad.ini" \
  > "$W/run3.txt" 2>&1; then
  fail "a failing chunk gave exit 0"
fi
grep -q "2 of 2 chunks failed" "$W/run3.txt" || { cat "$W/run3.txt"; fail "failures not listed"; }
grep -q "unknown key 'voxel_sise'" "$W/bad/logs/chunk-1.log" || fail "chunk log without the cause"
[ ! -e "$W/bad/map" ] || fail "a map after failed chunks"
rm -rf "$W"
echo "chunked-clean: GNU parallel and Slurm runs agree, resume skips, failures named"
