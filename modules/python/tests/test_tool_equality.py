# SPDX-License-Identifier: BSD-3-Clause
# The module gives what the C++ tools give, byte for byte, on the committed sample
# (rawlogs/hall-small, 40 sweeps of an OS0-64 512 x 10):
#  - organized images (the rawlog's 3D range scans as dynobj.read_sweeps returns them):
#    dynobj.Detector vs dynobj-detect with [hindsight] lag = 0, dynobj.process_sequence vs
#    dynobj-detect (offline by default), compared as label files v1;
#  - unordered sweeps (each image's returns row by row) in a KITTI folder of .bin files: the
#    example kitti_to_semantickitti.py (online and offline) vs dynobj-eval --predictions-out of the
#    same folder, compared as SemanticKITTI .label files.
import os
import subprocess
import sys

import numpy as np
import pytest

import dynobj
from conftest import HALL, OS0_64_512, SHARE, label_file_text, ns, run_app, unordered

EXAMPLE = os.path.join(SHARE, "python", "kitti_to_semantickitti.py")


@pytest.fixture(scope="module")
def lag0_ini(tmp_path_factory):
    p = tmp_path_factory.mktemp("cfg") / "online.ini"
    p.write_text("[hindsight]\nlag = 0\n")
    return str(p)


def test_organized_online_equals_dynobj_detect(hall_sweeps, lag0_ini, tmp_path):
    out = tmp_path / "cpp.labels"
    run_app("dynobj-detect", "-i", HALL, "--sensor", OS0_64_512, "-c", lag0_ini, "-o", str(out),
            "-q")
    d = dynobj.Detector(sensor=OS0_64_512)
    masks = [d.process(image, t) for image, t in hall_sweeps]
    mine = label_file_text(64, 512, [ns(t) for _, t in hall_sweeps], masks)
    assert sum(int(m.sum()) for m in masks) > 1000
    assert mine.encode() == out.read_bytes()


def test_organized_offline_equals_dynobj_detect(hall_sweeps, tmp_path):
    out = tmp_path / "cpp.labels"
    run_app("dynobj-detect", "-i", HALL, "--sensor", OS0_64_512, "-o", str(out), "-q")
    masks = list(dynobj.process_sequence(hall_sweeps, sensor=OS0_64_512))
    mine = label_file_text(64, 512, [ns(t) for _, t in hall_sweeps], masks)
    assert mine.encode() == out.read_bytes()


@pytest.fixture(scope="module")
def hall_bin_folder(hall_sweeps, tmp_path_factory):
    """hall-small's sweeps as a KITTI velodyne folder, and an all-static SemanticKITTI truth."""
    root = tmp_path_factory.mktemp("hall-kitti")
    velodyne, truth = root / "velodyne", root / "truth"
    velodyne.mkdir()
    truth.mkdir()
    for k, (image, _) in enumerate(hall_sweeps):
        pts = unordered(image)
        pts.astype("<f4").tofile(velodyne / f"{k:06d}.bin")
        np.full(len(pts), dynobj.SEMANTIC_KITTI_STATIC, "<u4").tofile(truth / f"{k:06d}.label")
    return root


@pytest.mark.parametrize("mode", ["online", "offline"])
def test_unordered_example_equals_dynobj_eval_predictions(hall_bin_folder, mode, tmp_path):
    root = hall_bin_folder
    run_app("dynobj-eval", "--run", str(root / "velodyne"), "--truth", str(root / "truth"),
            "--modes", mode, "--predictions-out", str(tmp_path / "cpp"), "-o",
            str(tmp_path / "report"), "-q")
    args = [sys.executable, EXAMPLE, str(root / "velodyne"), str(tmp_path / "py")]
    if mode == "online":
        args.append("--online")
    p = subprocess.run(args, capture_output=True, text=True)
    assert p.returncode == 0, p.stdout + p.stderr
    names = sorted(os.listdir(root / "velodyne"))
    moving = 0
    for n in names:
        label = n.replace(".bin", ".label")
        mine = (tmp_path / "py" / label).read_bytes()
        assert mine == (tmp_path / "cpp" / mode / label).read_bytes(), label
        moving += int((np.frombuffer(mine, "<u4") == dynobj.SEMANTIC_KITTI_MOVING).sum())
    assert moving > 1000


def test_example_refuses_to_overwrite_and_names_bad_sweeps(hall_bin_folder, tmp_path):
    root = hall_bin_folder
    out = tmp_path / "py"
    args = [sys.executable, EXAMPLE, str(root / "velodyne"), str(out), "--online"]
    assert subprocess.run(args, capture_output=True).returncode == 0
    before = (out / "000000.label").read_bytes()
    p = subprocess.run(args, capture_output=True, text=True)
    assert p.returncode != 0 and "exists" in p.stderr
    assert (out / "000000.label").read_bytes() == before
    bad = tmp_path / "bad"
    bad.mkdir()
    (bad / "000000.bin").write_bytes((root / "velodyne" / "000000.bin").read_bytes())
    (bad / "000001.bin").write_bytes(b"\0" * 20)
    p = subprocess.run([sys.executable, EXAMPLE, str(bad), str(tmp_path / "o")], capture_output=True,
                       text=True)
    assert p.returncode != 0 and "000001.bin" in p.stderr and "multiple of 16" in p.stderr
    assert not (tmp_path / "o").exists() or not os.listdir(tmp_path / "o")  # no partial output
    empty = tmp_path / "empty"
    empty.mkdir()
    p = subprocess.run([sys.executable, EXAMPLE, str(empty), str(tmp_path / "o2")],
                       capture_output=True, text=True)
    assert p.returncode != 0 and "no .bin sweep" in p.stderr
