#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs, builds and runs every test (unit, real-data, command-line, package consumer).
# Exits non-zero on any failure. Usage: scripts/test.sh [extra ctest args]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"

# chromium: the HTML report of dynobj-eval and dynobj-label's page are checked in a headless
# browser; nodejs runs the page's test (DevTools protocol over a pipe, Node's own modules only);
# parallel: the test of scripts/batch-clean.sh (GNU parallel runs its jobs).
ensure_packages chromium nodejs parallel clang-format
BUILD_DIR="${DYNOBJ_BUILD_DIR:-$DYNOBJ_ROOT/build}"
build_project "$BUILD_DIR" -DDYNOBJ_BUILD_TESTS=ON
log "running tests"
cd "$BUILD_DIR"
ctest --output-on-failure -j "$(nproc)" "$@"
