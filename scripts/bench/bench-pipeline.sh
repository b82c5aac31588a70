#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Times, in one run on the same rawlog: stock rawlog-edit copying it (--remove-label of a label it
# does not have), rawlog-dynobj --mode drop at each compression level and thread count, and
# dynobj-detect (read + convert + detect, no output). Prints, per command, the best wall time of
# N runs, ms per LiDAR sweep, the ratio to the stock copy, CPU time (user + sys) and peak RSS
# (GNU time). Outputs go to a scratch folder that is removed at the end.
#
#   scripts/bench/bench-pipeline.sh [-n runs] [-l "levels"] [-t "threads"] [-b build-dir] <in.rawlog>
#
# Defaults: 3 runs, levels "0 1 2 3", threads "1 <cores>", build dir ./build. The figures in
# docs/performance.md were made with it. Nothing here asserts a time: it only measures.
set -euo pipefail

RUNS=3
LEVELS="0 1 2 3"
THREADS="1 $(nproc)"
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
BUILD="$ROOT/build"
usage() { sed -n '3,11p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
while getopts "n:l:t:b:h" opt; do
  case "$opt" in
    n) RUNS="$OPTARG" ;;
    l) LEVELS="$OPTARG" ;;
    t) THREADS="$OPTARG" ;;
    b) BUILD="$OPTARG" ;;
    *) usage ;;
  esac
done
shift $((OPTIND - 1))
[ $# -eq 1 ] || usage
IN="$1"
[ -f "$IN" ] || { echo "bench-pipeline: no rawlog '$IN'" >&2; exit 1; }
[ -x /usr/bin/time ] || { echo "bench-pipeline: needs GNU time (/usr/bin/time, package 'time')" >&2; exit 1; }
RD="$BUILD/apps/rawlog-dynobj"
DETECT="$BUILD/apps/dynobj-detect"
for b in "$RD" "$DETECT"; do [ -x "$b" ] || { echo "bench-pipeline: build first: no $b" >&2; exit 1; }; done
command -v rawlog-edit >/dev/null || { echo "bench-pipeline: rawlog-edit (mrpt-apps) not found" >&2; exit 1; }

SCRATCH="$(mktemp -d "${TMPDIR:-/tmp}/bench-pipeline.XXXXXX")"
trap 'rm -rf "$SCRATCH"' EXIT

# Sweeps: the LiDAR frames rawlog-dynobj reports (one quick plain run, also a warm-up of the
# page cache for the input).
SWEEPS=$("$RD" -i "$IN" -o "$SCRATCH/count.rawlog" -w -q --compression-level 0 |
         sed -n 's/.* \([0-9][0-9]*\) LiDAR frames.*/\1/p')
rm -f "$SCRATCH/count.rawlog"
[ -n "$SWEEPS" ] && [ "$SWEEPS" -gt 0 ] || { echo "bench-pipeline: no LiDAR frames in '$IN'" >&2; exit 1; }

# The commands, each a name and a command line (run through eval, arguments quoted).
NAMES=() CMDS=()
add() { NAMES+=("$1"); shift; local q; printf -v q '%q ' "$@"; CMDS+=("$q"); }
add "rawlog-edit copy (stock, zlib level 1)" \
  rawlog-edit -q -w -i "$IN" -o "$SCRATCH/stock.rawlog" --remove-label DYNOBJ_BENCH_NO_SUCH_LABEL
for t in $THREADS; do
  for l in $LEVELS; do
    add "rawlog-dynobj --mode drop, threads $t, level $l" \
      "$RD" -i "$IN" -o "$SCRATCH/rd.rawlog" -w -q --mode drop --threads "$t" --compression-level "$l"
  done
done
add "dynobj-detect (read + detect, no output)" "$DETECT" -i "$IN"

# Runs interleaved (every command once per round, N rounds): a change of the machine's load
# during the benchmark then hits every command alike. Best wall time per command.
BEST=()
for ((r = 0; r < RUNS; r++)); do
  for i in "${!CMDS[@]}"; do
    eval "/usr/bin/time -f '%e %U %S %M' -o '$SCRATCH/time' ${CMDS[$i]}" > "$SCRATCH/out.log" 2>&1 ||
      { echo "bench-pipeline: '${NAMES[$i]}' failed:" >&2; tail -3 "$SCRATCH/out.log" >&2; exit 1; }
    line=$(tail -1 "$SCRATCH/time")
    if [ -z "${BEST[$i]:-}" ] || awk -v a="${line%% *}" -v b="${BEST[$i]%% *}" 'BEGIN{exit !(a < b)}'; then
      BEST[$i]="$line"
    fi
    rm -f "$SCRATCH"/*.rawlog
  done
done

echo "bench-pipeline: $IN ($SWEEPS LiDAR sweeps, $(du -h "$IN" | cut -f1))"
echo "machine: $(nproc) cores, $(uname -m), $(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -1)," \
     "load average $(cut -d' ' -f1-3 /proc/loadavg)"
printf "%-48s %8s %9s %6s %8s %8s\n" "command" "wall s" "ms/sweep" "ratio" "CPU s" "RSS MB"
STOCK_S="${BEST[0]%% *}"
for i in "${!CMDS[@]}"; do
  read -r wall user sys rss <<< "${BEST[$i]}"
  awk -v n="${NAMES[$i]}" -v w="$wall" -v u="$user" -v s="$sys" -v r="$rss" -v k="$SWEEPS" -v st="$STOCK_S" \
    'BEGIN{printf "%-48s %8.2f %9.1f %6.2f %8.2f %8.0f\n", n, w, 1000*w/k, w/st, u+s, r/1024}'
done
echo "(best of $RUNS interleaved rounds; ratio: wall time / stock rawlog-edit copy; CPU: user + sys"
echo " of that run; RSS: its peak; load average after: $(cut -d' ' -f1-3 /proc/loadavg))"
