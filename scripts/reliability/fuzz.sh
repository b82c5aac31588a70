#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Builds the libFuzzer harnesses (tests/fuzz, DYNOBJ_BUILD_FUZZERS=ON: clang, ASan + UBSan) and
# runs each for SECONDS, starting from the committed seed corpus tests/fuzz/<harness>/.
# Findings (crash-*, leak-*, oom-*, timeout-*) go to $OUT/artifacts/<harness>/; the corpus grows in
# $OUT/corpus/<harness>/ (reused by the next run). Not part of CI (see docs/performance.md).
#
# Usage: scripts/reliability/fuzz.sh SECONDS [harness ...]      (default: all harnesses)
#   FUZZ_JOBS=2   harnesses run at the same time (default 1)
#   DYNOBJ_FUZZ_BUILD_DIR (default build-fuzz/)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../common.sh"
SECONDS_EACH="${1:?usage: scripts/reliability/fuzz.sh SECONDS [harness ...]}"
shift
ALL=(label_file pose_file pcd kitti_bin ouster_metadata ouster_pcap detector_params scenario_yaml rawlog)
HARNESSES=("${@:-${ALL[@]}}")
JOBS="${FUZZ_JOBS:-1}"
BUILD="${DYNOBJ_FUZZ_BUILD_DIR:-$DYNOBJ_ROOT/build-fuzz}"
OUT="$BUILD/fuzz-runs"

# clang + libclang-rt-14-dev: libFuzzer and the sanitizer runtimes (-fsanitize=fuzzer).
ensure_packages clang libclang-rt-14-dev
log "configuring $BUILD (clang, fuzzers, ASan + UBSan)"
cmake -S "$DYNOBJ_ROOT" -B "$BUILD" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" -DDYNOBJ_BUILD_FUZZERS=ON -DDYNOBJ_BUILD_TESTS=OFF \
  -DDYNOBJ_BUILD_APPS=OFF >/dev/null
targets=()
for h in "${HARNESSES[@]}"; do targets+=("fuzz_$h"); done
log "building ${targets[*]}"
cmake --build "$BUILD" -j "${FUZZ_BUILD_JOBS:-1}" --target "${targets[@]}"

run_one() {
  local h="$1" corpus="$OUT/corpus/$1" art="$OUT/artifacts/$1/"
  mkdir -p "$corpus" "$art"
  cp -n "$DYNOBJ_ROOT/tests/fuzz/$h"/* "$corpus"/ 2>/dev/null || true
  # ASan's leak check is off: MRPT keeps singletons (class registry, memory pools) until exit.
  ASAN_OPTIONS=detect_leaks=0:allocator_may_return_null=1 UBSAN_OPTIONS=print_stacktrace=1 \
    "$BUILD/tests/fuzz/fuzz_$h" "$corpus" -max_total_time="$SECONDS_EACH" -timeout=20 \
    -rss_limit_mb=3072 -max_len=65536 -print_final_stats=1 -artifact_prefix="$art" \
    >"$OUT/$h.log" 2>&1 || true
  local execs findings
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$OUT/$h.log" | grep -o '[0-9]*$' || echo "?")
  findings=$(find "$art" -type f | wc -l)
  printf '%-16s %6ss  %10s runs  corpus %5s files  findings %s\n' "$h" "$SECONDS_EACH" "$execs" \
    "$(find "$corpus" -type f | wc -l)" "$findings" | tee -a "$OUT/summary.txt"
}

mkdir -p "$OUT"
echo "# $(date -u +%FT%TZ) scripts/reliability/fuzz.sh $SECONDS_EACH ${HARNESSES[*]} (FUZZ_JOBS=$JOBS)" >>"$OUT/summary.txt"
running=0
for h in "${HARNESSES[@]}"; do
  run_one "$h" &
  running=$((running + 1))
  if [ "$running" -ge "$JOBS" ]; then
    wait -n
    running=$((running - 1))
  fi
done
wait
total=$(find "$OUT/artifacts" -type f | wc -l)
log "findings: $total (in $OUT/artifacts; reproduce: $BUILD/tests/fuzz/fuzz_<harness> <file>)"
[ "$total" -eq 0 ]
