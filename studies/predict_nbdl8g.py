#!/usr/bin/env python3
"""Prediction at a severity the model was not fitted to: NBDL 8 g.

    python3 studies/predict_nbdl8g.py [--h5 SEV=RESULT.h5 ...]
    python3 studies/predict_nbdl8g.py --fit LABEL=CALIBRATION_LISTING ...

reference/ holds no 8 g time histories, only the 8 g peaks of
reference/reference-data.md section 3 (n = 10 runs, each CFC 60). The deck
input/nbdl8g.inp drives T1 with the 12 g mean drive scaled to the 8 g mean T1
peak (python3 -m hhneck.validation.nbdl_tables). This runs it (and the 12 g and 15 g decks:
the shipped set is fitted to the 12 g runs, calibration; 15 g is its
prediction) and prints, per severity, the model's
peaks with the same definitions as section 3 -- T1 and head x-acceleration
(least), head angular acceleration (largest) and deceleration (least), head
angular velocity and flexion (largest), each channel CFC 60, 30-250 ms --
against the volunteers' mean +- SD there, with (model - mean)/SD. The 8 g
column is a prediction; the T1 row shows how well the synthetic drive meets
the one 8 g number it was scaled to.

With --fit (one or more listings of `hhneck --calibrate`, as
studies/cross_severity.py takes them) it runs the 8 g deck with each fit's
parameters instead (set on a temporary copy of the model deck, the way the
PARAM cards of input/calibrate_nbdl.inp bind them) and prints one row of
8 g peaks per fit: which fit carries to a third severity.
"""
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))
from hhneck.tools.compare_nbdl import run_deck  # noqa: E402
from hhneck.ratings import peak, s3  # noqa: E402
from hhneck.signals import cfc  # noqa: E402
from hhneck.volunteers import stop  # noqa: E402
from hhneck.decks import CardError, check_cards, field, is_card, set_field, write_deck  # noqa: E402

SEVERITIES = ("8g", "12g", "15g")
# (row label of reference-data.md section 3, model channel, sign of the peak)
ROWS = [
    ("peak T1 x-accel (g)", "T1_AX", -1),
    ("peak head x-accel (g)", "HEAD_AX", -1),
    ("peak head angular accel (rad/s²)", "HEAD_ALPHY", +1),
    ("peak angular deceleration (rad/s²)", "HEAD_ALPHY", -1),
    ("peak head angular velocity (rad/s)", "HEAD_OMEGY", +1),
    ("peak head flexion (deg)", "HEAD_THETY", +1),
]


def volunteer_peaks(path="reference/reference-data.md"):
    """{row label: {severity: (mean, sd)}} from the table of section 3."""
    out = {}
    for line in open(path, encoding="utf-8"):
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 4 and cells[0] in [r[0] for r in ROWS]:
            vals = {}
            for sev, cell in zip(SEVERITIES, cells[1:]):
                m = re.match(r"([−-]?[\d.]+) ± ([\d.]+)", cell)
                vals[sev] = (float(m.group(1).replace("−", "-")), float(m.group(2)))
            out[cells[0]] = vals
    return out


def model_peaks(h5):
    """The model's six peaks, each channel CFC 60 (hhneck.ratings.model_channels)."""
    import h5py
    f = h5py.File(h5, "r")
    tm = f["time"][:] * 1e3
    dt = (tm[1] - tm[0]) * 1e-3
    out = {}
    for label, chan, sign in ROWS:
        x = cfc(f["channels"][chan][:], 60, dt)
        out[label] = peak(tm, x, sign)
    return out


def fitted_values(listing):
    """[(name, value)] from the PARAM lines of a calibration listing."""
    out = []
    for line in open(listing):
        m = re.match(r"PARAM (\S+)\s+= (\S+)", line)
        if m:
            out.append((m.group(1), float(m.group(2))))
    return out


def bindings(path="input/calibrate_nbdl.inp"):
    """{name: (field number, card, item)} of the PARAM cards (kind FIELDn)."""
    out = {}
    for line in open(path):
        if line.startswith("PARAM"):
            name, kind, card, item = (field(line, n) for n in (1, 2, 3, 4))
            out[name] = (int(kind[len("FIELD"):]), card, item)
    return out


def with_values(model, values, bind):
    """The model deck text with field n of the card CARD whose F1 is ITEM set to each value."""
    lines = model.splitlines()
    for name, value in values:
        n, card, item = bind[name]
        hits = [i for i, line in enumerate(lines) if is_card(line, card, item)]
        if len(hits) != 1:
            sys.exit("parameter %s: %d %s cards named %s in the model deck" % (name, len(hits), card, item))
        old = field(lines[hits[0]], n)
        try:
            same = float(old) == float("%.6g" % value)
        except ValueError:
            same = False
        if not same:        # a field that holds the value already keeps its text
            lines[hits[0]] = set_field(lines[hits[0]], n, "%.6g" % value)
    return "\n".join(lines) + "\n"


def fit_deck(model, listing, bind, inc):
    """The 8 g case deck for standard input with the parameters of the
    calibration listing set on the model deck text `model` (bindings()),
    that copy written to `inc` and named on its INCLUDE card; CardError when
    a card would pass column 80 (that INCLUDE card, with a long path)."""
    deck = open("input/nbdl8g.inp").read().replace("input/head_neck_54dof.inp", inc)
    check_cards(deck.splitlines(), "the 8 g case deck of %s" % listing)
    write_deck(inc, with_values(model, fitted_values(listing), bind))
    return deck


def fits_table(fits, vol):
    """One row of 8 g peaks per calibration listing (label, path)."""
    exe = subprocess.run(["fpm", "run", "--profile", "release", "--runner", "echo"], capture_output=True, text=True,
                         check=True).stdout.split()[-1]
    bind = bindings()
    model = open("input/head_neck_54dof.inp").read()
    tmp = tempfile.mkdtemp()
    rows = ["| fitted on | " + " | ".join(r[0].replace("peak ", "") for r in ROWS[1:]) + " | head peaks in 1 SD |",
            "|---" * (len(ROWS) + 1) + "|"]
    for label, listing in fits:
        try:
            deck = fit_deck(model, listing, bind, os.path.join(tmp, "model_%d.inp" % len(rows)))
        except CardError as e:
            stop("%s (a shorter TMPDIR fits)" % e)
        h5 = os.path.join(tmp, "r%d.h5" % len(rows))
        subprocess.run([exe, "-I", os.getcwd(), "--h5", h5], input=deck, text=True, capture_output=True, check=True)
        pk = model_peaks(h5)
        cells, inside = [], 0
        for row in ROWS[1:]:
            mean, sd = vol[row[0]]["8g"]
            z = (pk[row[0]][0] - mean) / sd
            inside += abs(z) <= 1.0
            cells.append("%s (%+.2f SD)" % (s3(pk[row[0]][0]), z))
        rows.append("| %s | %s | %d of %d |" % (label, " | ".join(cells), inside, len(ROWS) - 1))
    mean_row = ["%s ± %s" % (s3(vol[r[0]]["8g"][0]), s3(vol[r[0]]["8g"][1])) for r in ROWS[1:]]
    rows.append("| 8 g volunteers (mean ± SD) | " + " | ".join(mean_row) + " | |")
    print("\n".join(rows))


def main():
    given, fits = {}, []
    args = sys.argv[1:]
    while args:
        a = args.pop(0)
        if a == "--h5":
            k, v = args.pop(0).split("=", 1)
            given[k] = v
        elif a == "--fit":
            fits.append(tuple(args.pop(0).split("=", 1)))
        else:
            sys.exit("usage: predict_nbdl8g.py [--h5 SEV=FILE ...] [--fit LABEL=LISTING ...]")
    vol = volunteer_peaks()
    if fits:
        fits_table(fits, vol)
        return
    tmp = tempfile.mkdtemp()
    res = {sev: model_peaks(given.get(sev) or run_deck(sev, tmp)) for sev in SEVERITIES}
    head = ("| peak | 8 g model (prediction) | 8 g volunteers | z | 12 g model (calibration) | 12 g volunteers"
            " | z | 15 g model (prediction) | 15 g volunteers | z |")
    lines = [head, "|---" * 10 + "|"]
    count = {s: 0 for s in SEVERITIES}
    for label, _, _ in ROWS:
        row = [label]
        for sev in SEVERITIES:
            mp, mt = res[sev][label]
            mean, sd = vol[label][sev]
            z = (mp - mean) / sd
            if label != ROWS[0][0]:
                count[sev] += abs(z) <= 1.0
            row += ["%s at %s ms" % (s3(mp), s3(mt)), "%s ± %s" % (s3(mean), s3(sd)), "%+.2f" % z]
        lines.append("| " + " | ".join(row) + " |")
    lines += ["", "Head peaks within 1 SD (the five head rows): " +
              ", ".join("%s %d of 5" % (s.replace("g", " g"), count[s]) for s in SEVERITIES) + "."]
    print("\n".join(lines))


if __name__ == "__main__":
    main()
