#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Sourced by batch-clean.sh and chunked-clean.sh: the checks of the options both take.

# batch_check_jobs <script>: THREADS must be a positive number; JOBS defaults to the cores over
# THREADS (at least 1) and must be a positive number; GNU parallel must be installed.
batch_check_jobs() {
  [[ "$THREADS" =~ ^[1-9][0-9]*$ ]] || { echo "$1: -t must be a positive number" >&2; exit 2; }
  [ -z "$JOBS" ] && JOBS=$(( $(nproc) / THREADS > 0 ? $(nproc) / THREADS : 1 ))
  [[ "$JOBS" =~ ^[1-9][0-9]*$ ]] || { echo "$1: -j must be a positive number" >&2; exit 2; }
  command -v parallel >/dev/null ||
    { echo "$1: GNU parallel is not installed (Debian package 'parallel')" >&2; exit 1; }
}

# batch_find_tool <tool>: BIN, when empty, becomes <tool> on the PATH, else this tree's
# build/apps/<tool>.
batch_find_tool() {
  if [ -z "$BIN" ]; then
    BIN="$(command -v "$1" || true)"
    [ -n "$BIN" ] || BIN="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)/build/apps/$1"
  fi
}
