"""The NBDL sled cases' volunteer runs and their comparison with the model:
the library of hhneck-compare-nbdl and python3 -m hhneck.validation.nbdl_tables.

    from hhneck import volunteers as nbdl
    t, runs, names = nbdl.runs("T1_XAccel", "12g")     # one channel of the 12 g runs
    chans, peaks, overall = nbdl.compare("15g", "nbdl15g.h5")[:3]

A case's runs are a directory of CHANNEL.csv files (columns time_ms,
run_...): the shipped cases' are the project's reference/nbdl_15g and
reference/nbdl_12g (data_dir), another's is given as `data`. Every
volunteer run and the model are filtered CFC 60 (SAE J211/1) unless said
otherwise; the ratings and peaks are those of hhneck.tools.compare_nbdl's
docstring (method in docs/validation.md)."""
import os
import sys

import numpy as np

from . import ratings
from .paths import project_path

G = 9.80665
WINDOW = (30.0, 250.0)   # ms
SEVERITIES = ("15g", "12g")

RATED = ["head x-acceleration (g)", "head z-acceleration (g)", "head angular acceleration (rad/s2)",
         "head angular velocity (rad/s)", "head rotation (deg)"]
REPORTED = ["head x-displacement rel. T1 (mm)", "head z-displacement rel. T1 (mm)"]
MODEL = {
    "head x-acceleration (g)": "HEAD_AX",
    "head z-acceleration (g)": "HEAD_AZ",
    "head angular acceleration (rad/s2)": "HEAD_ALPHY",
    "head angular velocity (rad/s)": "HEAD_OMEGY",
    "head rotation (deg)": "HEAD_THETY",
    "head x-displacement rel. T1 (mm)": "HEAD_DX",
    "head z-displacement rel. T1 (mm)": "HEAD_DZ",
}
HEAD_FILES = ("Head_XAccel", "Head_ZAccel", "Head_YrotAccel", "Head_YrotDisp")   # the rated channels' files
CHANNELS = HEAD_FILES + ("Head_XDisp", "Head_ZDisp", "T1_XAccel", "T1_ZAccel", "T1_YrotDisp", "T1_XDisp", "T1_ZDisp")
# peak: (label, channel, sign, window ms)
PEAKS = [
    ("x-acceleration (g)", "head x-acceleration (g)", -1, (30.0, 250.0)),
    ("z-acceleration dip (g)", "head z-acceleration (g)", -1, (30.0, 125.0)),
    ("z-acceleration rebound (g)", "head z-acceleration (g)", +1, (125.0, 250.0)),
    ("angular acceleration (rad/s2)", "head angular acceleration (rad/s2)", +1, (30.0, 250.0)),
    ("angular velocity (rad/s)", "head angular velocity (rad/s)", +1, (30.0, 250.0)),
    ("rotation (deg)", "head rotation (deg)", +1, (30.0, 250.0)),
]


def s3(x):
    """Three significant digits, without an exponent."""
    if x == 0 or not np.isfinite(x):
        return "%g" % x
    d = max(0, 2 - int(np.floor(np.log10(abs(x)))))
    return "%.*f" % (d, float("%.3g" % x))


def cfc(x, cls, dt):
    """SAE J211/1 Appendix C filter, forward then backward, started from rest."""
    wd = 2 * np.pi * cls * 2.0775
    wa = np.tan(wd * dt / 2)
    den = 1 + np.sqrt(2) * wa + wa ** 2
    a0 = wa ** 2 / den
    a1, a2 = 2 * a0, a0
    b1 = -2 * (wa ** 2 - 1) / den
    b2 = (-1 + np.sqrt(2) * wa - wa ** 2) / den

    def one(u):
        v = np.empty_like(u)
        u1 = u2 = v1 = v2 = u[0]
        for n in range(len(u)):
            v[n] = a0 * u[n] + a1 * u1 + a2 * u2 + b1 * v1 + b2 * v2
            u2, u1, v2, v1 = u1, u[n], v1, v[n]
        return v

    return one(one(np.asarray(x, float))[::-1])[::-1]


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


def peak(t, x, sign, window=WINDOW):
    """The extreme of sign*x within the window (ms): (value, time)."""
    m = (t >= window[0]) & (t <= window[1])
    i = np.argmax(sign * x[m])
    return x[m][i], t[m][i]


def cora(t, model, mean, sd):
    """Corridor rating C and cross-correlation rating X (docs/validation.md)."""
    m = (t >= WINDOW[0]) & (t <= WINDOW[1])
    y, r, s = model[m], mean[m], sd[m]
    floor = 0.05 * np.max(np.abs(r))
    inner = np.maximum(s, floor)
    outer = np.maximum(3 * s, 3 * floor)
    d = np.abs(y - r)
    c = np.where(d <= inner, 1.0, np.where(d >= outer, 0.0, ((outer - d) / (outer - inner)) ** 2))
    C = c.mean()
    dt = t[1] - t[0]
    maxlag = int(round(30.0 / dt))
    best, lag = -2, 0
    for k in range(-maxlag, maxlag + 1):
        lo, hi = max(0, k), len(y) + min(0, k)
        a = y[lo - k:hi - k]
        rho = np.corrcoef(a, r[lo:hi])[0, 1]
        if rho > best:
            best, lag = rho, k
    shift = abs(lag) * dt
    EP = 1.0 if shift <= 2.0 else max(0.0, (30.0 - shift) / (30.0 - 2.0))
    EV = ((1 + best) / 2) ** 2
    a_m, a_r = np.sum(y ** 2), np.sum(r ** 2)
    ES = min(a_m, a_r) / max(a_m, a_r)
    X = (EP + EV + ES) / 3
    return C, X, 0.5 * C + 0.5 * X, lag * dt


def model_channels(h5):
    """The model's rated and reported channels of result file h5, filtered
    CFC 60: (t_ms, {label: values})."""
    import h5py
    with h5py.File(h5, "r") as f:
        tm = f["time"][:] * 1e3
        dtm = (tm[1] - tm[0]) * 1e-3
        return tm, {k: cfc(f["channels"][v][:], 60, dtm) for k, v in MODEL.items()}


def compare(sev, h5, data=None):
    """Ratings and peaks of one case against its runs (in directory `data`,
    default data_dir(sev)): (channel rows, peak rows, overall, the curves,
    the model's curves, the number of runs)."""
    vol, cols = volunteer_channels(sev, data)
    tm, model = model_channels(h5)
    chans, peaks, curves = [], [], {}
    for label, (t, data) in vol.items():
        mi = np.interp(t, tm, model[label])
        mean, sd = data.mean(axis=0), data.std(axis=0, ddof=1)
        m = (t >= WINDOW[0]) & (t <= WINDOW[1])
        C, X, score, lag = cora(t, mi, mean, sd)
        inside = np.mean(np.abs(mi[m] - mean[m]) <= sd[m])
        iso = ratings.rate(t * 1e-3, mean, mi, window=(WINDOW[0] * 1e-3, WINDOW[1] * 1e-3))["overall"]
        chans.append(dict(label=label, C=C, X=X, score=score, lag=lag, inside=inside, iso=iso,
                          rated=label in RATED))
        curves[label] = (t, data, mean, sd)
    for plabel, label, sign, win in PEAKS:
        if label not in curves:
            continue                        # the case's runs do not have the channel
        t, data, mean, sd = curves[label]
        mi = np.interp(t, tm, model[label])
        pk = np.array([peak(t, r, sign, win) for r in data])
        mp, mt = peak(t, mi, sign, win)
        pm, ps, tmn, tsd = pk[:, 0].mean(), pk[:, 0].std(ddof=1), pk[:, 1].mean(), pk[:, 1].std(ddof=1)
        peaks.append(dict(label=plabel, mp=mp, mt=mt, pm=pm, ps=ps, tmn=tmn, tsd=tsd,
                          z=(mp - pm) / ps, ok_peak=abs(mp - pm) <= ps, ok_time=abs(mt - tmn) <= 10.0))
    overall = np.mean([c["score"] for c in chans if c["rated"]])
    return chans, peaks, overall, curves, (tm, model), len(cols)
