#!/bin/sh
# SPDX-License-Identifier: BSD-3-Clause
# run_keeps_file.sh <file> <command...>: runs the command and exits with its status, or with 9
# when <file> no longer holds the single line "keep" (the command replaced an existing output).
file="$1"
shift
"$@"
rc=$?
if [ "$(cat "$file" 2>/dev/null)" != keep ]; then
  echo "run_keeps_file.sh: '$file' was replaced" >&2
  exit 9
fi
exit $rc
