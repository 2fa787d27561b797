"""Newton's law between a sled test's head accelerations and its load cell.

The load cell of a potted specimen carries everything above it: its force
(the load on the part above, SAE J211 axes, tared) is the sum of m (a - g)
over the head and the neck, less its value at rest. Two terms hold nearly
all of it: the head's lab-frame acceleration times an effective mass Mh
(the head and the upper neck moving with it) and the potted body's
acceleration (the sled pulse) times Mn (the lower neck riding with it):

    F(t) = Mh a_head(t + s) + Mn a_T1(t)

fit_lag fits the lag s (on a grid) and the two masses by least squares.
Channels that share a time base fit at s near 0 with Mh near a head's
mass; a model obeys the law by construction, so its own curves check the
method. The head's lab acceleration comes from its accelerometer's tared
reading and the head's rotation (lab_acceleration).

The Kang 2018 cases' channels (hhneck.validation.specimens' names and signs): PLANE,
PAIRS; balance() gives the rows of one case (docs/validation.md, "Do the
specimens' head and load cell obey Newton's law together?"; the
catalogue prints them under each Kang case).

API: lab_acceleration, accelerometer_reading, fit_lag, balance, kang_channels, kang_data, kang_pulse,
kang_rows, PLANE, PAIRS, LAGS.
"""
import os

import numpy as np

from . import specimen_data, specimens

G = 9.81
#: the lags tried [ms]
LAGS = np.arange(-40.0, 40.25, 0.5)
#: per Kang case: the head's in-plane acceleration channel, its rotation
#: channel and the rotation's sense (lab_acceleration)
PLANE = {"front": ("head_acc_x", "head_rot_y", 1.0), "side": ("head_acc_y", "head_rot_x", -1.0)}
#: per Kang case and axis compared: (axis, the cell's force channel, the
#: sign of the T1 pulse on that axis, 0 where T1 is not driven along it)
PAIRS = {"front": [("x", "loadcell_force_x", -1.0), ("z", "loadcell_force_z", 0.0)],
         "side": [("y", "loadcell_force_y", 1.0), ("z", "loadcell_force_z", 0.0)]}


def lab_acceleration(a_in, a_z, rot_deg, sense):
    """The head's lab acceleration [m/s^2] (J211 axes, in the plane of the
    rotation): (in-plane, z) from the accelerometer's tared readings [g]
    along the head's in-plane axis (x front, y side) and z, and the head's
    rotation [deg] as the catalogue's channels give it; sense: +1 for a
    rotation about y in the (x, z) plane, -1 about x in the (y, z) plane
    (the planes' axes turn the other way round their normals)."""
    f1, f3 = np.asarray(a_in) * G, np.asarray(a_z) * G - G   # untared: upright, the z axis reads -g
    c, s = np.cos(np.radians(rot_deg)), sense * np.sin(np.radians(rot_deg))
    return c * f1 + s * f3, -s * f1 + c * f3 + G


def accelerometer_reading(lab_in, lab_z, rot_deg, sense):
    """The inverse of lab_acceleration: the accelerometer's tared readings
    [g] (in-plane, z) of a head with the lab acceleration (lab_in, lab_z)
    [m/s^2] and the rotation rot_deg [deg]."""
    f1, f3 = np.asarray(lab_in), np.asarray(lab_z) - G      # specific force a - g, lab axes
    c, s = np.cos(np.radians(rot_deg)), sense * np.sin(np.radians(rot_deg))
    return (c * f1 - s * f3) / G, (s * f1 + c * f3 + G) / G


def fit_lag(cell, head, pulse, window, lags=LAGS):
    """Least squares F(t) = Mh a(t + s) + Mn a_T1(t) over the window [ms]
    for every lag s [ms]: the best (R^2, s, Mh, Mn). cell, head, pulse:
    (t [ms], value) curves; a pulse of None fits the head's term alone
    (Mn 0)."""
    g = np.arange(window[0], window[1], 0.1)
    f = np.interp(g, *cell)
    best = None
    for s in lags:
        cols = [np.interp(g + s, *head)] + ([np.interp(g, *pulse)] if pulse is not None else [])
        x = np.column_stack(cols)
        coef = np.linalg.lstsq(x, f, rcond=None)[0]
        r = f - x @ coef
        r2 = 1.0 - r @ r / ((f - f.mean()) @ (f - f.mean()))
        cand = (float(r2), float(s), float(coef[0]), float(coef[1]) if pulse is not None else 0.0)
        if best is None or cand[0] > best[0]:
            best = cand
    return best


def _peak_time(curve):
    """The time of a curve's largest magnitude where the Kang rating
    searches it (hhneck.validation.specimens.KANG_PEAK_SEARCH)."""
    t, v = curve
    lo, hi = specimens.KANG_PEAK_SEARCH
    keep = (t >= lo - 1e-9) & (t <= hi + 1e-9)
    return t[keep][int(np.argmax(np.abs(v[keep])))]


def balance(direction, curves, reference, pulse):
    """The rows of one Kang case: for each axis of PAIRS, dict(axis, window
    (ms), best=(R^2, s, Mh, Mn), at_zero=(R^2, 0, Mh, Mn)) of `curves`
    ({channel: (t [ms], value)}, the model's or the data's). The window
    is 0 to 1.2 x the later of the two channels' peak times in
    `reference` (the data's curves, so that model and data share it; each
    peak searched where the rating searches it, _peak_time);
    pulse: (t [ms], T1's acceleration along the case's drive [m/s^2])."""
    acc, rot, sense = PLANE[direction]
    grid = np.arange(0.0, 200.0, 0.1)
    lab_in, lab_z = lab_acceleration(*(np.interp(grid, *curves[c]) for c in (acc, "head_acc_z", rot)), sense)
    rows = []
    for axis, force, psign in PAIRS[direction]:
        head_ch = acc if axis != "z" else "head_acc_z"
        t1 = 1.2 * max(_peak_time(reference[head_ch]), _peak_time(reference[force]))
        drive = (pulse[0], psign * np.asarray(pulse[1])) if psign else None
        head = (grid, lab_z if axis == "z" else lab_in)
        rows.append(dict(axis=axis, window=(0.0, t1), best=fit_lag(curves[force], head, drive, (0.0, t1)),
                         at_zero=fit_lag(curves[force], head, drive, (0.0, t1), lags=[0.0])))
    return rows


def kang_channels(direction):
    """The channels a Kang case's balance reads."""
    return set(PLANE[direction][:2]) | {"head_acc_z"} | {p[1] for p in PAIRS[direction]}


def kang_pulse(data_dir):
    """The Kang sled pulse (t [ms], a [m/s^2]) of the data folder."""
    t, a = specimen_data.read_pulse(os.path.join(data_dir, "kang2018_sled_pulse.csv"))
    return t * 1e3, a


def kang_data(direction, data_dir, channels=None):
    """{channel: (t [ms], reference)} of a Kang case's data (the corridor
    midline or the specimens' mean, as the catalogue rates them:
    hhneck.validation.specimens.REFERENCE): the channels its balance reads, or those
    named."""
    case = "kang_" + direction
    path = os.path.join(data_dir, specimens.DATA_FILE[case])
    return {c: specimen_data.reference(path, c, specimens.REFERENCE[case])[:2]
            for c in channels or kang_channels(direction)}


def kang_rows(direction, model, data_dir):
    """{"model": balance rows of the model's catalogue curves (hhneck.validation.specimens.
    model_channels), "specimens": those of the data's references}, the
    window from the data's; the pulse of the data folder, along the case's
    drive."""
    data = kang_data(direction, data_dir)
    pulse = kang_pulse(data_dir)
    return {"model": balance(direction, model, data, pulse), "specimens": balance(direction, data, data, pulse)}
