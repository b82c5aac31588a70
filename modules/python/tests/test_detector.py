# SPDX-License-Identifier: BSD-3-Clause
# dynobj.Detector: masks in the input's layout, tracks, timings, the GIL released while it runs,
# and every user mistake a ValueError naming the bad shape, dtype, key, value or timestamp.
import os
import threading
import warnings
import time

import numpy as np
import pytest

import dynobj
from conftest import OS0_64_512, SHARE, unordered


def test_unordered_sweeps_give_one_flag_per_input_point(hall_sweeps):
    d = dynobj.Detector()
    flagged = 0
    for image, t in hall_sweeps[:20]:
        pts = unordered(image)
        mask = d.process(pts, t)
        assert mask.dtype == np.bool_ and mask.shape == (len(pts),)
        flagged += int(mask.sum())
    assert flagged > 500  # the hall's walkers, once their tracks are confirmed


def test_organized_sweeps_give_one_flag_per_pixel_and_none_where_no_return(hall_sweeps):
    d = dynobj.Detector(sensor=OS0_64_512)
    flagged = 0
    for image, t in hall_sweeps[:20]:
        mask = d.process(image, t)
        assert mask.dtype == np.bool_ and mask.shape == (64, 512)
        assert not mask[~np.isfinite(image[:, :, 0])].any()
        flagged += int(mask.sum())
    assert flagged > 500


def test_float64_input_gives_the_float32_result(hall_sweeps):
    a, b = dynobj.Detector(), dynobj.Detector()
    for image, t in hall_sweeps[:15]:
        pts = unordered(image)
        assert np.array_equal(a.process(pts, t), b.process(pts.astype(np.float64), t))


def test_non_contiguous_input_is_read_as_given(hall_sweeps):
    a, b = dynobj.Detector(), dynobj.Detector()
    for image, t in hall_sweeps[:12]:
        pts = unordered(image)
        wide = np.zeros((len(pts), 8), np.float32)
        wide[:, ::2] = pts  # every other column: a strided view
        assert np.array_equal(a.process(pts, t), b.process(wide[:, ::2], t))


def test_tracks_describe_the_flagged_objects(hall_sweeps):
    d = dynobj.Detector()
    dynamic_seen = 0
    for image, t in hall_sweeps[:30]:
        pts = unordered(image)
        mask = d.process(pts, t)
        for tr in d.tracks():
            assert set(tr) >= {"id", "box", "velocity", "dynamic", "centroid"}
            c, s = np.array(tr["box"]["center"]), np.array(tr["box"]["size"])
            assert (s >= 0).all()
            assert (np.abs(np.array(tr["centroid"]) - c) <= s / 2 + 1e-6).all()
            if not tr["dynamic"]:
                continue
            dynamic_seen += 1
            inside = (np.abs(pts[:, :3] - c) <= s / 2 + 0.05).all(axis=1)
            assert (mask & inside).sum() > 0  # its points are flagged
            assert np.hypot(*tr["velocity"]) > 0.1
    assert dynamic_seen > 5
    t = d.timings()
    assert t["total"] > 0 and t["conversion"] > 0
    assert set(t) >= {"foreground", "ego_motion", "clustering", "region_growing", "conversion"}
    assert dynobj.Detector().timings() == {}  # before the first sweep


def test_the_gil_is_released_while_the_detector_runs(hall_sweeps):
    d = dynobj.Detector()
    for image, t in hall_sweeps[:5]:
        d.process(unordered(image), t)
    count, stop = [0], [False]

    def spin():
        while not stop[0]:
            count[0] += 1

    th = threading.Thread(target=spin)
    th.start()
    try:
        time.sleep(0.05)
        image, t = hall_sweeps[5]
        pts = np.tile(unordered(image), (8, 1))  # a long call (8 x the points)
        before = count[0]
        start = time.perf_counter()
        d.process(pts, t)
        elapsed = time.perf_counter() - start
        during = count[0] - before
    finally:
        stop[0] = True
        th.join()
    # A call holding the GIL would freeze the other thread for its whole duration.
    assert elapsed > 0.005
    assert during > 1000, f"{during} increments in {elapsed * 1e3:.0f} ms"


@pytest.mark.parametrize("shape,dtype,what", [
    ((100, 3), np.float32, r"shape \(100, 3\)"),
    ((100,), np.float32, r"shape \(100,\)"),
    ((64, 512, 3), np.float32, r"shape \(64, 512, 3\)"),
    ((2, 64, 512, 4), np.float32, r"shape \(2, 64, 512, 4\)"),
    ((100, 4), np.int32, "dtype int32"),
    ((100, 4), np.float16, "dtype float16"),
])
def test_bad_shapes_and_dtypes_are_value_errors_naming_them(shape, dtype, what):
    with pytest.raises(ValueError, match=what):
        dynobj.Detector().process(np.zeros(shape, dtype), 0.1)


def test_a_list_or_an_empty_array_is_a_value_error():
    with pytest.raises(ValueError, match="numpy array"):
        dynobj.Detector().process([[0, 0, 0, 0]], 0.1)
    with pytest.raises(ValueError, match="no point"):
        dynobj.Detector().process(np.zeros((0, 4), np.float32), 0.1)


def test_a_sweep_whose_rows_cannot_be_recovered_asks_for_the_sensor(hall_sweeps):
    pts = unordered(hall_sweeps[0][0])
    shuffled = pts[np.random.default_rng(3).permutation(len(pts))]  # no firing order, no ring
    with pytest.raises(ValueError, match=r"^points: .*rows cannot be recovered.*sensor="):
        dynobj.Detector().process(shuffled, 0.1)
    mask = dynobj.Detector(sensor=OS0_64_512).process(shuffled, 0.1)  # the preset's table
    assert mask.shape == (len(pts),)


def test_timestamps_must_increase_and_be_times(hall_sweeps):
    image, _ = hall_sweeps[0]
    pts = unordered(image)
    d = dynobj.Detector()
    d.process(pts, 1.0)
    with pytest.raises(ValueError, match="not after the previous"):
        d.process(pts, 1.0)
    for bad in (float("nan"), np.datetime64("NaT"), "soon", -1.0):
        with pytest.raises(ValueError, match="timestamp"):
            dynobj.Detector().process(pts, bad)
    d.process(pts, np.datetime64(1_100_000_000, "ns"))  # seconds and datetime64 mix


@pytest.mark.parametrize("config,what", [
    ({"foreground.threshhold": 1}, r"unknown key 'foreground.threshhold'.*foreground\.threshold"),
    ({"forground.threshold": 1}, r"unknown section 'forground'.*'foreground'"),
    ({"threshold": 1}, "not 'section.key'"),
    ({"foreground.threshold": "abc"}, "threshold"),
    ({"hindsight.lag": -1}, "lag"),
    ({"pipeline.threads": {}}, "pipeline.threads"),
])
def test_bad_config_keys_and_values_are_value_errors_naming_them(config, what):
    with pytest.raises(ValueError, match=what):
        dynobj.Detector(config=config)


def test_config_from_a_dict_equals_the_same_ini(hall_sweeps, tmp_path):
    ini = tmp_path / "my.ini"
    ini.write_text("[clustering]\nmin_points = 12\n[pipeline]\nthreads = 1\n")
    a = dynobj.Detector(config=str(ini))
    b = dynobj.Detector(config={"clustering.min_points": 12, "pipeline.threads": 1})
    c = dynobj.Detector()
    differ = 0
    for image, t in hall_sweeps[:25]:
        pts = unordered(image)
        ma, mb, mc = a.process(pts, t), b.process(pts, t), c.process(pts, t)
        assert np.array_equal(ma, mb)
        differ += int((ma != mc).sum())
    assert differ > 0  # the parameter was read


def test_bad_config_and_sensor_files_are_value_errors_naming_them(tmp_path):
    ini = tmp_path / "typo.ini"
    ini.write_text("[foreground]\nthreshhold = 3\n")
    with pytest.raises(ValueError, match=r"typo.ini:2: unknown key 'threshhold'"):
        dynobj.Detector(config=ini)
    with pytest.raises(ValueError, match="missing.ini"):
        dynobj.Detector(config=str(tmp_path / "missing.ini"))
    with pytest.raises(ValueError, match="missing.ini"):
        dynobj.Detector(sensor=str(tmp_path / "missing.ini"))
    with pytest.raises(ValueError, match="config"):
        dynobj.Detector(config=42)
    dynobj.Detector(config=os.path.join(SHARE, "config", "dynobj.ini"),
                    sensor=os.path.join(SHARE, "sensors", "hdl-64.ini"))


def test_an_organized_array_that_is_not_the_presets_size_is_a_value_error():
    with pytest.raises(ValueError, match=r"64x1024 but the sensor preset .* is 64x512"):
        dynobj.Detector(sensor=OS0_64_512).process(np.zeros((64, 1024, 4), np.float32), 0.1)


def test_faults_of_the_data_are_warnings_naming_the_sweep(hall_sweeps):
    (a, _), (b, _), (c, _) = hall_sweeps[:3]
    d = dynobj.Detector()
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # clean data: no warning
        first = d.process(unordered(a), 0.1)
        second = d.process(unordered(b), 0.2)
    with pytest.warns(dynobj.DataFaultWarning, match="sweep 2: the same ranges"):
        repeat = d.process(unordered(b), 0.3)  # a stale sensor repeating its sweep
    assert np.array_equal(repeat, second)  # not used: the sweep before's mask
    with pytest.warns(dynobj.DataFaultWarning, match=r"sweep 3: a gap of 4\.700 s"):
        d.process(unordered(c), 5.0)
    assert issubclass(dynobj.DataFaultWarning, UserWarning) and first.shape == (len(unordered(a)),)
