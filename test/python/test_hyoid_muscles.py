"""The eight cervical muscles mapped from the HYOID neck model (hhneck.validation.hyoid_muscles,
reference/parameters.md S22): the parameter table holds what the mapping
computes from the shared data (no hand-copied value); the model's F0 =
PCSA x sigma_max gives back the data's F0; each mapped line is the data's
line scaled by the two columns' height ratio, to within the difference of
the two models' (scaled) joint spacing between T1-C7 and the vertebra's
joint (the origin and the insertion keep their offsets from those two
joint centres: the triangle inequality bounds the length's change by that
difference); the deck carries them, the scalenes on FLEX
and the others on EXT, and the controller groups each with its side."""
import csv
import math
import os

import pytest

from conftest import ROOT
from hhneck.validation import hyoid_muscles as hm
from hhneck.validation import model_deck as md

pytestmark = pytest.mark.skipif(not os.path.isdir(hm.data_dir()), reason="shared/data/neck_muscles is not beside the project")


@pytest.fixture(scope="module")
def table():
    return md.read_table()


def test_table_rows_are_the_mapping(table):
    by_name = {r["name"]: r for r in table}
    new = hm.rows(md.table_values(table))
    assert len(new) == 8 * 9
    for r in new:
        assert r["name"] in by_name, r["name"]
        assert by_name[r["name"]] == r, r["name"]


def test_force_and_fibres_are_the_data(table):
    p = md.table_values(table)
    arch = {r["muscle"]: r for r in csv.DictReader(open(os.path.join(hm.data_dir(), "muscles.csv")))}
    for key, name, _ in hm.MUSCLES:
        f0 = p["muscle.%s.pcsa" % key] * 1e-4 * p["muscle.sigma_max"]
        assert f0 == pytest.approx(float(arch[name]["F0_N"]), rel=1e-4), key
        assert p["muscle.%s.lopt" % key] == pytest.approx(float(arch[name]["lopt_m"]), rel=1e-4), key


def test_lines_are_the_data_lines_scaled(table):
    p = md.table_values(table)
    geo = md._Geometry(p)
    scale = (geo.joint["HEAD"][2] - geo.joint["C7"][2]) / (hm.JOINTS["HEAD"][1] - hm.JOINTS["C7"][1])
    assert scale == pytest.approx(1.089, abs=0.001)
    points = {}
    for r in csv.DictReader(open(os.path.join(hm.data_dir(), "path_points.csv"))):
        points.setdefault(r["muscle"], []).append(r)
    for key, name, body in hm.MUSCLES:
        path = sorted(points[name], key=lambda r: int(r["order"]))
        a = [r for r in path if r["hhneck_body_inferred"] == "T1"][-1]
        b = [r for r in path if r["hhneck_body_inferred"] == body][0]
        data = math.dist(*[[float(r["%s_spine_neutral_derived_m" % c]) for c in "xyz"] for r in (a, b)])
        o = [p["muscle.%s.origin_%s" % (key, c)] for c in "xyz"]
        i = [p["muscle.%s.insertion_%s" % (key, c)] + geo.centre[body][k] for k, c in enumerate("xyz")]
        ours = [geo.joint[body][k] - geo.joint["C7"][k] for k in (0, 2)]             # forward, up
        theirs = [scale * (hm.JOINTS[body][k] - hm.JOINTS["C7"][k]) for k in (0, 1)]  # anterior, superior
        assert abs(math.dist(o, i) - scale * data) <= math.dist(ours, theirs) + 1e-9, key
        assert o[1] > 0 and i[1] > 0, key + ": the table's points are the left side's"


def test_deck_and_controller_carry_them():
    deck = open(os.path.join(ROOT, "input", "head_neck_54dof.inp")).read().splitlines()
    ctl = open(os.path.join(ROOT, "input", "volunteer_controller.inp")).read().splitlines()
    hill = {l[10:20].strip(): (l[20:30].strip(), l[30:40].strip(), l[60:70].strip()) for l in deck if l.startswith("HILL")}
    fibre = {l[10:20].strip() for l in deck if l.startswith("FIBRE")}
    group = {l[10:20].strip(): l[20:30].strip() for l in ctl if l.startswith("GROUP")}
    for key, _, body in hm.MUSCLES:
        hist = "FLEX" if key.startswith("SCAL") else "EXT"
        for side in "LR":
            assert hill[key + side] == ("T1", body, hist), key + side
            assert key + side in fibre, key + side
            assert group[key + side] == hist + side, key + side
