"""The specimen cases' data readers (python/hhneck/specimen_data.py):
corridor outlines split into their bounds against a band of known
boundaries, specimens averaged, and the pulses' velocity changes against
the figures the data's README gives."""
import os

import numpy as np
import pytest

from hhneck import segments, specimen_data as sd

DATA = segments.DATA_DIR


def test_outline_of_a_known_band():
    """An outline drawn forward along sin(t/20) + 1 and back along
    sin(t/20), with unequal point spacing and a 1 ms back-step: bounds,
    midline and the covered times come back."""
    tu = np.array([0.0, 7.0, 15.0, 14.0, 30.0, 55.0, 80.0, 100.0])       # 15 -> 14: a back-step
    tl = np.array([100.0, 90.0, 61.0, 40.0, 22.0, 9.0, 0.5])
    t = np.concatenate([tu, tl])
    v = np.concatenate([np.sin(tu / 20) + 1, np.sin(tl / 20)])
    grid, lo, hi, mid = sd.outline_bounds(t, v, dt=0.5)
    assert grid[0] == pytest.approx(0.5) and grid[-1] == pytest.approx(100.0)
    # linear interpolation between the digitised points: compare at them
    for tk in (7.0, 30.0, 55.0, 80.0):
        assert np.interp(tk, grid, hi) == pytest.approx(np.sin(tk / 20) + 1, abs=1e-12)
    for tk in (9.0, 22.0, 40.0, 61.0, 90.0):
        assert np.interp(tk, grid, lo) == pytest.approx(np.sin(tk / 20), abs=1e-12)
    assert np.all(hi >= lo) and np.allclose(mid, 0.5 * (lo + hi))
    with pytest.raises(ValueError):
        sd.outline_bounds(np.arange(5.0), np.zeros(5))                  # time only rises: not an outline


def test_specimen_mean_over_common_times():
    curves = {"a": (np.array([0.0, 10.0, 20.0]), np.array([0.0, 10.0, 20.0])),
              "b": (np.array([5.0, 25.0, 15.0]), np.array([15.0, 35.0, 25.0]))}   # unsorted points
    grid, mean = sd.specimen_mean(curves, dt=1.0)
    assert grid[0] == 5.0 and grid[-1] == 20.0
    assert np.allclose(mean, grid + 5.0)                                 # (t + (t + 10)) / 2


def test_stemper_reference_curves():
    path = os.path.join(DATA, "stemper2004_1p8ms_experiment.csv")
    curves = sd.read_curves(path)
    assert sorted(curves) == ["head_T1_angle", "head_T1_retraction"] + ["seg_angle_C%d_C%d" % (k, k + 1)
                                                                          for k in range(2, 7)]
    g, ref, lo, hi = sd.reference(path, "head_T1_angle")
    assert 0.0 < g[0] < 1.0 and 126.0 < g[-1] < 127.0                   # the corridors' 0 to 126 ms
    assert np.all(hi >= lo) and np.all((ref >= lo) & (ref <= hi))
    # the outline's own extremes bound the midline's (README: -2.62 to 55.3 deg)
    t, v = curves["head_T1_angle"]["stemper2004_corridor_outline"]
    assert v.min() <= ref.min() and ref.max() <= v.max()
    assert ref.max() > 40.0                                              # the head extends relative to T1
    g, ref, lo, hi = sd.reference(path, "head_T1_retraction")
    assert ref.min() < -80.0 and ref.max() < 0.0                         # rearward, README -104 to 3 mm


def test_kang_side_reference_is_the_specimens_mean():
    path = os.path.join(DATA, "kang2018_side_experiment.csv")
    by = sd.read_curves(path)["head_rot_x"]
    assert sorted(by) == ["pmhs1", "pmhs2"]
    g, ref, lo, hi = sd.reference(path, "head_rot_x")
    k = np.argmin(ref)
    each = [np.interp(g[k], *sd._as_function(*by[n])) for n in ("pmhs1", "pmhs2")]
    assert ref[k] == pytest.approx(np.mean(each)) and lo[k] == pytest.approx(min(each))


def test_pulses_velocity_change_as_the_readme_gives():
    t, a = sd.read_pulse(os.path.join(DATA, "stemper2004_1p8ms_pulse.csv"))
    # README: 1.814 m/s at 100 ms, 1.833 at 150 ms, 1.863 at 1000 ms
    assert [round(sd.delta_v(t, a, x), 3) for x in (0.1, 0.15, 1.0)] == [1.814, 1.833, 1.863]
    t, a = sd.read_pulse(os.path.join(DATA, "kang2018_sled_pulse.csv"))
    # README: 3.7444 m/s at 100 ms, 2.7370 at 500 ms, largest 3.9070 at 67 ms
    assert sd.delta_v(t, a, 0.1) == pytest.approx(3.7444, abs=0.003)
    assert sd.delta_v(t, a, 0.5) == pytest.approx(2.7370, abs=0.003)
    ts = np.arange(0.001, 0.5, 0.001)
    dv = [sd.delta_v(t, a, x) for x in ts]
    assert max(dv) == pytest.approx(3.9070, abs=0.003) and ts[int(np.argmax(dv))] == pytest.approx(0.067, abs=0.002)
