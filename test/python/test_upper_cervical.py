"""The upper-cervical factors (python/hhneck/validation/upper_cervical.py) against
independent truth: scale_cards changes exactly the C2-C1 and C1-HEAD
discs' Iy and J and their ligaments' l1 and l2, by the factors, and the
program reads the result; range_edge is the hand distance from a NEUTRAL
card to a ROM card's ends; the bisection finds the closed-form factor of a
rotation M/(K f); the factors fitted on the shipped deck are the largest at
which the segment case reaches its target (real runs at the factor and 5 %
above it); the generator applies a CSV's factors only when asked; and the
fitter refuses a deck that already carries them. The generator's muscle
and disc variants: test_model_variants.py."""
import os
import subprocess
import tempfile

import pytest

from conftest import ROOT, hhneck_executable, hhneck_module
from hhneck.validation import fit_joints, segments
from hhneck.validation import upper_cervical as uc

def _generate(*args):
    """The lines of the model deck the generator (python3 -m hhneck.validation.model_deck
    ARGS) writes, run outside the repository."""
    r = hhneck_module("validation.model_deck", *args, cwd=tempfile.gettempdir())
    assert r.returncode == 0, r.stderr
    return r.stdout.splitlines()


def _cards(lines):
    """{(card, name): the card and its continuations} of DISC and LIGAMENT
    cards, comments left out."""
    out, key = {}, None
    for line in lines:
        if line.startswith("*"):
            continue
        if line.startswith(" ") and key:
            out[key].append(line)
            continue
        f = segments._fields(line)
        key = (f[0], f[1]) if f[0] in ("DISC", "LIGAMENT") else None
        if key:
            out[key] = [line]
    return out


def test_scale_cards_changes_only_the_upper_cervical_fields_by_the_factors(tmp_path):
    base = _generate()
    scaled = uc.scale_cards(base, 0.5, 0.1)
    assert sum(l.startswith(uc.MARKER) for l in scaled) == 1 and max(len(l) for l in scaled) <= 80
    a, b = _cards(base), _cards(scaled)
    assert a.keys() == b.keys()
    upper = {("C2", "C1"), ("C1", "HEAD")}
    n_disc = n_lig = 0
    for key, lines in a.items():
        f = segments._fields(lines[0])
        if (f[2], f[3]) not in upper:
            assert b[key] == lines, key                  # every other element untouched
            continue
        if key[0] == "DISC":
            n_disc += 1
            assert b[key][:2] == lines[:2]
            g0, g1 = segments._fields(lines[2]), segments._fields(b[key][2])
            assert [g1[1], g1[2], g1[5]] == [g0[1], g0[2], g0[5]]          # G, Ix (lateral), k kept
            assert float(g1[3]) == pytest.approx(0.5 * float(g0[3]), rel=1e-5)   # Iy
            assert float(g1[4]) == pytest.approx(0.5 * float(g0[4]), rel=1e-5)   # J
        else:
            n_lig += 1
            g0, g1 = segments._fields(lines[0]), segments._fields(b[key][0])
            assert g1[:4] == g0[:4] and g1[6] == g0[6]                     # names and exponent n kept
            assert float(g1[4]) == pytest.approx(0.1 * float(g0[4]), abs=1e-30)
            assert float(g1[5]) == pytest.approx(0.1 * float(g0[5]), rel=1e-5)
    assert (n_disc, n_lig) == (2, 12)
    non_element = [l for l in base if not l.startswith(("DISC", "LIGAMENT", " ", "*"))]
    assert non_element == [l for l in scaled if not l.startswith(("DISC", "LIGAMENT", " ", "*"))]
    (tmp_path / "input").mkdir()
    (tmp_path / "input" / "head_neck_54dof.inp").write_text("\n".join(scaled) + "\n")
    with open(os.path.join(ROOT, "input", "case6-2.inp")) as f:
        r = subprocess.run([hhneck_executable(), "--check"], stdin=f, capture_output=True, text=True, cwd=tmp_path)
    assert r.returncode == 0, r.stderr


def test_range_edge_is_the_distance_from_the_neutral_to_the_nearer_end():
    lines = ["ROM       HEAD      RY        -17.6     2.4       50.0      3.0",
             "NEUTRAL   HEAD      RY        -7.6",
             "ROM       C2        RY        -10.0733  3.5933    50.0      3.0",
             "NEUTRAL   C2        RY        -3.24",
             "ROM       C1        RZ        -35.0     30.0      50.0      3.0"]
    assert uc.range_edge(lines, "HEAD", "RY") == pytest.approx(10.0)
    assert uc.range_edge(lines, "C2", "RY") == pytest.approx(3.5933 + 3.24)
    assert uc.range_edge(lines, "C1", "RZ") == pytest.approx(30.0)       # no NEUTRAL card: 0
    assert uc.range_edge(lines, "C1", "RX") == float("inf")


@pytest.mark.parametrize("k, want", [(40.0, 5.0), (8.0, 3.0), (300.0, 0.4)])
def test_largest_factor_is_the_closed_form_rounded_down(k, want):
    """rotation(f) = M / (K f) in deg with M = 1 N m: f* = M / (K want)."""
    rotation = lambda f: 180.0 / 3.141592653589793 / (k * f)  # noqa: E731
    exact = 180.0 / 3.141592653589793 / (k * want)
    got = uc.largest_factor(rotation, want)
    if exact >= 1.0:
        assert got == 1.0
    else:
        assert got <= exact and got == pytest.approx(exact, rel=5e-3) and rotation(got) >= want
        assert float("%.3g" % got) == got


def test_largest_factor_says_when_no_factor_reaches():
    with pytest.raises(ValueError, match="below"):
        uc.largest_factor(lambda f: min(10.0, 1.0 / f), 12.0)


def test_csv_round_trip_and_bounds(tmp_path):
    path = str(tmp_path / "uc.csv")
    fit = {"f_lig": dict(value=0.0419, segment="C1_C2", motion="axial_rotation", model_deg=22.08, target_deg=22.07),
           "f_rot": dict(value=0.505, segment="C1_C2", motion="flexion_extension", model_deg=10.0, target_deg=10.0)}
    uc.write_csv(path, fit)
    assert uc.read_csv(path) == (0.505, 0.0419)
    fit["f_rot"]["value"] = 1.5
    uc.write_csv(path, fit)
    with pytest.raises(ValueError, match="f_rot"):
        uc.read_csv(path)


def test_fitter_refuses_a_deck_with_the_factors(tmp_path, capsys):
    deck = tmp_path / "model.inp"
    deck.write_text("\n".join(uc.scale_cards(_generate(), 0.5, 0.5)) + "\n")
    assert uc.deck_has_factors(str(deck)) and not uc.deck_has_factors(segments.MODEL_DECK)
    assert fit_joints.main(["--model", str(deck), "--csv", str(tmp_path / "nz.csv"), "--upper-cervical",
                            "--upper-csv", str(tmp_path / "uc.csv"), "--work", str(tmp_path / "w")]) == 1
    assert "already has the upper-cervical factors" in capsys.readouterr().err
    assert not os.path.exists(tmp_path / "uc.csv") and not os.path.exists(tmp_path / "nz.csv")


def test_generator_applies_the_factors_of_a_csv_only_when_asked(tmp_path):
    path = str(tmp_path / "uc.csv")
    fit = {"f_lig": dict(value=0.25, segment="C1_C2", motion="axial_rotation", model_deg=1.0, target_deg=1.0),
           "f_rot": dict(value=0.5, segment="C1_C2", motion="flexion_extension", model_deg=1.0, target_deg=1.0)}
    uc.write_csv(path, fit)
    plain = _generate()
    assert plain == _generate("--upper-cervical", "none") == open(segments.MODEL_DECK).read().splitlines()
    assert _generate("--upper-cervical", path) == uc.scale_cards(plain, 0.5, 0.25)


def test_fitted_factors_are_the_largest_that_reach_the_target(tmp_path):
    """fit_factors on the shipped deck (real segment runs, springs dropped):
    at each fitted factor (at most 1: the shipped column may reach a target
    unscaled) the case turns at least to its target, 5 % above the factor
    (where it is below 1) it does not; the targets are the
    data's rotation at its largest moment or the range edge (10 deg for
    C1-C2 flexion, the C1 RY ROM card about its neutral)."""
    exe = hhneck_executable()
    fit = uc.fit_factors(exe, segments.MODEL_DECK, workdir=str(tmp_path / "fit"))
    assert fit["f_lig"]["target_deg"] == pytest.approx(22.07, abs=0.01)     # Panjabi C1-C2 axial, +1.04 N m
    assert fit["f_rot"]["target_deg"] == pytest.approx(10.0)                # the range edge, before 12.1
    base = open(segments.MODEL_DECK).read().splitlines()
    data = segments.load_panjabi()
    found = {"f_rot": 1.0, "f_lig": 1.0}
    for name, target in uc.TARGETS:
        value = fit[name]["value"]
        assert 0.0 < value <= 1.0          # 1: the column reaches the target unscaled
        found[name] = value
        got, want = uc._rotation_reached(exe, uc.scale_cards(base, found["f_rot"], found["f_lig"]), target,
                                         str(tmp_path), data)
        assert got >= want and got == pytest.approx(fit[name]["model_deg"], rel=1e-6)
        if value < 1.0:
            above = dict(found, **{name: 1.05 * value})
            got5, _ = uc._rotation_reached(exe, uc.scale_cards(base, above["f_rot"], above["f_lig"]), target,
                                           str(tmp_path), data)
            assert got5 < want, (name, got5, want)
    assert min(found.values()) < 1.0 or all(fit[n]["model_deg"] >= fit[n]["target_deg"] for n in fit)



def test_fit_factors_at_bound_takes_the_bound_where_no_factor_reaches(tmp_path, monkeypatch):
    """A joint whose other elements hold it below the target at every
    factor (rotation 10 / (1 + f) deg against 22 deg): ValueError naming
    the factor, or with at_bound the bound F_MIN (a column fit's candidate
    rated with its ligaments there); a reachable target is unaffected."""
    deck = tmp_path / "plain.inp"
    deck.write_text("\n".join(_generate()) + "\n")
    monkeypatch.setattr(uc.segments, "load_panjabi", lambda d=None: {})
    monkeypatch.setattr(uc, "_rotation_reached", lambda exe, lines, target, work, data: (10.0, 22.0))
    with pytest.raises(ValueError, match="f_lig C1_C2 axial_rotation"):
        uc.fit_factors("unused", str(deck), workdir=str(tmp_path / "w"))
    fit = uc.fit_factors("unused", str(deck), workdir=str(tmp_path / "w"), at_bound=True)
    assert fit["f_lig"]["value"] == fit["f_rot"]["value"] == uc.F_MIN
    monkeypatch.setattr(uc, "_rotation_reached", lambda exe, lines, target, work, data: (30.0, 22.0))
    fit = uc.fit_factors("unused", str(deck), workdir=str(tmp_path / "w"), at_bound=True)
    assert fit["f_lig"]["value"] == fit["f_rot"]["value"] == 1.0
