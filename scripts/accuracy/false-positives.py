#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Where do a simulated sequence's false positives lie? Splits the flagged static pixels of a
detection run into: actors at rest that moved within the last second (a walker who paused: the
simulator's truth calls an actor slower than moving_speed static), actors at rest longer, and
scenery (no actor: walls, parked cars, vegetation...). Reads the simulator's .gt.labels,
.gt.instances and .gt.objects.csv (docs/formats.md) beside the predictions; never used by the
detector.

Usage: scripts/accuracy/false-positives.py <sim dir> <scenario name> <pred.labels>
  e.g. dynobj-sim -s share/dynobj/scenarios/plaza.yaml --seed 101 -n 100 -o sim
       dynobj-detect -i sim/plaza.rawlog -o pred.labels
       scripts/accuracy/false-positives.py sim plaza pred.labels
"""
import collections
import csv
import sys


def read_labels(path, instances=False):
    sweeps = []
    with open(path, encoding="ascii") as f:
        f.readline()  # header
        for line in f:
            if line.startswith("#"):
                continue  # "# reviewed" line
            t = line.split()
            if instances:
                sweeps.append({int(a.split(":")[0]): int(a.split(":")[1]) for a in t[2:]})
            else:
                sweeps.append({int(a) for a in t[2:]})
    return sweeps


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    d, name, pred_path = sys.argv[1:]
    pred = read_labels(pred_path)
    gt = read_labels(f"{d}/{name}.gt.labels")
    ids = read_labels(f"{d}/{name}.gt.instances", instances=True)
    if not len(pred) == len(gt) == len(ids):
        sys.exit(f"sweep counts differ: predictions {len(pred)}, truth {len(gt)}, instances {len(ids)}")
    moving = collections.defaultdict(dict)  # sweep -> actor id -> moving (0/1)
    with open(f"{d}/{name}.gt.objects.csv", encoding="ascii") as f:
        for r in csv.DictReader(f):
            moving[int(r["sweep"])][int(r["id"])] = int(r["moving"])
    window = 10  # sweeps: 1 s at 10 Hz
    scenery = paused = resting = 0
    for i, (p, g, ii) in enumerate(zip(pred, gt, ids)):
        for px in p - g:
            if px not in ii:
                scenery += 1
            elif any(moving[j].get(ii[px], 0) for j in range(max(0, i - window), i + 1)):
                paused += 1
            else:
                resting += 1
    total = scenery + paused + resting
    share = lambda n: f"{100 * n / total:.0f} %" if total else "n/a"
    print(f"false positives: {total} pixels; actors at rest < 1 s after moving: {paused} "
          f"({share(paused)}); actors at rest longer: {resting} ({share(resting)}); "
          f"scenery: {scenery} ({share(scenery)})")


if __name__ == "__main__":
    main()
