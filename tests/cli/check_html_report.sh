#!/bin/sh
# SPDX-License-Identifier: BSD-3-Clause
# Loads an HTML report in headless Chromium and checks that the page loaded and every image in it
# decoded (the report's own script records data-images / data-images-ok on <body>).
set -eu
report="$1"
# Under /tmp, not TMPDIR (build/tests/tmp in scripts/test.sh): Chromium's SingletonSocket goes into
# <TMPDIR>/org.chromium.Chromium.XXXXXX/, and a Unix socket path has at most 107 characters.
profile=$(mktemp -d /tmp/dynobj-chromium-XXXXXX)
trap 'rm -rf "$profile"' EXIT
if ! dom=$(TMPDIR="$profile" timeout 120 chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
  --disable-background-networking --disable-component-update --disable-sync \
  --user-data-dir="$profile" --virtual-time-budget=5000 --dump-dom "file://$report" 2>"$profile/stderr"); then
  echo "chromium failed on $report; the end of its output:"
  tail -n 8 "$profile/stderr"
  exit 1
fi
total=$(printf '%s' "$dom" | sed -n 's/.*data-images="\([0-9]*\)".*/\1/p' | head -n1)
ok=$(printf '%s' "$dom" | sed -n 's/.*data-images-ok="\([0-9]*\)".*/\1/p' | head -n1)
if [ -z "$total" ] || [ -z "$ok" ]; then
  echo "report did not load in Chromium (no data-images attribute)"; exit 1
fi
echo "chromium: $ok of $total images loaded"
[ "$total" -gt 0 ] && [ "$ok" -eq "$total" ]
