#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Cleans a manifest of rawlogs with rawlog-dynobj, one job per rawlog, run by GNU parallel on this
# machine or over ssh hosts. Each job writes <out-dir>/<name>.rawlog (name = the input's file name
# without .rawlog / .gz) and its own log <out-dir>/logs/<name>.log; GNU parallel's job log (exit
# code and time of every job) is <out-dir>/logs/joblog.tsv. Jobs whose outputs exist are skipped
# (rawlog-dynobj --skip-existing: outputs are only ever complete), so a failed or interrupted
# batch is resumed by running the same command again.
#
#   scripts/batch/batch-clean.sh [-j jobs] [-t threads-per-job] [-S sshlogin]... [-b rawlog-dynobj]
#                                -o out-dir manifest [-- rawlog-dynobj options...]
#
#   manifest   one rawlog path per line; blank lines and lines starting with # are ignored.
#              Relative paths are relative to the manifest's folder.
#   -j N       jobs at once per host (default: the number of cores / threads per job, at least 1)
#   -t N       rawlog-dynobj --threads of each job (default 2: its reader, detection and
#              compression overlap; more jobs rather than more threads scale further)
#   -S login   run jobs over ssh (GNU parallel --sshlogin, e.g. "8/user@host", ":" = this
#              machine); repeatable. The hosts must see the same paths (a shared file system)
#              and have rawlog-dynobj (-b) installed.
#   -b path    the rawlog-dynobj to run (default: $RAWLOG_DYNOBJ, else rawlog-dynobj on PATH,
#              else this tree's build/apps/rawlog-dynobj)
#
# Exit code: 0 when every job succeeded (or was skipped), 1 when some failed (listed with their
# logs), 2 on a bad command line. Example: docs/usage.md, "Batch over many recordings".
set -euo pipefail

source "$(dirname "${BASH_SOURCE[0]}")/batch-common.sh"
usage() { sed -n '3,24p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
JOBS=""
THREADS=2
OUT=""
SSH=()
BIN="${RAWLOG_DYNOBJ:-}"
while getopts "j:t:S:b:o:h" opt; do
  case "$opt" in
    j) JOBS="$OPTARG" ;;
    t) THREADS="$OPTARG" ;;
    S) SSH+=(--sshlogin "$OPTARG") ;;
    b) BIN="$OPTARG" ;;
    o) OUT="$OPTARG" ;;
    *) usage ;;
  esac
done
shift $((OPTIND - 1))
[ $# -ge 1 ] && [ -n "$OUT" ] || usage
MANIFEST="$1"
shift
[ "${1:-}" = "--" ] && shift
EXTRA=("$@")
batch_check_jobs batch-clean
[ -f "$MANIFEST" ] || { echo "batch-clean: no manifest '$MANIFEST'" >&2; exit 2; }
batch_find_tool rawlog-dynobj
[ ${#SSH[@]} -gt 0 ] || [ -x "$BIN" ] || { echo "batch-clean: no rawlog-dynobj at '$BIN' (-b)" >&2; exit 1; }

mkdir -p "$OUT/logs"
OUT="$(cd "$OUT" && pwd)"
MDIR="$(cd "$(dirname "$MANIFEST")" && pwd)"

# The inputs, as absolute paths; two inputs with the same name would write the same output.
INPUTS="$OUT/logs/inputs.txt"
: > "$INPUTS"
declare -A seen=()
while IFS= read -r line || [ -n "$line" ]; do
  line="${line#"${line%%[![:space:]]*}"}"
  line="${line%"${line##*[![:space:]]}"}"
  [ -z "$line" ] || [ "${line:0:1}" = "#" ] && continue
  [ "${line:0:1}" = "/" ] || line="$MDIR/$line"
  name="$(basename "$line")"
  name="${name%.gz}"
  name="${name%.rawlog}"
  if [ -n "${seen[$name]:-}" ]; then
    echo "batch-clean: '$line' and '${seen[$name]}' would both write $OUT/$name.rawlog" >&2
    exit 2
  fi
  seen[$name]="$line"
  printf '%s\n' "$line" >> "$INPUTS"
done < "$MANIFEST"
N=$(wc -l < "$INPUTS")
[ "$N" -gt 0 ] || { echo "batch-clean: '$MANIFEST' lists no rawlog" >&2; exit 2; }

# One job: rawlog-dynobj on {} (the input); {/.} is its file name without the last extension.
# The name is computed again in the job (for .rawlog.gz) so that remote hosts need nothing more.
QEXTRA=""
for a in "${EXTRA[@]}"; do QEXTRA+=" $(printf '%q' "$a")"; done
JOB="in={}; n=\$(basename \"\$in\"); n=\${n%.gz}; n=\${n%.rawlog};"
JOB+=" $(printf '%q' "$BIN") -i \"\$in\" -o $(printf '%q' "$OUT")/\"\$n\".rawlog --skip-existing -q"
JOB+=" --threads $THREADS$QEXTRA > $(printf '%q' "$OUT")/logs/\"\$n\".log 2>&1"

echo "batch-clean: $N rawlogs -> $OUT ($JOBS jobs at once per host, --threads $THREADS each)"
rc=0
parallel --will-cite --jobs "$JOBS" --joblog "$OUT/logs/joblog.tsv" "${SSH[@]}" \
  "$JOB" :::: "$INPUTS" || rc=$?

# Summary from the logs: skipped, cleaned, failed.
done_n=0 skipped=0 failed=()
while IFS= read -r in; do
  n="$(basename "$in")"; n="${n%.gz}"; n="${n%.rawlog}"
  log="$OUT/logs/$n.log"
  if [ -f "$OUT/$n.rawlog" ] && grep -q "exists: skipped" "$log" 2>/dev/null; then
    skipped=$((skipped + 1))
  elif [ -f "$OUT/$n.rawlog" ] && grep -q "^rawlog-dynobj: [0-9]* entries" "$log" 2>/dev/null; then
    done_n=$((done_n + 1))
  else
    failed+=("$in (log: $log)")
  fi
done < "$INPUTS"
echo "batch-clean: $done_n cleaned, $skipped skipped (output existed), ${#failed[@]} failed"
for f in "${failed[@]}"; do echo "  failed: $f"; done
[ ${#failed[@]} -eq 0 ] && [ "$rc" -eq 0 ] && exit 0
exit 1
