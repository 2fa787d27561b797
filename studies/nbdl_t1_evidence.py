#!/usr/bin/env python3
"""What the NBDL data say about how T1 should drive the model:

    python3 studies/nbdl_t1_evidence.py

Two Markdown tables from the volunteer runs in reference/nbdl_15g and
reference/nbdl_12g (docs/validation.md, "How T1 drives the model"):

1. Axes of the accelerations. Each run's acceleration is integrated twice
   (trapezoid, from rest; mm from g and ms) and compared with the run's
   displacement channel, with the acceleration taken as given (fixed axes)
   and rotated by the segment's measured rotation theta either way (as if the
   accelerometers had measured in the segment's rotating axes):
   z: mean over the runs of |double integral of a_z - z displacement|;
   x: the displacement channels are relative to the sled, so the double
   integral minus the displacement is the sled's travel, which must be the
   same from T1 and from the head: mean over the runs of |sled(T1) -
   sled(head)|.
2. Repeatability of the T1 accelerations across runs. Per frequency band
   (window 40-240 ms, Hann), |mean of the runs' spectra|^2 / mean of
   |spectrum|^2: 1 for a motion every run repeats, 1/n for runs out of phase
   with each other; the runs' strongest frequency above 30 Hz; the mean and
   the SD across runs at 100 ms (each run CFC 60).
3. Size of the T1 z ringing: per run (CFC 60), the least and largest T1
   z-acceleration in 85-120 ms, and the T1 z-displacement at 100 ms.
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))
from hhneck.signals import cfc  # noqa: E402
from hhneck.volunteers import runs  # noqa: E402

MM_PER_MS2 = 9.80665e-3      # 1 g in mm/ms^2
TIMES = (100.0, 150.0, 250.0)
BANDS = ((0, 10), (10, 20), (20, 30), (30, 60), (60, 100))
ROT_SCALE = {"15g": np.pi / 180.0, "12g": 1.0}   # 12 g T1 rotation read as radians


def dint(a, t):
    """Double trapezoid integral from rest."""
    dt = t[1] - t[0]
    v = np.concatenate([[0.0], np.cumsum(0.5 * (a[1:] + a[:-1]) * dt)])
    return np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * dt)])


def rotated(ax, az, th, sign):
    """(ax, az) in axes turned by sign*th about y, expressed in fixed axes."""
    c, s = np.cos(th), sign * np.sin(th)
    return c * ax + s * az, -s * ax + c * az


def axes_table():
    rows = ["| severity | check | at (ms) | fixed axes | rotated by +theta | rotated by -theta |",
            "|---|---|---|---|---|---|"]
    for sev in ("15g", "12g"):
        t = runs("T1_XAccel", sev)[0]
        ch = {k: runs(k, sev)[1] for k in ("T1_XAccel", "T1_ZAccel", "T1_XDisp", "T1_ZDisp", "T1_YrotDisp",
                                           "Head_XAccel", "Head_ZAccel", "Head_XDisp", "Head_ZDisp",
                                           "Head_YrotDisp")}
        th = {"T1": ch["T1_YrotDisp"] * ROT_SCALE[sev], "Head": np.radians(ch["Head_YrotDisp"])}
        idx = [int(np.searchsorted(t, x)) for x in TIMES]
        err = {}
        for sign in (0, 1, -1):
            sled, zerr = {}, {}
            for seg in ("T1", "Head"):
                ax, az = ch[seg + "_XAccel"], ch[seg + "_ZAccel"]
                if sign:
                    ax, az = rotated(ax, az, th[seg], sign)
                sled[seg] = np.array([dint(a * MM_PER_MS2, t) for a in ax]) - ch[seg + "_XDisp"]
                zerr[seg] = np.abs(np.array([dint(a * MM_PER_MS2, t) for a in az]) - ch[seg + "_ZDisp"])
            err[sign] = {"T1 z": zerr["T1"], "head z": zerr["Head"], "x": np.abs(sled["T1"] - sled["Head"])}
        for key, label in (("T1 z", "T1: double integral of z-acc. - z-disp. (mm)"),
                           ("head z", "head: double integral of z-acc. - z-disp. (mm)"),
                           ("x", "x: sled travel from T1 - from head (mm)")):
            for i, tm in zip(idx, TIMES):
                rows.append("| %s | %s | %.0f | %s |" % (sev.replace("g", " g"), label, tm, " | ".join(
                    "%.1f" % err[s][key][:, i].mean() for s in (0, 1, -1))))
    return rows


def coherence_table():
    rows = ["| severity | channel | runs (1/n) | " + " | ".join("%d-%d Hz" % b for b in BANDS)
            + " | strongest above 30 Hz | mean at 100 ms (g) | SD at 100 ms (g) |",
            "|---|---|---|" + "---|" * len(BANDS) + "---|---|---|"]
    for sev in ("15g", "12g"):
        for chan in ("T1_XAccel", "T1_ZAccel"):
            t, data, _ = runs(chan, sev)
            dt = (t[1] - t[0]) * 1e-3
            m = (t >= 40.0) & (t < 240.0)
            x = data[:, m] - data[:, m].mean(axis=1, keepdims=True)
            spec = np.fft.rfft(x * np.hanning(x.shape[1]), axis=1)
            f = np.fft.rfftfreq(x.shape[1], dt)
            power = np.mean(np.abs(spec) ** 2, axis=0)
            coh = np.abs(spec.mean(axis=0)) ** 2 / power
            hi = f > 30.0
            filt = np.array([cfc(r, 60, dt) for r in data])
            i100 = int(np.searchsorted(t, 100.0))
            rows.append("| %s | %s | %d (%.2f) | %s | %.0f Hz | %.1f | %.1f |" % (
                sev.replace("g", " g"), chan, len(data), 1.0 / len(data),
                " | ".join("%.2f" % coh[(f >= lo) & (f < up)].mean() for lo, up in BANDS),
                f[hi][np.argmax(power[hi])], filt[:, i100].mean(), filt[:, i100].std(ddof=1)))
    return rows


def ringing_table():
    rows = ["| severity | run | least T1 z-acc. in 85-120 ms (g) | largest (g) | T1 z-disp. at 100 ms (mm) |",
            "|---|---|---|---|---|"]
    for sev in ("15g", "12g"):
        t, acc, cols = runs("T1_ZAccel", sev)
        disp = runs("T1_ZDisp", sev)[1]
        dt = (t[1] - t[0]) * 1e-3
        m = (t >= 85.0) & (t <= 120.0)
        i100 = int(np.searchsorted(t, 100.0))
        for name, a, d in zip(cols, acc, disp):
            f = cfc(a, 60, dt)[m]
            rows.append("| %s | %s | %.1f | %.1f | %.1f |" % (sev.replace("g", " g"), name[4:], f.min(), f.max(),
                                                            d[i100]))
    return rows


def main():
    print("\n".join(axes_table() + [""] + coherence_table() + [""] + ringing_table()))


if __name__ == "__main__":
    main()
