#!/bin/sh
# SPDX-License-Identifier: BSD-3-Clause
# make_wide_sweeps.sh <dir>: a folder of two unordered PCD sweeps whose 500 points each lie 5 m
# away at elevations spread over +-40 deg, and a sensor preset <dir>/narrow.ini seeing only +-5 deg
# (for cli.import_preset_field_of_view_misses_the_points_fails).
set -eu
dir="$1"
rm -rf "$dir"
mkdir -p "$dir/sweeps"
for k in 0 1; do
  awk -v seed=$((7 + k)) 'BEGIN {
    srand(seed); n = 500
    printf "VERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\n"
    printf "WIDTH %d\nHEIGHT 1\nPOINTS %d\nDATA ascii\n", n, n
    for (i = 0; i < n; i++) {
      a = rand() * 6.2832; e = (rand() * 80 - 40) * 3.14159 / 180
      printf "%.3f %.3f %.3f %d\n", 5 * cos(e) * cos(a), 5 * cos(e) * sin(a), 5 * sin(e), int(rand() * 255)
    }
  }' > "$dir/sweeps/00000$k.pcd"
done
printf '[sensor]\nmodel = narrow\nrows = 16\ncols = 360\nelevation_top = 5\nelevation_bottom = -5\nmin_range = 0.5\nmax_range = 100\nfrequency = 10\n' > "$dir/narrow.ini"
