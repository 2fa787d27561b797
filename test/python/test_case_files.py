"""Case files (reference/cases, docs/case-files.md): the given cases read
from their files, a file with a wrong key refused naming the file and the
key, and a new direction made by a new file alone: an oblique Kang sled
(the front case's pulse along (-1, -1, 0)/sqrt 2) written into a temporary
folder and run by the catalogue's own steps, its potted body moved along
the direction as the pulse's double integral says."""
import argparse
import os

import h5py
import numpy as np
import pytest

from conftest import hhneck_executable
from hhneck.validation import catalogue, segments, specimen_data, specimens


def test_given_cases_are_files():
    assert [c["name"] for c in specimens.load_cases()] == ["stemper", "kang_front", "kang_side", "twist_demo"]
    assert [c["rated"] for c in specimens.load_cases()] == [True, True, True, False]
    assert specimens.CASES["kang_side"]["reference"]["curve"] == ("pmhs1", "pmhs2")
    assert specimens.CASES["kang_front"]["window"] == {"kind": "peak", "search": (0.0, 99.9), "factor": 1.2}
    assert specimens.ANGLES[("kang_front", "head_rot_y")] == ("integrated", "HEAD_OMEGY")
    assert specimens.ANGLES[("stemper", "head_T1_angle")] == ("planar", "HEAD", "T1", "y")
    assert [c[4] for c in specimens.CHANNELS["kang_side"]] == [180, 180, 180, 180, 60, 60]


def _write(path, text):
    with open(path, "w") as f:
        f.write(text)
    return str(path)


def _front_with(**changes):
    """The Kang front case file's text with some of its lines replaced."""
    text = open(specimens.CASES["kang_front"]["path"]).read()
    for old, new in changes.items():
        assert old in text
        text = text.replace(old, new)
    return text


@pytest.mark.parametrize("old, new, message", [
    ('kind = "HOLD"', 'kind = "CABLES"', r"bad.toml \[support\]: kind 'CABLES'"),
    ("direction = [-1.0, 0.0, 0.0]", "direction = [-1.0, 0.0]", r"\[pulse\]: key 'direction' .* expected 3 numbers"),
    ("cfc = 60", "cfc = 50", r"\[\[channel\]\] 1: cfc 50"),
    ('definition = "integrated"', 'definition = "euler"', r"\[\[channel\]\] 3: definition 'euler'"),
    ('title = "Kang 2018 front 14 km/h"\n', "", r"bad.toml: missing key 'title'")])
def test_bad_keys_are_named(tmp_path, old, new, message):
    p = _write(tmp_path / "bad.toml", _front_with(**{old: new}))
    with pytest.raises(specimens.CaseError, match=message):
        specimens.load_case(p)


OBLIQUE = {'name = "kang_front"': 'name = "kang_oblique"',
           'title = "Kang 2018 front 14 km/h"': 'title = "Kang 2018 oblique 14 km/h (demonstration)"',
           'newton_balance = "front"\n': "",
           "direction = [-1.0, 0.0, 0.0]": "direction = [-0.70710678, -0.70710678, 0.0]",
           "end_time = 0.2": "end_time = 0.12"}


def test_oblique_deck(tmp_path):
    case = specimens.load_case(_write(tmp_path / "oblique.toml", _front_with(**OBLIQUE)))
    text = open(specimens.case_deck(case, str(tmp_path))).read().splitlines()
    assert "PRESCRIB  T1        TX        ACCEL     KANGX     0.0       0.0" in text
    assert "PRESCRIB  T1        TY        ACCEL     KANGY     0.0       0.0" in text
    assert not any(line.startswith("PRESCRIB  T1        TX        CONSTANT") for line in text)
    assert "PRESCRIB  T1        TZ        CONSTANT" in text
    t, a = specimen_data._as_function(*specimen_data.read_pulse(os.path.join(segments.DATA_DIR,
                                                                            "kang2018_sled_pulse.csv")))
    for comp in ("x", "y"):
        v = np.loadtxt(tmp_path / ("kang_oblique_pulse_%s.csv" % comp), delimiter=",", skiprows=1)
        assert np.allclose(v[:, 1], -0.70710678 * a, rtol=1e-8, atol=1e-6)


def test_new_direction_is_a_file(tmp_path):
    """The catalogue's steps on a folder holding one new case file: it is
    built, run and rated with no code; T1 moves along the file's direction
    by the pulse's double integral (x(T) = int_0^T (T - s) a(s) ds)."""
    folder = tmp_path / "cases"
    folder.mkdir()
    _write(folder / "kang_oblique.toml", _front_with(**OBLIQUE))
    work = tmp_path / "work"
    work.mkdir()
    a = argparse.Namespace(cases=str(folder), exe=hhneck_executable(), data=segments.DATA_DIR, quick=True, jobs=1)
    steps = dict(catalogue.catalogue_steps(a, str(work)))
    title = "Kang 2018 oblique 14 km/h (demonstration)"
    assert title in steps and not any("front" in name for name in steps)
    pr = catalogue.Progress(str(tmp_path / "r.md"), 1, [title], 1)
    steps[title](pr)
    rated, _ = pr.cases[title]
    assert sorted(rated) == sorted(specimens.CHANNELS["kang_front"][k][0] for k in range(6))
    assert all(0.0 <= v["overall"] <= 1.0 for v in rated.values())
    with h5py.File(work / "kang_oblique_hold_passive.h5", "r") as f:
        names = [n.decode() if isinstance(n, bytes) else str(n) for n in f["model"].attrs["bodies"]]
        time, pos = f["time"][:], f["bodies/position"][:, names.index("T1"), :]
    t, acc = specimen_data._as_function(*specimen_data.read_pulse(os.path.join(segments.DATA_DIR,
                                                                              "kang2018_sled_pulse.csv")))
    s = np.linspace(0.0, time[-1], 200001)
    closed = np.trapezoid((time[-1] - s) * np.interp(s, t, acc), s)
    moved = pos[-1] - pos[0]
    assert closed > 0.2                                     # the sled has moved well over 20 cm
    assert moved[0] == pytest.approx(-closed / np.sqrt(2), rel=1e-3)
    assert moved[1] == pytest.approx(-closed / np.sqrt(2), rel=1e-3)
    assert abs(moved[2]) < 1e-6
    report = catalogue.write_report([], str(tmp_path / "r.md"), 1.0, 1, pr.cases, {}, {}, {}, [], None, False)
    assert title in open(str(tmp_path / "r.md")).read()


def test_twist_demo_deck(tmp_path):
    """The demonstration twist case: T1 held whole, no pulse, the clamp's
    cards after the model deck."""
    text = open(specimens.case_deck("twist_demo", str(tmp_path))).read().splitlines()
    include = text.index("INCLUDE   input/head_neck_54dof.inp")
    assert text.index("CLAMP     RIG       HEAD      R         1.0E6     2000.0    1.0E4     20.0") > include
    assert sum(line.startswith("PRESCRIB  T1") and "CONSTANT" in line for line in text) == 6
    assert not any("ACCEL" in line or line.startswith("HOLD") for line in text)


def test_twist_demo_runs(tmp_path):
    """The demonstration twist case runs to its end (1 s, its energy
    balance kept): the rig's angle is 20 deg/s times t, and the neck resists
    the twist (the clamp's couple about the vertical grows with it)."""
    specimens.run_case("twist_demo", str(tmp_path), hhneck_executable())
    with h5py.File(tmp_path / "twist_demo_clamp_passive.h5", "r") as f:
        t, angle, mz = f["time"][:], f["channels"]["RIG_A"][:], f["channels"]["RIG_MZ"][:]
    assert t[-1] == pytest.approx(1.0)
    assert np.max(np.abs(angle - np.degrees(20.0 * 0.01745329) * t)) < 1e-9
    half = np.searchsorted(t, 0.5)
    assert 0.0 < mz[half] < mz[-1]
