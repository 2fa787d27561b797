#!/usr/bin/env python3
"""Does the neck stand with less of the discs' bending, judged by its motion
at rest instead of the linear margin, and what do postural feedback loops
change there?

    python3 studies/rest_motion.py

For the discs' bending fraction NZBEND at 0.6 (shipped), 0.45 and 0.35 (the
shipped springs, muscles and factors otherwise):
- the largest real part at rest with the muscles, as the calibration checks
  it (input/calibrate_nbdl12g.inp scored once at the model deck's values,
  FIT F2 = 0, on a copy of the model deck with NZBEND set);
- a 6 s run at rest (T1 held in all six coordinates, HOLD POSTURE, the
  bracing activation, C3 RX and C4 RY started at 5 deg/s): the largest
  excursion of any joint coordinate from its start and where, and the head's
  rotation about the lab's y axis; the same with two FEEDBACK loops on the
  head's rotation (extensors kp 3 per rad, kd 0.1 s per rad; flexors -3,
  -0.1; 25 ms, sampled every 1 ms); and the same with the stretch loops of
  input/nbdl12g_spindle.inp instead (SPINDLE cards: every flexor and
  extensor fed back from its own stretch, kp 5 per lopt, 60 ms).
"""
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))
from hhneck import run  # noqa: E402
from hhneck.decks import is_card, set_field, write_deck  # noqa: E402

FRACTIONS = (0.6, 0.45, 0.35)
REST = """TITLE     THE MODEL AT REST, T1 HELD, PERTURBED
CONTROL   6.0       1.0E-4    0.01      ROS34PW2  1.0E-3    1.0E-5
SOLVER    ABA       STRUCT
OUTPUT    1.0E-3
HOLD      POSTURE
INCLUDE   {model}
PRESCRIB  T1        TX        CONSTANT
PRESCRIB  T1        TY        CONSTANT
PRESCRIB  T1        TZ        CONSTANT
PRESCRIB  T1        RX        CONSTANT
PRESCRIB  T1        RY        CONSTANT
PRESCRIB  T1        RZ        CONSTANT
INITIAL   C3        RX        0.0       5.0
INITIAL   C4        RY        -3.24     5.0
"""
LOOPS = """FEEDBACK  EXT       HEAD      Y         3.0       0.1       0.025     0.001
FEEDBACK  FLEX      HEAD      Y         -3.0      -0.1      0.025     0.001
"""
with open(os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "input/nbdl12g_spindle.inp")) \
        as deck:   # the stretch loops of the 12 g experiment deck
    SPINDLES = "".join(line for line in deck if line.startswith("SPINDLE"))
COORDS = ("TX", "TY", "TZ", "RX", "RY", "RZ")
BODIES = ("T1", "C7", "C6", "C5", "C4", "C3", "C2", "C1", "HEAD")   # the model deck's order


def model_copy(fraction, path):
    """The model deck with the discs' bending fraction (SCALE NZBEND) set, written to path."""
    lines = open("input/head_neck_54dof.inp").read().splitlines()
    hits = [i for i, ln in enumerate(lines) if is_card(ln, "SCALE", "NZBEND")]
    if len(hits) != 1:
        sys.exit("%d SCALE NZBEND cards in the model deck" % len(hits))
    lines[hits[0]] = set_field(lines[hits[0]], 4, "%g" % fraction)
    write_deck(path, lines)


def rest_margin(model, tmp):
    """The largest real part at rest [1/s] of the 12 g calibration scored once on the model deck `model`."""
    lines = []
    for ln in open("input/calibrate_nbdl12g.inp").read().splitlines():
        if ln.startswith("VALUES"):
            continue                                   # the model deck's own values
        if ln.startswith("FIT"):
            ln = set_field(set_field(ln, 2, "0"), 3, "2")   # one point scored
        if ln.startswith("CASE"):
            ln = "CASE      " + os.path.join(tmp, "case.inp")
        lines.append(ln)
    text = "\n".join(lines) + "\n"
    case = open("input/nbdl12g.inp").read().replace("input/head_neck_54dof.inp", model)
    write_deck(os.path.join(tmp, "case.inp"), case.splitlines())
    r = subprocess.run([run.find_executable(), "--calibrate"], input=text, capture_output=True, text=True)
    m = re.search(r"LARGEST REAL PART AT REST\s+(\S+) 1/S", r.stdout)
    return float(m.group(1)) if m else float("nan")


def excursion(h5):
    """(largest |x - x0| of a rotation [rad], its coordinate, time it settles within 5 % of it [s],
    the head's largest |rotation about lab y| [deg])."""
    import h5py
    with h5py.File(h5, "r") as f:
        t = f["time"][:]
        x = f["coordinates/x"][:]
        th = f["channels/HEAD_THETY"][:]
        if f["model/mass"].shape[0] != len(BODIES):
            sys.exit("expected the %d bodies %s" % (len(BODIES), ", ".join(BODIES)))
    rot = [k for k in range(x.shape[1]) if k % 6 >= 3]
    d = np.abs(x[:, rot] - x[0, rot])
    j = int(np.argmax(d.max(axis=0)))
    k = rot[j]
    peak = d[:, j].max()
    settle = t[np.argmax(d[:, j] >= 0.95 * peak)]
    body = BODIES[k // 6]
    return peak, "%s %s" % (body, COORDS[k % 6]), settle, np.abs(th).max()


def main():
    tmp = tempfile.mkdtemp(prefix="rest-")
    print("| discs' bending | largest real part at rest (1/s) | 6 s at rest: largest excursion (rad, deg, where,"
          " 95 % reached by) | head rotation (deg) | with the loops: largest excursion | head rotation (deg) |"
          " with the stretch loops: largest excursion | head rotation (deg) |")
    print("|---|---|---|---|---|---|---|---|")
    for fr in FRACTIONS:
        model = os.path.join(tmp, "model_%g.inp" % fr)
        model_copy(fr, model)
        cells = ["%g %%" % (100 * fr), "%+.3g" % rest_margin(model, tmp)]
        for k, loops in enumerate(("", LOOPS, SPINDLES)):
            deck = REST.format(model=model) + loops
            h5 = os.path.join(tmp, "rest_%g_%d.h5" % (fr, k))
            run.run_deck(deck, h5=h5)
            peak, where, settle, head = excursion(h5)
            cells += ["%.3g (%.3g deg, %s, %.2g s)" % (peak, np.degrees(peak), where, settle), "%.3g" % head]
        print("| " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
