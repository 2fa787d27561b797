#!/usr/bin/env python3
"""Writes the T1 input tables of the NBDL sled decks from the volunteer runs
in reference/:

    python3 tools/make_nbdl_tables.py

input/nbdl15g_t1.inp (runs 1635-1644, n = 7) and input/nbdl12g_t1.inp (runs
1607-1617, n = 10): T1 x- and z-acceleration [g] and sagittal rotation, each
run filtered (SAE J211/1, the filter of tools/compare_nbdl.py), mean over the
runs, every 1 ms from 0 to 299 ms. The x-acceleration and the rotation are
filtered CFC 60; the z-acceleration CFC 20: above about 20 Hz the runs' T1
z-accelerations are out of phase with each other (a mount ringing at 50-60 Hz,
up to 88 g with millimetre displacements, at 85-120 ms), not a motion of the
torso the model's rigid T1 should transmit to the head; the evidence is
printed by tools/nbdl_t1_evidence.py (docs/validation.md). The 15 g rotation
is in degrees; the 12 g rotation file carries no unit and is read as radians
(the table's value scale converts it; reasons in reference/cases.md).
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from compare_nbdl import cfc, runs  # noqa: E402

Z_CFC = 20   # filter class of the T1 z-acceleration (the others: CFC 60)
CASES = {
    "15g": dict(runs="1635-1644 (n = 7)", rot_scale="1.0", rot_unit="deg"),
    "12g": dict(runs="1607-1617 (n = 10)", rot_scale="57.2958", rot_unit="rad, scaled to deg"),
}


def table(name, t, mean, scale):
    keep = np.abs(t - np.round(t)) < 1e-9
    tt, vv = t[keep], mean[keep]
    out = ["%-8s  %-10s%10d%10s%10s" % ("TABLE", name, len(tt), "0.001", scale)]
    for i in range(0, len(tt), 3):
        out.append(" " * 10 + "".join("%10.1f%10.4f" % (a, b) for a, b in zip(tt[i:i + 3], vv[i:i + 3])))
    return out


def t1_tables(sev, z_cfc=Z_CFC):
    """The lines of input/nbdlSEV_t1.inp, the z-acceleration filtered CFC z_cfc."""
    c = CASES[sev]
    lines = [
        "* T1 drive of the NBDL %s frontal sled, runs %s: x- and" % (sev.replace("g", " g"), c["runs"]),
        "* z-acceleration [g], sagittal rotation [%s]; each run CFC 60" % c["rot_unit"],
        "* (the z-acceleration CFC %d: its runs are out of phase above about" % z_cfc,
        "* 20 Hz), mean over the runs, every 1 ms. Written by",
        "* tools/make_nbdl_tables.py from reference/nbdl_%s (Ewing & Thomas" % sev,
        "* 1972, NHTSA Biomechanics Test Database, via IMMC-UWaterloo/ARCGen).",
        "* Time in ms (scale 0.001 s).",
    ]
    for name, chan, scale, cls in (("T1XACC", "T1_XAccel", "9.80665", 60),
                                   ("T1ZACC", "T1_ZAccel", "9.80665", z_cfc),
                                   ("T1RY", "T1_YrotDisp", c["rot_scale"], 60)):
        t, data, _ = runs(chan, sev)
        dt = (t[1] - t[0]) * 1e-3
        mean = np.mean([cfc(r, cls, dt) for r in data], axis=0)
        lines += table(name, t, mean, scale)
    for line in lines:
        assert len(line) <= 80, line
    return lines


def main():
    for sev in CASES:
        with open(os.path.join("input", "nbdl%s_t1.inp" % sev), "w") as f:
            f.write("\n".join(t1_tables(sev)) + "\n")


if __name__ == "__main__":
    main()
