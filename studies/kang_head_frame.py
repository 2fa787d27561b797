#!/usr/bin/env python3
"""In which frame are the Kang specimens' head accelerations to be compared:
the lab's, the head's own axes, or as the head's accelerometer reads them?

    python3 studies/kang_head_frame.py

The shipped Kang decks (python/hhneck/validation/specimens.py, HOLD POSTURE) run once
each; every head-acceleration channel of the data (front: x, z; side: y,
z; SAE J211 signs) is rated by ISO/TS 18571 on the catalogue's window
against three readings of the same run:
- lab: the head mass centre's acceleration in R (HEAD_AX, HEAD_AY,
  HEAD_AZ), what the catalogue rated before;
- head axes: the same acceleration in the head's axes (HEAD_AXL ...), what
  a finite-element model's accelerometer node gives without gravity;
- accelerometer: the specific force a - g in the head's axes (HEAD_AXS ...)
  from its value at t = 0, what a head-mounted accelerometer tared upright
  senses (the catalogue's choice).
Each reading filtered by the channel's CFC class, as the catalogue filters
it (hhneck.validation.specimens.CHANNELS). For each: the score, the model's peak and
its time against the reference's, and the largest head rotation of the run
(what separates the frames).
"""
import os
import sys
import tempfile

import numpy as np

sys.path[:0] = [os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python")]
import h5py  # noqa: E402
from hhneck.validation import specimens  # noqa: E402
from hhneck.export import kinematic_to_j211  # noqa: E402
from hhneck.ratings import s3  # noqa: E402

#: per direction: the data's head-acceleration channels and their axis (0 x, 1 y, 2 z)
CHANNELS = {"front": (("head_acc_x", 0), ("head_acc_z", 2)), "side": (("head_acc_y", 1), ("head_acc_z", 2))}
READINGS = (("lab", "HEAD_A%s", False), ("head axes", "HEAD_A%sL", False), ("accelerometer", "HEAD_A%sS", True))


def readings(h5, axis):
    """({reading: (t [ms], value in J211 signs [g])} of one axis of a run, the head's largest rotation
    about x or y in R [deg])."""
    out = {}
    with h5py.File(h5, "r") as f:
        t = f["time"][:] * 1e3
        for label, pattern, tared in READINGS:
            v = kinematic_to_j211([f["channels"][pattern % c][:] for c in "XYZ"])[axis]
            out[label] = (t, v - v[0] if tared else v)
        rot = float(np.max(np.abs(np.stack([f["channels"]["HEADL_R" + c][:] for c in "XY"]))))
    return out, rot


def main():
    work = tempfile.mkdtemp(prefix="kang-head-frame-")
    print("| case | channel | reference peak (ms) | " + " | ".join("%s: ISO 18571, peak (ms)" % r[0] for r in READINGS)
          + " | largest head rotation in R |")
    print("|---|---|---|" + "---|" * len(READINGS) + "---|")
    for direction, chans in CHANNELS.items():
        h5 = specimens._run(specimens.kang_deck(work, direction), work, None)
        reads = {axis: readings(h5, axis) for _, axis in chans}
        rated = {}
        cls = {c[0]: c[4] for c in specimens.CHANNELS["kang_" + direction]}
        for label, _, _ in READINGS:          # the catalogue's rating, the head's channels read each way
            model = specimens.model_channels("kang_" + direction, h5)
            for name, axis in chans:          # filtered by the channel's class, as the catalogue's
                t, v = reads[axis][0][label]
                model[name] = (t, specimens.filtered(t, v, cls[name]))
            rated[label] = specimens.rate_kang(direction, model)
        for name, axis in chans:
            ref = rated[READINGS[0][0]][name]["peak_ref"]
            cells = ["%s, %s (%.0f)" % (s3(rated[label][name]["overall"]), s3(rated[label][name]["peak_model"][0]),
                                        rated[label][name]["peak_model"][1]) for label, _, _ in READINGS]
            print("| Kang %s | %s | %s (%.0f) | %s | %s deg |" % (direction, name, s3(ref[0]), ref[1], " | ".join(cells),
                                                               s3(reads[axis][1])))


if __name__ == "__main__":
    main()
