"""The ratings of model curves against reference curves: ISO/TS 18571, and
the CORA-style rating and the peaks of the NBDL cases (method in
docs/validation.md).

    rate(t, reference, model, window=None, ndigits=None) -> dict     # ISO/TS 18571
    rate_many(channels, window=None, ndigits=None) -> dict
    cora(t, model, mean, sd) -> (C, X, score, lag)                    # CORA-style, t in ms
    compare(sev, h5, data=None) -> (channels, peaks, overall, ...)    # a NBDL run against its volunteers

ISO/TS 18571, by the standard's published implementation, the PyPI package
objective-rating-metrics (version 1.3, TU Graz, MIT; a dependency of this
package). Nothing is computed here but the sampling the package needs: the
corridor, phase, magnitude and slope scores are the package's own (class
ISO18571, its default parameters), and the overall rating is its weighted
sum of them, with the package's weights in its order (its overall_rating()
to the bit, without computing the four scores a second time).

Sampling. The package takes two arrays of the same shape (time, value) and
does not interpolate; its documentation asks for 10 kHz sampling (the
standard's), and its slope score smooths the derivative over 9 samples and
its phase and DTW windows are counted in samples, so the rate matters.
rate() therefore gives the package the curves at 10 kHz: unchanged when t
is already equally spaced at 0.1 ms, otherwise linearly interpolated
(numpy.interp) onto t[0] + k * 0.1 ms, k = 0 .. floor((t[-1] - t[0]) / 0.1 ms
+ 1e-6), the same grid as src/analysis/hn_iso18571.f90 uses. The
derivative's step dt handed to the package is that 0.1 ms.

Rounding. The package rounds each score to ndigits=3 by default (and rounds
the overall rating of the unrounded scores); rate() returns the unrounded
values (ndigits < 0 in the package) unless ndigits is given.

Usage as a program, with a CSV of three columns (time [s], reference, model):

    hhneck-iso18571 CURVES.csv [T0 T1]

The NBDL cases (compare): the rated channels (RATED, the head's
kinematics) of the model's result file and the volunteers' runs
(hhneck.volunteers), each filtered CFC 60, over WINDOW: per channel the
CORA-style rating (cora: corridor C, cross-correlation X, their mean) and
the ISO/TS 18571 rating against the volunteers' mean; the peaks (PEAKS)
against the mean +- SD of the runs' peaks; the overall rating, the mean
of the rated channels' CORA-style ratings. hhneck-compare-nbdl prints
them (hhneck.tools.compare_nbdl)."""
import argparse
import sys

import numpy as np

from . import volunteers
from .signals import cfc

DT = 1.0e-4          # the package's (and the standard's) sampling: 10 kHz
MIN_SAMPLES = 16     # fewer samples leave no room for the 9-point slope smoothing
SCORES = ("corridor", "phase", "magnitude", "slope", "overall")
#: the standard's weights of the corridor, phase, magnitude and slope scores
#: in the overall rating (the package's defaults, handed to it explicitly)
WEIGHTS = dict(w_z=0.4, w_p=0.2, w_m=0.2, w_s=0.2)


def resample(t, *curves):
    """The time grid at DT and each curve on it (module docstring)."""
    t = np.asarray(t, dtype=float)
    curves = [np.asarray(c, dtype=float) for c in curves]
    if t.ndim != 1 or any(c.shape != t.shape for c in curves):
        raise ValueError("times and curves must be one-dimensional and of the same length")
    if t.size < 2 or np.any(np.diff(t) <= 0):
        raise ValueError("times must increase")
    if np.all(np.abs(np.diff(t) - DT) <= 1e-9 * DT):
        return (t,) + tuple(curves)
    n = int(np.floor((t[-1] - t[0]) / DT + 1e-6)) + 1
    grid = t[0] + DT * np.arange(n)
    return (grid,) + tuple(np.interp(grid, t, c) for c in curves)


def _package_class():
    """The package's class ISO18571, imported on first use: the package
    (numba under it) takes seconds to import, which a command's --help or a
    module that only imports this one need not pay. The numba functions of
    its DTW (dtwalign) are cached on disk, where numba can write: each
    process would otherwise compile them again, 14 s of processor time,
    where loading them takes under 1 s; numba recompiles when their source
    changes."""
    from objective_rating_metrics.rating import ISO18571
    try:
        from numba.core.registry import CPUDispatcher
        from dtwalign import backtrack, cost, window
        for module in (backtrack, cost, window):
            for f in vars(module).values():
                if isinstance(f, CPUDispatcher) and f._cache.__class__.__name__ == "NullCache":
                    f.enable_caching()
    except Exception:          # another dtwalign or numba, or nowhere to write: compiled as before
        pass
    return ISO18571


def rate(t, reference, model, window=None, ndigits=None):
    """ISO/TS 18571 scores of `model` against `reference`, both sampled at
    the times `t` [s]: dict(corridor=, phase=, magnitude=, slope=, overall=).

    window: (t0, t1) [s], the interval of evaluation (samples with
    t0 <= t <= t1); None for all of t. The curves are resampled to 10 kHz
    when they are not at 10 kHz already (module docstring). ndigits: None
    for the unrounded scores, else the package's rounding to that many
    digits. Raises ValueError for curves the rating cannot be computed on
    (too short, a reference that is zero or constant)."""
    t = np.asarray(t, dtype=float)
    reference = np.asarray(reference, dtype=float)
    model = np.asarray(model, dtype=float)
    if window is not None:
        t0, t1 = window
        keep = (t >= t0) & (t <= t1)
        t, reference, model = t[keep], reference[keep], model[keep]
    if t.size < 2:
        raise ValueError("fewer than two samples in the interval of evaluation")
    grid, ref, mod = resample(t, reference, model)
    if grid.size < MIN_SAMPLES:
        raise ValueError("%d samples at 10 kHz: at least %d needed" % (grid.size, MIN_SAMPLES))
    if np.max(np.abs(ref)) == 0 or np.ptp(ref) == 0:
        raise ValueError("the reference curve is zero or constant: nothing to rate against")
    iso = _package_class()(np.column_stack((grid, ref)), np.column_stack((grid, mod)), dt=DT, **WEIGHTS)
    z, e_p, e_m, e_s = (iso.corridor_rating(ndigits=-1), iso.phase_rating(ndigits=-1),
                        iso.magnitude_rating(ndigits=-1), iso.slope_rating(ndigits=-1))
    # the package's overall_rating() computes the four scores again (its
    # magnitude score's DTW twice per rating): the same weighted sum of the
    # same unrounded scores, in its order, is its overall rating to the bit
    overall = WEIGHTS["w_z"] * z + WEIGHTS["w_p"] * e_p + WEIGHTS["w_m"] * e_m + WEIGHTS["w_s"] * e_s
    scores = dict(corridor=z, phase=e_p, magnitude=e_m, slope=e_s, overall=overall)
    return {k: float(v if ndigits is None or ndigits < 0 else round(v, ndigits=ndigits)) for k, v in scores.items()}


def rate_many(channels, window=None, ndigits=None):
    """Several channels: `channels` maps a name to (t, reference, model).
    Returns dict(channels={name: rate(...)}, overall=mean of the channels'
    overall ratings)."""
    if not channels:
        raise ValueError("no channels to rate")
    each = {name: rate(t, r, m, window=window, ndigits=ndigits) for name, (t, r, m) in channels.items()}
    return dict(channels=each, overall=float(np.mean([s["overall"] for s in each.values()])))


# ---------------------------------------------------------------- the NBDL cases

WINDOW = (30.0, 250.0)   # ms
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
    default volunteers.data_dir(sev)): (channel rows, peak rows, overall, the curves,
    the model's curves, the number of runs)."""
    vol, cols = volunteers.volunteer_channels(sev, data)
    tm, model = model_channels(h5)
    chans, peaks, curves = [], [], {}
    for label, (t, data) in vol.items():
        mi = np.interp(t, tm, model[label])
        mean, sd = data.mean(axis=0), data.std(axis=0, ddof=1)
        m = (t >= WINDOW[0]) & (t <= WINDOW[1])
        C, X, score, lag = cora(t, mi, mean, sd)
        inside = np.mean(np.abs(mi[m] - mean[m]) <= sd[m])
        iso = rate(t * 1e-3, mean, mi, window=(WINDOW[0] * 1e-3, WINDOW[1] * 1e-3))["overall"]
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


def main(argv=None):
    p = argparse.ArgumentParser(prog="hhneck-iso18571",
                                description="ISO/TS 18571 rating of a model curve against a reference curve.")
    p.add_argument("csv", help="CSV of three columns: time [s], reference, model")
    p.add_argument("window", nargs="*", type=float, metavar="T",
                   help="T0 T1: the interval of evaluation [s] (default: all of it)")
    args = p.parse_args(argv)
    if len(args.window) not in (0, 2):
        p.error("give both T0 and T1, or neither")
    data = np.loadtxt(args.csv, delimiter=",", ndmin=2)
    window = tuple(args.window) if args.window else None
    scores = rate(data[:, 0], data[:, 1], data[:, 2], window=window)
    for key in SCORES:
        print("%-10s %.6f" % (key, scores[key]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
