#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""The Python module's cost per sweep beside the C++ detector's (docs/performance.md).

Reads the sweeps of INPUT once (dynobj.read_sweeps: a folder of .pcd / .bin sweeps gives (N, 4)
arrays, a rawlog (rows, cols, 4) images) and writes them, as they are, for the C++ side
(dynobj_python_bench_reference: the same conversion, detector and mask as process(), without
Python, in a process of its own). Each round, a fresh dynobj.Detector and a fresh C++ side go
through the sweeps in turn, sweep by sweep (which one goes first switching every sweep), with the
same threads and sensor: both see the same load of the machine. Per sweep, on both sides: the
wall time of the whole call, its conversion and the detector's own time (Python:
Detector.timings()), and the CPU time of the whole call (the process's, all its threads: it does
not count the time the process waits for a core on a shared machine, which the wall time does).
The binding's own cost is the rest of process()'s wall time (arguments, GIL, the mask as a numpy
array). Prints the medians over all rounds' sweeps (the first sweep of each round left out:
allocation) and each round's medians (the spread between rounds); fails unless both sides flag
the same points in every sweep.

  binding_overhead.py /work/data/data_2 --reference build/python/dynobj_python_bench_reference
"""
import argparse
import os
import statistics
import subprocess
import tempfile
import time

import numpy as np

import dynobj

KEYS = ("wall", "conversion", "detector", "cpu")


class PythonSide:
    def __init__(self, threads, sensor):
        self.detector = dynobj.Detector(config={"pipeline.threads": threads}, sensor=sensor)

    def process(self, points, t):
        cpu0 = time.process_time()
        start = time.perf_counter()
        mask = self.detector.process(points, t)
        end = time.perf_counter()
        cpu = (time.process_time() - cpu0) * 1e3
        timings = self.detector.timings()
        return ((end - start) * 1e3, timings["conversion"], timings["total"], cpu,
                int(np.count_nonzero(mask)))


class CppSide:
    def __init__(self, exe, folder, threads, sensor):
        args = [exe, folder, str(threads)] + ([sensor] if sensor else [])
        self.p = subprocess.Popen(args, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)

    def process(self):
        self.p.stdin.write("next\n")
        self.p.stdin.flush()
        line = self.p.stdout.readline().split()
        if len(line) != 5:
            raise SystemExit("binding_overhead: the C++ side stopped")
        conversion, detector, wall, cpu = (float(v) for v in line[:4])
        return wall, conversion, detector, cpu, int(line[4])

    def close(self):
        self.p.stdin.close()
        self.p.wait()


def write_sweeps(sweeps, folder):
    with open(os.path.join(folder, "sweeps.txt"), "w") as listing:
        for k, (points, t) in enumerate(sweeps):
            name = f"{k:06d}.f32"
            np.ascontiguousarray(points, np.float32).tofile(os.path.join(folder, name))
            cols = points.shape[1] if points.ndim == 3 else 0
            ns = int(np.datetime64(t, "ns").astype(np.int64))
            listing.write(f"{name} {points.shape[0]} {cols} {ns}\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("input", help="a rawlog or a folder of .pcd / .bin sweeps")
    ap.add_argument("--reference", default="build/python/dynobj_python_bench_reference",
                    help="the C++ side (cmake --build build --target "
                    "dynobj_python_bench_reference)")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--threads", type=int, default=1, choices=[1, 2])
    ap.add_argument("--sensor", help="sensor preset INI, for both")
    ap.add_argument("--sensor-label", default="", help="the LiDAR of a rawlog")
    a = ap.parse_args()
    if a.rounds < 1:
        raise SystemExit("binding_overhead: --rounds must be >= 1")
    if not os.access(a.reference, os.X_OK):
        raise SystemExit(f"binding_overhead: '{a.reference}' is not built (--reference)")
    sweeps = list(dynobj.read_sweeps(a.input, a.sensor, a.sensor_label))
    if len(sweeps) < 3:
        raise SystemExit(f"binding_overhead: '{a.input}' has {len(sweeps)} sweeps (3 or more)")
    got = {"py": {k: [] for k in KEYS}, "cpp": {k: [] for k in KEYS}}
    rounds = []
    with tempfile.TemporaryDirectory() as tmp:
        write_sweeps(sweeps, tmp)
        for _ in range(a.rounds):
            py, cpp = PythonSide(a.threads, a.sensor), CppSide(a.reference, tmp, a.threads,
                                                               a.sensor)
            this = {"py": {k: [] for k in KEYS}, "cpp": {k: [] for k in KEYS}}
            try:
                for k, (points, t) in enumerate(sweeps):
                    first, second = ("py", "cpp") if k % 2 == 0 else ("cpp", "py")
                    r = {}
                    for side in (first, second):
                        r[side] = py.process(points, t) if side == "py" else cpp.process()
                    if r["py"][4] != r["cpp"][4]:
                        raise SystemExit(f"binding_overhead: sweep {k}: Python flags {r['py'][4]} "
                                         f"points, C++ {r['cpp'][4]}")
                    if k == 0:
                        continue
                    for side in ("py", "cpp"):
                        for key, value in zip(KEYS, r[side]):
                            this[side][key].append(value)
            finally:
                cpp.close()
            for side in ("py", "cpp"):
                for key in KEYS:
                    got[side][key] += this[side][key]
            rounds.append({side: {key: statistics.median(this[side][key]) for key in ("wall", "cpu")}
                           for side in ("py", "cpp")})
    m = {side: {key: statistics.median(v) for key, v in d.items()} for side, d in got.items()}
    glue = statistics.median(w - c - d for w, c, d in
                             zip(got["py"]["wall"], got["py"]["conversion"], got["py"]["detector"]))

    def vs(p, c):
        return f"{100 * (p - c) / c:+.1f} %"

    shape = "x".join(str(n) for n in sweeps[0][0].shape)
    print(f"{a.input}: {len(sweeps)} sweeps ({shape} the first), {a.rounds} rounds, threads "
          f"{a.threads}; medians over {len(got['py']['wall'])} sweeps [ms]; the same points "
          "flagged")
    print(f"  {'':27s} {'wall':>7s} {'conversion':>11s} {'detector':>9s} {'CPU':>7s}")
    for name, side in (("C++ (reference)", "cpp"), ("Python Detector.process()", "py")):
        print(f"  {name:27s} " + " ".join(f"{m[side][key]:{w}.2f}" for key, w in
                                          zip(KEYS, (7, 11, 9, 7))))
    print(f"  Python against C++: wall {vs(m['py']['wall'], m['cpp']['wall'])}, CPU "
          f"{vs(m['py']['cpu'], m['cpp']['cpu'])}; the binding's own per call {glue:.2f} ms "
          f"({100 * glue / m['cpp']['wall']:.1f} % of the C++ wall)")
    for k, r in enumerate(rounds):
        print(f"  round {k}: wall Python {r['py']['wall']:7.2f} C++ {r['cpp']['wall']:7.2f} "
              f"({vs(r['py']['wall'], r['cpp']['wall']):>8s}), CPU Python {r['py']['cpu']:7.2f} "
              f"C++ {r['cpp']['cpu']:7.2f} ({vs(r['py']['cpu'], r['cpp']['cpu']):>8s})")


if __name__ == "__main__":
    main()
