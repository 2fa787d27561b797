"""The deck generator's model variants (python3 -m hhneck.validation.model_deck; the
experiments of docs/validation.md "The upper cervical joints" and
docs/validation-history.md "Segmental muscles"), each against the shipped deck: --suboccipital yes
adds exactly the four suboccipital muscles per side with F0 = sectional
area x sigma_max; --segmental yes exactly two muscles per subaxial level
and side, each joining adjacent vertebrae; --sub-bend F scales exactly the
subaxial discs' Ix and Iy, --sub-flexion F exactly the Iy of the discs
C3-C4 ... C7-T1; every variant is read by the program; at its shipped setting
(segmental muscles on, the others off), each gives the shipped deck."""
import os
import subprocess

import pytest

from conftest import ROOT, hhneck_executable
from hhneck.validation import segments
from test_upper_cervical import _cards, _generate

def _program_reads(tmp_path, lines):
    """hhneck --check passes on input/nbdl12g.inp with the model deck `lines`."""
    (tmp_path / "input").mkdir(exist_ok=True)
    (tmp_path / "input" / "head_neck_54dof.inp").write_text("\n".join(lines) + "\n")
    for name in ("nbdl12g_t1.inp", "volunteer_controller.inp"):
        (tmp_path / "input" / name).write_text(open(os.path.join(ROOT, "input", name)).read())
    with open(os.path.join(ROOT, "input", "nbdl12g.inp")) as fin:
        r = subprocess.run([hhneck_executable(), "--check"], stdin=fin, capture_output=True, text=True,
                           cwd=tmp_path)
    assert r.returncode == 0, r.stderr


def _hill(lines):
    return [l for l in lines if l.startswith("HILL")]


def _data_cards(lines, without=("HILL",)):
    """The non-comment cards other than `without` and their continuations."""
    out, skip = [], False
    for l in lines:
        if l.startswith("*"):
            continue
        if not l.startswith(" "):
            skip = l.startswith(without)
        if not skip:
            out.append(l)
    return out


def test_every_variant_at_its_shipped_setting_is_the_shipped_deck():
    shipped = open(segments.MODEL_DECK).read().splitlines()
    assert _generate("--suboccipital", "no", "--segmental", "yes", "--sub-bend", "1", "--sub-flexion", "1") == shipped


def test_segmental_muscles_join_adjacent_subaxial_vertebrae(tmp_path):
    plain, seg = _generate("--segmental", "no"), _generate()
    extra = [l for l in _hill(seg) if l not in _hill(plain)]
    assert len(extra) == 24 and len(_hill(seg)) == len(_hill(plain)) + 24
    order = ["T1", "C7", "C6", "C5", "C4", "C3", "C2"]
    sigma_scale = 0.5e6 * 1e-4
    for l in extra:
        f = segments._fields(l)
        assert f[1][:2] in ("MU", "IT") and f[6] == "EXT"
        assert order.index(f[3]) == order.index(f[2]) + 1          # lower -> the next vertebra up
        assert float(f[4]) == pytest.approx((1.0 if f[1][:2] == "MU" else 0.4) * sigma_scale)
    assert _data_cards(seg) == _data_cards(plain)
    _program_reads(tmp_path, seg)


def _only_disc_fields_scaled(plain, variant, discs, scaled, factor):
    """Every DISC and LIGAMENT card of `variant` as in `plain`, but the
    third lines of the DISC cards `discs`, whose fields `scaled` (G 1, Ix 2,
    Iy 3, J 4, k 5) are `factor` times plain's and the others kept; every
    card of another kind unchanged."""
    a, b = _cards(plain), _cards(variant)
    n = 0
    for key, lines in a.items():
        if key[0] != "DISC" or key[1] not in discs:
            assert b[key] == lines, key
            continue
        n += 1
        assert b[key][:2] == lines[:2], key
        g0, g1 = segments._fields(lines[2]), segments._fields(b[key][2])
        for k in range(1, 6):
            want = factor * float(g0[k]) if k in scaled else float(g0[k])
            assert float(g1[k]) == pytest.approx(want, rel=1e-5), (key, k)
    assert n == len(discs)
    assert [l for l in variant if not l.startswith(" ")] == [l for l in plain if not l.startswith(" ")]


def test_sub_bend_scales_only_the_subaxial_discs_bending(tmp_path):
    soft = _generate("--sub-bend", "0.2")
    _only_disc_fields_scaled(_generate(), soft, {"T1C7", "C7C6", "C6C5", "C5C4", "C4C3", "C3C2"}, (2, 3), 0.2)
    _program_reads(tmp_path, soft)


def test_sub_flexion_scales_only_the_lower_discs_flexion_extension(tmp_path):
    """--sub-flexion F: Iy (flexion-extension bending) of the discs C3-C4
    ... C7-T1 times F, and nothing else of any card; C2-C3 and the upper
    joints kept; the program reads the deck."""
    soft = _generate("--sub-flexion", "0.25")
    _only_disc_fields_scaled(_generate(), soft, {"T1C7", "C7C6", "C6C5", "C5C4", "C4C3"}, (3,), 0.25)
    _program_reads(tmp_path, soft)


def test_suboccipital_muscles_only_when_asked(tmp_path):
    """--suboccipital yes: four more Hill muscles per side on EXT, F0 = the
    source's sectional area x sigma_max (RCPMAJ 1.8 cm^2 x 0.5 MPa = 90 N,
    OCI 2.5 cm^2: 125 N), joining the upper-cervical bodies; every other
    card as without it; the program reads the deck."""
    plain, sub = _generate(), _generate("--suboccipital", "yes")
    assert _generate("--suboccipital", "no") == plain
    hill = _hill
    extra = [l for l in hill(sub) if l not in hill(plain)]
    assert len(hill(sub)) == len(hill(plain)) + 8 and len(extra) == 8
    f = {segments._fields(l)[1]: segments._fields(l) for l in extra}
    assert sorted(f) == sorted(m + s for m in ("RCPMAJ", "RCPMIN", "OCI", "OCS") for s in "LR")
    assert all(v[6] == "EXT" and {v[2], v[3]} <= {"C2", "C1", "HEAD"} for v in f.values())
    assert float(f["RCPMAJL"][4]) == pytest.approx(90.0) and float(f["OCIR"][4]) == pytest.approx(125.0)
    assert [l for l in sub if not l.startswith(("HILL", " ", "*"))] == \
        [l for l in plain if not l.startswith(("HILL", " ", "*"))]
    _program_reads(tmp_path, sub)


def test_values_listing_regenerates_the_shipped_deck(tmp_path):
    # the shipped deck's values of the NBDL fit's parameters, as the
    # generator's --fit reads them (the starting point of dev/fit_model.sh
    # and the joint fit's, calibration.values_listing), and the springs of
    # reference/nz_springs.csv give the shipped deck byte for byte
    from hhneck.validation import calibration
    listing = tmp_path / "values.txt"
    listing.write_text(calibration.values_listing())
    assert listing.read_text().count("PARAM ") == 15
    got = _generate("--fit", str(listing), "--nz-springs", os.path.join(ROOT, "reference", "nz_springs.csv"))
    assert got == open(segments.MODEL_DECK).read().splitlines()
