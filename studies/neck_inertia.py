#!/usr/bin/env python3
"""How much of the Kang load cell's force is the neck's own inertia, and
what would lighter cervical segments change in every case?

    python3 studies/neck_inertia.py

1. The shipped Kang decks (python/hhneck/validation/specimens.py, HOLD POSTURE) run;
   the load cell's tared force along the pulse (side: Fy, front: Fx, in
   T1's axes) is split into each body's m a from the bodies' mass-centre
   positions (central differences of /bodies/position): the head's part
   and the neck's (C7 ... C1). Their sum must give the channel back (the
   cell carries the inertia of what is above it: the holding forces are
   load pairs between joined bodies, gravity is tared with T1 held), which
   the script checks. For the specimens the same split is estimated: the
   head's part as the model's head mass times the specimens' head
   acceleration (an assumption: the sources give no head masses; their
   accelerometer's axes taken as the cell's, which holds while their head
   has turned less than 5 deg, to 40 ms; later rows mix the axes), the
   rest of their cell force the neck's and the potting's.
2. The passive couplings between T1 and the neck one at a time (CHANGE
   cards on the shipped set: the discs' shear and torsion modulus G, their
   lateral bending BENDX, axial stiffness E and bending damping VBEND, the
   range-of-motion stiffness ROMK, the joint-limit dampers' C0): the Kang
   side cell's Fy (its ISO/TS 18571 and peak) and the case's mean.
3. The cervical segments' masses and inertias (C1 ... C7, BODY cards of
   the model deck) scaled by 1, 0.72 and 0.5 (CHANGE cards, nothing
   refitted): every rated channel of both Kang cases and Stemper
   (ISO/TS 18571, prediction), and NBDL 12 g (calibration) and 15 g
   (prediction) by hhneck-compare-nbdl's ratings. The segment tests are
   quasi-static and left out.
"""
import os
import sys
import tempfile

import numpy as np

sys.path[:0] = [os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python")]
import h5py  # noqa: E402
from hhneck import run
from hhneck.validation import segments, specimen_data, specimens  # noqa: E402
from hhneck.ratings import compare, s3  # noqa: E402
from hhneck.export import kinematic_to_j211  # noqa: E402

NECK = ("C7", "C6", "C5", "C4", "C3", "C2", "C1")
SCALES = (1.0, 0.72, 0.5)
#: per Kang direction: the driven axis (0 x, 1 y), the cell's force channel,
#: the data's force and head-acceleration channels
KANG = {"side": (1, "T1CELL_JFY", "loadcell_force_y", "head_acc_y"),
        "front": (0, "T1CELL_JFX", "loadcell_force_x", "head_acc_x")}
TIMES_MS = (20, 30, 36, 40, 50, 64)


#: part 2: (label, CHANGE card) of each coupling softened
COUPLINGS = [("discs' %s x%g" % (item, f), run.change_card("C%s%g" % (item, f), "FAMILY", "DISCS", item, "SCALE", f))
             for item, f in (("G", 0.3), ("G", 0.05), ("BENDX", 0.3), ("E", 0.3), ("VBEND", 0.2))]
COUPLINGS += [("ROMK x0.3", run.change_card("CROMK", "FAMILY", "LIMITS", "ROMK", "SCALE", 0.3)),
              ("dampers' C0 x0.1", run.change_card("CC0", "FAMILY", "LIMITS", "C0", "SCALE", 0.1))]


def mass_changes(scale):
    """CHANGE cards scaling every cervical segment's mass and inertia."""
    return [run.change_card(item[0] + b, "BODY", b, item, "SCALE", scale) for b in NECK for item in ("MASS", "INERTIA")]


def with_changes(deck, cards):
    """Append CHANGE cards to a written deck file; returns its path."""
    with open(deck, "a") as f:
        f.write("\n".join(cards) + "\n")
    return deck


def inertia_parts(h5, axis, channel):
    """(t [ms], cell force tared [N], head's part, neck's part, worst |cell + sum m a| [N] from
    10 ms on, the head's mass [kg]) of a Kang run: each part m a along `axis` of T1's axes in SAE J211 (the cell's axes: the cell's force on
    what is above it equals their momentum's rate, gravity tared)."""
    with h5py.File(h5, "r") as f:
        t = f["time"][:]
        pos = f["bodies/position"][:]
        names = [str(n) for n in f["model"].attrs["bodies"]]
        mass = f["model/mass"][:]
        st1 = f["bodies/rotation"][0, names.index("T1")].T          # T1 held: its axes at the start
        cell = f["channels"][channel][:]
    acc = np.gradient(np.gradient(pos, t, axis=0), t, axis=0) @ st1  # in T1's axes
    acc = kinematic_to_j211(np.moveaxis(acc, -1, 0))[axis]             # SAE J211's: y right, z down
    part = mass[None, :] * acc
    head = part[:, names.index("HEAD")]
    neck = part[:, [names.index(b) for b in NECK]].sum(axis=1)
    cell = cell - cell[0]
    # away from the digitised pulse's first corners (0-10 ms) and the run's ends, where the
    # differences of the positions smear the jumps of the prescribed acceleration
    inner = (t >= 0.010) & (t <= t[-1] - 0.010)
    return t * 1e3, cell, head, neck, float(np.max(np.abs(cell - head - neck)[inner])), float(mass[names.index("HEAD")])


def split_table(work):
    """Part 1: the cell's force split into the head's and the neck's inertia, model and specimens."""
    for direction, (axis, channel, data_force, data_acc) in KANG.items():
        h5 = specimens._run(specimens.kang_deck(work, direction), work, None)
        t, cell, head, neck, worst, head_mass = inertia_parts(h5, axis, channel)
        if worst > 0.05 * np.max(np.abs(cell)):
            sys.exit("%s: the parts do not add up to the cell (%.3g N off)" % (direction, worst))
        path = os.path.join(segments.DATA_DIR, "kang2018_%s_experiment.csv" % direction)
        gf, force = specimen_data.reference(path, data_force)[:2]
        ga, acc = specimen_data.reference(path, data_acc)[:2]
        print("\n### Kang %s: the cell's %s [N] and its parts (model: the sum of the parts is the channel "
              "within %.2g N)\n" % (direction, data_force.split("_")[-1].upper(), worst))
        print("| t [ms] | model cell | model head (m a) | model neck (C7-C1) | specimens' cell | "
              "specimens' head (%.3g kg x their acceleration) | specimens' rest |" % head_mass)
        print("|---|---|---|---|---|---|---|")
        for ms in TIMES_MS:
            k = int(np.argmin(np.abs(t - ms)))
            fs = float(np.interp(ms, gf, force))
            hs = head_mass * 9.80665 * float(np.interp(ms, ga, acc))  # both in J211 signs
            print("| %d | %s | %s | %s | %s | %s | %s |" % (ms, s3(cell[k]), s3(head[k]), s3(neck[k]), s3(fs),
                                                       s3(hs), s3(fs - hs)))


def specimen_scores(work, scale):
    """({case: (mean ISO/TS 18571, {channel: score})}, the two cells' force peaks) of both Kang cases and
    Stemper at a neck-mass scale."""
    out = {}
    cards = mass_changes(scale)
    for direction in ("front", "side"):
        deck = with_changes(specimens.kang_deck(work, direction), cards)
        rated = specimens.rate_kang(direction, specimens.model_channels("kang_" + direction,
                                                                        specimens._run(deck, work, None)))
        out["Kang " + direction] = rated
    deck = with_changes(specimens.stemper_deck(work), cards)
    out["Stemper"] = specimens.rate_stemper(specimens.model_channels("stemper", specimens._run(deck, work, None)))
    peaks = "front Fx %s N, side Fy %s N" % (s3(out["Kang front"]["loadcell_force_x"]["peak_model"][0]),
                                             s3(out["Kang side"]["loadcell_force_y"]["peak_model"][0]))
    return {case: (float(np.mean([s["overall"] for s in r.values()])), {c: s["overall"] for c, s in r.items()})
            for case, r in out.items()}, peaks


def coupling_table(work):
    """Part 2: the Kang side cell's Fy with each coupling softened."""
    print("\n### The Kang side cell's Fy with one passive coupling softened (nothing refitted)\n")
    print("| change | Fy ISO 18571 | Fy peak [N] | Kang side mean |")
    print("|---|---|---|---|")
    for label, card in [("none (shipped)", None)] + COUPLINGS:
        deck = with_changes(specimens.kang_deck(work, "side"), [card] if card else [])
        rated = specimens.rate_kang("side", specimens.model_channels("kang_side", specimens._run(deck, work, None)))
        fy = rated["loadcell_force_y"]
        print("| %s | %s | %s | %s |" % (label, s3(fy["overall"]), s3(fy["peak_model"][0]),
                                         s3(np.mean([r["overall"] for r in rated.values()]))))


def nbdl_scores(work, scale):
    """'12 g CORA (ISO; peaks in 1 SD)' cells at a neck-mass scale (the shipped calibration)."""
    cells = []
    for sev in ("12g", "15g"):
        r = run.run_deck("input/nbdl%s.inp" % sev, changes=mass_changes(scale),
                         h5=os.path.join(work, "nbdl%s_%g.h5" % (sev, scale)))
        chans, peaks, overall = compare(sev, r.h5)[:3]
        iso = np.mean([c["iso"] for c in chans if c["rated"]])
        cells.append("%s (ISO %s; %d of %d)" % (s3(overall), s3(iso), sum(p["ok_peak"] for p in peaks), len(peaks)))
    return cells


def main():
    work = tempfile.mkdtemp(prefix="neck-inertia-")
    split_table(work)
    coupling_table(work)
    print("\n### The cervical segments' masses and inertias scaled (nothing refitted)\n")
    print("| neck mass scale | NBDL 12 g (calibration) | 15 g (prediction) | Kang front | Kang side | Stemper | "
          "cell force peaks | channels that move by 0.02 or more (from scale 1) |")
    print("|---|---|---|---|---|---|---|---|")
    base = None
    for scale in SCALES:
        sc, peaks = specimen_scores(work, scale)
        base = base or sc
        moved = ["%s %s %s -> %s" % (case, ch, s3(base[case][1][ch]), s3(v)) for case, (_, chans) in sc.items()
                 for ch, v in chans.items() if abs(v - base[case][1][ch]) >= 0.02]
        print("| %g | %s | %s | %s | %s |" % (scale, " | ".join(nbdl_scores(work, scale)),
                                                " | ".join(s3(sc[c][0]) for c in ("Kang front", "Kang side", "Stemper")),
                                                peaks, "; ".join(moved) or "none"))


if __name__ == "__main__":
    main()
