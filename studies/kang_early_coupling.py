#!/usr/bin/env python3
"""What couples the head to T1 in the first 25 ms of the Kang front case?

    python3 studies/kang_early_coupling.py

The specimens' heads stay nearly still while the sled pulls T1 rearward
(head x-acceleration -0.43 g at 20 ms, -1.09 g at 25 ms; the pulse is at
103 m/s^2 at 20 ms), then turn sharply (-11 g at 38 ms). The model's head
follows T1 at once (-2.3 g at 20 ms). The shipped Kang front deck
(python/hhneck/validation/specimens.py, HOLD POSTURE) runs with one coupling between
T1 and the head changed at a time (CHANGE cards, nothing refitted):

* the discs' bending and torsion damping (DISCS VBEND, the retardation
  time the NBDL calibration fitted, 38.7 x 5 ms on 60 % of the bending
  stiffness) x0.1 and x0.01;
* the discs' own bending and torsion stiffness (DISCS BEND) x0.3;
* the discs' shear (DISCS G) x0.2;
* the muscles switched off (FAMILY MUSCLES OFF: their passive force and
  damping gone);
* the upper two joints' discs (C2-C1, C1-head) with a tenth of their
  bending and torsion (the Ix, Iy and J of their DISC cards; a scratch
  copy of the model deck).

For each: the head's x-acceleration (the catalogue's channel: the
accelerometer, J211, CFC 60) at 10-40 ms against the specimens' corridor
midline, and the case's ISO/TS 18571 per channel (prediction).
"""
import os
import sys
import tempfile

import numpy as np

sys.path[:0] = [os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python")]
from hhneck import run
from hhneck.validation import segments, specimen_data, specimens  # noqa: E402
from hhneck.ratings import s3  # noqa: E402

TIMES_MS = (10, 20, 25, 30, 35, 40)
UPPER_DISCS = ("C2C1", "C1HD")

#: (label, CHANGE cards, the upper discs' bending factor)
VARIANTS = [("shipped", [], 1.0),
            ("discs' VBEND x0.1", [run.change_card("CVBEND", "FAMILY", "DISCS", "VBEND", "SCALE", 0.1)], 1.0),
            ("discs' VBEND x0.01", [run.change_card("CVBEND", "FAMILY", "DISCS", "VBEND", "SCALE", 0.01)], 1.0),
            ("discs' BEND x0.3", [run.change_card("CBEND", "FAMILY", "DISCS", "BEND", "SCALE", 0.3)], 1.0),
            ("discs' G x0.2", [run.change_card("CG", "FAMILY", "DISCS", "G", "SCALE", 0.2)], 1.0),
            ("muscles off", ["FAMILY    MUSCLES   OFF"], 1.0),
            ("upper two discs' bending and torsion x0.1", [], 0.1)]


def upper_discs_model(path, factor):
    """The model deck with the Ix, Iy and J (fields 2-4 of the second
    continuation card) of the upper two discs times factor, into path."""
    lines = open(os.path.join(segments.ROOT, "input", "head_neck_54dof.inp")).read().splitlines()
    for k, line in enumerate(lines):
        if line.startswith("DISC") and line[10:20].strip() in UPPER_DISCS:
            f = [lines[k + 2][i:i + 10] for i in range(0, 80, 10)]
            f[2:5] = ["%-10.4g" % (float(v) * factor) for v in f[2:5]]
            lines[k + 2] = "".join(f).rstrip()
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def front_deck(work, cards, upper):
    """The shipped Kang front deck with CHANGE cards (and the scratch model
    deck when the upper discs change) in work; its path."""
    model = {}
    if upper != 1.0:
        upper_discs_model(os.path.join(work, "upper_model.inp"), upper)
        model = {"model": "upper_model.inp"}
    deck = specimens.kang_deck(work, "front", **model)
    with open(deck, "a") as f:
        f.write("".join(c + "\n" for c in cards))
    return deck


def main():
    g, ref = specimen_data.reference(os.path.join(segments.DATA_DIR, "kang2018_front_experiment.csv"),
                                     "head_acc_x")[:2]
    chans = specimens.KANG_CHANNELS["front"]
    print("| variant | head x-acceleration [g] at %s ms | %s | mean |" % (", ".join(map(str, TIMES_MS)),
                                                                       " | ".join(chans)))
    print("|---|---|" + "---|" * len(chans) + "---|")
    print("| specimens (corridor midline) | %s |%s |" % (", ".join(s3(np.interp(t, g, ref)) for t in TIMES_MS),
                                                        " |" * len(chans)))
    for label, cards, upper in VARIANTS:
        work = tempfile.mkdtemp(prefix="kang-early-")
        model = specimens.model_channels("kang_front", specimens._run(front_deck(work, cards, upper), work, None))
        rated = specimens.rate_kang("front", model)
        t, ax = model["head_acc_x"]
        print("| %s | %s | %s | %s |" % (label, ", ".join(s3(np.interp(x, t, ax)) for x in TIMES_MS),
                                         " | ".join(s3(rated[c]["overall"]) for c in chans),
                                         s3(np.mean([rated[c]["overall"] for c in chans]))))


if __name__ == "__main__":
    main()
