# SPDX-License-Identifier: BSD-3-Clause
# Real data: the 22 HDL-64 sweeps of ../shared/realdata/kitti-hdl64-city-22 (PCD, unordered, rows
# recovered from the firing order), read by dynobj.read_sweeps, give per point what dynobj-eval
# --predictions-out gives for the folder, online and offline. Skipped when the folder is absent.
import os

import numpy as np
import pytest

import dynobj
from conftest import SOURCE, run_app

CITY = os.path.normpath(os.path.join(SOURCE, "..", "shared", "realdata", "kitti-hdl64-city-22"))

pytestmark = pytest.mark.skipif(not os.path.isdir(CITY),
                                reason=f"real data absent: {CITY} (see docs/python.md)")


@pytest.mark.parametrize("mode", ["online", "offline"])
def test_city_masks_equal_dynobj_eval_predictions(mode, tmp_path):
    sweeps = list(dynobj.read_sweeps(CITY))
    assert len(sweeps) == 22 and all(p.ndim == 2 for p, _ in sweeps)
    truth = tmp_path / "truth"
    truth.mkdir()
    for k, (pts, _) in enumerate(sweeps):
        np.full(len(pts), dynobj.SEMANTIC_KITTI_STATIC, "<u4").tofile(truth / f"{k:06d}.label")
    run_app("dynobj-eval", "--run", CITY, "--truth", str(truth), "--modes", mode,
            "--predictions-out", str(tmp_path / "cpp"), "-o", str(tmp_path / "report"), "-q")
    if mode == "online":
        d = dynobj.Detector()
        masks = [d.process(p, t) for p, t in sweeps]
    else:
        masks = list(dynobj.process_sequence(sweeps))
    moving = 0
    for k, ((pts, _), m) in enumerate(zip(sweeps, masks)):
        assert m.shape == (len(pts),)
        cpp = np.fromfile(tmp_path / "cpp" / mode / f"{k:06d}.label", "<u4")
        assert np.array_equal(cpp == dynobj.SEMANTIC_KITTI_MOVING, m), f"sweep {k}"
        moving += int(m.sum())
    assert moving > 1000
