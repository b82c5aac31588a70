#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# AddressSanitizer + UndefinedBehaviorSanitizer build (DYNOBJ_SANITIZE=ON, g++, -O1 -g) in
# build-asan/, and the tests that exercise our parsers and error paths under it: every unit test
# (label -L unit) and the damaged-rawlog test (cli.rawlog_dynobj_damaged_inputs: rawlog-dynobj on
# 96 damaged inputs). Extra arguments go to ctest (e.g. "-L cli" for more).
# Cost and schedule: docs/performance.md, "Sanitizers".
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
ensure_packages
BUILD="${DYNOBJ_ASAN_BUILD_DIR:-$DYNOBJ_ROOT/build-asan}"
log "configuring $BUILD (ASan + UBSan)"
cmake -S "$DYNOBJ_ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DDYNOBJ_SANITIZE=ON -DDYNOBJ_BUILD_TESTS=ON >/dev/null
start=$(date +%s)
cmake --build "$BUILD" -j "${DYNOBJ_JOBS:-$(nproc)}"
log "build: $(($(date +%s) - start)) s"
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
