#!/usr/bin/env python3
"""How far does the Kang front case's head z-acceleration miss in time,
measured by the source's own comparison?

    python3 studies/kang_notebook_shift.py

The source's notebook (README of shared/data/pmhs_neck, "What the notebook
computes", Ambiguities 7) plots the SAFER HBM's front head z-acceleration
against the corridor shifted 25 ms earlier (time_z - 25) and its head
rotation against the corridor 5 ms earlier (time_rot - 5): its own model
meets those corridors only so. The catalogue reproduces no shift or offset.
This study runs the shipped front deck once and rates the two channels as
the catalogue does (ISO/TS 18571, window 0 to 1.2 x the reference's peak
time) against the corridor as given and as the notebook shifted it. The
shifted scores are a measurement of the timing, not a rating of the model.
"""
import os
import sys
import tempfile

sys.path[:0] = [os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python")]
from hhneck.validation import specimens  # noqa: E402
from hhneck.ratings import s3  # noqa: E402

#: the notebook's shifts of the front corridors' times [ms]
SHIFTS = {"head_acc_z": -25.0, "head_rot_y": -5.0}


def main():
    model = specimens.run_kang("front", tempfile.mkdtemp(prefix="kang-shift-"))
    print("| channel | corridor shift (ms) | ISO 18571 | model peak (ms) | reference peak (ms) |")
    print("|---|---|---|---|---|")
    for channel, shift in SHIFTS.items():
        for s in (0.0, shift):
            sc = specimens.rate_kang("front", model, shifts={channel: s})[channel]
            print("| %s | %g | %s | %s (%.0f) | %s (%.0f) |" % (
                channel, s, s3(sc["overall"]), s3(sc["peak_model"][0]), sc["peak_model"][1],
                s3(sc["peak_ref"][0]), sc["peak_ref"][1]))


if __name__ == "__main__":
    main()
