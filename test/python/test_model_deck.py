"""The model deck from its parameter table (python/hhneck/validation/model_deck.py,
reference/model_parameters.csv; reference/parameters.md): the shipped deck
regenerated from the table, from a folder outside the repository, is
input/head_neck_54dof.inp byte for byte; every row of the table is read and
changes the deck, and every number of every card moves with some row (the
fields that none moves are the listed structural constants); a row changed
alone changes exactly its card fields; the table's fitted rows are what the
fits wrote (reference/column_fit.csv and reference/nz_springs.csv recorded
again leave the table as it is); a column CSV recorded lands in exactly its
rows (status fitted, stage segments) and the regenerated deck differs from
the shipped one in exactly those card fields, and the program reads it; a
spring CSV recorded lands in the nz rows; dev/fit_model.sh writes both
stages into the table and the deck from it; a table or CSV the writer
cannot use is refused with the reason and nothing written."""
import csv
import os
import re
import shutil
import subprocess

import pytest

from conftest import ROOT, hhneck_executable, hhneck_module
from hhneck.validation import fit_joints, segments
from hhneck.validation import model_deck as md
from hhneck.decks import field

SHIPPED_TABLE = os.path.join(ROOT, "reference", "model_parameters.csv")
COLUMN_CSV = os.path.join(ROOT, "reference", "column_fit.csv")


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
    r = hhneck_module("validation.model_deck", "--output", out, cwd=tmp_path)
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
    assert counts["fitted"] == 4 + 24 * 5 and counts["sourced"] > 40 and counts["assumed"] > 100
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
# vertebra's mass-centre height (VIA z), a ligament on the midline (the y
# of its points: a row of y = 0 would make it a pair), and the passive
# activation histories (ACTIVATE u0, u1 and delay zero: the specimen state)
STRUCTURAL = {("JOINT", k) for k in (2, 3, 5, 6)} | {("JOINT T1", k) for k in range(2, 8)} | \
    {("DISC+1", k) for k in (1, 2, 4, 5, 7)} | {("LIGAMENT", 4)} | {("NEUTRAL C1", 3)} | \
    {("LIGAMENT+1", k) for k in (2, 5)} | {("VIA", 5)} | {("ACTIVATE", k) for k in (2, 3, 5)}


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
    assert _changes("SIGMA", 1.25) == {("SCALE", "SIGMA", "MUSCLES", 0, 4): ("1.0", "1.25")}
    bend = md.table_values(_rows())["disc.bend_fraction"]
    vbend = md.scale_factor(md.table_values(_rows()), "VBEND")
    # the bending fraction moves the discs' retardation time with it: S1's damping coefficient kept
    assert _changes("disc.bend_fraction", 0.5) == {("SCALE", "NZBEND", "DISCS", 0, 4): (md.fmt(bend), "0.5"),
                                                   ("SCALE", "VBEND", "DISCS", 0, 4): (md.fmt(vbend), "40.0")}
    rom = _changes("rom.k", 60.0)
    assert len(rom) == 24 and all(k[0] == "ROM" and k[3:] == (0, 5) and v == ("50.0", "60.0")
                                  for k, v in rom.items())
    m0 = md.table_values(_rows())["nz.C4.RZ.m0_plus"]
    assert _changes("nz.C4.RZ.m0_plus", 0.5) == {("NZSPRING", "C4", "RZ", 0, 3): (md.fmt(m0), "0.5")}
    # S1's flexion stiffness of C3-C5 moves Iy (and G, J through the shear
    # law) of the discs C5-C4 and C4-C3 alone
    disc = _changes("disc.C3-C5.flexion", 30.0)
    assert {k[:2] for k in disc} == {("DISC", "C5C4"), ("DISC", "C4C3")}
    assert {k[3:] for k in disc} == {(2, 1), (2, 3), (2, 4)}
    # the shear stiffness k_shear: G and with it J of every disc
    shear = _changes("disc.k_shear", 4.0e5)
    assert {k[3:] for k in shear} == {(2, 1), (2, 4)} and len(shear) == 16


def test_the_fitted_rows_are_what_the_fits_wrote(tmp_path):
    """Recording reference/column_fit.csv and reference/nz_springs.csv (the
    column's fit's output) changes no byte of the table."""
    copy = tmp_path / "t.csv"
    shutil.copy(SHIPPED_TABLE, copy)
    for stage, path in (("segments", COLUMN_CSV), ("nz_springs", os.path.join(ROOT, "reference", "nz_springs.csv"))):
        r = hhneck_module("validation.model_deck", "--table", copy, "--record", stage, path, cwd=tmp_path)
        assert r.returncode == 0 and r.stdout == "", r.stderr
    assert copy.read_bytes() == open(SHIPPED_TABLE, "rb").read()


def test_a_column_fit_lands_in_its_rows_and_the_deck(tmp_path):
    """A column CSV with every factor 10 % off the shipped value: the rows
    are exactly its (value as written, fitted, stage segments), the deck
    differs from the shipped one in exactly the four SCALE fields, and the
    program reads it."""
    shipped = {r["name"]: r for r in _rows()}
    fit = {r["name"]: "%.6g" % (1.1 * float(shipped[r["name"]]["value"]))
           for r in csv.DictReader(l for l in open(COLUMN_CSV) if not l.startswith("#"))}
    assert len(fit) == 4
    (tmp_path / "fit.csv").write_text("name,value\n" + "".join("%s,%s\n" % kv for kv in fit.items()))
    table = tmp_path / "t.csv"
    shutil.copy(SHIPPED_TABLE, table)
    deck = tmp_path / "input" / "head_neck_54dof.inp"
    deck.parent.mkdir()
    r = hhneck_module("validation.model_deck", "--table", table, "--record", "segments", "fit.csv", "--output", deck,
                      cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    for row in md.read_table(str(table)):
        want = dict(shipped[row["name"]])
        if row["name"] in fit:
            want.update(value=fit[row["name"]], status="fitted", stage="segments", source="S21")
        assert row == want
    scale = {"disc.bend_fraction": "NZBEND", "disc.torsion_fraction": "NZTORS", "ROMK": "ROMK", "ROMT0": "ROMT0"}
    got, base = deck.read_text().splitlines(), open(segments.MODEL_DECK).read().splitlines()
    assert len(got) == len(base)
    changed = [(field(a, 1), field(b, 4)) for a, b in zip(base, got) if a != b]
    assert all(a.startswith("SCALE") for a, b in zip(base, got) if a != b)
    want = {scale[n]: float(v) for n, v in fit.items()}
    # the discs' retardation time follows their bending fraction (S1's damping coefficient kept)
    want["VBEND"] = md.table_values(md.read_table(str(table)))["VBEND"] / float(fit["disc.bend_fraction"])
    assert {n: float(v) for n, v in changed} == pytest.approx(want, rel=1e-5)
    with open(os.path.join(ROOT, "input", "case6-1.inp")) as f:
        r = subprocess.run([hhneck_executable(), "--check"], stdin=f, cwd=tmp_path, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr


def _spring_csv(path, change=None):
    """reference/nz_springs.csv through python3 -m hhneck.validation.fit_joints' writer's format,
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
    r = hhneck_module("validation.model_deck", "--table", table, "--record", "nz_springs", tmp_path / "nz.csv", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    new, old = md.read_table(str(table)), _rows()
    assert [(a["name"], a["value"]) for a, b in zip(new, old) if a != b] == [("nz.C5.RY.ths_minus_deg", "12.5")]
    lines = md.deck_lines(md.table_values(new))
    q = md.table_values(old)
    assert [l for l in lines if l.startswith("NZSPRING  C5        RY")] == \
        [md.card("NZSPRING", "C5", "RY", q["nz.C5.RY.m0_plus"], q["nz.C5.RY.ths_plus_deg"],
                 q["nz.C5.RY.m0_minus"], 12.5, q["nz.C5.RY.mlin"])]


@pytest.mark.parametrize("stage, text, message", [
    ("segments", "name,value\nROMK,1.1\nKPE,2.0\n", "names no row of the table: KPE"),
    ("segments", "no parameters\n", "has no row with a name and a value"),
    ("segments", "name,value\nROMK,x1.1\n", "ROMK: 'x1.1' is not a finite number"),
    ("nbdl12g", "name,value\nROMK,1.1\n", "stage 'nbdl12g'; expected one of nz_springs, segments"),
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
    r = hhneck_module("validation.model_deck", "--table", table, "--record", stage, src, "--output", tmp_path / "d.inp",
                      cwd=tmp_path)
    assert r.returncode == 1 and message in r.stderr and "not written" in r.stderr, r.stderr
    assert table.read_bytes() == open(SHIPPED_TABLE, "rb").read() and not (tmp_path / "d.inp").exists()


@pytest.mark.parametrize("edit, message", [
    (lambda t: t.replace("body.C7.mass,0.523,", "body.C7.mass,0.5x23,", 1), "line 6 (body.C7.mass): '0.5x23'"),
    (lambda t: t.replace(",sourced,S1,,C6 vertebra", ",measured,S1,,C6 vertebra", 1), "status 'measured'"),
    (lambda t: re.sub(r"^(ROMK,[^,]*,1,fitted,S21,)segments,", r"\1,", t, count=1, flags=re.M),
     "(ROMK): stage '' with status fitted"),
    (lambda t: t.replace("body.C6.mass,", "body.C7.mass,", 1), "line 7: the name 'body.C7.mass' is empty or repeated"),
    (lambda t: t.replace("name,value,", "name,val,", 1), "line 1: the columns are"),
])
def test_a_bad_table_is_refused_naming_the_line(tmp_path, edit, message):
    table = tmp_path / "t.csv"
    text = open(SHIPPED_TABLE).read()
    table.write_text(edit(text))
    assert table.read_text() != text
    r = hhneck_module("validation.model_deck", "--table", table, "--output", tmp_path / "d.inp", cwd=tmp_path)
    assert r.returncode == 1 and message in r.stderr, r.stderr
    assert not (tmp_path / "d.inp").exists()


def _script(path, text):
    path.write_text("#!/bin/sh\n" + text)
    path.chmod(0o755)


def test_fit_model_writes_the_table_then_the_deck(tmp_path):
    """dev/fit_model.sh in a copy of the tree, the column's fit stood in for
    by a command that writes reference/column_fit.csv with ROMK at 2.5 and
    reference/nz_springs.csv with C5 RY ths- at 12.5 deg: the table's rows
    of both stages are what the step wrote, every other row unchanged, and
    the deck is the generator's from that table; the cervical muscles'
    rows, mapped again from the shared data beside the copy, unchanged."""
    copy = tmp_path / "tree"
    os.symlink(os.path.join(os.path.dirname(ROOT), "shared"), tmp_path / "shared")
    for d in ("dev", "input", "reference", "python"):
        shutil.copytree(os.path.join(ROOT, d), copy / d, ignore=shutil.ignore_patterns("__pycache__", "*.h5"))
    shutil.copy(os.path.join(ROOT, "fpm.toml"), copy / "fpm.toml")    # the copy is a project (hhneck.paths)
    (copy / "dev" / "fit_controller.sh").unlink(missing_ok=True)
    bin_ = tmp_path / "bin"
    bin_.mkdir()
    _script(bin_ / "fpm", "echo %s\n" % hhneck_executable())
    _script(bin_ / "fit-column", "awk -F, 'BEGIN {OFS = \",\"} $1 == \"ROMK\" {$2 = \"2.5\"} {print}' "
            "reference/column_fit.csv > c.tmp && mv c.tmp reference/column_fit.csv\n"
            "awk -F, 'BEGIN {OFS = \",\"} $1 == \"C5\" && $2 == \"RY\" {$6 = \"12.5\"} "
            "{print}' reference/nz_springs.csv > nz.tmp && mv nz.tmp reference/nz_springs.csv\n")
    env = dict(os.environ, PATH=str(bin_) + os.pathsep + os.environ["PATH"], FIT_COLUMN=str(bin_ / "fit-column"))
    env.pop("PYTHONPATH", None)
    r = subprocess.run(["sh", str(copy / "dev" / "fit_model.sh")], cwd=copy, env=env, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-3000:]
    got, shipped = md.read_table(str(copy / "reference" / "model_parameters.csv")), _rows()
    changed = {a["name"]: a["value"] for a, b in zip(got, shipped) if a != b}
    assert [a["name"] for a in got] == [b["name"] for b in shipped]
    assert changed == {"ROMK": "2.5", "nz.C5.RY.ths_minus_deg": "12.5"}
    assert all(a["status"] == "fitted" and a["stage"] == ("nz_springs" if a["name"].startswith("nz.") else "segments")
               for a in got if a["name"] in changed)
    assert (copy / "input" / "head_neck_54dof.inp").read_text().splitlines() == md.deck_lines(md.table_values(got))
