"""The specimen cases' data of shared/data/pmhs_neck (Stemper 2004 rear
impact, Kang 2018 front and side mini-sled) as curves a rating can use;
the README of the data gives the sources and the decisions named here.

    read_curves(path) -> {channel: {specimen_or_bound: (t [ms], value)}}
    outline_bounds(t, v, dt=0.1) -> (grid [ms], lower, upper, midline)
    specimen_mean(curves, dt=0.1) -> (grid [ms], mean)
    reference(path, channel, dt=0.1) -> (grid [ms], reference, lower, upper)
    read_pulse(path) -> (t [s], value), delta_v(t, a, t_end) [m/s]

A corridor is digitised as a closed outline (README "What was done"): its
points run forward in time along one boundary and back along the other,
turning at the point of largest time. outline_bounds splits it there, makes
each boundary a function of time (its points sorted by time: some outlines
step back by up to 2 ms, README "Ambiguities" 12), interpolates both on a
common grid over the times both cover, and gives the lower and upper bound
and their midline, the reference of the catalogue's ratings. Individual
specimens (Kang side: PMHS1 and PMHS2) give their mean over the times all
cover, each curve sorted by time and interpolated linearly (as the source's
notebook does with np.interp). No offsets, shifts or sign changes: the
values are the digitised ones.
"""
import csv

import numpy as np


def read_curves(path):
    """{channel: {specimen_or_bound: (time [ms], value)}} of an experiment
    file, each curve in its digitised point order."""
    pts = {}
    with open(path) as f:
        for r in csv.DictReader(f):
            pts.setdefault(r["channel"], {}).setdefault(r["specimen_or_bound"], []).append(
                (int(r["point"]), float(r["time_ms"]), float(r["value"])))
    out = {}
    for ch, by in pts.items():
        out[ch] = {}
        for name, p in by.items():
            p.sort()
            out[ch][name] = (np.array([q[1] for q in p]), np.array([q[2] for q in p]))
    return out


def _as_function(t, v):
    """A digitised curve as a function of time: sorted by time (stable),
    repeated times merged into their mean value."""
    order = np.argsort(t, kind="stable")
    t, v = t[order], v[order]
    ut, inv = np.unique(t, return_inverse=True)
    uv = np.bincount(inv, weights=v) / np.bincount(inv)
    return ut, uv


def _grid(t0, t1, dt):
    n = int(np.floor((t1 - t0) / dt + 1e-9)) + 1
    return t0 + dt * np.arange(n)


def outline_bounds(t, v, dt=0.1):
    """Lower and upper bounds and midline of a closed corridor outline on a
    grid of step dt [ms] over the times both boundaries cover."""
    t, v = np.asarray(t, float), np.asarray(v, float)
    k = int(np.argmax(t))
    if k == 0 or k == t.size - 1:
        raise ValueError("not a closed outline: the largest time is at an end of the curve")
    ta, va = _as_function(t[:k + 1], v[:k + 1])
    tb, vb = _as_function(t[k:], v[k:])
    grid = _grid(max(ta[0], tb[0]), min(ta[-1], tb[-1]), dt)
    a, b = np.interp(grid, ta, va), np.interp(grid, tb, vb)
    lower, upper = np.minimum(a, b), np.maximum(a, b)
    return grid, lower, upper, 0.5 * (lower + upper)


def specimen_mean(curves, dt=0.1):
    """Mean of several specimens' curves {name: (t, v)} on a grid of step
    dt [ms] over the times every curve covers."""
    fs = [_as_function(np.asarray(t, float), np.asarray(v, float)) for t, v in curves.values()]
    grid = _grid(max(f[0][0] for f in fs), min(f[0][-1] for f in fs), dt)
    return grid, np.mean([np.interp(grid, *f) for f in fs], axis=0)


def reference(path, channel, dt=0.1):
    """The reference curve of one channel of an experiment file: the
    midline of its corridor outline, or the mean of its specimens (and
    their lowest and highest value as the bounds)."""
    by = read_curves(path)[channel]
    outlines = [n for n in by if n.endswith("corridor_outline")]
    if outlines:
        return (lambda g, lo, hi, mid: (g, mid, lo, hi))(*outline_bounds(*by[outlines[0]], dt=dt))
    grid, mean = specimen_mean(by, dt)
    each = np.array([np.interp(grid, *_as_function(*c)) for c in by.values()])
    return grid, mean, each.min(axis=0), each.max(axis=0)


def read_pulse(path):
    """A pulse file (time_ms, value, unit): time [s] and value (SI)."""
    t, v = [], []
    with open(path) as f:
        for r in csv.DictReader(f):
            t.append(float(r["time_ms"]) * 1e-3)
            v.append(float(r["value"]))
    return np.array(t), np.array(v)


def delta_v(t, a, t_end, t_start=0.0):
    """Velocity change [m/s] of an acceleration pulse from t_start to t_end
    [s] (trapezoidal, the pulse's own points and the two ends)."""
    grid = np.union1d(t[(t > t_start) & (t < t_end)], [t_start, t_end])
    y = np.interp(grid, t, a)
    return float(np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(grid)))
