"""The neutral-zone spring fit (python/hhneck/validation/fit_joints.py) against
independent truth: the sinh fit recovers the constants of exact synthetic
points; the subtraction of the other elements' moment, on a synthetic run
whose rotation is the moment over known stiffnesses, leaves M - K theta and
drops the points the others carry; the data points are the data file's with
the coordinate's sign; the generator's NZSPRING cards hold the CSV's
numbers in 10-column fields; write_deck drops NZSPRING cards on request; and
one real run of a disc alone (C4-C5 flexion) gives the others' moment of
the disc's closed form d1 Iy/h theta. The whole fitter is not run here."""
import csv
import math
import os
import subprocess

import numpy as np
import pytest

from conftest import ROOT, hhneck_executable, hhneck_module
from hhneck.validation import fit_joints as fj
from hhneck.validation import segments
from hhneck.validation import model_deck as md
from test_segments import _disc_card
from test_upper_cervical import _generate



# ---------------------------------------------------------------- the sinh fit

@pytest.mark.parametrize("m0, ths", [(0.05, 4.0), (0.002, 0.8), (1.5, 20.0), (0.0123, 0.35)])
def test_sinh_fit_recovers_known_constants(m0, ths):
    theta = np.array([0.6, 1.7, 3.1, 4.4]) * max(ths, 1.0)
    moment = m0 * np.sinh(theta / ths)
    got_m0, got_ths, rms = fj.fit_sinh(theta, moment)
    assert got_m0 == pytest.approx(m0, rel=1e-6) and got_ths == pytest.approx(ths, rel=1e-6)
    assert rms < 1e-6 * theta.max()


def test_sinh_fit_minimises_the_rotation_residual():
    """Noisy points: no nearby (M0, ths) has a smaller sum of squared
    rotation residuals than the fit's."""
    theta = np.array([2.0, 3.5, 5.0, 6.0, 7.2])
    moment = 0.03 * np.sinh(theta / 1.6) * np.array([1.1, 0.93, 1.05, 0.97, 1.02])
    m0, ths, rms = fj.fit_sinh(theta, moment)
    best = np.sum(fj.rotation_residuals(theta, moment, m0, ths) ** 2)
    assert rms == pytest.approx(math.sqrt(best / theta.size))
    for dm in (0.999, 1.001):
        for dt in (0.999, 1.0, 1.001):
            assert np.sum(fj.rotation_residuals(theta, moment, m0 * dm, ths * dt) ** 2) > best


def test_fit_ends_on_the_bound_and_says_so():
    """Points of a law with M0 below 1e-3 N m: the fit's M0 is the bound."""
    theta = np.array([3.0, 3.5, 4.0])
    side = fj.fit_side(theta, 1e-5 * np.sinh(theta / 0.3))
    assert side["m0"] == pytest.approx(fj.M0_BOUNDS[0], rel=1e-9) and "M0 at bound" in side["method"]
    assert fj.THS_BOUNDS[0] <= side["ths"] <= fj.THS_BOUNDS[1] and side["n"] == 3


def test_fallback_rules():
    one = fj.fit_side([4.0], [0.6])
    assert one["method"] == "secant" and one["ths"] == 30.0 and one["n"] == 1
    assert one["m0"] * math.sinh(4.0 / 30.0) == pytest.approx(0.6, rel=1e-12)   # through the point
    none = fj.fit_side([], [])
    assert (none["m0"], none["ths"], none["n"], none["rms"], none["method"]) == (1e-3, 30.0, 0, None, "none")


# ---------------------------------------------------------------- the others

def _linear_run(k_pos, k_neg, peak):
    """A run of the segments' protocol whose rotation (data sign) is the
    moment over k_pos (positive moments) or k_neg (negative) [N m/deg]."""
    t = np.arange(0.0, segments.T_END + 1e-9, 0.01)
    table = [(0.0, 0.0), (segments.RAMP, peak), (segments.RAMP + segments.HOLD, peak), (segments.T_NEG, 0.0),
             (segments.T_NEG + segments.RAMP, -peak), (segments.T_END, -peak)]
    m = np.interp(t, *zip(*table))
    return t, np.where(m >= 0, m / k_pos, m / k_neg)


def test_ramp_curves_put_each_ramp_on_its_coordinate_side():
    t, rot = _linear_run(0.5, 0.25, 2.0)
    # flexion (sign +1): the data's positive ramp is the coordinate's + side
    c = fj.ramp_curves(t, rot, 2.0, +1.0)
    assert np.allclose(c[+1][1], 0.5 * c[+1][0]) and np.allclose(c[-1][1], 0.25 * c[-1][0])
    assert c[+1][1][-1] == pytest.approx(2.0) and c[-1][0][-1] == pytest.approx(8.0)
    # lateral bending (sign -1): the data's positive (left) ramp is -RX
    c = fj.ramp_curves(t, rot, 2.0, -1.0)
    assert np.allclose(c[-1][1], 0.5 * c[-1][0]) and np.allclose(c[+1][1], 0.25 * c[+1][0])


def test_subtraction_of_a_linear_others_moment():
    k = 0.3                                          # [N m/deg]
    t, rot = _linear_run(k, k, 1.0)                  # the run reaches 1/0.3 = 3.33 deg
    th, m = fj.ramp_curves(t, rot, 1.0, +1.0)[+1]
    theta = np.array([1.0, 2.0, 3.0, 5.0, 8.0, 2.0])
    moment = np.array([0.5, 0.9, 0.918, 2.5, 2.0, 0.61])
    m_nz, m_o, kept, extra = fj.neutral_zone_moments(moment, theta, th, m)
    assert np.allclose(m_o, k * theta, rtol=1e-9)                 # beyond 3.33 deg: the line continued
    assert np.allclose(m_nz, moment - k * theta, rtol=1e-9, atol=1e-12)
    assert list(extra) == [False, False, False, True, True, False]
    # 0.918 - 0.9 = 0.018 <= 2 % of 0.918; 2.0 - 2.4 < 0; 0.61 - 0.6 = 0.01 <= 2 %
    assert list(kept) == [True, True, False, True, False, False]


def test_others_moment_extrapolates_the_stiffening_end():
    """A curve that stiffens at its end (m = theta^2): beyond its last
    rotation the slope of its last tenth of moment, not the secant."""
    th = np.linspace(0.0, 2.0, 2001)
    m_o, extra = fj.others_moment([1.0, 3.0], th, th ** 2)
    assert m_o[0] == pytest.approx(1.0, rel=1e-6) and not extra[0] and extra[1]
    # the least-squares line through m = theta^2 on [sqrt(3.6), 2]: slope near 2 theta = 3.9
    assert 3.8 < (m_o[1] - 4.0) / 1.0 < 4.0


def test_data_points_are_the_files_with_the_coordinates_sign():
    panjabi = segments.load_panjabi()
    pts = fj.data_points("C4_C5", "lateral_bending")
    m, r = panjabi[("C4_C5", "lateral_bending")]
    want = sorted((-a, -b) for a, b in zip(m, r) if abs(a) > 0.1)       # -RX is the data's +
    got = sorted((p[1], p[2]) for p in pts)
    assert len(pts) == 6 and np.allclose(got, want, rtol=1e-12, atol=0)
    flex = fj.data_points("C4_C5", "flexion_extension")
    assert sum(p[0] == fj.NIGHTINGALE for p in flex) == 14 and sum(p[0] == fj.PANJABI for p in flex) == 6
    # Nightingale's C4-C5 flexion at 3.5 N m, as digitised, flexion +RY
    assert any(p[1] == pytest.approx(3.512382914) and p[2] == pytest.approx(8.745209641) for p in flex)
    sources, moment, theta = fj.side_points(flex, -1)
    assert len(moment) == 10 and np.all(moment > 0) and np.all(theta > 0)


# ---------------------------------------------------------------- cards

ROWS = [("HEAD", "RY", 0.00430321, 0.522874, 0.001, 30.0), ("C4", "RZ", 0.0523612, 12.3456, 1.39155, 0.368822),
        ("C7", "RX", 2.5, 1.85029, 0.0731384, 1.61638)]


def _csv_rows():
    out = []
    for body, coord, m0p, tp, m0m, tm in ROWS:
        side = lambda m0, ths: dict(m0=m0, ths=ths, n=3, rms=0.01, method="lsq", sources=fj.PANJABI)  # noqa: E731
        out.append({"body": body, "coord": coord, "segment": "C4_C5", +1: side(m0p, tp), -1: side(m0m, tm)})
    return out


def test_csv_round_trip(tmp_path):
    path = str(tmp_path / "nz.csv")
    fj.write_csv(path, _csv_rows())
    assert open(path).readline().startswith("# written by python3 -m hhneck.validation.fit_joints")
    rows = fj.read_csv(path)
    assert [r["body"] for r in rows] == ["HEAD", "C4", "C7"] and list(rows[0]) == list(fj.CSV_COLUMNS)
    assert float(rows[1]["ths_plus_deg"]) == 12.3456 and rows[2]["sources_minus"] == fj.PANJABI


def test_generator_writes_one_nzspring_card_per_row_in_ten_column_fields(tmp_path):
    path = str(tmp_path / "nz.csv")
    fj.write_csv(path, _csv_rows())
    lines = _generate("--nz-springs", path)
    cards = [l for l in lines if l.startswith("NZSPRING")]
    assert len(cards) == len(ROWS)
    for line, (body, coord, *vals) in zip(cards, ROWS):
        assert len(line) <= 80
        fields = [line[i:i + 10] for i in range(0, 80, 10)]
        assert fields[0] == "NZSPRING  " and fields[1].strip() == body and fields[2].strip() == coord
        # each number within columns 10n+1 .. 10n+9, a blank before the next field
        assert all(f[-1] == " " for f in fields[3:7]) and line[70:].strip() == "100.0"
        assert [float(f) for f in fields[3:7]] == pytest.approx(vals, rel=2e-5)
    # after the last ROM card, before the SCALE cards
    last_rom = max(i for i, l in enumerate(lines) if l.startswith("ROM "))
    first = lines.index(cards[0])
    assert last_rom < first < min(i for i, l in enumerate(lines) if l.startswith("SCALE"))
    assert all(l.startswith("*") for l in lines[last_rom + 1:first])
    assert "Panjabi" in "".join(lines[last_rom + 1:first]) and "hhneck.validation.fit_joints" in "".join(lines[last_rom + 1:first])
    # the program reads them: case 6-2 with this model deck passes hhneck --check
    _program_takes(tmp_path, lines)


def _program_takes(tmp_path, lines):
    """hhneck --check passes on input/case6-2.inp with the model deck `lines`
    (read where its INCLUDE finds input/head_neck_54dof.inp)."""
    (tmp_path / "input").mkdir(exist_ok=True)
    (tmp_path / "input" / "head_neck_54dof.inp").write_text("\n".join(lines) + "\n")
    with open(os.path.join(ROOT, "input", "case6-2.inp")) as f:
        r = subprocess.run([hhneck_executable(), "--check"], stdin=f, capture_output=True, text=True, cwd=tmp_path)
    assert r.returncode == 0, r.stderr


def test_generator_disc_rotation_scales_and_no_springs_without_a_csv(tmp_path):
    """--nz-springs with a file not written yet, or none: the discs'
    rotation scaled by the table's fractions, no springs; without the
    option (the table's springs): the shipped deck."""
    p = md.table_values(md.read_table())
    for arg in (str(tmp_path / "not_yet.csv"), "none"):
        lines = _generate("--nz-springs", arg)
        assert not any(l.startswith("NZSPRING") for l in lines)
        scales = [l for l in lines if l.startswith("SCALE")]
        assert md.card("SCALE", "NZBEND", "DISCS", "BEND", p["disc.bend_fraction"]) in scales
        assert md.card("SCALE", "NZTORS", "DISCS", "TORSION", p["disc.torsion_fraction"]) in scales
    _program_takes(tmp_path, lines)
    with open(segments.MODEL_DECK) as f:
        assert _generate() == f.read().splitlines()


def test_generator_refuses_a_row_of_an_unknown_body(tmp_path):
    path = str(tmp_path / "nz.csv")
    rows = _csv_rows()
    rows[0]["body"] = "C8"
    fj.write_csv(path, rows)
    r = hhneck_module("validation.model_deck", "--nz-springs", path)
    assert r.returncode != 0 and "C8" in r.stderr


# ---------------------------------------------------------------- segment decks

def _model_with_springs(tmp_path):
    """The model deck with NZSPRING cards on C4 and C3 and an NZSPRINGS SCALE card."""
    text = "".join(l for l in open(segments.MODEL_DECK).readlines() if not l.startswith("NZSPRING"))
    (tmp_path / "model_plain.inp").write_text(text)        # the model deck without its own springs
    extra = ["NZSPRING  C4        RY        0.01      1.0       0.02      2.0       100.0",
             "NZSPRING  C3        RY        0.01      1.0       0.02      2.0       100.0",
             "SCALE     NZM       NZSPRINGS M0        1.5"]
    path = tmp_path / "model_nz.inp"
    path.write_text(text + "\n".join(extra) + "\n")
    return str(path)


def test_write_deck_takes_or_drops_the_nzspring_cards(tmp_path):
    model = _model_with_springs(tmp_path)
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    (tmp_path / "c").mkdir()
    with_nz = tmp_path / "a" / "s.inp"
    segments.write_deck(str(with_nz), "C4_C5", "flexion_extension", 1.0, model=model)
    cards = [l for l in with_nz.read_text().splitlines() if l.startswith(("NZSPRING", "SCALE     NZM"))]
    assert cards == ["NZSPRING  C4        RY        0.01      1.0       0.02      2.0       100.0",
                     "SCALE     NZM       NZSPRINGS M0        1.5"]
    dropped = tmp_path / "b" / "s.inp"
    segments.write_deck(str(dropped), "C4_C5", "flexion_extension", 1.0, model=model, drop=("NZSPRING",))
    plain = tmp_path / "c" / "s.inp"
    segments.write_deck(str(plain), "C4_C5", "flexion_extension", 1.0, model=str(tmp_path / "model_plain.inp"))
    assert dropped.read_text() == plain.read_text()          # the model deck without the springs
    disc = tmp_path / "c" / "d.inp"
    segments.write_deck(str(disc), "C4_C5", "flexion_extension", 1.0, model=model, disc_only=True)
    assert "NZSPRING" not in disc.read_text().replace("NZSPRINGS", "")


def test_others_of_a_disc_alone_are_its_closed_form(tmp_path):
    """C4-C5 flexion with the disc alone, solved as statics (as
    hhneck.validation.fit_column runs the others): M_o(theta) is d1 Iy/h theta, the
    disc's closed form, within 0.2 %; a wrong stiffness, side or sign is off
    by far more."""
    exe = hhneck_executable()
    t, rot = segments.run_case("C4_C5", "flexion_extension", 1.0, str(tmp_path), exe, disc_only=True, statics=True)
    d1, h, g, ix, iy, j = _disc_card(str(tmp_path / "C4_C5_flexion_extension_1Nm_disc_statics.inp"), "C5C4")
    k = d1 * iy / h * math.pi / 180.0                 # [N m/deg]
    curves = fj.ramp_curves(t, rot, 1.0, +1.0)
    for side in (+1, -1):
        th, m = curves[side]
        theta = np.array([0.25, 0.5, 0.9]) * th[-1]
        m_o, extra = fj.others_moment(theta, th, m)
        assert np.all(np.abs(m_o - k * theta) < 0.002 * k * theta) and not extra.any(), (side, m_o, k * theta)


def test_check_refuses_a_model_deck_without_springs(tmp_path, capsys):
    deck = tmp_path / "m.inp"
    deck.write_text("\n".join(_generate("--nz-springs", str(tmp_path / "not_yet.csv"))) + "\n")
    assert fj.main(["--check", "--model", str(deck), "--work", str(tmp_path)]) == 1
    assert "has no NZSPRING card" in capsys.readouterr().err


def test_fitted_springs_bring_one_segment_to_its_data(tmp_path):
    """C4-C5 axial rotation, end to end, as statics: the others' run (the
    generated deck, the discs' torsion at the table's fraction, no
    springs), the fit of both sides, the NZSPRING card of C4 RZ added to
    the deck, and the run with it turns by
    the data's rotation at each Panjabi moment, within the fit's residual
    (its rms over 1 %) plus 2 %; the others alone turn 1.4 to 1.8 times as
    far."""
    exe = hhneck_executable()
    lines = _generate("--nz-springs", str(tmp_path / "not_yet.csv"))
    deck0 = tmp_path / "m0.inp"
    deck0.write_text("\n".join(lines) + "\n")
    seg, motion = "C4_C5", "axial_rotation"
    points = fj.data_points(seg, motion)
    peak = max(abs(p[1]) for p in points)
    t, rot = segments.run_case(seg, motion, peak, str(tmp_path), exe, drop=fj.DROP, model=str(deck0), statics=True)
    fit = fj.fit_case(points, peak, t, rot, motion)
    assert [fit[s]["n"] for s in (+1, -1)] == [3, 3]
    card = "NZSPRING  %-10s%-10s%-10.5g%-10.5g%-10.5g%-10.5g%-10s" % (
        "C4", "RZ", fit[+1]["m0"], fit[+1]["ths"], fit[-1]["m0"], fit[-1]["ths"], "100.0")
    deck1 = tmp_path / "m1.inp"
    deck1.write_text("\n".join(lines + [card.rstrip()]) + "\n")
    (tmp_path / "nz").mkdir()
    t1, rot1 = segments.run_case(seg, motion, peak, str(tmp_path / "nz"), exe, model=str(deck1), statics=True)
    sign = segments.MOTIONS[motion][1]
    data_m = np.array([sign * p[1] for p in points])
    data_th = np.array([sign * p[2] for p in points])
    others = segments.rotations_at(t, rot, peak, data_m) / data_th
    model = segments.rotations_at(t1, rot1, peak, data_m) / data_th
    assert np.all(others > 1.3), others
    tol = 0.02 + max(fit[s]["rms"] for s in (+1, -1)) / np.min(np.abs(data_th))
    assert np.all(np.abs(model - 1.0) < tol), (model, tol)
