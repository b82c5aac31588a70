#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Soak: SWEEPS simulated sweeps (default 36,000 = one hour at 10 Hz, OS0-64 512 x 10, the hall
# scenario) through the observation filter (drop mode), resident memory sampled every EVERY sweeps.
# Writes $OUT/soak.csv and prints the memory after warm-up (first sample after 10 % of the run),
# at the end, and the largest sample. Usage: scripts/reliability/soak.sh [SWEEPS=36000] [EVERY=600]
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
SWEEPS="${1:-36000}"
EVERY="${2:-600}"
BUILD="${DYNOBJ_BUILD_DIR:-$ROOT/build}"
OUT="${OUT:-$BUILD/soak}"
mkdir -p "$OUT"
cmake --build "$BUILD" -j1 --target soak_filter >/dev/null
"$BUILD/tests/soak_filter" --sweeps "$SWEEPS" --every "$EVERY" | tee "$OUT/soak.csv"
awk -F, -v warm=$((SWEEPS / 10)) '
  /^[0-9]/ && $1 >= warm && !w { w = $3; ws = $1 }
  /^[0-9]/ { last = $3; ls = $1; if ($3 > max) max = $3; if ($1 > 0) { ms += $4; n++ } }
  END { printf "soak: RSS %.1f MiB after warm-up (sweep %d), %.1f MiB at sweep %d, max %.1f MiB; drift %+.1f MiB; %.1f ms/sweep\n",
               w, ws, last, ls, max, last - w, ms / n }' "$OUT/soak.csv" | tee "$OUT/summary.txt"
