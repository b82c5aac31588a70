#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# N damaged copies of the sample rawlog through rawlog-dynobj: bits flipped, bytes
# zeroed or inserted, files cut short, in the gzip file and in the uncompressed stream (8 kinds,
# seeded by the case number). Every case must end in exit 0 with an output MRPT reads to its end,
# or exit 1 with a message naming the entry/byte: never a crash, a hang or a leftover .partial.
# Parallel (JOBS shards) and resumable (results are appended per case; a rerun skips done cases).
#
# Usage: scripts/reliability/damaged-rawlogs.sh [N=10000] [JOBS=nproc] [ENTRIES=6]
#   DYNOBJ_BUILD_DIR (default build/) must hold a configured build with DYNOBJ_BUILD_TESTS=ON.
# Output: $OUT (default $DYNOBJ_BUILD_DIR/damaged-rawlogs/), results-<shard>.txt, summary.txt.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
N="${1:-10000}"
JOBS="${2:-$(nproc)}"
ENTRIES="${3:-6}"
BUILD="${DYNOBJ_BUILD_DIR:-$ROOT/build}"
OUT="${OUT:-$BUILD/damaged-rawlogs}"

cmake --build "$BUILD" -j1 --target rawlog-dynobj damaged_rawlogs >/dev/null
mkdir -p "$OUT"
echo "[damaged-rawlogs] $N cases, $JOBS shards, base = first $ENTRIES entries of the sample; results in $OUT"
start=$(date +%s)
pids=()
for ((j = 0; j < JOBS; j++)); do
  first=$((N * j / JOBS))
  last=$((N * (j + 1) / JOBS))
  "$BUILD/tests/damaged_rawlogs" --base "$ROOT/rawlogs/hall-small/hall-small.rawlog" \
    --entries "$ENTRIES" --work "$OUT/work-$j" --first "$first" --count $((last - first)) \
    --results "$OUT/results-$j.txt" --timeout 300 \
    -- "$BUILD/apps/rawlog-dynobj" -i '{in}' -o '{out}' --mode drop -q \
    >"$OUT/shard-$j.log" 2>&1 &
  pids+=($!)
done
rc=0
for p in "${pids[@]}"; do wait "$p" || rc=1; done
secs=$(($(date +%s) - start))

{
  echo "damaged rawlogs: $(cat "$OUT"/results-*.txt | wc -l) cases (of $N asked), $secs s this run, $JOBS shards"
  echo "per kind and verdict (ok = exit 0 + complete output; error = exit 1 naming the entry/byte):"
  cut -d'|' -f1 "$OUT"/results-*.txt | tr -cd '[:print:]\n'  | awk '{print $2, $3}' | sort | uniq -c
  echo "failures (crash, hang, other exit code, leftover .partial, unreadable output, vague message):"
  grep -ah " FAIL " "$OUT"/results-*.txt || echo "  none"
  echo "error messages, by kind of damage found:"
  grep -ah " error " "$OUT"/results-*.txt | sed -e 's/.*| //' -e 's/rawlog .* is \(damaged\|truncated\) at entry [0-9]* ([a-z ]*, byte [0-9]*)/rawlog is \1/' \
    -e 's/[0-9][0-9]*/N/g' | cut -c1-110 | sort | uniq -c | sort -rn | head -25
} | tee "$OUT/summary.txt"
exit $rc
