"""The model deck from its parameter table (python/hhneck/model_deck.py,
reference/model_parameters.csv; reference/parameters.md): the shipped deck
regenerated from the table, from a folder outside the repository, is
input/head_neck_54dof.inp byte for byte; every row of the table is read and
changes the deck, and every number of every card moves with some row (the
fields that none moves are the listed structural constants); a row changed
alone changes exactly its card fields; the table's fitted rows are what the
fits wrote (reference/nz_springs.csv and the shipped deck's fitted values
recorded again leave the table as it is); a real, quick NBDL 12 g
calibration's listing recorded by the fit's writer lands in exactly its
rows (status fitted, stage nbdl12g) and the regenerated deck differs from
the shipped one in exactly those card fields, and the program reads it; a
spring CSV recorded lands in the nz rows; dev/fit_model.sh writes both
stages into the table and the deck from it; a table, listing or CSV the
writer cannot use is refused with the reason and nothing written."""
import csv
import os
import re
import shutil
import subprocess

import pytest

from conftest import ROOT, hhneck_executable, hhneck_module
from hhneck import calibration, fit_joints, segments
from hhneck import model_deck as md
from hhneck.deck_fields import field

SHIPPED_TABLE = os.path.join(ROOT, "reference", "model_parameters.csv")
# the fitted rows of stage nbdl12g and the card field each lands in
SCALE_ROWS = [s[0] for s in md.SCALES]
ACT_FIELDS = {"BRACE": 2, "REFLEX": 3, "DELAY": 5}


def _rows():
    return md.read_table(SHIPPED_TABLE)


def _deck(p, **kw):
    """The deck's lines with every variant's muscles (so every row is read)."""
    return md.deck_lines(p, suboccipital=True, segmental=True, **kw)


def _fields(lines):
    """{(line index, field): text} of the numbers of the non-comment lines."""
    out = {}
    for i, line in enumerate(lines):
        if line.startswith("*"):
            continue
        for k in range(1, 8):
            t = field(line, k)
            if re.fullmatch(r"[-+]?[0-9.]+(E[-+]?[0-9]+)?", t):
                out[(i, k)] = t
    return out


def _perturbed(name, value):
    """The deck with row `name` at `value`, every other row as shipped."""
    p = md.table_values(_rows())
    p[name] = value
    return _deck(p)


def _moved(name):
    """A value of row `name` that differs from the shipped one by 1 % (a zero by 1e-3)."""
    v = md.table_values(_rows())[name]
    return v * 1.01 if v else 1e-3


def test_regenerated_from_any_folder_is_the_shipped_deck_byte_for_byte(tmp_path):
    out = tmp_path / "deck.inp"
    r = hhneck_module("model_deck", "--output", out, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    with open(segments.MODEL_DECK, "rb") as f:
        assert out.read_bytes() == f.read()
    # the dev/ name the deck's header gives runs the same generator
    r = subprocess.run(["python3", os.path.join(ROOT, "dev", "make_head_neck_deck.py")], cwd=tmp_path,
                       capture_output=True)
    assert r.returncode == 0 and r.stdout == out.read_bytes()


def test_table_columns_statuses_and_sources():
    """Every row has a unit and a known status; a fitted row names its
    stage and that stage's data; every source tag is one of
    reference/parameters.md's Sources; the table reads back and writes
    back byte for byte."""
    rows = _rows()
    tags = set(re.findall(r"^\| (S\d+) \|", open(os.path.join(ROOT, "reference", "parameters.md")).read(), re.M))
    for r in rows:
        assert r["unit"] and r["description"], r["name"]
        assert (r["status"] == "fitted") == bool(r["stage"]), r["name"]
        if r["status"] == "fitted":
            assert r["source"] == md.STAGES[r["stage"]][0], r["name"]
        if r["status"] == "sourced":
            assert r["source"], r["name"]
        assert r["source"] in tags | {""}, r["name"]
    counts = {s: sum(r["status"] == s for r in rows) for s in md.STATUSES}
    assert counts["fitted"] == 15 + 24 * 5 and counts["sourced"] > 40 and counts["assumed"] > 100
    assert {r["stage"] for r in rows if r["stage"]} == set(md.STAGES)


def test_write_table_round_trip(tmp_path):
    copy = tmp_path / "t.csv"
    md.write_table(str(copy), _rows())
    assert copy.read_bytes() == open(SHIPPED_TABLE, "rb").read()


def test_every_row_is_read_and_changes_the_deck():
    rows = _rows()
    p = md.table_values(rows)
    base = _deck(p)
    assert p.used == {r["name"] for r in rows}
    unchanged = [r["name"] for r in rows if _perturbed(r["name"], _moved(r["name"])) == base]
    assert unchanged == []


# the card fields no row moves: the column is straight along Z in every body
# frame (JOINT and DISC plate x, y; the discs untilted), T1 the root at the
# origin, the ligaments' linear term l1 = 0 (the fitted curve is l2 d^n), C1
# aligned with C2 in the seated posture (NEUTRAL C1 RY), a via point at its
# vertebra's mass-centre height (VIA z), and a ligament on the midline (the y
# of its points: a row of y = 0 would make it a pair)
STRUCTURAL = {("JOINT", k) for k in (2, 3, 5, 6)} | {("JOINT T1", k) for k in range(2, 8)} | \
    {("DISC+1", k) for k in (1, 2, 4, 5, 7)} | {("LIGAMENT", 4)} | {("NEUTRAL C1", 3)} | \
    {("LIGAMENT+1", k) for k in (2, 5)} | {("VIA", 5)}


def _kind(lines, i):
    """The structural key of line i: its card's name (+n on the card's
    n-th continuation line), with the body for JOINT T1 and NEUTRAL C1."""
    n = 0
    while lines[i - n].startswith(" "):
        n += 1
    head = lines[i - n]
    if n == 0 and (field(head, 0), field(head, 1)) in (("JOINT", "T1"), ("NEUTRAL", "C1")):
        return field(head, 0) + " " + field(head, 1)
    return field(head, 0) + ("+%d" % n if n else "")


def test_every_card_number_moves_with_a_row():
    """Each row changed alone (1 %; a zero by 1e-3 where that keeps the
    cards' count): the union of the card fields that change covers every
    number of every card but the structural constants, and those hold."""
    rows = _rows()
    base = _deck(md.table_values(rows))
    numbers = _fields(base)
    moved = set()
    for r in rows:
        lines = _perturbed(r["name"], _moved(r["name"]))
        if len(lines) == len(base):
            got = _fields(lines)
            moved |= {key for key, t in numbers.items() if got.get(key) != t}
    fixed = {key for key in numbers if key not in moved}
    kinds = {(_kind(base, i), k) for i, k in fixed}
    assert kinds <= STRUCTURAL, sorted(kinds - STRUCTURAL)
    assert all(float(numbers[key]) == 0.0 for key in fixed)
    # the midline ligaments' y is the table's zero: 4 of the 5 at every level
    assert sum(1 for i, k in fixed if _kind(base, i) == "LIGAMENT+1" and k == 2) == 4 * 8


def _changes(name, value):
    """{(card, name, line of the card, field): (shipped, changed)} of the
    deck with row `name` at `value` (the same cards)."""
    base, lines = _deck(md.table_values(_rows())), _perturbed(name, value)
    assert len(lines) == len(base)
    out, card = {}, None
    for i, (a, b) in enumerate(zip(base, lines)):
        if a.startswith("*"):
            continue
        if not a.startswith(" "):
            card, n = (field(a, 0), field(a, 1), field(a, 2)), 0
        else:
            n += 1
        for k in range(1, 8):
            if field(a, k) != field(b, k):
                out[card + (n, k)] = (field(a, k), field(b, k))
    return out


def test_a_row_changes_exactly_its_fields():
    assert _changes("body.HEAD.mass", 4.5) == {("BODY", "HEAD", "C1", 0, 3): ("3.847", "4.5")}
    assert _changes("SIGMA", 1.25) == {("SCALE", "SIGMA", "MUSCLES", 0, 4): ("0.927739", "1.25")}
    assert _changes("DELAYE", 0.05) == {("ACTIVATE", "EXT", "0.282193", 0, 5): ("0.0996544", "0.05")}
    rom = _changes("rom.k", 60.0)
    assert len(rom) == 24 and all(k[0] == "ROM" and k[3:] == (0, 5) and v == ("50.0", "60.0")
                                  for k, v in rom.items())
    assert _changes("nz.C4.RZ.m0_plus", 0.5) == {("NZSPRING", "C4", "RZ", 0, 3): ("0.0028543", "0.5")}
    # S1's flexion stiffness of C3-C5 moves Iy (and G, J through the shear
    # law) of the discs C5-C4 and C4-C3 alone
    disc = _changes("disc.C3-C5.flexion", 30.0)
    assert {k[:2] for k in disc} == {("DISC", "C5C4"), ("DISC", "C4C3")}
    assert {k[3:] for k in disc} == {(2, 1), (2, 3), (2, 4)}
    # the shear stiffness k_shear: G and with it J of every disc
    shear = _changes("disc.k_shear", 4.0e5)
    assert {k[3:] for k in shear} == {(2, 1), (2, 4)} and len(shear) == 16


def test_the_fitted_rows_are_what_the_fits_wrote(tmp_path):
    """Recording reference/nz_springs.csv (hhneck-fit-joints' output) and
    the shipped deck's values of the calibration's PARAM names (the
    listing the shipped deck was written from) changes no byte of the table."""
    copy = tmp_path / "t.csv"
    shutil.copy(SHIPPED_TABLE, copy)
    listing = tmp_path / "values.txt"
    listing.write_text(calibration.values_listing())
    for stage, path in (("nz_springs", os.path.join(ROOT, "reference", "nz_springs.csv")),
                        ("nbdl12g", listing)):
        r = hhneck_module("model_deck", "--table", copy, "--record", stage, path, cwd=tmp_path)
        assert r.returncode == 0 and r.stdout == "", r.stderr
    assert copy.read_bytes() == open(SHIPPED_TABLE, "rb").read()


def _quick_listing(tmp_path):
    """The listing of hhneck --calibrate on input/calibrate_nbdl12g.inp cut to
    4 evaluations from 2 starting points (the fit's quick form)."""
    deck = open(os.path.join(ROOT, "input", "calibrate_nbdl12g.inp")).read()
    quick = re.sub(r"^FIT       NELDER    2500      300       ", "FIT       NELDER    4         2         ", deck,
                   flags=re.M)
    assert quick != deck
    (tmp_path / "quick.inp").write_text(quick)
    r = subprocess.run([hhneck_executable(), "-I", ROOT, "--calibrate", "quick.inp"], cwd=tmp_path,
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-2000:]
    (tmp_path / "fit.txt").write_text(r.stdout)
    return dict(md.read_fit(str(tmp_path / "fit.txt")))


def test_a_quick_calibration_lands_in_its_rows_and_the_deck(tmp_path):
    fit = _quick_listing(tmp_path)
    assert sorted(fit) == sorted(SCALE_ROWS + [k + s for k in ACT_FIELDS for _, s in md.HISTORIES])
    shipped_rows = _rows()
    shipped = {r["name"]: r for r in shipped_rows}
    assert any(float(v) != float(shipped[n]["value"]) for n, v in fit.items())
    table = tmp_path / "t.csv"
    shutil.copy(SHIPPED_TABLE, table)
    deck = tmp_path / "input" / "head_neck_54dof.inp"
    deck.parent.mkdir()
    r = hhneck_module("model_deck", "--table", table, "--record", "nbdl12g", "fit.txt", "--output", deck,
                      cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    # the rows: exactly the listing's, value as it prints it, fitted, stage nbdl12g
    for row in md.read_table(str(table)):
        want = dict(shipped[row["name"]])
        if row["name"] in fit:
            want.update(value=fit[row["name"]], status="fitted", stage="nbdl12g", source="S6")
        assert row == want
    # the deck: the shipped one but the fitted fields, each the listing's number
    got, base = deck.read_text().splitlines(), open(segments.MODEL_DECK).read().splitlines()
    assert len(got) == len(base)
    where = {}
    for i, line in enumerate(base):
        if line.startswith("SCALE") and field(line, 1) in fit:
            where[(i, 4)] = field(line, 1)
        if line.startswith("ACTIVATE"):
            s = dict(md.HISTORIES)[field(line, 1)]
            where.update({(i, k): n + s for n, k in ACT_FIELDS.items()})
    assert len(where) == 15
    for i, (a, b) in enumerate(zip(base, got)):
        ks = [k for k in range(1, 8) if (i, k) in where]
        if not ks:
            assert a == b
        for k in ks:
            assert float(field(b, k)) == pytest.approx(float(fit[where[(i, k)]]), rel=1e-12)
    # the program reads it
    (tmp_path / "input" / "nbdl12g_t1.inp").write_text(open(os.path.join(ROOT, "input", "nbdl12g_t1.inp")).read())
    with open(os.path.join(ROOT, "input", "nbdl12g.inp")) as f:
        r = subprocess.run([hhneck_executable(), "--check"], stdin=f, cwd=tmp_path, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr


def _spring_csv(path, change=None):
    """reference/nz_springs.csv through hhneck-fit-joints' writer's format,
    with (body, coord, column, value) `change` applied."""
    rows = fit_joints.read_csv(os.path.join(ROOT, "reference", "nz_springs.csv"))
    if change:
        b, c, k, v = change
        [r for r in rows if (r["body"], r["coord"]) == (b, c)][0][k] = v
    with open(path, "w", newline="") as f:
        f.write("# test\n")
        w = csv.DictWriter(f, fieldnames=list(rows[0]), lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
    return rows


def test_recorded_springs_land_in_their_rows(tmp_path):
    table = tmp_path / "t.csv"
    shutil.copy(SHIPPED_TABLE, table)
    _spring_csv(tmp_path / "nz.csv", ("C5", "RY", "ths_minus_deg", "12.5"))
    r = hhneck_module("model_deck", "--table", table, "--record", "nz_springs", tmp_path / "nz.csv", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    new, old = md.read_table(str(table)), _rows()
    assert [(a["name"], a["value"]) for a, b in zip(new, old) if a != b] == [("nz.C5.RY.ths_minus_deg", "12.5")]
    lines = md.deck_lines(md.table_values(new))
    assert [l for l in lines if l.startswith("NZSPRING  C5        RY")] == \
        ["NZSPRING  C5        RY        0.001     30.0      0.001     12.5      1.01082"]


@pytest.mark.parametrize("stage, text, message", [
    ("nbdl12g", "PARAM SIGMA = 1.1\nPARAM KPE = 2.0\n", "names no row of the table: KPE"),
    ("nbdl12g", "no parameters\n", "has no PARAM line"),
    ("nbdl12g", "PARAM SIGMA = x1.1\n", "PARAM SIGMA: 'x1.1' is not a finite number"),
    ("nbdl15g", "PARAM SIGMA = 1.1\n", "stage 'nbdl15g'; expected one of nz_springs, nbdl12g"),
    ("nz_springs", None, "has no value for nz.HEAD.RX.m0_minus"),
])
def test_the_writer_refuses_what_it_cannot_use(tmp_path, stage, text, message):
    table = tmp_path / "t.csv"
    shutil.copy(SHIPPED_TABLE, table)
    src = tmp_path / "in.txt"
    if text is None:
        rows = _spring_csv(src)
        with open(src, "w", newline="") as f:       # the first row (HEAD RX) left out
            w = csv.DictWriter(f, fieldnames=list(rows[0]), lineterminator="\n")
            w.writeheader()
            w.writerows(rows[1:])
    else:
        src.write_text(text)
    r = hhneck_module("model_deck", "--table", table, "--record", stage, src, "--output", tmp_path / "d.inp",
                      cwd=tmp_path)
    assert r.returncode == 1 and message in r.stderr and "not written" in r.stderr, r.stderr
    assert table.read_bytes() == open(SHIPPED_TABLE, "rb").read() and not (tmp_path / "d.inp").exists()


@pytest.mark.parametrize("edit, message", [
    (lambda t: t.replace("body.C7.mass,0.523,", "body.C7.mass,0.5x23,", 1), "line 6 (body.C7.mass): '0.5x23'"),
    (lambda t: t.replace(",sourced,S1,,C6 vertebra", ",measured,S1,,C6 vertebra", 1), "status 'measured'"),
    (lambda t: t.replace("SIGMA,0.927739,1,fitted,S6,nbdl12g,", "SIGMA,0.927739,1,fitted,S6,,", 1),
     "(SIGMA): stage '' with status fitted"),
    (lambda t: t.replace("body.C6.mass,", "body.C7.mass,", 1), "line 7: the name 'body.C7.mass' is empty or repeated"),
    (lambda t: t.replace("name,value,", "name,val,", 1), "line 1: the columns are"),
])
def test_a_bad_table_is_refused_naming_the_line(tmp_path, edit, message):
    table = tmp_path / "t.csv"
    text = open(SHIPPED_TABLE).read()
    table.write_text(edit(text))
    assert table.read_text() != text
    r = hhneck_module("model_deck", "--table", table, "--output", tmp_path / "d.inp", cwd=tmp_path)
    assert r.returncode == 1 and message in r.stderr, r.stderr
    assert not (tmp_path / "d.inp").exists()


def _script(path, text):
    path.write_text("#!/bin/sh\n" + text)
    path.chmod(0o755)


def test_fit_model_writes_the_table_then_the_deck(tmp_path):
    """dev/fit_model.sh in a copy of the tree, the calibration in its quick
    form (the real program, 4 evaluations from 2 starting points) and the
    spring fit stood in for by a command that writes reference/nz_springs.csv
    with C5 RY ths- at 12.5 deg: the table's rows of both stages are what
    the two steps wrote, every other row unchanged, and the deck is the
    generator's from that table."""
    copy = tmp_path / "tree"
    for d in ("dev", "input", "reference", "python"):
        shutil.copytree(os.path.join(ROOT, d), copy / d, ignore=shutil.ignore_patterns("__pycache__", "*.h5"))
    shutil.copy(os.path.join(ROOT, "fpm.toml"), copy / "fpm.toml")    # the copy is a project (hhneck.paths)
    bin_ = tmp_path / "bin"
    bin_.mkdir()
    _script(bin_ / "fpm", "echo %s\n" % (bin_ / "hhneck"))
    _script(bin_ / "hhneck", '[ "$1" = --calibrate ] || exit 9\n'
            "sed 's/^FIT       NELDER    2500      300       /FIT       NELDER    4         2         /' > q.inp\n"
            '"%s" --calibrate q.inp\n' % hhneck_executable())
    _script(bin_ / "hhneck-fit-joints", "awk -F, 'BEGIN {OFS = \",\"} $1 == \"C5\" && $2 == \"RY\" {$6 = \"12.5\"} "
            "{print}' reference/nz_springs.csv > nz.tmp && mv nz.tmp reference/nz_springs.csv\n")
    env = dict(os.environ, PATH=str(bin_) + os.pathsep + os.environ["PATH"], FIT_JOINTS=str(bin_ / "hhneck-fit-joints"))
    env.pop("PYTHONPATH", None)
    r = subprocess.run(["sh", str(copy / "dev" / "fit_model.sh"), str(tmp_path / "fit.txt")], cwd=tmp_path, env=env,
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-3000:]
    fit = dict(md.read_fit(str(tmp_path / "fit.txt")))
    assert len(fit) == 15
    got, shipped = md.read_table(str(copy / "reference" / "model_parameters.csv")), _rows()
    changed = {a["name"]: a["value"] for a, b in zip(got, shipped) if a != b}
    assert [a["name"] for a in got] == [b["name"] for b in shipped]
    old = {r["name"]: r["value"] for r in shipped}
    want = {n: v for n, v in fit.items() if v != old[n]}
    want["nz.C5.RY.ths_minus_deg"] = "12.5"
    assert changed == want and len(want) > 10
    assert all(a["status"] == "fitted" and a["stage"] == ("nz_springs" if a["name"].startswith("nz.") else "nbdl12g")
               for a in got if a["name"] in changed)
    assert (copy / "input" / "head_neck_54dof.inp").read_text().splitlines() == md.deck_lines(md.table_values(got))
