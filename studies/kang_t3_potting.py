#!/usr/bin/env python3
"""Does potting the Kang specimens at T3 instead of T1 change the Kang
cases? (README of shared/data/pmhs_neck, "Ambiguities" 4: the source's FE
model is potted at T3, its data speak of "the loadcell at T1".)

    python3 studies/kang_t3_potting.py

The shipped Kang decks (python/hhneck/validation/specimens.py, HOLD POSTURE) pot T1:
T1 moves with the sled, and the load cell cuts T1 from C7. Here two upper
thoracic bodies are added below T1 and T3 is potted instead:

* bodies: T3 (the potted body, prescribed as the shipped T1 was: the
  pulse along x or y, its other coordinates held, its pitch the shipped
  T1 tilt, so the column starts in the shipped posture), T2 and T1, each a
  vertebra of C7's mass and inertia (0.523 kg, source S1 of the model deck;
  that a thoracic specimen vertebra weighs what C7 does is assumed, A),
  vertebral bodies 17 mm high and joints 4.5 mm (A), all neutrals zero
  (T1 keeps its shipped slope through T3's tilt);
* the thoracic joints T3-T2 and T2-T1 rotate only (their translations
  locked, A): one neutral-zone spring per rotation (NZSPRING, the model's
  own law Q = -M0 sinh(D/ths)) through the mean range of motion of Wilke
  et al. 2017 (S20 of reference/parameters.md; 68 thoracic functional spinal units
  with their costovertebral joints, pure moments +-7.5 N m): T1-T2 the
  most flexible segment, flexion-extension 14 deg, lateral bending and
  axial rotation taken as 12 deg (the upper end of the upper thoracic
  10-12 deg, T1-T2 having the largest range); T2-T3 flexion-extension 7
  deg (the 6-8 deg of the other thoracic segments), lateral bending and
  axial rotation 11 deg (the middle of 10-12); half of each range at
  7.5 N m: M0 = 7.5 N m and ths = (range/2)/asinh(1), linear past 7.5 N m;
  no damping (A);
* the load cell: cut T2 from T3 (everything above the pot: T2, T1, the
  neck and the head), about the shipped cell point (the potting centre
  81 mm behind and 229 mm below the head's mass centre at the start,
  KANG_CELL_POINT) in T3's axes (the sled's); and, to separate the
  compliance from where the cell cuts, the shipped cut (C7 from T1, in
  T1's axes) on the same model.

Variants (each front and side, rated as the catalogue rates them,
ISO/TS 18571, prediction; nothing refitted): T1 potted (shipped); T3
potted, cell below T2; T3 potted, cell between T1 and C7; T3 potted with
the thoracic springs ten times stiffer (the stiffness's leverage); T3
potted with the two vertebrae at a fifth of their mass (the masses'
leverage).
"""
import math
import os
import sys
import tempfile

import numpy as np

sys.path[:0] = [os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python")]
from hhneck.validation import segments, specimens  # noqa: E402

MODEL_DECK = os.path.join(segments.ROOT, "input", "head_neck_54dof.inp")
VERTEBRA_MASS = 0.523                      # C7's (S1); a thoracic vertebra's assumed (A)
VERTEBRA_H, JOINT_H = 0.017, 0.0045        # A
#: Wilke et al. 2017: full range of motion at +-7.5 N m [deg]: (lateral
#: bending about x, flexion-extension about y, axial rotation about z)
THORACIC_ROM = {"T1": (12.0, 14.0, 12.0),   # the T1-T2 joint (T1 on T2)
                "T2": (11.0, 7.0, 11.0)}    # the T2-T3 joint (T2 on T3)
M_TEST = 7.5                               # N m


def elliptic_cylinder(m, h, a=0.055, b=0.055):
    """Centroidal inertia of a solid elliptic cylinder, axis z (the model
    deck's segment_inertia)."""
    return m * (b * b / 4 + h * h / 12), m * (a * a / 4 + h * h / 12), m * (a * a + b * b) / 4


def t3_model(path, stiffness=1.0, mass=1.0):
    """Write the model deck with T3 and T2 below T1 into path."""
    m = VERTEBRA_MASS * mass
    inertia = "".join("%-10.4g" % v for v in elliptic_cylinder(m, VERTEBRA_H))
    dz = VERTEBRA_H / 2 + JOINT_H / 2
    out = []
    for line in open(MODEL_DECK):
        if line.startswith("BODY") and line[10:20].strip() == "T1":
            out += ["* T3 (potted), T2, T1: thoracic vertebrae (studies/kang_t3_potting.py)\n",
                    "BODY      T3        R         %-10.4g%s\n" % (m, inertia),
                    "BODY      T2        T3        %-10.4g%s\n" % (m, inertia),
                    "BODY      T1        T2        %-10.4g%s\n" % (m, inertia)]
        elif line.startswith("JOINT") and line[10:20].strip() == "T1":
            for b in ("T2", "T1"):
                out.append("JOINT     %-10s0.0       0.0       %-10.5f0.0       0.0       %-10.5f\n"
                           % (b, dz, -dz))
        else:
            out.append(line)
    for body, rom in THORACIC_ROM.items():
        out.append("LOCK      %-10sTX        TY        TZ\n" % body)
        for axis, r in zip(("RX", "RY", "RZ"), rom):
            ths = (r / 2) / math.asinh(1.0) / stiffness
            out.append("NZSPRING  %-10s%-10s%-10.4g%-10.4g%-10.4g%-10.4g%-10.4g\n"
                       % (body, axis, M_TEST, ths, M_TEST, ths, M_TEST))
    with open(path, "w") as f:
        f.writelines(out)


def t3_deck(work, direction, cell="T3", stiffness=1.0, mass=1.0):
    """The shipped Kang deck of `direction` turned into its T3-potted form:
    the model deck above, T3 driven and held where T1 was, the cell cut
    below T2 (cell "T3") or between T1 and C7 (cell "T1")."""
    os.makedirs(work, exist_ok=True)
    t3_model(os.path.join(work, "t3_model.inp"), stiffness, mass)
    shipped = specimens.kang_deck(work, direction, model="t3_model.inp")
    lift = 2 * (VERTEBRA_H + JOINT_H)       # T3's mass centre below T1's at the start
    px, py, pz = specimens.KANG_CELL_POINT
    lines = []
    for line in open(shipped):
        if line.startswith("PRESCRIB") and line[10:20].strip() == "T1":
            line = line[:10] + "T3        " + line[20:]
        elif line.startswith("LOADCELL") and cell == "T3":
            line = "LOADCELL  T1CELL    T2        %-10.4f%-10.4f%-10.4fT3\n" % (px, py, pz + lift)
        lines.append(line)
    with open(shipped, "w") as f:         # the same name: its H5FILE card names the result file
        f.writelines(lines)
    return shipped


def rate(direction, h5):
    """{channel: ISO/TS 18571 dict} of a Kang run's result file."""
    return specimens.rate_kang(direction, specimens.model_channels("kang_" + direction, h5))


VARIANTS = [("T1 potted (shipped)", None),
            ("T3 potted, cell below T2", dict(cell="T3")),
            ("T3 potted, cell between T1 and C7", dict(cell="T1")),
            ("T3 potted, thoracic springs x3", dict(cell="T3", stiffness=3.0)),
            ("T3 potted, thoracic springs x10", dict(cell="T3", stiffness=10.0)),
            ("T3 potted, T1 and T2 at 1/5 mass", dict(cell="T3", mass=0.2))]


def main():
    work = tempfile.mkdtemp(prefix="hhneck-kang-t3-")
    exe = segments.default_executable()
    for direction in ("front", "side"):
        chans = specimens.KANG_CHANNELS[direction]
        print("\nKang %s: ISO/TS 18571 per channel (the model's peak at ms)" % direction)
        rows = []
        for label, kw in VARIANTS:
            sub = os.path.join(work, "%s_%d" % (direction, len(rows)))
            os.makedirs(sub, exist_ok=True)
            deck = specimens.kang_deck(sub, direction) if kw is None else t3_deck(sub, direction, **kw)
            sc = rate(direction, specimens._run(deck, sub, exe))
            rows.append((label, sc))
        print("| variant | " + " | ".join(chans) + " | mean |")
        print("|---" * (len(chans) + 2) + "|")
        for label, sc in rows:
            vals = [sc[c]["overall"] for c in chans]
            print("| %s | %s | %.3f |" % (label, " | ".join(
                "%.3f (%.3g at %.0f)" % (sc[c]["overall"], sc[c]["peak_model"][0], sc[c]["peak_model"][1])
                for c in chans), float(np.mean(vals))))
        ref = rows[0][1]
        print("| reference peak | %s | |" % " | ".join(
            "%.3g at %.0f" % (ref[c]["peak_ref"][0], ref[c]["peak_ref"][1]) for c in chans))
    print("\nwork files in", work, file=sys.stderr)


if __name__ == "__main__":
    main()
