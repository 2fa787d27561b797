"""ISO/TS 18571 objective rating of a model curve against a reference curve,
by the standard's published implementation, the PyPI package
objective-rating-metrics (version 1.3, TU Graz, MIT; a dependency of this
package). Nothing is computed here but the sampling the package needs: the
corridor, phase, magnitude and slope scores and their weighted overall
rating are the package's own (class ISO18571, its default parameters).

    rate(t, reference, model, window=None, ndigits=None) -> dict
    rate_many(channels, window=None, ndigits=None) -> dict

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
"""
import argparse
import sys

import numpy as np

DT = 1.0e-4          # the package's (and the standard's) sampling: 10 kHz
MIN_SAMPLES = 16     # fewer samples leave no room for the 9-point slope smoothing
SCORES = ("corridor", "phase", "magnitude", "slope", "overall")


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
    iso = _package_class()(np.column_stack((grid, ref)), np.column_stack((grid, mod)), dt=DT)
    nd = -1 if ndigits is None else ndigits
    return dict(corridor=float(iso.corridor_rating(ndigits=nd)),
                phase=float(iso.phase_rating(ndigits=nd)),
                magnitude=float(iso.magnitude_rating(ndigits=nd)),
                slope=float(iso.slope_rating(ndigits=nd)),
                overall=float(iso.overall_rating(ndigits=nd)))


def rate_many(channels, window=None, ndigits=None):
    """Several channels: `channels` maps a name to (t, reference, model).
    Returns dict(channels={name: rate(...)}, overall=mean of the channels'
    overall ratings)."""
    if not channels:
        raise ValueError("no channels to rate")
    each = {name: rate(t, r, m, window=window, ndigits=ndigits) for name, (t, r, m) in channels.items()}
    return dict(channels=each, overall=float(np.mean([s["overall"] for s in each.values()])))


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
