#!/usr/bin/env python3
"""Do the Kang specimens' head accelerations and their load cell obey
Newton's second law together, in time?

    python3 studies/kang_newton_check.py

The load cell carries everything above it (hhneck.validation.newton_balance, whose
functions this study runs): its force (the load on the part above, SAE
J211 axes, tared) is the sum of m (a - g) over the head and the neck, less
its value at rest. Two terms hold nearly all of it: the head's lab-frame
acceleration times an effective mass Mh (the head and the upper neck
moving with it) and T1's acceleration (the source's pulse) times Mn (the
lower neck riding with the potted T1):

    F(t) = Mh a_head(t + s) + Mn a_T1(t)

For each pair (the cell's force along an axis, the head's acceleration
along it) the lag s and the two masses are fitted by least squares, s on
a 0.5 ms grid from -40 to +40 ms; a pair whose channels share a time base
fits at s near 0 with Mh near a head's mass (about 4 kg). The head's
acceleration in the lab comes from the accelerometer's reading (specific
force in the head's axes, tared) and the head's rotation: untared, turned
by the rotation into the lab's axes, gravity added back. The model obeys
Newton's law by construction, so its own channels (the catalogue's curves
of the shipped decks, every one as the catalogue filters it) check the
method: they must fit at s near 0. The data: the corridors' midlines
(front) and the mean of the two specimens (side), as the catalogue rates
them, and (side) each specimen alone; the window 0 to 1.2 x the later of the two references' peak times.

Second, the front head z-acceleration the specimens' own load cell implies:
the head's lab acceleration from the cell's forces (a = (F - Mn a_T1) / Mh,
the model's fitted masses), read as the accelerometer reads it (with the
specimens' head rotation), rated by ISO/TS 18571 against the corridor as
the catalogue rates the model's: what a model whose load cell matched the
specimens' could score on that channel. Likewise the side cell's lateral
force the specimens' own head implies (F = Mh a_head + Mn a_T1, the
model's fitted masses) against the specimens' mean.
"""
import os
import sys
import tempfile

import numpy as np

sys.path[:0] = [os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python")]
from hhneck.validation import segments, specimen_data, specimens  # noqa: E402
from hhneck.ratings import s3  # noqa: E402
from hhneck.validation.newton_balance import (PAIRS, PLANE, accelerometer_reading, balance, kang_channels,  # noqa: E402
                                   kang_data, kang_pulse, lab_acceleration)


def curves(direction, model):
    """[(label, {channel: (t [ms], value)})]: the model's catalogue curves,
    the data's references and, where the data give individual specimens
    (side), each specimen's own curves."""
    names = kang_channels(direction)
    out = [("model", {c: model[c] for c in names}), ("specimens", kang_data(direction, segments.DATA_DIR))]
    raw = specimen_data.read_curves(os.path.join(segments.DATA_DIR, "kang2018_%s_experiment.csv" % direction))
    for who in sorted(set.intersection(*(set(raw[c]) for c in names)) - {"corridor_outline"}):
        out.append((who.upper(), {c: specimen_data._as_function(*raw[c][who]) for c in names}))
    return out


def main():
    tp, ap = kang_pulse(segments.DATA_DIR)
    print("| case | axis | curves | window (ms) | lag s (ms) | Mh (kg) | Mn (kg) | R^2 | R^2 at s = 0 (Mh, Mn) |")
    print("|---|---|---|---|---|---|---|---|---|")
    fitted = {}
    for direction in PAIRS:
        model = specimens.run_kang(direction, tempfile.mkdtemp(prefix="kang-newton-"))
        sets = curves(direction, model)
        rows = {label: balance(direction, c, dict(sets)["specimens"], (tp, ap)) for label, c in sets}
        for k, (axis, _, _) in enumerate(PAIRS[direction]):
            for label, _ in sets:
                r = rows[label][k]
                best, at0 = r["best"], r["at_zero"]
                fitted[(direction, axis, label)] = best
                print("| %s | %s | %s | 0-%.0f | %+.1f | %s | %s | %s | %s (%s, %s) |" % (
                    direction, axis, label, r["window"][1], best[1], s3(best[2]), s3(best[3]), s3(best[0]),
                    s3(at0[0]), s3(at0[2]), s3(at0[3])))
    # the front head z-acceleration the specimens' own load cell implies
    ref = kang_data("front", segments.DATA_DIR, ("head_rot_y", "loadcell_force_x", "loadcell_force_z"))
    grid = np.arange(0.0, 190.0, 0.1)
    _, _, mhx, mnx = fitted[("front", "x", "model")]
    _, _, mhz, _ = fitted[("front", "z", "model")]
    ax_lab = (np.interp(grid, *ref["loadcell_force_x"]) - mnx * np.interp(grid, tp, -ap)) / mhx
    az_lab = np.interp(grid, *ref["loadcell_force_z"]) / mhz
    _, reading_z = accelerometer_reading(ax_lab, az_lab, np.interp(grid, *ref["head_rot_y"]), PLANE["front"][2])
    sc = specimens.rate_channel(*specimens.kang_reference("front", "head_acc_z"), grid, reading_z)
    print()
    print("front head z-acceleration implied by the specimens' load cell (Mh %s / %s kg, Mn %s kg): "
          "ISO/TS 18571 %s against the corridor, peak %s g at %.0f ms (corridor %s g at %.0f ms)" % (
              s3(mhx), s3(mhz), s3(mnx), s3(sc["overall"]), s3(sc["peak_model"][0]), sc["peak_model"][1],
              s3(sc["peak_ref"][0]), sc["peak_ref"][1]))
    # the side load cell's lateral force the specimens' own head implies
    ref = kang_data("side", segments.DATA_DIR, ("head_acc_y", "head_acc_z", "head_rot_x"))
    _, _, mhy, mny = fitted[("side", "y", "model")]
    lab_y, _ = lab_acceleration(*(np.interp(grid, *ref[c]) for c in ("head_acc_y", "head_acc_z", "head_rot_x")),
                                PLANE["side"][2])
    fy = mhy * lab_y + mny * np.interp(grid, tp, ap)
    sc = specimens.rate_channel(*specimens.kang_reference("side", "loadcell_force_y"), grid, fy)
    print("side load cell Fy implied by the specimens' head (Mh %s kg, Mn %s kg): ISO/TS 18571 %s against "
          "the specimens' mean, peak %s N at %.0f ms (specimens %s N at %.0f ms)" % (
              s3(mhy), s3(mny), s3(sc["overall"]), s3(sc["peak_model"][0]), sc["peak_model"][1],
              s3(sc["peak_ref"][0]), sc["peak_ref"][1]))


if __name__ == "__main__":
    main()
