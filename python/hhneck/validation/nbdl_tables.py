"""Writes the T1 input tables of the NBDL sled decks from the volunteer runs
in reference/:

    python3 -m hhneck.validation.nbdl_tables

input/nbdl15g_t1.inp (runs 1635-1644, n = 7) and input/nbdl12g_t1.inp (runs
1607-1617, n = 10): T1 x- and z-acceleration [g] and sagittal rotation, each
run filtered (SAE J211/1, the filter of hhneck.tools.compare_nbdl), mean over the
runs, every 1 ms from 0 to 299 ms. The x-acceleration and the rotation are
filtered CFC 60; the z-acceleration CFC 20: above about 20 Hz the runs' T1
z-accelerations are out of phase with each other (a mount ringing at 50-60 Hz,
up to 88 g with millimetre displacements, at 85-120 ms), not a motion of the
torso the model's rigid T1 should transmit to the head; the evidence is
printed by studies/nbdl_t1_evidence.py (docs/validation.md). The 15 g rotation
is in degrees; the 12 g rotation file carries no unit and is read as radians
(the table's value scale converts it; reasons in reference/cases.md).

input/nbdl8g_t1.inp: a synthetic 8 g drive for prediction. No 8 g time
histories are in reference/, only the 8 g peaks of reference/reference-data.md
section 3 (n = 10). The 12 g tables (same filters) are multiplied by
s = 17.4 g / (mean of the 12 g runs' T1 x-acceleration peaks, each run CFC 60):
the 8 g mean peak over the 12 g mean peak computed the way section 3 computes
its peaks. The same factor on the z-acceleration and the rotation, and the
12 g time course, are assumptions (docs/validation.md).

Other runs of the same kind (a directory with the same CHANNEL.csv files):

    python3 -m hhneck.validation.nbdl_tables --data DIR --name NAME [--rot-unit deg|rad] [--into DIR2]

writes input/NAME_t1.inp (same filters, mean over the directory's runs) and
input/NAME.inp (the 12 g deck with that drive; --into: another directory
than input/); compare with
`hhneck-compare-nbdl --data X=DIR --deck X=input/NAME.inp --case X
--out DIR2`. Without --rot-unit the T1 rotation is read as radians when the
largest |mean| is below 1.5 (as the 12 g files, reference/cases.md), else as
degrees; the choice is printed. Without T1_ZAccel.csv or T1_YrotDisp.csv
the deck holds that coordinate (PRESCRIB ... CONSTANT, printed); the tables
are written every 1 ms over the runs' span whatever their sampling step. Runs
whose pulse starts more than 10 ms away from the shipped runs' (their mean T1
x-acceleration first below -1 g at about 52 ms) get a warning that says how
far to shift their time_ms. The comments that name DIR and the deck go on
continuation comment cards when they pass column 80 (hhneck.decks);
an INCLUDE card (--into) or H5FILE card (--name) that would pass it is
refused, and neither deck is written.
"""
import argparse
import os
import re
import sys

import numpy as np

from ..decks import CardError, Right, card, check_cards, comment_cards, hold, write_decks
from ..paths import project_path
from ..ratings import peak
from ..signals import cfc
from ..volunteers import channel_file, has_channel, runs, stop

Z_CFC = 20   # filter class of the T1 z-acceleration (the others: CFC 60)
T1_PEAK_8G = 17.4   # g: mean T1 x-acceleration peak of the 8 g runs (reference/reference-data.md section 3)
SHIPPED_ONSET = 52.0   # ms: where the shipped runs' mean T1 x-acceleration first passes -1 g (51.5 at 15 g, 52.0 at 12 g)
CASES = {
    "15g": dict(runs="1635-1644 (n = 7)", rot_scale="1.0", rot_unit="deg"),
    "12g": dict(runs="1607-1617 (n = 10)", rot_scale="57.2958", rot_unit="rad, scaled to deg"),
}


def table(name, t, mean, scale):
    """A TABLE card and its points every 1 ms over the runs' span (linear
    interpolation between the samples; at the samples themselves when the
    runs are sampled on whole milliseconds, as the shipped ones are)."""
    tt = np.arange(np.ceil(t[0] - 1e-9), np.floor(t[-1] + 1e-9) + 1.0) + 0.0   # + 0.0: no "-0.0"
    vv = np.interp(tt, t, mean)
    out = [card("TABLE", name, Right("%d" % len(tt)), Right("0.001"), Right(scale))]
    for i in range(0, len(tt), 3):
        out.append(card("", *[Right(x) for a, b in zip(tt[i:i + 3], vv[i:i + 3]) for x in ("%.1f" % a, "%.4f" % b)]))
    return out


def label(sev):
    """'15 g' for the shipped cases, the case name as given otherwise."""
    return sev.replace("g", " g") if re.fullmatch(r"\d+g", sev) else sev


def pulse_onset(t, data):
    """Time (ms) at which the runs' mean T1 x-acceleration (each run CFC 60)
    first passes -1 g; None when it never does."""
    dt = (t[1] - t[0]) * 1e-3
    below = np.mean([cfc(r, 60, dt) for r in data], axis=0) < -1.0
    return float(t[np.argmax(below)]) if below.any() else None


def t1_peak_mean(sev):
    """Mean over the runs of the T1 x-acceleration peak (g, each run CFC 60,
    the peak of hhneck.tools.compare_nbdl), as reference-data.md section 3 has it."""
    t, data, _ = runs("T1_XAccel", sev)
    dt = (t[1] - t[0]) * 1e-3
    return float(np.mean([peak(t, cfc(r, 60, dt), -1)[0] for r in data]))


def scale_8g():
    """Factor from the 12 g drive to the synthetic 8 g drive."""
    return T1_PEAK_8G / abs(t1_peak_mean("12g"))


def t1_tables_8g():
    """The lines of input/nbdl8g_t1.inp: the 12 g tables times scale_8g()."""
    s = scale_8g()
    lines = [
        "* SYNTHETIC T1 drive of an NBDL 8 g frontal sled, for prediction: the",
        "* 12 g tables (runs 1607-1617, filters as there) times %.4f = 17.4 g" % s,
        "* (8 g mean T1 x-acceleration peak, reference/reference-data.md",
        "* section 3) / %.2f g (the 12 g runs' mean peak, each run CFC 60)." % abs(t1_peak_mean("12g")),
        "* The same factor on z and rotation and the 12 g time course are",
        "* assumptions. Written by hhneck.validation.nbdl_tables.",
        "* Time in ms (scale 0.001 s).",
    ]
    for line in t1_tables("12g"):
        if line.startswith("TABLE"):
            f = line.split()
            line = card("TABLE", f[1], Right(f[2]), Right(f[3]), Right("%.6g" % (float(f[4]) * s)))
        if not line.startswith("*"):
            lines.append(line)
    return lines


def t1_tables(sev, z_cfc=Z_CFC, x_cfc=60, data=None, case=None):
    """The lines of input/nbdlSEV_t1.inp, the z-acceleration filtered CFC
    z_cfc, the x-acceleration CFC x_cfc (the shipped tables: 60); the runs
    in directory `data` (default: the shipped case's), described by `case`
    (a dict as CASES[sev], the default)."""
    c = case or CASES[sev]
    lines = comment_cards("T1 drive of the NBDL %s frontal sled, runs %s: x- and" % (label(sev), c["runs"])) + [
        "* z-acceleration [g], sagittal rotation [%s]; each run CFC 60" % c["rot_unit"],
        "* (the z-acceleration CFC %d: its runs are out of phase above about" % z_cfc,
        "* 20 Hz), mean over the runs, every 1 ms. Written by",
    ] + comment_cards("hhneck.validation.nbdl_tables from reference/nbdl_%s (Ewing & Thomas" % sev) + [
        "* 1972, NHTSA Biomechanics Test Database, via IMMC-UWaterloo/ARCGen).",
        "* Time in ms (scale 0.001 s).",
    ]
    for name, chan, scale, cls in (("T1XACC", "T1_XAccel", "9.80665", x_cfc),
                                   ("T1ZACC", "T1_ZAccel", "9.80665", z_cfc),
                                   ("T1RY", "T1_YrotDisp", c["rot_scale"], 60)):
        if chan != "T1_XAccel" and not has_channel(chan, sev, data):
            lines.append("* No %s.csv in the runs: no %s table; the deck holds that coordinate." % (chan, name))
            continue
        t, values, _ = runs(chan, sev, data)
        dt = (t[1] - t[0]) * 1e-3
        mean = np.mean([cfc(r, cls, dt) for r in values], axis=0)
        lines += table(name, t, mean, scale)
    return check_cards(lines, "the T1 tables of %s" % label(sev))


def new_case(folder, name, rot_unit=None, into=None):
    """INTO/NAME_t1.inp and INTO/NAME.inp for the runs in `folder` (INTO:
    default the project's input/, named input/ in the decks' cards)."""
    t, ax, cols = runs("T1_XAccel", name, folder)
    onset = pulse_onset(t, ax)
    if onset is None:
        stop("%s: the runs' mean T1 x-acceleration never passes -1 g: no frontal sled pulse to "
             "drive the model with" % channel_file("T1_XAccel", name, folder))
    if abs(onset - SHIPPED_ONSET) > 10.0:
        print("T1 x-acceleration first passes -1 g at %.1f ms, against about %.0f ms in the shipped runs (the "
              "source's time origin): the deck starts from rest at 0 ms (HOLD POSTURE sets its holding forces "
              "there) and hhneck-compare-nbdl rates 30-250 ms with the z dip before 125 ms; shift the runs' "
              "time_ms by %+.0f ms to match" % (onset, SHIPPED_ONSET, SHIPPED_ONSET - onset), file=sys.stderr)
    held = {coord: chan for coord, chan in (("TZ", "T1_ZAccel"), ("RY", "T1_YrotDisp"))
            if not has_channel(chan, name, folder)}
    for coord, chan in held.items():
        print("%s.csv not in %s: T1 %s is held at its initial value (PRESCRIB ... CONSTANT)" % (chan, folder, coord),
              file=sys.stderr)
    if "RY" not in held:
        t, rot, _ = runs("T1_YrotDisp", name, folder)
        dt = (t[1] - t[0]) * 1e-3
        big = float(np.max(np.abs(np.mean([cfc(r, 60, dt) for r in rot], axis=0))))
        if rot_unit is None:
            rot_unit = "rad" if big < 1.5 else "deg"
            print("T1 rotation: largest |mean| %.3g, read as %s (--rot-unit to choose)" % (big, rot_unit),
                  file=sys.stderr)
    case = dict(runs="of %s (n = %d)" % (os.path.basename(os.path.normpath(folder)), len(cols)),
                rot_scale="57.2958" if rot_unit == "rad" else "1.0",
                rot_unit="rad, scaled to deg" if rot_unit == "rad" else "deg")
    # the cards name INTO as given (input/ by default, found through the
    # include path), the files go there (the project's input/ by default)
    named = into or "input"
    folder_of = into or project_path("input")
    tables = os.path.join(named, name + "_t1.inp")
    with open(project_path("input", "nbdl12g.inp")) as f:
        deck = f.read().splitlines()
    out = (comment_cards("%s: the 54-DOF head/neck model with T1 driven by the mean of the %d runs"
                         % (name, len(cols)))
           + comment_cards("in %s (T1 tables by python3 -m hhneck.validation.nbdl_tables --data)." % folder)
           + ["* Compare: hhneck-compare-nbdl --case X --out OUT"]
           + comment_cards("  --data X=%s" % folder)
           + comment_cards("  --deck X=%s" % os.path.join(named, name + ".inp")))
    for line in deck:
        if line.startswith("*") and not any(l.startswith("TITLE") for l in out):
            continue                      # the 12 g deck's own header
        if line.startswith("TITLE"):
            line = card("TITLE", ("T1 DRIVEN BY THE MEAN OF %d RUNS: %s" % (len(cols), name)).upper()[:70], strip=False)
        elif line.startswith("H5FILE"):
            line = card("H5FILE", name + ".h5")
        out.append(line.replace("input/nbdl12g_t1.inp", tables))
    try:
        # both checked before either is written: a card beyond column 80 (the
        # INCLUDE card of a long --into path, the H5FILE card of a long name)
        # leaves no file behind
        write_decks({os.path.join(folder_of, name + "_t1.inp"): t1_tables(name, data=folder, case=case),
                     os.path.join(folder_of, name + ".inp"): hold(out, "T1", held)})
    except CardError as e:
        stop("%s; not written (a shorter --into directory or --name fits)" % e)
    return os.path.join(folder_of, name + "_t1.inp")


def main(argv=None):
    p = argparse.ArgumentParser(prog="python3 -m hhneck.validation.nbdl_tables", description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--data", metavar="DIR", help="a directory of other runs (CHANNEL.csv files)")
    p.add_argument("--name", help="the new case's name (with --data)")
    p.add_argument("--rot-unit", choices=("deg", "rad"), help="unit of the runs' T1 rotation (with --data)")
    p.add_argument("--into", metavar="DIR2", help="where the decks go (with --data; default: the project's input/)")
    args = p.parse_args(argv)
    if args.data or args.name:
        if not (args.data and args.name):
            p.error("--data and --name go together")
        new_case(args.data, args.name, args.rot_unit, args.into)
        return 0
    if args.rot_unit or args.into:
        p.error("--rot-unit and --into go with --data and --name")
    decks = {project_path("input", "nbdl%s_t1.inp" % sev): t1_tables(sev) for sev in CASES}
    decks[project_path("input", "nbdl8g_t1.inp")] = t1_tables_8g()
    write_decks(decks)
    return 0


if __name__ == "__main__":
    sys.exit(main())
