"""hhneck.ratings against the package objective-rating-metrics itself,
and the expected scores of the Fortran agreement test
(test/unit/data/iso18571_expected.csv, read by test/unit/test_iso18571.pf)
regenerated here from the package and compared with the file, so that the
stored numbers are the package's.

The curves of the agreement cases are closed formulas written the same way
here and in test_iso18571.pf (math.sin and math.exp of the same expressions
on t = i dt, so that both languages sample the same numbers). To write the
file again after changing a case (in both places):

    python3 test/python/test_iso18571.py --write
"""
import csv
import math
import os
import sys

import numpy as np
import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
if __name__ == "__main__":
    sys.path.insert(0, os.path.join(ROOT, "python"))
from hhneck import ratings as iso18571  # noqa: E402
from objective_rating_metrics.rating import ISO18571  # noqa: E402

EXPECTED = os.path.join(ROOT, "test", "unit", "data", "iso18571_expected.csv")
COLUMNS = ("case", "dt", "n") + iso18571.SCORES
DT = 1.0e-4
N = 1001          # 0 .. 100 ms at 10 kHz


def half_sine(t, t0=0.01, dur=0.06):
    """A half-sine pulse of unit height from t0 for dur [s], zero elsewhere."""
    if t < t0 or t > t0 + dur:
        return 0.0
    return math.sin(math.pi * (t - t0) / dur)


def noise(t):
    """Noise from a fixed formula: two sines at 910 and 1370 Hz."""
    return 0.02 * math.sin(2.0 * math.pi * 910.0 * t) + 0.01 * math.cos(2.0 * math.pi * 1370.0 * t + 0.3)


def damped(t, f=40.0, tau=0.03, phi=0.0):
    """A damped oscillation of frequency f [Hz], decay time tau [s], phase lag phi."""
    return math.exp(-t / tau) * math.sin(2.0 * math.pi * f * t - phi)


def triangle(t):
    """A triangle pulse of unit height at 40 ms, 60 ms wide."""
    return max(0.0, 1.0 - abs(t - 0.04) / 0.03)


# name: (dt, samples, reference(t), model(t))
CASES = {
    "half_sine_self": (DT, N, half_sine, half_sine),
    "half_sine_late_5ms": (DT, N, half_sine, lambda t: half_sine(t, t0=0.015)),
    "half_sine_early_3ms": (DT, N, half_sine, lambda t: half_sine(t, t0=0.007)),
    "half_sine_x0.8": (DT, N, half_sine, lambda t: 0.8 * half_sine(t)),
    "half_sine_x0.5": (DT, N, half_sine, lambda t: 0.5 * half_sine(t)),
    "half_sine_noise": (DT, N, half_sine, lambda t: half_sine(t) + noise(t)),
    "half_sine_wide_x1.2": (DT, N, half_sine, lambda t: 1.2 * half_sine(t, t0=0.008, dur=0.07)),
    "half_sine_late_25ms": (DT, N, half_sine, lambda t: half_sine(t, t0=0.035)),
    "triangle_vs_half_sine": (DT, N, half_sine, triangle),
    "damped_phase_0.4": (DT, N, damped, lambda t: damped(t, phi=0.4)),
    "damped_freq_tau": (DT, N, damped, lambda t: 1.1 * damped(t, f=45.0, tau=0.025)),
    "damped_4khz_x0.9_late": (2.5e-4, 401, damped, lambda t: 0.9 * damped(t - 0.002)),
}


def curves(name):
    """Times, reference and model of an agreement case."""
    dt, n, ref, mod = CASES[name]
    t = [i * dt for i in range(n)]
    return np.array(t), np.array([ref(x) for x in t]), np.array([mod(x) for x in t])


def package_scores(t, reference, model):
    """The package's unrounded scores on curves already at 10 kHz."""
    iso = ISO18571(np.column_stack((t, reference)), np.column_stack((t, model)), dt=DT)
    return dict(corridor=iso.corridor_rating(-1), phase=iso.phase_rating(-1),
                magnitude=iso.magnitude_rating(-1), slope=iso.slope_rating(-1),
                overall=iso.overall_rating(-1))


def expected_rows():
    """One row per case: the scores that hhneck-iso18571 gets from the package."""
    rows = []
    for name, (dt, n, _, _) in CASES.items():
        scores = iso18571.rate(*curves(name))
        rows.append([name, repr(dt), str(n)] + [repr(scores[k]) for k in iso18571.SCORES])
    return rows


def read_expected():
    with open(EXPECTED, newline="") as f:
        lines = [l for l in f if not l.startswith("#")]
    rows = list(csv.reader(lines))
    assert tuple(rows[0]) == COLUMNS
    return rows[1:]


def write_expected():
    with open(EXPECTED, "w", newline="") as f:
        f.write("# ISO/TS 18571 scores by objective-rating-metrics 1.3 (unrounded), written by\n"
                "# test/python/test_iso18571.py --write; the curves are defined there and in\n"
                "# test/unit/test_iso18571.pf\n")
        w = csv.writer(f, lineterminator="\n")
        w.writerow(COLUMNS)
        w.writerows(expected_rows())


# --- the stored numbers are the package's ------------------------------------

def test_expected_file_is_the_packages_scores():
    stored = read_expected()
    fresh = expected_rows()
    assert [r[:3] for r in stored] == [r[:3] for r in fresh], "the cases differ from the file's"
    for s, f in zip(stored, fresh):
        for col, a, b in zip(COLUMNS[3:], s[3:], f[3:]):
            assert float(a) == pytest.approx(float(b), abs=1e-12), "%s %s" % (s[0], col)


def test_expected_file_has_the_cases_the_fortran_test_rates():
    stored = read_expected()
    assert len(stored) >= 6
    pf = open(os.path.join(ROOT, "test", "unit", "test_iso18571.pf")).read()
    for row in stored:
        assert "'%s'" % row[0] in pf, row[0]


def test_the_cases_are_not_all_alike():
    """Every score takes values well away from 1 in some case."""
    stored = read_expected()
    for k, col in enumerate(COLUMNS[3:]):
        assert min(float(r[3 + k]) for r in stored) < 0.8, col


# --- hhneck-iso18571 against the package -----------------------------------

def test_identical_curves_rate_one():
    t, r, _ = curves("half_sine_self")
    scores = iso18571.rate(t, r, r.copy())
    for k in iso18571.SCORES:
        assert scores[k] == pytest.approx(1.0, abs=1e-12), k


def test_rate_is_the_package_at_10_khz():
    for name in ("half_sine_noise", "damped_phase_0.4", "triangle_vs_half_sine"):
        t, r, m = curves(name)
        ours = iso18571.rate(t, r, m)
        theirs = package_scores(t, r, m)
        for k in iso18571.SCORES:
            assert ours[k] == theirs[k], (name, k)


def test_rate_rounds_as_the_package_does():
    t, r, m = curves("damped_freq_tau")
    ours = iso18571.rate(t, r, m, ndigits=3)
    iso = ISO18571(np.column_stack((t, r)), np.column_stack((t, m)), dt=DT)
    assert ours == dict(corridor=iso.corridor_rating(), phase=iso.phase_rating(),
                        magnitude=iso.magnitude_rating(), slope=iso.slope_rating(),
                        overall=iso.overall_rating())
    assert all(round(v, 3) == v for v in ours.values())


def test_scaled_by_one_half_rates_lower_than_by_0_8():
    t, r, _ = curves("half_sine_self")
    half = iso18571.rate(t, r, 0.5 * r)
    most = iso18571.rate(t, r, 0.8 * r)
    assert half["overall"] < most["overall"] < 1.0
    assert half["magnitude"] < most["magnitude"] and half["corridor"] < most["corridor"]
    assert half["overall"] == package_scores(t, r, 0.5 * r)["overall"]


def test_a_shift_lowers_the_phase_score_only():
    t, r, m = curves("half_sine_late_5ms")
    s = iso18571.rate(t, r, m)
    # 50 samples of the 0.2 * 1001 allowed
    assert s["phase"] == pytest.approx((200.2 - 50) / 200.2, rel=1e-12)
    assert s["magnitude"] == pytest.approx(1.0, abs=1e-9)
    assert s["slope"] == pytest.approx(1.0, abs=1e-9)


def test_other_sampling_is_interpolated_to_10_khz():
    t, r, m = curves("damped_4khz_x0.9_late")
    grid, r10, m10 = iso18571.resample(t, r, m)
    assert grid.size == 1001 and grid[-1] == pytest.approx(0.1, abs=1e-15)
    assert np.allclose(r10, np.interp(grid, t, r), rtol=0, atol=0)
    assert iso18571.rate(t, r, m) == package_scores(grid, r10, m10)


def test_window_selects_the_interval_of_evaluation():
    t, r, m = curves("damped_phase_0.4")
    keep = (t >= 0.02) & (t <= 0.08)
    assert iso18571.rate(t, r, m, window=(0.02, 0.08)) == package_scores(t[keep], r[keep], m[keep])


def test_rate_many_means_the_overall_ratings():
    channels = {name: curves(name) for name in ("half_sine_x0.8", "damped_freq_tau", "half_sine_self")}
    many = iso18571.rate_many(channels)
    each = [iso18571.rate(*channels[name])["overall"] for name in channels]
    assert many["overall"] == pytest.approx(sum(each) / 3, rel=1e-15)
    assert set(many["channels"]) == set(channels)
    assert many["channels"]["half_sine_self"]["overall"] == pytest.approx(1.0)


def test_curves_that_cannot_be_rated_are_refused():
    t, r, m = curves("half_sine_self")
    with pytest.raises(ValueError):
        iso18571.rate(t, np.zeros_like(r), m)
    with pytest.raises(ValueError):
        iso18571.rate(t[:10], r[:10], m[:10])
    with pytest.raises(ValueError):
        iso18571.rate(t, r, m[:-1])
    with pytest.raises(ValueError):
        iso18571.rate_many({})


if __name__ == "__main__":
    if sys.argv[1:] == ["--write"]:
        write_expected()
        print("wrote", os.path.relpath(EXPECTED, ROOT))
    else:
        print(__doc__)
