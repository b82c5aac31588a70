#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Sanitizer builds (g++, -O1 -g) and the tests that exercise them. Cost and schedule:
# docs/performance.md, "Sanitizers".
#
#   scripts/sanitize.sh [ctest args]           AddressSanitizer + UndefinedBehaviorSanitizer
#       (DYNOBJ_SANITIZE=ON) in build-asan/: every unit test (label -L unit) and the
#       damaged-rawlog test (cli.rawlog_dynobj_damaged_inputs: rawlog-dynobj on 96 damaged
#       inputs). Extra arguments go to ctest instead (e.g. "-L cli" for more).
#   scripts/sanitize.sh --thread [ctest args]  ThreadSanitizer (DYNOBJ_SANITIZE_THREAD=ON) in
#       build-tsan/, only the targets the threaded code needs: the core and mrpt unit tests
#       (StageWorker, the detector with [pipeline] threads = 2, the pipelined filterRawlog's
#       lanes, RawlogWriter's compression pool), the pipelined rawlog-dynobj CLI tests, then
#       rawlog-dynobj pipelined (--threads 3) on the hall-small sample (offline split, online drop)
#       and on real KITTI city-22 (imported from ../shared/realdata/kitti-hdl64-city-22, or
#       DYNOBJ_REALDATA; skipped with a message when absent). Any report fails the run.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
ensure_packages
JOBS="${DYNOBJ_JOBS:-$(nproc)}"

# configure_and_build <dir> <what> <cmake -D...> [-- targets...]
configure_and_build() {
  local dir="$1" what="$2" option="$3"
  shift 3
  log "configuring $dir ($what)"
  cmake -S "$DYNOBJ_ROOT" -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" "$option" -DDYNOBJ_BUILD_TESTS=ON >/dev/null
  local start targets=()
  if [ "${1:-}" = "--" ]; then
    shift
    targets=(--target "$@")
  fi
  start=$(date +%s)
  cmake --build "$dir" -j "$JOBS" "${targets[@]}"
  log "build: $(($(date +%s) - start)) s"
}

# rawlog_dynobj_tsan <name> <input> [args...]: one pipelined run, its outputs in a temporary folder.
rawlog_dynobj_tsan() {
  local name="$1" input="$2" start
  shift 2
  start=$(date +%s)
  "$BUILD/apps/rawlog-dynobj" -i "$input" -o "$TMP/$name.rawlog" -w --threads 3 \
    --labels-out "$TMP/$name.labels" "$@"
  log "rawlog-dynobj $name: $(($(date +%s) - start)) s"
}

if [ "${1:-}" = "--thread" ]; then
  shift
  BUILD="${DYNOBJ_TSAN_BUILD_DIR:-$DYNOBJ_ROOT/build-tsan}"
  configure_and_build "$BUILD" "ThreadSanitizer" -DDYNOBJ_SANITIZE_THREAD=ON -- \
    rawlog-dynobj dynobj-import dynobj_core_unittests dynobj_mrpt_unittests compare_rawlogs
  # A report ends the process at once with exit code 66 (the test, the run and this script fail).
  # No suppressions: every run below is clean with none.
  export TSAN_OPTIONS="halt_on_error=1 exitcode=66 second_deadlock_stack=1"
  TMP="$(mktemp -d)"
  trap 'rm -rf "$TMP"' EXIT
  start=$(date +%s)
  cd "$BUILD"
  if [ $# -eq 0 ]; then
    ctest --output-on-failure -j "$(nproc)" -R '^(core|mrpt)\.|^cli\.rawlog_dynobj_pipelined'
    SAMPLE="$DYNOBJ_ROOT/rawlogs/hall-small/hall-small.rawlog"
    rawlog_dynobj_tsan hall-small "$SAMPLE" --sensor-label LIDAR --mode split
    rawlog_dynobj_tsan hall-small-online "$SAMPLE" --sensor-label LIDAR --online
    CITY="${DYNOBJ_REALDATA:-$DYNOBJ_ROOT/../shared/realdata}/kitti-hdl64-city-22"
    if [ -d "$CITY" ]; then
      "$BUILD/apps/dynobj-import" -i "$CITY" -o "$TMP/city-22-in.rawlog" -q >/dev/null
      rawlog_dynobj_tsan city-22 "$TMP/city-22-in.rawlog"
    else
      log "city-22 skipped: $CITY does not exist (../shared/realdata/README.md)"
    fi
  else
    ctest --output-on-failure -j "$(nproc)" "$@"
  fi
  log "tests: $(($(date +%s) - start)) s"
  exit 0
fi

BUILD="${DYNOBJ_ASAN_BUILD_DIR:-$DYNOBJ_ROOT/build-asan}"
configure_and_build "$BUILD" "ASan + UBSan" -DDYNOBJ_SANITIZE=ON
cd "$BUILD"
# Leak checking off: MRPT keeps class registries and memory pools until exit; UBSan findings are
# fatal (-fno-sanitize-recover=undefined in DynobjHelpers.cmake).
export ASAN_OPTIONS="detect_leaks=0:abort_on_error=0" UBSAN_OPTIONS="print_stacktrace=1"
start=$(date +%s)
if [ $# -eq 0 ]; then
  ctest --output-on-failure -j "$(nproc)" -L unit
  ctest --output-on-failure -R 'cli\.rawlog_dynobj_damaged_inputs'
else
  ctest --output-on-failure -j "$(nproc)" "$@"
fi
log "tests: $(($(date +%s) - start)) s"
