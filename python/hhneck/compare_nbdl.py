"""Compare the model's NBDL sled runs with the volunteers (15 g and 12 g).

    hhneck-compare-nbdl [--case 15g|12g|both|NAME] [--h5 SEV=RESULT.h5 ...] [--out DIR]
                        [--data NAME=DIR] [--deck NAME=DECK]

Without --h5 it runs input/nbdlSEVg.inp for each case (hhneck.run.run_deck:
$HHNECK, else the project's release build). Volunteer data: reference/nbdl_15g (runs 1635-1644) and
reference/nbdl_12g (runs 1607-1617), raw, every 0.5 ms. Every volunteer run
and the model are filtered CFC 60 (SAE J211/1, as the library does).

Rated channels (the head's kinematics): x- and z-acceleration, angular
acceleration, angular velocity, rotation; each gets a CORA-style rating
(method in docs/validation.md) and the overall rating of a case is their
mean; each gets its ISO/TS 18571 rating too (hhneck.iso18571, reference =
the volunteers' mean, same window), and their mean. The head displacements relative to T1 are reported and rated but not
in the overall rating (their frames and points are not documented).
Peaks: x-acceleration, z-acceleration dip and rebound, angular acceleration,
angular velocity, rotation, each against the mean +- SD of the runs' peaks
(value and time). Writes a table on stdout, DIR/validation_table.md and
DIR/validation_nbdlSEV.png (default DIR: docs). Every number has three
significant digits.

Other runs of the same kind (a directory with the same CHANNEL.csv files,
columns time_ms,run_...): `--data NAME=DIR --case NAME` compares the deck
input/nbdlNAME.inp (or `--deck NAME=DECK`) with them; hhneck-nbdl-tables
--data DIR --name nbdlNAME writes that deck and its T1 tables. A channel
whose file the directory lacks is left out (the overall rating is the mean
over the rated channels present, and the table names the missing ones); a
file that cannot be read as evenly spaced runs stops the tool with its name.
"""
import argparse
import os
import sys
import tempfile

import numpy as np

from . import iso18571, run

G = 9.80665
WINDOW = (30.0, 250.0)   # ms
SEVERITIES = ("15g", "12g")
DATA_DIRS = {}   # case name -> directory of volunteer runs (default reference/nbdl_NAME)
DECKS = {}       # case name -> deck (default input/nbdlNAME.inp)

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


def channel_file(name, sev):
    """Path of one channel file of a case's runs."""
    return os.path.join(DATA_DIRS.get(sev, os.path.join("reference", "nbdl_" + sev)), name + ".csv")


def has_channel(name, sev="15g"):
    """True when the case's directory holds the channel's file."""
    return os.path.isfile(channel_file(name, sev))


def runs(name, sev="15g"):
    """One channel of a case's runs: (t_ms, runs[nrun, nt], run column names).
    A missing file, a file without a time_ms column or run_ columns, or
    times not evenly spaced (the filter needs one step) stop the tool with a
    message that names the file."""
    path = channel_file(name, sev)
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


def volunteer_channels(sev):
    """Each channel the case's runs have, as (t_ms, runs[nrun, nt]) filtered
    CFC 60; a channel whose file is missing is left out."""
    out = {}
    present = [c for c in HEAD_FILES if has_channel(c, sev)]
    if not present:
        stop("%s has none of the head channels' files (%s.csv)"
             % (os.path.dirname(channel_file(HEAD_FILES[0], sev)), ".csv, ".join(HEAD_FILES)))
    t, _, cols = runs(present[0], sev)
    dt = (t[1] - t[0]) * 1e-3

    def f(name):
        tc, data, cc = runs(name, sev)
        if len(tc) != len(t) or np.max(np.abs(tc - t)) > 1e-9 or cc != cols:
            stop("%s: its times or runs differ from %s's; every channel file of a case needs the same time_ms "
                 "column and run_ columns" % (channel_file(name, sev), present[0]))
        return np.array([cfc(r, 60, dt) for r in data])

    for label, name in (("head x-acceleration (g)", "Head_XAccel"), ("head z-acceleration (g)", "Head_ZAccel"),
                        ("head angular acceleration (rad/s2)", "Head_YrotAccel")):
        if has_channel(name, sev):
            out[label] = (t, f(name))
    if has_channel("Head_YrotDisp", sev):
        rot = f("Head_YrotDisp")
        # angular velocity: derivative of the filtered rotation (no drift, unlike
        # integrating the angular acceleration)
        out["head angular velocity (rad/s)"] = (t, np.gradient(np.radians(rot), dt, axis=1))
        out["head rotation (deg)"] = (t, rot)
    for label, head, t1 in (("head x-displacement rel. T1 (mm)", "Head_XDisp", "T1_XDisp"),
                            ("head z-displacement rel. T1 (mm)", "Head_ZDisp", "T1_ZDisp")):
        if has_channel(head, sev) and has_channel(t1, sev):
            out[label] = (t, f(head) - f(t1))
    return out, cols


def peak(t, x, sign, window=WINDOW):
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
    import h5py
    f = h5py.File(h5, "r")
    tm = f["time"][:] * 1e3
    dtm = (tm[1] - tm[0]) * 1e-3
    return tm, {k: cfc(f["channels"][v][:], 60, dtm) for k, v in MODEL.items()}


def compare(sev, h5):
    """Ratings and peaks of one case: (channel rows, peak rows, overall)."""
    vol, cols = volunteer_channels(sev)
    tm, model = model_channels(h5)
    chans, peaks, curves = [], [], {}
    for label, (t, data) in vol.items():
        mi = np.interp(t, tm, model[label])
        mean, sd = data.mean(axis=0), data.std(axis=0, ddof=1)
        m = (t >= WINDOW[0]) & (t <= WINDOW[1])
        C, X, score, lag = cora(t, mi, mean, sd)
        inside = np.mean(np.abs(mi[m] - mean[m]) <= sd[m])
        iso = iso18571.rate(t * 1e-3, mean, mi, window=(WINDOW[0] * 1e-3, WINDOW[1] * 1e-3))["overall"]
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


def tables(sev, chans, peaks, overall, nrun):
    sevt = sev.replace("g", " g")
    L = ["### NBDL %s (%d volunteer runs)" % (sevt, nrun), "",
         "| channel | corridor C | cross-corr. X | CORA-style | lag (ms) | time inside mean ± 1 SD | ISO/TS 18571 |",
         "|---|---|---|---|---|---|---|"]
    for c in chans:
        L.append("| %s%s | %.3f | %.3f | **%.3f** | %+.1f | %.0f %% | %.3f |" % (
            c["label"], "" if c["rated"] else " (reported)", c["C"], c["X"], c["score"], c["lag"], 100 * c["inside"],
            c["iso"]))
    L += ["", "| head peak | model | at (ms) | volunteers (mean ± SD) | at (ms) | (model − mean)/SD | "
          "within 1 SD | within 10 ms |", "|---|---|---|---|---|---|---|---|"]
    for p in peaks:
        L.append("| %s | %s | %.0f | %s ± %s | %.0f ± %.0f | %+.2f | %s | %s |" % (
            p["label"], s3(p["mp"]), p["mt"], s3(p["pm"]), s3(p["ps"]), p["tmn"], p["tsd"], p["z"],
            "yes" if p["ok_peak"] else "no", "yes" if p["ok_time"] else "no"))
    rep = np.mean([c["score"] for c in chans])
    rated = [c["label"] for c in chans if c["rated"]]
    nrep = len(chans) - len(rated)
    which = "the five rated head channels" if len(rated) == len(RATED) else \
        "the %d rated head channels the runs have; not in them: %s" % (
            len(rated), ", ".join(c for c in RATED if c not in rated))
    with_rep = "; with the two displacement channels: %.3f" % rep if nrep == len(REPORTED) else \
        "; with the displacement channel: %.3f" % rep if nrep else ""
    iso = np.mean([c["iso"] for c in chans if c["rated"]])
    L += ["", "Overall CORA-style rating %s (mean of %s): **%.3f** (target ≥ 0.85: %s)%s. "
          "ISO/TS 18571 (objective-rating-metrics; reference the volunteers' mean, CFC 60, the same window), "
          "mean of the same channels: **%.3f**. "
          "Peaks within 1 SD: %d of %d; peak times within 10 ms: %d of %d."
          % (sevt, which, overall, "met" if overall >= 0.85 else "not met", with_rep, iso,
             sum(p["ok_peak"] for p in peaks), len(peaks), sum(p["ok_time"] for p in peaks), len(peaks)), ""]
    return L


def figure(sev, curves, model_curves, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    tm, model = model_curves
    fig, axes = plt.subplots(2, 4, figsize=(18, 8))
    for ax, (label, (t, data, mean, sd)) in zip(axes.flat, curves.items()):
        for r in data:
            ax.plot(t, r, color="0.6", lw=0.6)
        ax.fill_between(t, mean - sd, mean + sd, color="tab:blue", alpha=0.25, label="volunteer mean ± 1 SD")
        ax.plot(t, mean, color="tab:blue", lw=1.2)
        ax.plot(tm, model[label], color="tab:red", lw=2.2, label="model")
        ax.set_xlim(0, 300)
        ax.set_title(label, fontsize=10)
        ax.set_xlabel("time (ms)")
        ax.grid(alpha=0.3)
    axes.flat[0].legend(fontsize=8)
    for ax in axes.flat[len(curves):]:
        ax.axis("off")                      # the channels the runs do not have, and the caption's place
    axes.flat[-1].text(0.0, 0.5, "NBDL %s frontal sled\nvolunteer runs (thin grey),\nmean ± 1 SD (band),\n"
                       "model (thick red);\nall CFC 60" % sev.replace("g", " g"), fontsize=11, va="center")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def run_deck(sev, tmp):
    """Run a case's deck (input/nbdlSEV.inp or its --deck) to TMP/nbdlSEV.h5; the result file's path."""
    return run.run_deck(DECKS.get(sev, "input/nbdl%s.inp" % sev), h5=os.path.join(tmp, "nbdl%s.h5" % sev)).h5


def pair(text):
    """NAME=VALUE of an option as (NAME, VALUE)."""
    if "=" not in text:
        raise argparse.ArgumentTypeError("expected NAME=VALUE, got %r" % text)
    return tuple(text.split("=", 1))


def main(argv=None):
    p = argparse.ArgumentParser(prog="hhneck-compare-nbdl", description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--case", default="both", help="15g, 12g, both (default) or the NAME of --data")
    p.add_argument("--h5", action="append", type=pair, default=[], metavar="SEV=RESULT.h5",
                   help="the model's result file of a case (default: run its deck)")
    p.add_argument("--out", default="docs", metavar="DIR",
                   help="where validation_table.md and the figures go (default docs)")
    p.add_argument("--data", action="append", type=pair, default=[], metavar="NAME=DIR",
                   help="runs of another case: a directory of CHANNEL.csv files")
    p.add_argument("--deck", action="append", type=pair, default=[], metavar="NAME=DECK",
                   help="the deck of a case (default input/nbdlNAME.inp)")
    args = p.parse_args(argv)
    outdir, which, given = args.out, args.case, dict(args.h5)
    DATA_DIRS.update(dict(args.data))
    DECKS.update(dict(args.deck))
    sevs = SEVERITIES if which == "both" else (which,)
    tmp = tempfile.mkdtemp()
    lines = []
    os.makedirs(outdir, exist_ok=True)
    for sev in sevs:
        h5 = given.get(sev) or run_deck(sev, tmp)
        chans, peaks, overall, curves, mc, nrun = compare(sev, h5)
        lines += tables(sev, chans, peaks, overall, nrun)
        figure(sev, curves, mc, os.path.join(outdir, "validation_nbdl%s.png" % sev))
    text = "\n".join(lines)
    print(text)
    with open(os.path.join(outdir, "validation_table.md"), "w") as out:
        out.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
