# SPDX-License-Identifier: BSD-3-Clause
# Shared by the Python module's tests: where the sources, the apps and the sample are (ctest sets
# DYNOBJ_SOURCE_DIR and DYNOBJ_APPS, and PYTHONPATH to the built module), and small helpers.
import os
import shutil
import subprocess
import tempfile

import numpy as np
import pytest

SOURCE = os.environ.get("DYNOBJ_SOURCE_DIR",
                        os.path.abspath(os.path.join(os.path.dirname(__file__), "../../..")))
APPS = os.environ.get("DYNOBJ_APPS", os.path.join(SOURCE, "build", "apps"))
SHARE = os.path.join(SOURCE, "share", "dynobj")
HALL = os.path.join(SOURCE, "rawlogs", "hall-small", "hall-small.rawlog")
OS0_64_512 = os.path.join(SHARE, "sensors", "os0-64-512.ini")


@pytest.hookimpl(tryfirst=True)
def pytest_configure(config):
    """tmp_path and tmp_path_factory under a folder of TMPDIR that is removed when the tests end
    (pytest's default, TMPDIR/pytest-of-<user>, keeps the last three runs)."""
    if config.option.basetemp is None:
        base = tempfile.mkdtemp(prefix="dynobj-pytest-")
        config.option.basetemp = base
        config.add_cleanup(lambda: shutil.rmtree(base, ignore_errors=True))


def run_app(name, *args):
    """Runs a built app; fails the test with its output when it exits non-zero."""
    exe = os.path.join(APPS, name)
    if not os.path.exists(exe):
        pytest.fail(f"{exe} is not built (build the apps before the python tests)")
    p = subprocess.run([exe, *args], capture_output=True, text=True)
    assert p.returncode == 0, f"{name} {' '.join(args)} exited {p.returncode}:\n{p.stdout}{p.stderr}"
    return p.stdout


def label_file_text(rows, cols, stamps_ns, masks):
    """A dynamic-label file v1 (docs/formats.md section 6) of per-pixel masks."""
    lines = [f"# dynobj-labels v1 rows={rows} cols={cols}"]
    for t, m in zip(stamps_ns, masks):
        idx = np.flatnonzero(np.asarray(m).reshape(-1))
        lines.append(" ".join([str(t), str(len(idx))] + [str(i) for i in idx]))
    return "\n".join(lines) + "\n"


def ns(t):
    """A numpy.datetime64 as integer nanoseconds."""
    return int(np.datetime64(t, "ns").astype(np.int64))


@pytest.fixture(scope="session")
def hall_sweeps():
    """hall-small's 40 sweeps as the tools read them: (64, 512, 4) float32 images (NaN where no
    return) and their times (numpy.datetime64)."""
    import dynobj
    return list(dynobj.read_sweeps(HALL))


def unordered(image):
    """The returns of an organized image, row by row (the sensor's firing order): (N, 4)."""
    flat = image.reshape(-1, 4)
    return np.ascontiguousarray(flat[np.isfinite(flat[:, 0])])
