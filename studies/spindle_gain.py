#!/usr/bin/env python3
"""Do stretch-loop gains that rise with the muscle's activation (SPINDLE
F6: kp and kd times 1 + g a_b, the stretch reflex's automatic gain
compensation) carry the NBDL volunteers on the segmental column, where
fixed gains (fit B of studies/spindle_segmental.py) rate 12 g 0.799?

    python3 studies/spindle_gain.py [--fit LABEL=LISTING ...]

In spindle_segmental.py's scratch copy (the segmental column, its
neutral-zone springs refitted at the calibration's starting point), without
--fit, two calibrations run side by side (release build):
input/calibrate_nbdl12g_spindle_gain.inp (fit B's nineteen and the gain
rises GAINE, GAINF, from fit B's point with g = 0) and the same with the
disc and stop factors held at the column's (the muscles, the loops and
their gain rises, 13 parameters). Fit B's point is scored first (its J by
the same calibration deck with no evaluations beyond it). Each set is then
scored as spindle_segmental.py does: NBDL 12 g (calibration), 15 g and the
8 g peaks (prediction), the braking arcs, 6 s at rest and the catalogue
(ISO/TS 18571, prediction).
"""
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path[:0] = [os.path.join(ROOT, "python"), HERE]
from feedback_nbdl import fit_arguments, reduced_deck, run_calibrations  # noqa: E402
from predict_nbdl8g import fitted_values  # noqa: E402
from spindle_segmental import PASSIVE, column_copy, deck_values, report  # noqa: E402

CALIBRATION = "input/calibrate_nbdl12g_spindle_gain.inp"
MUSCLES_TITLE = "NBDL 12 G: THE MUSCLES, STRETCH LOOPS AND GAIN RISES ONLY"


def one_point(text):
    """The calibration deck text scoring its VALUES point only (the FIT card's F2 = 0)."""
    return re.sub(r"^(FIT       NELDER    )\S+ *", lambda m: m.group(1) + "%-10s" % "0", text, flags=re.M)


def restarted(text, listing):
    """The calibration deck text with its VALUES point the best point of `listing` (a Nelder-Mead
    run again from where the last one stopped)."""
    values = [v for _, v in fitted_values(listing)]
    lines = [ln for ln in text.splitlines() if not ln.startswith("VALUES")]
    lines += ["VALUES    " + "".join("%-10.6g" % v for v in values[k:k + 7]).rstrip() for k in range(0, len(values), 7)]
    return "\n".join(lines) + "\n"


def main():
    fits = fit_arguments(sys.argv[1:], "spindle_gain.py")
    tmp, copy, env, start = column_copy("spindle-gain-")
    text = open(CALIBRATION).read()
    point_b = run_calibrations([("fit B's point, g = 0", one_point(text))], tmp)[0][1]
    os.rename(point_b, os.path.join(tmp, "point_b.txt"))
    point_b = os.path.join(tmp, "point_b.txt")
    if not fits:
        muscles = reduced_deck(CALIBRATION, PASSIVE, MUSCLES_TITLE)
        fits = run_calibrations([("fit B's nineteen and the gain rises (21 parameters)", text),
                                 ("the muscles, the loops and the gain rises (13)", muscles)], tmp)
        os.rename(fits[0][1], os.path.join(tmp, "fit21.txt"))
        fits[0] = (fits[0][0], os.path.join(tmp, "fit21.txt"))
        fits.insert(1, run_calibrations([("the 21 again from there (a second 2500 evaluations)",
                                          restarted(text, fits[0][1]))], tmp)[0])
    rows = [("fit B's point, g = 0", deck_values(CALIBRATION), point_b)]
    rows += [(label, fitted_values(listing), listing) for label, listing in fits]
    report(rows, [(label, listing) for label, _, listing in rows], CALIBRATION, start, copy, env, tmp)


if __name__ == "__main__":
    main()
