"""The NBDL sled cases' volunteer runs: reading them, filtered, channel by
channel (the library of hhneck-compare-nbdl and
python3 -m hhneck.validation.nbdl_tables; the ratings against them:
hhneck.ratings).

    from hhneck import volunteers
    t, runs, names = volunteers.runs("T1_XAccel", "12g")     # one channel of the 12 g runs
    channels, names = volunteers.volunteer_channels("15g")   # the head's channels, CFC 60

A case's runs are a directory of CHANNEL.csv files (columns time_ms,
run_...): the shipped cases' are the project's reference/nbdl_15g and
reference/nbdl_12g (data_dir), another's is given as `data`. Every
volunteer run is filtered CFC 60 (SAE J211/1, hhneck.signals.cfc) unless
said otherwise."""
import os
import sys

import numpy as np

from .paths import project_path
from .signals import cfc

G = 9.80665
SEVERITIES = ("15g", "12g")

HEAD_FILES = ("Head_XAccel", "Head_ZAccel", "Head_YrotAccel", "Head_YrotDisp")   # the rated channels' files
CHANNELS = HEAD_FILES + ("Head_XDisp", "Head_ZDisp", "T1_XAccel", "T1_ZAccel", "T1_YrotDisp", "T1_XDisp", "T1_ZDisp")


def stop(message):
    """Stop the tool with `message` on stderr, prefixed by the tool's name (exit 1)."""
    sys.exit("%s: %s" % (os.path.basename(sys.argv[0]), message))


def data_dir(sev):
    """The project's directory of a shipped case's volunteer runs,
    reference/nbdl_SEV (hhneck.paths)."""
    return project_path("reference", "nbdl_" + sev)


def channel_file(name, sev, data=None):
    """Path of one channel file of a case's runs, in directory `data`
    (default: the shipped case's, data_dir(sev))."""
    return os.path.join(data or data_dir(sev), name + ".csv")


def has_channel(name, sev="15g", data=None):
    """True when the case's directory holds the channel's file."""
    return os.path.isfile(channel_file(name, sev, data))


def runs(name, sev="15g", data=None):
    """One channel of a case's runs: (t_ms, runs[nrun, nt], run column names).
    A missing file, a file without a time_ms column or run_ columns, or
    times not evenly spaced (the filter needs one step) stop the tool with a
    message that names the file. `data`: the runs' directory (default:
    the shipped case's, data_dir(sev))."""
    path = channel_file(name, sev, data)
    if not os.path.isfile(path):
        stop("%s not found: a case's directory holds one CSV file per channel (%s), each with the columns "
             "time_ms,run_..." % (path, ", ".join(CHANNELS)))
    d = np.genfromtxt(path, delimiter=",", names=True)
    cols = [c for c in (d.dtype.names or ()) if c.startswith("run_")]
    if "time_ms" not in (d.dtype.names or ()) or not cols or d.ndim != 1 or len(d) < 3:
        stop("%s: expected a header time_ms,run_...,run_... and at least three rows of numbers" % path)
    t = d["time_ms"]
    step = np.diff(t)
    if not np.all(np.isfinite(t)) or step[0] <= 0 or np.max(np.abs(step - step[0])) > 1e-6 * step[0]:
        stop("%s: the times (column time_ms) are not evenly spaced and increasing; resample the runs to one step"
             % path)
    data = np.array([d[c] for c in cols])
    if not np.all(np.isfinite(data)):
        stop("%s: a run has an empty or non-numeric value" % path)
    return t, data, cols


def volunteer_channels(sev, data=None):
    """Each channel the case's runs have (in directory `data`, default
    data_dir(sev)), as (t_ms, runs[nrun, nt]) filtered CFC 60; a channel
    whose file is missing is left out."""
    out = {}
    present = [c for c in HEAD_FILES if has_channel(c, sev, data)]
    if not present:
        stop("%s has none of the head channels' files (%s.csv)"
             % (os.path.dirname(channel_file(HEAD_FILES[0], sev, data)), ".csv, ".join(HEAD_FILES)))
    t, _, cols = runs(present[0], sev, data)
    dt = (t[1] - t[0]) * 1e-3

    def f(name):
        tc, values, cc = runs(name, sev, data)
        if len(tc) != len(t) or np.max(np.abs(tc - t)) > 1e-9 or cc != cols:
            stop("%s: its times or runs differ from %s's; every channel file of a case needs the same time_ms "
                 "column and run_ columns" % (channel_file(name, sev, data), present[0]))
        return np.array([cfc(r, 60, dt) for r in values])

    for label, name in (("head x-acceleration (g)", "Head_XAccel"), ("head z-acceleration (g)", "Head_ZAccel"),
                        ("head angular acceleration (rad/s2)", "Head_YrotAccel")):
        if has_channel(name, sev, data):
            out[label] = (t, f(name))
    if has_channel("Head_YrotDisp", sev, data):
        rot = f("Head_YrotDisp")
        # angular velocity: derivative of the filtered rotation (no drift, unlike
        # integrating the angular acceleration)
        out["head angular velocity (rad/s)"] = (t, np.gradient(np.radians(rot), dt, axis=1))
        out["head rotation (deg)"] = (t, rot)
    for label, head, t1 in (("head x-displacement rel. T1 (mm)", "Head_XDisp", "T1_XDisp"),
                            ("head z-displacement rel. T1 (mm)", "Head_ZDisp", "T1_ZDisp")):
        if has_channel(head, sev, data) and has_channel(t1, sev, data):
            out[label] = (t, f(head) - f(t1))
    return out, cols
