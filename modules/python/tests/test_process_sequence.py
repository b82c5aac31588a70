# SPDX-License-Identifier: BSD-3-Clause
# dynobj.process_sequence: the offline loop (SequenceRunner) over a Python iterable: masks in
# order, one per sweep, streamed as the hindsight lag releases them; lag 0 = dynobj.Detector.
import warnings

import numpy as np
import pytest

import dynobj
from conftest import OS0_64_512, unordered


def test_lag_zero_gives_the_online_detectors_masks(hall_sweeps):
    d = dynobj.Detector()
    sweeps = [(unordered(image), t) for image, t in hall_sweeps]
    online = [d.process(p, t) for p, t in sweeps]
    seq = list(dynobj.process_sequence(sweeps, config={"hindsight.lag": 0}))
    assert len(seq) == len(online)
    for a, b in zip(online, seq):
        assert np.array_equal(a, b)
    assert sum(int(m.sum()) for m in online) > 1000


def test_hindsight_flags_more_than_online_and_keeps_the_layout(hall_sweeps):
    sweeps = list(hall_sweeps)
    online = list(dynobj.process_sequence(sweeps, {"hindsight.lag": 0}, OS0_64_512))
    offline = list(dynobj.process_sequence(sweeps, sensor=OS0_64_512))
    assert [m.shape for m in offline] == [(64, 512)] * len(sweeps)
    # hindsight flags the sweeps before a track was confirmed: the first sweeps most of all
    assert sum(int(m.sum()) for m in offline[:8]) > sum(int(m.sum()) for m in online[:8])


def test_masks_stream_once_the_lag_has_passed(hall_sweeps):
    taken = [0]

    def sweeps():
        for image, t in hall_sweeps:
            taken[0] += 1
            yield unordered(image), t

    it = dynobj.process_sequence(sweeps())  # lag 1 s at 10 Hz
    first = next(it)
    assert first.ndim == 1
    assert 2 <= taken[0] < len(hall_sweeps)  # held for the lag, not the whole sequence
    assert len(list(it)) == len(hall_sweeps) - 1


def test_an_empty_iterable_gives_no_mask():
    assert list(dynobj.process_sequence([])) == []


def test_bad_items_are_value_errors_and_end_the_sequence(hall_sweeps):
    image, t = hall_sweeps[0]
    it = dynobj.process_sequence([(image, t), (image[:, :, :3], t + np.timedelta64(100, "ms"))])
    with pytest.raises(ValueError, match=r"shape \(64, 512, 3\)"):
        list(it)
    with pytest.raises(StopIteration):
        next(it)
    with pytest.raises(ValueError, match="pair"):
        list(dynobj.process_sequence([image]))
    with pytest.raises(ValueError, match="unknown key 'hindsight.lagg'"):
        dynobj.process_sequence([], config={"hindsight.lagg": 0})


def test_faults_of_the_data_are_warnings_and_as_errors_end_the_sequence(hall_sweeps):
    pts = [unordered(image) for image, _ in hall_sweeps[:3]]
    sweeps = [(pts[0], 0.1), (pts[1], 0.2), (pts[1], 0.3), (pts[2], 0.4)]
    with pytest.warns(dynobj.DataFaultWarning, match="sweep 2: the same ranges") as record:
        masks = list(dynobj.process_sequence(sweeps))
    assert len(masks) == 4 and len(record) == 1
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        it = dynobj.process_sequence(sweeps)
        with pytest.raises(dynobj.DataFaultWarning, match="sweep 2"):
            list(it)
        with pytest.raises(StopIteration):
            next(it)
