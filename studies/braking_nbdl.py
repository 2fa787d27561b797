#!/usr/bin/env python3
"""How do the volunteers and the model stop the head's flexion, and what
governs the model's braking at 8 g?

    python3 studies/braking_nbdl.py

The shipped model predicts the 8 g head angular deceleration at twice the
volunteers' (studies/predict_nbdl8g.py). Two parts answer where that comes
from.

1. The braking arc, per volunteer run at 12 g and 15 g (each rotation CFC 60,
   its derivative the angular velocity, as hhneck.tools.compare_nbdl reads them)
   and for the model at 8, 12 and 15 g: the time and head rotation at the
   angular velocity's peak (where the braking starts), the largest rotation
   and its time, and the arc between them. reference/ has no 8 g time
   histories, so no 8 g volunteer arc.
2. One parameter at a time: each of the fifteen parameters of the shipped
   calibration (the PARAM cards of input/calibrate_nbdl12g.inp) set to half
   and to twice its shipped value, clamped into its PARAM bounds (a variation
   the bounds leave at the shipped value is not run), by a CHANGE card on the
   three case decks; per variation the 8 g peaks as (model - mean)/SD against
   reference/reference-data.md section 3, the 12 g peaks of the same rows,
   and the braking arc at each severity.

Nothing is fitted; the shipped decks are not changed.
"""
import os
import sys

import numpy as np

sys.path[:0] = [os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"),
                os.path.dirname(os.path.abspath(__file__))]
from hhneck import run  # noqa: E402
from hhneck.ratings import WINDOW, s3  # noqa: E402
from hhneck.signals import cfc  # noqa: E402
from hhneck.volunteers import volunteer_channels  # noqa: E402
from hhneck.decks import field, is_card  # noqa: E402
from predict_nbdl8g import ROWS, SEVERITIES, model_peaks, volunteer_peaks  # noqa: E402

CALIBRATION = "input/calibrate_nbdl12g.inp"   # the calibration of the shipped parameters
MODEL_DECK = "input/head_neck_54dof.inp"
FACTORS = (0.5, 2.0)


def braking_arc(t, rot):
    """(time of the angular velocity's peak [ms], rotation there [deg], time of
    the largest rotation [ms], the largest rotation [deg], the arc between
    [deg]) of a head rotation history rot [deg] at times t [ms], inside the
    rating window."""
    m = (t >= WINDOW[0]) & (t <= WINDOW[1])
    tt, r = t[m], rot[m]
    w = np.gradient(r, tt)
    iv, im = int(np.argmax(w)), int(np.argmax(r))
    return tt[iv], r[iv], tt[im], r[im], r[im] - r[iv]


def model_arc(h5):
    """braking_arc of the model's head rotation (HEAD_THETY, CFC 60)."""
    import h5py
    with h5py.File(h5, "r") as f:
        t = f["time"][:] * 1e3
        rot = cfc(f["channels"]["HEAD_THETY"][:], 60, (t[1] - t[0]) * 1e-3)
    return braking_arc(t, rot)


def parameters(path=CALIBRATION, model=MODEL_DECK):
    """[(name, field number, card, item, low, high, shipped value)] of the
    calibration's PARAM cards (kind FIELDn), the shipped value read from the
    model deck's card."""
    lines = open(model).read().splitlines()
    out = []
    for line in open(path):
        if not line.startswith("PARAM"):
            continue
        name, kind, card, item, low, high = (field(line, n) for n in range(1, 7))
        n = int(kind[len("FIELD"):])
        hits = [ln for ln in lines if is_card(ln, card, item)]
        if len(hits) != 1:
            sys.exit("parameter %s: %d %s cards named %s in %s" % (name, len(hits), card, item, model))
        out.append((name, n, card, item, float(low), float(high), float(field(hits[0], n))))
    return out


def run_cases(changes, tmp, tag):
    """{severity: result file} of the three case decks run with the CHANGE cards."""
    return {sev: run.run_deck("input/nbdl%s.inp" % sev, changes=changes,
                              h5=os.path.join(tmp, "%s_%s.h5" % (tag, sev))).h5 for sev in SEVERITIES}


def z_cells(h5s, vol, sevs=("8g", "12g")):
    """The five head peaks' (model - mean)/SD at each severity of sevs, and the count inside 1 SD."""
    cells = []
    for sev in sevs:
        pk = model_peaks(h5s[sev])
        zs = [(pk[label][0] - vol[label][sev][0]) / vol[label][sev][1] for label, _, _ in ROWS[1:]]
        cells += ["%+.2f" % z for z in zs] + ["%d" % sum(abs(z) <= 1.0 for z in zs)]
    return cells


def main():
    import tempfile
    tmp = tempfile.mkdtemp(prefix="braking-")
    vol = volunteer_peaks()

    print("## The braking arc: from the angular velocity's peak to the largest flexion\n")
    print("| case | velocity peak at (ms) | rotation there (deg) | largest rotation at (ms) | largest rotation (deg)"
          " | braking arc (deg) |")
    print("|---|---|---|---|---|---|")
    for sev in ("12g", "15g"):
        ch, cols = volunteer_channels(sev)
        t, rot = ch["head rotation (deg)"]
        arcs = np.array([braking_arc(t, r) for r in rot])
        mean, sd = arcs.mean(axis=0), arcs.std(axis=0, ddof=1)
        print("| %s volunteers (%d runs, mean ± SD) | %s |" % (
            sev.replace("g", " g"), len(cols), " | ".join("%s ± %s" % (s3(m), s3(s)) for m, s in zip(mean, sd))))
    base = run_cases([], tmp, "shipped")
    for sev in SEVERITIES:
        print("| %s model | %s |" % (sev.replace("g", " g"), " | ".join(s3(v) for v in model_arc(base[sev]))))

    print("\n## One parameter at a time (the shipped calibration's fifteen)\n")
    labels = [r[0].replace("peak ", "").replace("head ", "") for r in ROWS[1:]]
    head = ["parameter", "value (shipped)"] + ["8 g " + s for s in labels] + ["8 g in 1 SD"] + \
           ["12 g " + s for s in labels] + ["12 g in 1 SD"] + ["arc %s (deg)" % s.replace("g", " g")
                                                             for s in SEVERITIES]
    print("| " + " | ".join(head) + " |")
    print("|---" * len(head) + "|")

    def row(name, value, h5s):
        arcs = [s3(model_arc(h5s[sev])[4]) for sev in SEVERITIES]
        print("| %s | %s |" % (" | ".join([name, value] + z_cells(h5s, vol)), " | ".join(arcs)))

    row("shipped", "", base)
    for name, n, card, item, low, high, v in parameters():
        for f in FACTORS:
            new = min(max(v * f, low), high)
            if abs(new - v) <= 1e-6 * max(abs(v), 1e-12):
                continue
            change = run.change_card(name[:10], "FIELD%d" % n, card, item, "SET", "%.6g" % new)
            row(name, "%s (%s)" % (s3(new), s3(v)), run_cases([change], tmp, "%s_%g" % (name, f)))


if __name__ == "__main__":
    main()
