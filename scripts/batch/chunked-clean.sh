#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Cleans one long recording with dynobj-mapclean in chunks run by GNU parallel, on this machine or
# over ssh hosts, and merges them into one map (docs/mapclean.md, "Long recordings in chunks"):
#   1. dynobj-mapclean -i <input> --plan-chunks <length>      -> <out-dir>/chunks.txt
#   2. one dynobj-mapclean --chunk-from/--chunk-to per chunk  -> <out-dir>/chunks/<n>/
#   3. dynobj-mapclean --merge <out-dir>/chunks/*             -> <out-dir>/map/
# A chunk whose chunk.ini exists is complete (it is written last) and is not run again: a failed or
# interrupted run is resumed by running the same command again.
#
#   scripts/batch/chunked-clean.sh [-j jobs] [-t threads-per-job] [-S sshlogin]... [-b dynobj-mapclean]
#                                  [-l length] [-O overlap] -o out-dir input [-- dynobj-mapclean options...]
#
#   input      a rawlog (or KTH folder) that every host sees at the same path
#   -l S       chunk length in seconds (default 600); each chunk also reads -O seconds before and
#              after it, so chunks much longer than the overlap waste little
#   -O S       dynobj-mapclean --chunk-overlap (default 30: the back-fill and free-space windows)
#   -j N       chunks at once per host (default: the number of cores / threads per job, at least 1)
#   -t N       dynobj-mapclean --threads of each chunk (default 1)
#   -S login   run chunks over ssh (GNU parallel --sshlogin, e.g. "8/user@host", ":" = this
#              machine); repeatable. The hosts need the same paths and dynobj-mapclean (-b).
#   -b path    the dynobj-mapclean to run (default: $DYNOBJ_MAPCLEAN, else dynobj-mapclean on
#              PATH, else this tree's build/apps/dynobj-mapclean)
#   options    given to every chunk (e.g. --poses ego, -c my.ini); a --formats is also the merge's
#
# Exit code: 0 when every chunk and the merge succeeded, 1 otherwise (failed chunks listed with their
# logs), 2 on a bad command line.
set -euo pipefail

source "$(dirname "${BASH_SOURCE[0]}")/batch-common.sh"
usage() { sed -n '3,27p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
JOBS="" THREADS=1 OUT="" LENGTH=600 OVERLAP=30
SSH=()
BIN="${DYNOBJ_MAPCLEAN:-}"
while getopts "j:t:S:b:o:l:O:h" opt; do
  case "$opt" in
    j) JOBS="$OPTARG" ;;
    t) THREADS="$OPTARG" ;;
    S) SSH+=(--sshlogin "$OPTARG") ;;
    b) BIN="$OPTARG" ;;
    o) OUT="$OPTARG" ;;
    l) LENGTH="$OPTARG" ;;
    O) OVERLAP="$OPTARG" ;;
    *) usage ;;
  esac
done
shift $((OPTIND - 1))
[ $# -ge 1 ] && [ -n "$OUT" ] || usage
INPUT="$1"
shift
[ "${1:-}" = "--" ] && shift
EXTRA=("$@")
batch_check_jobs chunked-clean
[ -e "$INPUT" ] || { echo "chunked-clean: no input '$INPUT'" >&2; exit 2; }
batch_find_tool dynobj-mapclean
[ -x "$BIN" ] || { echo "chunked-clean: no dynobj-mapclean at '$BIN' (-b)" >&2; exit 1; }
INPUT="$(cd "$(dirname "$INPUT")" && pwd)/$(basename "$INPUT")"
MERGE_FORMATS=()
for ((i = 0; i < ${#EXTRA[@]}; i++)); do
  [ "${EXTRA[$i]}" = "--formats" ] && MERGE_FORMATS=(--formats "${EXTRA[$((i + 1))]:-}")
done

mkdir -p "$OUT/logs" "$OUT/chunks"
OUT="$(cd "$OUT" && pwd)"
"$BIN" -i "$INPUT" --plan-chunks "$LENGTH" "${EXTRA[@]}" > "$OUT/chunks.txt"
N=$(wc -l < "$OUT/chunks.txt")

QEXTRA=""
for a in "${EXTRA[@]}"; do QEXTRA+=" $(printf '%q' "$a")"; done
Q() { printf '%q' "$1"; }
# One chunk: {#} its number, {1} {2} its range. Skipped when its chunk.ini exists (complete).
JOB="d=$(Q "$OUT")/chunks/{#}; [ -f \$d/chunk.ini ] && echo skipped > $(Q "$OUT")/logs/chunk-{#}.log && exit 0;"
JOB+=" $(Q "$BIN") -q -w -i $(Q "$INPUT") -o \$d --chunk-from {1} --chunk-to {2} --chunk-overlap $(Q "$OVERLAP")"
JOB+=" --threads $THREADS$QEXTRA > $(Q "$OUT")/logs/chunk-{#}.log 2>&1"
echo "chunked-clean: $N chunks of about $LENGTH s (+ $OVERLAP s overlap) of $INPUT -> $OUT ($JOBS at once per host)"
rc=0
parallel --will-cite --colsep ' ' --jobs "$JOBS" --joblog "$OUT/logs/joblog.tsv" "${SSH[@]}" \
  "$JOB" :::: "$OUT/chunks.txt" || rc=$?
failed=()
for ((k = 1; k <= N; k++)); do
  [ -f "$OUT/chunks/$k/chunk.ini" ] || failed+=("chunk $k: $(sed -n "${k}p" "$OUT/chunks.txt") s (log: $OUT/logs/chunk-$k.log)")
done
if [ ${#failed[@]} -gt 0 ] || [ "$rc" -ne 0 ]; then
  echo "chunked-clean: ${#failed[@]} of $N chunks failed; run the same command again to resume" >&2
  for f in "${failed[@]}"; do echo "  failed: $f" >&2; done
  exit 1
fi
CHUNKS=()
for ((k = 1; k <= N; k++)); do CHUNKS+=("$OUT/chunks/$k"); done
"$BIN" -q -w -o "$OUT/map" --merge "${CHUNKS[@]}" "${MERGE_FORMATS[@]}"
