"""Constraint 1 of the model (docs/validation.md, "Calibration"): the passive
column comes from tissue and segment data alone. Every passive row of
reference/model_parameters.csv (discs, ligaments, joint stops, neutral-zone
springs, and their SCALE factors) is sourced, assumed, or fitted by a
segment stage (segments, nz_springs), never by a volunteer fit; the shipped
deck's passive cards carry the table's values and its muscles are passive;
and the fit is code: one joint's springs fitted again on the shipped deck
by hhneck.validation.fit_joints (the others' run as statics, as hhneck.validation.fit_column
runs it) are the table's, and the least squares of those points returns them
(M0 three times off fits the points worse)."""
import math
import os

import pytest

from conftest import ROOT, hhneck_executable
from hhneck.validation import fit_column, fit_joints, segments
from hhneck.validation import model_deck as md
from hhneck.decks import field

SEGMENT_STAGES = ("segments", "nz_springs")


def _rows():
    return md.read_table()


def _passive(name):
    return name.startswith(md.PASSIVE_PREFIXES) or name in md.PASSIVE_SCALES


def test_every_passive_row_is_sourced_or_fitted_to_segments():
    rows = [r for r in _rows() if _passive(r["name"])]
    assert len(rows) > 150                       # the discs, ligaments, stops and 120 spring constants
    bad = [(r["name"], r["stage"]) for r in rows if r["status"] == "fitted" and r["stage"] not in SEGMENT_STAGES]
    assert bad == []
    # the stages a fit may write are the segment stages alone
    assert set(md.STAGES) == set(SEGMENT_STAGES)
    # the column's fit writes exactly the rows it names, all passive
    assert all(_passive(n) for n, _, _ in fit_column.PARAMS)


def test_the_deck_carries_the_tables_passive_values_and_passive_muscles():
    p = md.table_values(_rows())
    lines = open(segments.MODEL_DECK).read().splitlines()
    # the card's text is the table's value in the card's 9 columns (md.fmt)
    scales = {field(l, 1): field(l, 4) for l in lines if l.startswith("SCALE")}
    want = {name: p[name] for name, _, _ in md.SCALES}
    # S1's bushing time constant, 0.1 s, is the table's VBEND; the discs keep the
    # bending fraction of S1's stiffness, so S1's damping coefficient needs their
    # retardation time over that fraction: damping = fraction x stiffness x time
    assert p["VBEND"] * p["disc.tau"] == pytest.approx(0.1)
    want["VBEND"] = p["VBEND"] / p["disc.bend_fraction"]
    assert p["disc.bend_fraction"] * want["VBEND"] * p["disc.tau"] == pytest.approx(0.1)
    want.update(NZBEND=p["disc.bend_fraction"], NZTORS=p["disc.torsion_fraction"])
    assert scales == {k: md.fmt(v) for k, v in want.items()}
    springs = [l for l in lines if l.startswith("NZSPRING")]
    assert len(springs) == 24
    for l in springs:
        b, c = field(l, 1), field(l, 2)
        got = [field(l, k) for k in range(3, 8)]
        assert got == [md.fmt(p["nz.%s.%s.%s" % (b, c, k)]) for k in md.NZ_COLUMNS], (b, c)
    act = [l for l in lines if l.startswith("ACTIVATE")]
    assert len(act) == 2 and all(float(field(l, 2)) == 0.0 and float(field(l, 3)) == 0.0 for l in act)


def _c4_flexion(tmp_path):
    """The C4 RY springs fitted again on the shipped deck: (fit_case dict, the table's values)."""
    case = ("C4_C5", "flexion_extension")
    runs = fit_joints.run_others([case], hhneck_executable(), segments.MODEL_DECK, str(tmp_path), jobs=1,
                                 statics=True)
    pts, peak, t, rot, _ = runs[case]
    return fit_joints.fit_case(pts, peak, t, rot, case[1]), pts, (peak, t, rot)


def test_one_joints_springs_are_the_fits_output(tmp_path):
    p = md.table_values(_rows())
    fit, _, _ = _c4_flexion(tmp_path)
    for side, name in fit_joints.SIDES:
        for key, col in (("m0", "m0_%s" % name), ("ths", "ths_%s_deg" % name)):
            assert fit[side][key] == pytest.approx(p["nz.C4.RY.%s" % col], rel=1e-4), (name, key)
    # the least squares of the kept points returns the law (the rotation
    # residual is the fit's minimum, not a copied number)
    lsq = [s for s in fit.values() if s["method"].startswith("lsq")]
    assert lsq                                   # a side with two points or more
    s = lsq[0]
    kept = [q for q in s["points"] if q["kept"]]
    theta = [q["theta"] for q in kept]
    m_nz = [q["m_nz"] for q in kept]
    m0, ths, rms = fit_joints.fit_sinh(theta, m_nz)
    assert (m0, ths) == pytest.approx((s["m0"], s["ths"]), rel=1e-6) and len(kept) >= 2
    off = fit_joints.rotation_residuals(theta, m_nz, 3 * m0, ths)
    assert math.sqrt(sum(r * r for r in off) / len(off)) > rms + 0.05
