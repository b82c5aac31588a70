#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Test of scripts/batch/batch-clean.sh (GNU parallel) and scripts/batch/batch-clean.sbatch (run as Slurm would
# run one array task): three small sequences cut from the committed sample, cleaned with -j2 (the
# second time through GNU parallel's --sshlogin path with ":" = this machine); every output is
# read back by stock rawlog-edit and every log checked; a second run skips everything; a missing
# input fails alone, named, with a non-zero exit code.
#   check_batch_clean.sh <source-dir> <rawlog-dynobj> <sample.rawlog> <work-dir>
set -euo pipefail
SRC="$1" BIN="$2" SAMPLE="$3" W="$4"
fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$W" && mkdir -p "$W/in/b"
# Three sequences of 10 sweeps each (20 entries: LiDAR + odometry), one in a sub-folder.
rawlog-edit -q --cut --from-index 0 --to-index 19 -i "$SAMPLE" -o "$W/in/seq1.rawlog" > /dev/null
rawlog-edit -q --cut --from-index 20 --to-index 39 -i "$SAMPLE" -o "$W/in/seq2.rawlog" > /dev/null
rawlog-edit -q --cut --from-index 40 --to-index 59 -i "$SAMPLE" -o "$W/in/b/seq3.rawlog" > /dev/null
printf '# three sequences\nin/seq1.rawlog\n\n%s/in/seq2.rawlog\nin/b/seq3.rawlog\n' "$W" > "$W/manifest.txt"

"$SRC/scripts/batch/batch-clean.sh" -j 2 -t 1 -b "$BIN" -o "$W/out" "$W/manifest.txt" -- --mode drop \
  > "$W/run1.txt" 2>&1 || { cat "$W/run1.txt"; fail "first run exited non-zero"; }
grep -q "3 cleaned, 0 skipped .*, 0 failed" "$W/run1.txt" || { cat "$W/run1.txt"; fail "run 1 summary"; }
for s in seq1 seq2 seq3; do
  [ -f "$W/out/$s.rawlog" ] || fail "no output $s.rawlog"
  [ ! -e "$W/out/$s.rawlog.partial" ] || fail "$s.rawlog.partial left behind"
  grep -q "^rawlog-dynobj: 20 entries, 20 observations; 10 LiDAR frames (drop, offline)" "$W/out/logs/$s.log" ||
    { cat "$W/out/logs/$s.log"; fail "log of $s"; }
  rawlog-edit --info -i "$W/out/$s.rawlog" 2>&1 | grep -q "Overall number of objects *: 20" ||
    fail "stock rawlog-edit does not read 20 objects in $s.rawlog"
done
[ "$(tail -n +2 "$W/out/logs/joblog.tsv" | awk -F'\t' '$7 == 0' | wc -l)" -eq 3 ] ||
  { cat "$W/out/logs/joblog.tsv"; fail "joblog: not three jobs with exit code 0"; }

# Idempotent: the same command again (through parallel's ssh-login path, ':' = local) skips all.
"$SRC/scripts/batch/batch-clean.sh" -j 2 -t 1 -S 2/: -b "$BIN" -o "$W/out" "$W/manifest.txt" \
  > "$W/run2.txt" 2>&1 || { cat "$W/run2.txt"; fail "second run exited non-zero"; }
grep -q "0 cleaned, 3 skipped .*, 0 failed" "$W/run2.txt" || { cat "$W/run2.txt"; fail "run 2 summary"; }

# A missing input fails alone and is named; the exit code says so.
printf 'in/seq1.rawlog\nin/missing.rawlog\n' > "$W/manifest2.txt"
if "$SRC/scripts/batch/batch-clean.sh" -j 2 -t 1 -b "$BIN" -o "$W/out" "$W/manifest2.txt" > "$W/run3.txt" 2>&1; then
  fail "a failed job did not make the batch fail"
fi
grep -q "0 cleaned, 1 skipped .*, 1 failed" "$W/run3.txt" || { cat "$W/run3.txt"; fail "run 3 summary"; }
grep -q "failed: .*missing.rawlog" "$W/run3.txt" || fail "run 3 does not name the failed input"
grep -q "missing.rawlog' does not exist" "$W/out/logs/missing.log" || fail "log of the failed job"

# The Slurm array script, run as one array task would be (task 2 = the second rawlog).
SLURM_ARRAY_TASK_ID=2 RAWLOG_DYNOBJ="$BIN" bash "$SRC/scripts/batch/batch-clean.sbatch" "$W/manifest.txt" \
  "$W/slurm" --mode drop > "$W/slurm.txt" 2>&1 || { cat "$W/slurm.txt"; fail "sbatch task 2"; }
grep -q "^rawlog-dynobj: 20 entries" "$W/slurm.txt" || { cat "$W/slurm.txt"; fail "sbatch log"; }
[ -f "$W/slurm/seq2.rawlog" ] && [ ! -e "$W/slurm/seq1.rawlog" ] || fail "sbatch task 2 output"
cmp -s <(gzip -dc "$W/slurm/seq2.rawlog") <(gzip -dc "$W/out/seq2.rawlog") ||
  fail "sbatch and parallel outputs differ"
echo "batch-clean: 3 sequences cleaned with -j2, logs checked, rerun skipped all, a failure named, Slurm task ok"
