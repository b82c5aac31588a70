#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The accuracy regression guard outside ctest (the same check as ctest -R accuracy_guard):
#   scripts/accuracy/accuracy-guard.sh            check tests/accuracy_guard.tsv, print measured vs bound
#   scripts/accuracy/accuracy-guard.sh --measure  print the table re-measured (values and bounds), to paste
#                                                 into tests/accuracy_guard.tsv after a detector change
#   scripts/accuracy/accuracy-guard.sh [--measure] <scenario>   one row only
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../common.sh"
MEASURE=OFF
if [ "${1:-}" = "--measure" ]; then MEASURE=ON; shift; fi
BUILD_DIR="${DYNOBJ_BUILD_DIR:-$DYNOBJ_ROOT/build}"
[ -x "$BUILD_DIR/apps/dynobj-eval" ] || build_project "$BUILD_DIR"
WORK="${DYNOBJ_GUARD_WORK:-$BUILD_DIR/accuracy-guard}"
mkdir -p "$WORK"
only=()
[ $# -gt 0 ] && only=("-DONLY=$1")
cmake -DBIN="$BUILD_DIR/apps" -DSHARE="$DYNOBJ_ROOT/share/dynobj" \
  -DTABLE="$DYNOBJ_ROOT/tests/accuracy_guard.tsv" -DWORK="$WORK" -DMEASURE="$MEASURE" \
  "${only[@]}" -P "$DYNOBJ_ROOT/tests/cli/accuracy_guard.cmake"
