#!/usr/bin/env python3
"""Facet joints of the subaxial column (C2-C3 ... C7-T1): the include deck
from its table, the coupling they give, and what they move in the catalogue.

    python3 studies/facets.py --write-deck          # input/facets.inp from reference/facet_parameters.csv
    python3 studies/facets.py --coupling            # lateral bending 1 N m per segment, with and without
    python3 studies/facets.py --catalogue [--quick] # every case's score without and with the facets

--write-deck: one FACET card pair per side and joint (docs/deck-format.md,
FACET): the facet centre at (x, +-half width, z) in the lower body's frame,
z the joint point of the segment (the JOINT card of the upper body in the
model deck), the normal from the superior facet's inclination to the
transverse plane and its angle to the sagittal plane (the normal's turn
phi = sagittal - 90 deg on the left, 90 deg - sagittal on the right: a
facet at less than 90 deg faces posteromedially), k = E A / t of the
cartilage layer. Nothing here is fitted.

--coupling: the catalogue's segment test deck (hhneck.validation.segments.write_deck)
of every subaxial segment, lateral bending to +-1 N m as a quasi-static
ramp (STATICS), with the model deck's cards alone and with the facets'
cards of that joint; for each, the lateral bend and the coupled axial
rotation of the upper body at +-1 N m and their ratio (axial rotation per
degree of lateral bending, the sign + when both turn to the same side).

--catalogue: hhneck.validation.catalogue twice, on a scratch copy of the project
whose model deck is the shipped one with input/facets.inp's cards appended
(the catalogue has no option for another model deck; the segment decks
take a model card only when hhneck.validation.segments.ELEMENT_CARDS lists it, so the
run adds FACET there), and a table of every rated row's score without and
with the facets.
"""
import argparse
import csv
import os
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path[:0] = [os.path.join(ROOT, "python")]
from hhneck.validation import segments  # noqa: E402

TABLE = os.path.join(ROOT, "reference", "facet_parameters.csv")
DECK = os.path.join(ROOT, "input", "facets.inp")
#: joint -> (lower body, upper body)
JOINTS = {"C2-C3": ("C3", "C2"), "C3-C4": ("C4", "C3"), "C4-C5": ("C5", "C4"), "C5-C6": ("C6", "C5"),
          "C6-C7": ("C7", "C6"), "C7-T1": ("T1", "C7")}
#: the catalogue's subaxial segments (hhneck.validation.segments.SEGMENTS) and their joints
SEGMENT_JOINT = {"C2_C3": "C2-C3", "C3_C4": "C3-C4", "C4_C5": "C4-C5", "C5_C6": "C5-C6", "C6_C7": "C6-C7"}


#: values of the table changed by --set (the variants of the study)
CHANGED = {}


def table(path=TABLE):
    """The facet table: name -> value (a number, or the text of a non-numeric row), with --set's changes."""
    out = {}
    with open(path) as f:
        for r in csv.DictReader(f):
            try:
                out[r["name"]] = float(r["value"])
            except ValueError:
                out[r["name"]] = r["value"]
    unknown = [n for n in CHANGED if n not in out]
    if unknown:
        raise KeyError("no row %s in %s" % (", ".join(unknown), path))
    out.update(CHANGED)
    return out


def joint_heights(model=segments.MODEL_DECK):
    """Upper body -> z of its JOINT card in its parent's frame [m]."""
    z = {}
    with open(model) as f:
        for line in f:
            if line.startswith("JOINT "):
                fields = [line[k:k + 10].strip() for k in range(0, 80, 10)]
                z[fields[1]] = float(fields[4])
    return z


def field(v):
    """A 10-column field."""
    s = v if isinstance(v, str) else "%.6g" % v
    if len(s) > 10:
        raise ValueError("field %r longer than 10 columns" % s)
    return s.ljust(10)


def facet_cards(values=None, model=segments.MODEL_DECK, joints=None):
    """The FACET cards of `joints` (default all), a list of card images."""
    t = values or table()
    z = joint_heights(model)
    lines = []
    for j, (lower, upper) in JOINTS.items():
        if joints is not None and j not in joints:
            continue
        k = t["facet.modulus"] * 1e6 * t["facet.%s.area" % j] * 1e-6 / (t["facet.thickness"] * 1e-3)
        lines.append("* %s: k = E A / t = %.3g N/m" % (j, k))
        for side, sign in (("left", 1.0), ("right", -1.0)):
            sag = t["facet.%s.sagittal_%s" % (j, side)]
            phi = sag - 90.0 if side == "left" else 90.0 - sag
            name = "F%s%s%s" % (upper, lower, side[0].upper())
            lines.append("FACET     " + "".join(field(v) for v in (
                name, lower, upper, k, t["facet.exponent"], t["facet.damping"], t["facet.gap"])).rstrip())
            lines.append("          " + "".join(field(v) for v in (
                t["facet.x"], sign * t["facet.half_width"], z[upper], t["facet.%s.incl_%s" % (j, side)],
                round(phi, 3))).rstrip())
    return lines


def write_deck(path=DECK):
    """Write input/facets.inp."""
    head = ["* FACET JOINTS C2-C3 ... C7-T1 (docs/deck-format.md, FACET), for decks that",
            "* INCLUDE them after the model deck:  INCLUDE   input/facets.inp",
            "* Generated by studies/facets.py --write-deck from the table",
            "* reference/facet_parameters.csv (sources S23, S24 and the assumptions in",
            "* reference/parameters.md); edit the table, not this file. Per facet: the",
            "* lower body (the superior facet's plane),",
            "* the upper body (the inferior facet's point), k [N/m], exponent, damping",
            "* [N s/m], gap [m]; centre x y z [m] in the lower body's frame, inclination",
            "* to the transverse plane and turn of the normal towards +Y [deg]."]
    lines = head + facet_cards()
    for k, line in enumerate(lines):
        if len(line) > 80:
            raise ValueError("%s line %d: %d columns, card images have 80" % (path, k + 1, len(line)))
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def coupling(exe=None, peak=1.0):
    """Lateral bend and coupled axial rotation at +-peak N m per segment, without and with facets."""
    from hhneck import run
    from hhneck.results import read_channels
    import numpy as np
    exe = exe or run.find_executable(None, ROOT)
    work = tempfile.mkdtemp(prefix="facets-coupling-")
    rows = []
    for seg, joint in SEGMENT_JOINT.items():
        for with_facets in (False, True):
            model = segments.MODEL_DECK
            if with_facets:
                model = os.path.join(work, "model_%s.inp" % seg)
                with open(segments.MODEL_DECK) as f:
                    text = f.read()
                with open(model, "w") as f:
                    f.write(text + "\n".join(facet_cards(joints=[joint])) + "\n")
            deck = os.path.join(work, "%s_%d.inp" % (seg, with_facets))
            segments.write_deck(deck, seg, "lateral_bending", peak, model=model,
                                elements=segments.ELEMENT_CARDS + ("FACET",))
            h5 = deck[:-4] + ".h5"
            run.run_deck(deck, executable=exe, h5=h5, cwd=work)
            upper = segments.SEGMENTS[seg][1][-1]
            df = read_channels(h5, ["%s_RX" % upper, "%s_RZ" % upper])
            assert df.attrs["units"]["%s_RX" % upper] == "deg", df.attrs["units"]
            t = df.index.values
            rx = df.iloc[:, 0].values - df.iloc[0, 0]
            rz = df.iloc[:, 1].values - df.iloc[0, 1]
            m = np.interp(t, *zip(*segments.moment_table(peak)))
            for target in (peak, -peak):
                k = int(np.argmin(np.abs(m - target)))
                # RX < 0: bent to the left (left side down), RZ > 0: turned to the left; the ratio
                # -RZ/RX is + when both go to the same side (ipsilateral)
                rows.append((seg, with_facets, target, rx[k], rz[k], -rz[k] / rx[k] if abs(rx[k]) > 1e-9 else 0.0))
    return rows


def lateral(exe=None):
    """input/lateral7g.inp without and with the facets (the table's cards INCLUDEd after the case deck):
    per subaxial joint the peak lateral bend (RX) and axial rotation (RZ) of the upper body on the
    lower, with their times."""
    from hhneck import run
    from hhneck.results import read_channels
    import numpy as np
    exe = exe or run.find_executable(None, ROOT)
    work = tempfile.mkdtemp(prefix="facets-lateral-")
    with open(os.path.join(work, "facets.inp"), "w") as f:     # the table's cards, with --set's changes
        f.write("\n".join(facet_cards()) + "\n")
    deck = "TITLE     LATERAL 7 G WITH FACETS\nINCLUDE   input/lateral7g.inp\nINCLUDE   facets.inp\n"
    rows = []
    for wf, d in ((False, os.path.join(ROOT, "input", "lateral7g.inp")), (True, deck)):
        h5 = os.path.join(work, "lateral_%d.h5" % wf)
        run.run_deck(d, executable=exe, h5=h5, cwd=work, include=[ROOT])
        for j, (lower, upper) in JOINTS.items():
            if j == "C7-T1":
                continue
            df = read_channels(h5, ["%s_RX" % upper, "%s_RZ" % upper])
            peaks = []
            for c in df.columns:
                v = df[c].values - df[c].values[0]
                k = int(np.argmax(np.abs(v)))
                peaks += [v[k], 1000 * df.index[k]]
            rows.append((j, wf) + tuple(peaks))
    return rows


def scratch_project(work, with_facets):
    """A copy of the project (links) whose model deck holds the facets' cards when asked."""
    root = os.path.join(work, "with" if with_facets else "without")
    os.makedirs(os.path.join(root, "input"))
    shared = os.path.join(work, "shared")          # the data beside the project, as in a checkout's parent
    if not os.path.exists(shared):
        os.symlink(os.path.join(os.path.dirname(ROOT), "shared"), shared)
    for name in os.listdir(ROOT):
        if name not in ("input", "build", ".git"):
            os.symlink(os.path.join(ROOT, name), os.path.join(root, name))
    for name in os.listdir(os.path.join(ROOT, "input")):
        src = os.path.join(ROOT, "input", name)
        if name == os.path.basename(segments.MODEL_DECK) and with_facets:
            with open(src) as f:
                text = f.read()
            with open(os.path.join(root, "input", name), "w") as f:
                f.write(text + "\n".join(facet_cards()) + "\n")
        else:
            os.symlink(src, os.path.join(root, "input", name))
    return root


def run_catalogue(root, report, exe, quick, jobs):
    """hhneck.validation.catalogue on the scratch project `root` (FACET added to the segment decks' cards)."""
    code = ("import sys; from hhneck.validation import segments; segments.ELEMENT_CARDS += ('FACET',); "
            "from hhneck.validation.catalogue import main; sys.exit(main(sys.argv[1:]))")
    cmd = [sys.executable, "-c", code, "--exe", exe, "--data", segments.DATA_DIR, "--report", report]
    cmd += (["--quick"] if quick else []) + (["--jobs", str(jobs)] if jobs else [])
    env = dict(os.environ, HHNECK_ROOT=root, PYTHONPATH=os.path.join(ROOT, "python"))
    return subprocess.run(cmd, cwd=root, env=env, capture_output=True, text=True)


def scores(stderr):
    """Case title -> its score text, from the catalogue's progress lines on stderr."""
    out = {}
    for line in stderr.splitlines():
        m = re.match(r"hhneck-catalogue: \[\d+/\d+\] (.*?)(?::| FAILED:) (.*) \([\d.]+ s\)$", line)
        if m:
            out[m.group(1)] = m.group(2) if "FAILED" not in line else "FAILED " + m.group(2)[:60]
    return out


def numbers(text):
    """The numbers of a score text."""
    return [float(v) for v in re.findall(r"(?<![\w.])-?\d+\.\d+", text)]


def score_table(without, with_):
    """Markdown rows: case, score without, with, change of each number."""
    rows = ["| case | without facets | with facets | change |", "|---|---|---|---|"]
    for case in without:
        a, b = without[case], with_.get(case, "-")
        na, nb = numbers(a), numbers(b)
        change = ", ".join("%+.3f" % (y - x) for x, y in zip(na, nb)) if len(na) == len(nb) else "-"
        rows.append("| %s | %s | %s | %s |" % (case, a, b, change))
    return rows


def report_rows(path):
    """(section, first cell, second cell) -> the ISO 18571 cell of every table row of a catalogue report."""
    rows, section, col, motion = {}, "", None, False
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                section, col = line.strip("# \n"), None
            elif line.startswith("|"):
                cells = [c.strip() for c in line.strip().strip("|").split("|")]
                if "ISO 18571" in cells:
                    col, motion = cells.index("ISO 18571"), cells[1] == "motion"
                elif col is not None and not set(cells[0]) <= set("-") and len(cells) > col:
                    rows[(section, cells[0], cells[1] if motion else "")] = cells[col].strip("*")
            else:
                col = None if not line.strip() else col
    return rows


def channel_table(without_md, with_md):
    """Markdown rows: every rated curve or channel of the two reports whose score moved."""
    a, b = report_rows(without_md), report_rows(with_md)
    out = ["| section | curve or channel | without facets | with facets | change |", "|---|---|---|---|---|"]
    for key, va in a.items():
        vb = b.get(key)
        try:
            d = float(vb) - float(va)
        except (TypeError, ValueError):
            continue
        if abs(d) >= 0.0005:
            out.append("| %s | %s | %s | %s | %+.3f |" % (key[0][:40], (key[1] + " " + key[2]).strip(), va, vb, d))
    return out


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--write-deck", action="store_true", help="write input/facets.inp from the table")
    p.add_argument("--coupling", action="store_true", help="lateral bending of each subaxial segment")
    p.add_argument("--catalogue", action="store_true", help="the catalogue without and with the facets")
    p.add_argument("--lateral", action="store_true", help="the lateral 7 g sled deck without and with the facets")
    p.add_argument("--quick", action="store_true", help="the catalogue's --quick")
    p.add_argument("--jobs", type=int, help="the catalogue's --jobs")
    p.add_argument("--exe", help="the hhneck executable (default fpm's release build)")
    p.add_argument("--out", help="working folder (default a temporary one)")
    p.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                   help="a value of the facet table changed for --coupling and --catalogue (e.g. facet.gap=0.0005)")
    p.add_argument("--with-only", action="store_true", help="--catalogue: the run with the facets alone")
    a = p.parse_args(argv)
    for item in a.set:
        name, value = item.split("=", 1)
        if name not in CHANGED:
            CHANGED[name] = float(value)
    if a.write_deck:
        write_deck()
        print("wrote", os.path.relpath(DECK, ROOT))
    if a.coupling:
        print("segment  facets  moment [N m]  lateral RX [deg]  axial RZ [deg]  -RZ/RX (+: same side)")
        for seg, wf, m, rx, rz, ratio in coupling(a.exe):
            print("%-8s %-7s %+6.2f %17.3g %15.3g %7.3g" % (seg, "yes" if wf else "no", m, rx, rz, ratio))
    if a.lateral:
        print("joint  facets  peak RX [deg] (ms)  peak RZ [deg] (ms)")
        for j, wf, rx, trx, rz, trz in lateral(a.exe):
            print("%-6s %-7s %8.3g (%3.0f)      %8.3g (%3.0f)" % (j, "yes" if wf else "no", rx, trx, rz, trz))
    if a.catalogue:
        from hhneck import run
        exe = a.exe or run.find_executable(None, ROOT)
        work = a.out or tempfile.mkdtemp(prefix="facets-catalogue-")
        found = []
        for wf in ((True,) if a.with_only else (False, True)):
            root = scratch_project(work, wf)
            report = os.path.join(work, "report_%s" % ("with" if wf else "without"), "catalogue.md")
            r = run_catalogue(root, report, exe, a.quick, a.jobs)
            with open(os.path.join(work, "stderr_%s.txt" % ("with" if wf else "without")), "w") as f:
                f.write(r.stderr)
            print("catalogue %s facets: exit %d, report %s" % ("with" if wf else "without", r.returncode, report))
            found.append(scores(r.stderr))
        if not a.with_only:
            print("\n".join(score_table(*found)))
            print()
            print("\n".join(channel_table(*[os.path.join(work, "report_%s" % w, "catalogue.md")
                                            for w in ("without", "with")])))
    return 0


if __name__ == "__main__":
    sys.exit(main())
