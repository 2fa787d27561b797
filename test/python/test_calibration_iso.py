"""The calibration objective's ISO/TS 18571 (src/sweeps/hn_calibrate.f90 with
src/analysis/hn_iso18571.f90) against objective-rating-metrics
(hhneck.iso18571) on the same two curves: a calibration deck in
evaluate-only form (FIT with 0 evaluations, RATING F5 ISO18571) writes the
curves it rated (CURVES card) and prints each channel's scores to six
digits; the package, given those curves, gives the same scores. Two kinds
of case: the NBDL 15 g volunteers (their mean on the RATING window) and the
Stemper 2004 specimen case with a reference CSV and RATED cards
(hhneck.calibration), whose case mean is the catalogue's. Then the leave-one-out command's quick form: the
table it writes, the fitted value within its bounds, and the prediction
equal to an evaluation of the left-out case at the fitted value."""
import os
import re
import subprocess

import numpy as np
import pandas as pd
import pytest

from conftest import hhneck_executable
from hhneck import calibration, iso18571, segments, specimens

# printed to 6 decimals: the rounding is 5e-7; the tolerance is far above it
# and far below a score difference that matters (1e-3)
TOL = 2e-6

NBDL = """TITLE     ISO 18571 AGREEMENT, NBDL 15 G
CASE      input/nbdl15g.inp
DATA      reference/nbdl_15g
RATING    30.0      250.0     60        10.0      ISO18571
CHANNEL   HEAD_AX   VALUE               Head_XAccel.csv
CHANNEL   HEAD_AZ   VALUE               Head_ZAccel.csv
CHANNEL   HEAD_ALPHYVALUE               Head_YrotAccel.csv
CHANNEL   HEAD_OMEGYRATE      DEG-RAD   Head_YrotDisp.csv
CHANNEL   HEAD_THETYVALUE               Head_YrotDisp.csv
PEAK      HEAD_AX   MIN       30.0      250.0     X-ACCEL
FIT       NELDER    0         2         1
CURVES    nbdl_curves.csv
PARAM     SIGMA     FIELD4    SCALE     SIGMA     0.4       2.0       LOG
"""


def _fortran_scores(listing):
    """{(case, channel): {score: value}} of the ISO 18571 lines of a listing."""
    out, case = {}, 0
    for line in listing.splitlines():
        if line.startswith("CASE "):
            case += 1
        m = re.match(r"\s+(\S+)\s+ISO 18571\s+(\S+)\s+CORRIDOR\s+(\S+)\s+PHASE\s+(\S+)\s+MAGNITUDE\s+(\S+)"
                     r"\s+SLOPE\s+(\S+)", line)
        if m:
            out[(case, m.group(1))] = dict(zip(("overall", "corridor", "phase", "magnitude", "slope"),
                                               map(float, m.groups()[1:])))
    return out


def _agreement(listing, curves_csv):
    """Largest |Fortran - package| over every channel and score, and the count of channels."""
    fortran = _fortran_scores(listing)
    d = pd.read_csv(curves_csv, skipinitialspace=True)
    worst, n = 0.0, 0
    for (case, ch), g in d.groupby(["case", "channel"], sort=False):
        py = iso18571.rate(g.time_ms.values * 1e-3, g.reference.values, g.model.values)
        for k, v in fortran[(case, ch)].items():
            worst = max(worst, abs(v - py[k]))
        n += 1
    assert n == len(fortran)
    return worst, n


def _calibrate(deck, cwd):
    r = subprocess.run([hhneck_executable(), "-I", segments.ROOT, "--calibrate", deck], cwd=cwd,
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return r.stdout


def test_volunteer_case_agrees_with_the_package(tmp_path):
    (tmp_path / "nbdl.inp").write_text(NBDL)
    listing = _calibrate("nbdl.inp", str(tmp_path))
    assert "R: MEAN ISO 18571 OVERALL RATING" in listing
    worst, n = _agreement(listing, tmp_path / "nbdl_curves.csv")
    assert n == 5
    assert worst <= TOL, worst
    # the objective is 1 - the mean overall ISO rating (+ the peak term, w = 0.02)
    j = float(re.search(r"OBJECTIVE J =\s+(\S+)", listing).group(1))
    mean = float(re.search(r"MEAN RATING\s+(\S+)", listing).group(1))
    scores = _fortran_scores(listing)
    assert abs(mean - np.mean([s["overall"] for s in scores.values()])) < 1e-4
    assert j >= 1 - mean - 1e-4


def test_reference_case_agrees_with_the_package(tmp_path):
    deck = calibration.calibration_deck("stemper", ["stemper"], str(tmp_path), calibration.QUICK_PARAMS,
                                        values=[])
    listing = _calibrate(os.path.basename(deck), str(tmp_path))
    worst, n = _agreement(listing, tmp_path / "stemper_curves.csv")
    assert n == 7
    assert worst <= TOL, worst
    # no result file and no listing of the member run in the work folder
    assert not list(tmp_path.glob("*.h5"))
    # the reference CSV carries each channel on its own rows: C01 (C2-C3) starts later than C03 (C4-C5)
    ref = pd.read_csv(tmp_path / "stemper_reference.csv")
    assert ref.C03.first_valid_index() < ref.C01.first_valid_index()
    # the same channels as the catalogue (hhneck.specimens.CHANNELS): the
    # Fortran case mean is the catalogue's mean over the same channels, to the
    # resampling of the reference onto the CSV's common grid (within 0.005;
    # a wrong channel, sign or start moves a channel's score by far more)
    mean = calibration.parse_listing(listing)["cases"]
    catalogue = specimens.rate_stemper(specimens.run_stemper(str(tmp_path / "run"), hhneck_executable()))
    assert abs(list(mean.values())[0] - np.mean([c["overall"] for c in catalogue.values()])) < 0.005


def test_leave_one_out_quick(tmp_path, monkeypatch):
    monkeypatch.setenv("HHNECK", hhneck_executable())
    work = tmp_path / "loo"
    table = tmp_path / "table.md"
    assert calibration.main([str(work), "--quick", "--table", str(table)]) == 0
    text = table.read_text()
    assert text.count("\n") == 4 and "| stemper | kang_front |" in text and "| kang_front | stemper |" in text
    for row in text.splitlines()[2:]:
        cells = [c.strip() for c in row.strip("|").split("|")]
        shipped, cal, pred = map(float, cells[2:5])
        assert 0.0 < shipped < 1.0 and 0.0 < cal < 1.0 and 0.0 < pred < 1.0
        romk = float(cells[5].split()[1])
        assert 0.05 <= romk <= 5.0
    # the prediction is the left-out case scored at the fitted value: the same
    # evaluation again gives the same number
    listing = open(work / "predict_stemper.txt").read()
    again = _calibrate("predict_stemper.inp", str(work))
    assert calibration.parse_listing(again)["cases"] == calibration.parse_listing(listing)["cases"]
