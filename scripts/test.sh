#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs, builds and runs every test (unit, real-data, command-line, package consumer).
# Exits non-zero on any failure. Usage: scripts/test.sh [extra ctest args]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"

# chromium: the HTML report of dynobj-eval and dynobj-label's page are checked in a headless
# browser; nodejs runs the page's test (DevTools protocol over a pipe, Node's own modules only);
# parallel: the test of scripts/batch/batch-clean.sh (GNU parallel runs its jobs).
ensure_packages chromium nodejs parallel clang-format
BUILD_DIR="${DYNOBJ_BUILD_DIR:-$DYNOBJ_ROOT/build}"
build_project "$BUILD_DIR" -DDYNOBJ_BUILD_TESTS=ON
log "running tests"
cd "$BUILD_DIR"
# Every temporary file of the tests goes to a fresh TMPDIR, which must be empty afterwards: no
# test leaves files behind (and /tmp is not touched: the top-level entries are compared too).
export TMPDIR="$BUILD_DIR/tests/tmp"
rm -rf "$TMPDIR" && mkdir -p "$TMPDIR"
before=$(ls -A /tmp | sort)
ctest --output-on-failure -j "$(nproc)" "$@"
left=$(find "$TMPDIR" -mindepth 1 -maxdepth 2 | head -20)
if [ -n "$left" ]; then
  echo "[dynobj] the tests left files in their TMPDIR ($TMPDIR):" >&2
  echo "$left" >&2
  exit 1
fi
new=$(comm -13 <(echo "$before") <(ls -A /tmp | sort) | grep -E 'dynobj|mrpt_temp|scratch-' || true)
if [ -n "$new" ]; then
  echo "[dynobj] the tests left files in /tmp:" >&2
  echo "$new" >&2
  exit 1
fi
log "no temporary file left behind"
