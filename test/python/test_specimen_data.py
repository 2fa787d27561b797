"""The specimen cases' data readers (python/hhneck/validation/specimen_data.py):
corridor outlines split into their bounds against a band of known
boundaries, specimens averaged, and the pulses' velocity changes against
the figures the data's README gives."""
import os

import numpy as np
import pytest

from hhneck.validation import segments, specimen_data as sd

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


@pytest.mark.parametrize("turn", ["upper", "lower"])
def test_closing_edges_are_no_boundary(turn):
    """A band 0 to 10 digitised as the sources' outlines are: forward along
    one boundary, across at the largest time (the point of largest time on
    the upper boundary, or on the lower), back along the other and across
    again to a last point near the first. The midline is 5 wherever both
    boundaries have points: neither closing edge is taken for a boundary
    (cut at the largest time alone, the closing edge ends one boundary and
    the midline rises toward 10 over the last 0.2 ms)."""
    tu = np.arange(0.0, 101.0, 10.0)
    tl = np.arange(90.0, -1.0, -10.0)
    if turn == "upper":                  # ... (100, 10) -> (99.8, 0) -> (90, 0) ...
        t = np.concatenate([tu, [99.8], tl, [-0.3]])
        v = np.concatenate([np.full(tu.size, 10.0), [0.0], np.zeros(tl.size), [9.9]])
    else:                                # ... (99.8, 10) -> (100, 0) -> (90, 0) ...
        t = np.concatenate([tu[:-1], [99.8, 100.0], tl, [-0.3]])
        v = np.concatenate([np.full(tu.size, 10.0), [0.0], np.zeros(tl.size), [9.9]])
    grid, lo, hi, mid = sd.outline_bounds(t, v, dt=0.1)
    assert np.allclose(lo, 0.0, atol=1e-12) and np.allclose(hi, 10.0, atol=1e-12)
    assert np.allclose(mid, 5.0, atol=1e-12)
    assert grid[0] == pytest.approx(0.0) and 99.7 < grid[-1] <= 99.8 + 1e-9
    (ta, va), (tb, vb) = sd.outline_boundaries(t, v)
    # one boundary the upper (the last point, 9.9 near the first, with it), the other all zeros
    assert sorted([(va.min(), va.max()), (vb.min(), vb.max())]) == [(0.0, 0.0), (9.9, 10.0)]


def test_stemper_head_t1_midline_has_no_closing_edge():
    """Stemper's head-T1 corridor turns at (126.5 ms, 53.9 deg) and closes
    down to (126.2 ms, 20.7 deg): its midline ends at 37.4 deg, its largest
    value 37.6, with no jump over the last millisecond (the closing edge
    as a boundary made a "peak" of 49.5 deg at 126 ms)."""
    g, ref, lo, hi = sd.reference(os.path.join(DATA, "stemper2004_1p8ms_experiment.csv"), "head_T1_angle")
    assert ref[-1] == pytest.approx(37.4, abs=0.05) and ref.max() == pytest.approx(37.6, abs=0.05)
    assert abs(ref[-1] - ref[-11]) < 0.5 and 126.0 < g[-1] < 126.3
    assert np.max(np.abs(np.diff(ref))) < 0.5                            # no step anywhere on the 0.1 ms grid


def test_reference_curve_is_named(tmp_path):
    """A channel with two corridor outlines and a specimen: without a name
    the choice is refused (naming the curves), never the first in the
    file; a named outline gives its own midline, named specimens their
    mean; a name the file does not have is refused."""
    rows = ["channel,specimen_or_bound,point,time_ms,value,unit,source_columns"]
    for name, level in (("a_corridor_outline", 0.0), ("b_corridor_outline", 20.0)):
        t = [0.0, 50.0, 100.0, 100.0, 50.0, 0.0]
        v = [level + 2, level + 2, level + 2, level, level, level]
        rows += ["x,%s,%d,%g,%g,deg,X" % (name, k, tk, vk) for k, (tk, vk) in enumerate(zip(t, v))]
    rows += ["x,pmhs1,%d,%g,%g,deg,X" % (k, tk, 3.0 * tk) for k, tk in enumerate((0.0, 100.0))]
    rows += ["y,pmhs1,0,0,1,deg,X", "y,pmhs1,1,100,1,deg,X", "y,pmhs2,0,0,3,deg,X", "y,pmhs2,1,100,3,deg,X"]
    path = tmp_path / "two.csv"
    path.write_text("\n".join(rows) + "\n")
    with pytest.raises(ValueError, match="a_corridor_outline, b_corridor_outline, pmhs1"):
        sd.reference(str(path), "x")
    g, ref, lo, hi = sd.reference(str(path), "x", "b_corridor_outline")
    assert np.allclose(ref, 21.0) and np.allclose(lo, 20.0) and np.allclose(hi, 22.0)
    g, ref, lo, hi = sd.reference(str(path), "x", ("pmhs1",))
    assert np.allclose(ref, 3.0 * g)
    with pytest.raises(ValueError, match="no curve pmhs9"):
        sd.reference(str(path), "x", ("pmhs1", "pmhs9"))
    g, ref, lo, hi = sd.reference(str(path), "y")                       # specimens only: their mean
    assert np.allclose(ref, 2.0) and np.allclose(lo, 1.0) and np.allclose(hi, 3.0)


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
    assert ref.max() > 30.0                                              # the head extends relative to T1
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
