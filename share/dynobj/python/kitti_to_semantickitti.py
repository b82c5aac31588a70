#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Moving-object predictions for a KITTI-style folder of sweeps, as SemanticKITTI .label files.

Reads <velodyne>/NNNNNN.bin (float32 x y z intensity per point, sensor frame), runs the dynobj
detector over the sequence (offline, with the hindsight lag, as dynobj-detect; --online: causal)
and writes <out>/NNNNNN.label: one uint32 per point of the sweep, in its order, 251 (moving) or
9 (static), the values of the LiDAR-MOS benchmark (dynobj.SEMANTIC_KITTI_MOVING / _STATIC, the
values dynobj-eval --predictions-out writes). See docs/python.md.

  kitti_to_semantickitti.py sequences/08/velodyne predictions/sequences/08/predictions
"""
import argparse
import os
import sys

import numpy as np

import dynobj


def sweep_files(folder):
    """The folder's .bin sweeps in name order, each checked to hold whole points (before any
    output is written)."""
    names = sorted(n for n in os.listdir(folder) if n.endswith(".bin"))
    if not names:
        raise SystemExit(f"kitti_to_semantickitti: no .bin sweep in '{folder}'")
    paths = [os.path.join(folder, n) for n in names]
    for path in paths:
        size = os.path.getsize(path)
        if size == 0 or size % 16:
            raise SystemExit(f"kitti_to_semantickitti: '{path}' is {size} bytes, not a positive "
                             "multiple of 16 (float32 x y z intensity per point)")
    return paths


def read_bin(path):
    return np.fromfile(path, dtype=np.float32).reshape(-1, 4)


def timestamps(count, times, rate):
    """Sweep times as numpy.datetime64 [ns]: KITTI times.txt (seconds), else one every 1/rate s
    from 1/rate on (as the dynobj tools number a folder without times)."""
    if times:
        t = np.loadtxt(times, dtype=np.float64, ndmin=1)
        if len(t) < count:
            raise SystemExit(f"kitti_to_semantickitti: '{times}' has {len(t)} times for {count} "
                             "sweeps")
        return [np.datetime64(int(round(s * 1e9)), "ns") for s in t[:count]]
    period = int(round(1e9 / rate))
    return [np.datetime64((k + 1) * period, "ns") for k in range(count)]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("velodyne", help="folder of NNNNNN.bin sweeps")
    ap.add_argument("out", help="folder for the NNNNNN.label predictions (created)")
    ap.add_argument("-c", "--config", help="detector parameters (INI, as the tools' -c)")
    ap.add_argument("--sensor", help="sensor preset INI (default: rows recovered from the data)")
    ap.add_argument("--online", action="store_true", help="causal, no hindsight lag")
    ap.add_argument("--times", help="KITTI times.txt (seconds per sweep)")
    ap.add_argument("--rate", type=float, default=10.0, help="sweeps per second without --times")
    ap.add_argument("-w", "--overwrite", action="store_true", help="replace existing .label files")
    a = ap.parse_args(argv)
    if not a.rate > 0:
        raise SystemExit("kitti_to_semantickitti: --rate must be > 0")

    files = sweep_files(a.velodyne)
    names = [os.path.splitext(os.path.basename(f))[0] + ".label" for f in files]
    existing = [n for n in names if os.path.exists(os.path.join(a.out, n))]
    if existing and not a.overwrite:
        raise SystemExit(f"kitti_to_semantickitti: '{os.path.join(a.out, existing[0])}' exists "
                         f"({len(existing)} of the outputs do): -w replaces them")
    stamps = timestamps(len(files), a.times, a.rate)
    created = not os.path.isdir(a.out)
    os.makedirs(a.out, exist_ok=True)
    sweeps = ((read_bin(f), t) for f, t in zip(files, stamps))

    moving = points = 0
    written = []
    try:
        if a.online:
            detector = dynobj.Detector(a.config, a.sensor)
            masks = (detector.process(points, t) for points, t in sweeps)
        else:
            masks = dynobj.process_sequence(sweeps, config=a.config, sensor=a.sensor)
        for name, mask in zip(names, masks):
            labels = np.where(mask, dynobj.SEMANTIC_KITTI_MOVING, dynobj.SEMANTIC_KITTI_STATIC)
            path = os.path.join(a.out, name)
            labels.astype("<u4").tofile(path + ".partial")  # complete under its name, or absent
            os.replace(path + ".partial", path)
            written.append(path)
            moving += int(mask.sum())
            points += mask.size
    except BaseException:  # no set of predictions that looks complete but is not
        for path in written + [os.path.join(a.out, n + ".partial") for n in names]:
            if os.path.exists(path):
                os.remove(path)
        if created and not os.listdir(a.out):
            os.rmdir(a.out)
        raise
    print(f"kitti_to_semantickitti: {len(files)} sweeps, {points} points, {moving} moving "
          f"({'online' if a.online else 'offline'}) -> '{a.out}'")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except (ValueError, RuntimeError, OSError) as e:  # bad parameters, files, sweeps
        sys.exit(f"kitti_to_semantickitti: error: {e}")
