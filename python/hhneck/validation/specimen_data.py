"""The specimen cases' data of shared/data/pmhs_neck (Stemper 2004 rear
impact, Kang 2018 front and side mini-sled) as curves a rating can use;
the README of the data gives the sources and the decisions named here.

    read_curves(path) -> {channel: {specimen_or_bound: (t [ms], value)}}
    outline_bounds(t, v, dt=0.1) -> (grid [ms], lower, upper, midline)
    specimen_mean(curves, dt=0.1) -> (grid [ms], mean)
    reference(path, channel, curve=None, dt=0.1) -> (grid [ms], reference, lower, upper)
    read_pulse(path) -> (t [s], value), delta_v(t, a, t_end) [m/s]

A corridor is digitised as a closed outline (README "What was done"): its
points run forward in time along one boundary and back along the other,
turning at the point of largest time, and the last point comes back close
to the first. Two of its segments are no boundary: the closing edges that
cross from one boundary to the other at the outline's two ends in time.
At each end (the point of largest time, the point of smallest time, the
outline taken as a closed polygon) the closing edge is the steeper of its
two adjacent segments, the larger change of value per time (it crosses the
corridor's width at nearly one time; the other runs along a boundary);
where the corridor is narrow at an end the two are nearly alike, and
either choice gives nearly the same bounds. outline_bounds cuts the outline at the two closing edges
into its two boundaries, makes each a function of time (its points sorted
by time: some outlines step back by up to 2 ms, README "Ambiguities" 12),
interpolates both on a common grid over the times both cover, and gives
the lower and upper bound and their midline, the reference of the
catalogue's ratings. (Cut at the point of largest time alone, the closing
edge stays in one boundary and the midline of Stemper's head-T1 angle
rises from 37.4 to 49.5 deg over its last 0.2 ms.) Individual specimens
(Kang side: PMHS1 and PMHS2) give their mean over the times all cover,
each curve sorted by time and interpolated linearly (as the source's
notebook does with np.interp). No offsets, shifts or sign changes: the
values are the digitised ones.

Which curve of a channel is the reference is named, never taken by its
place in the file: reference(path, channel, curve) with curve the name of
a corridor outline (its specimen_or_bound) or a tuple of specimens whose
mean is taken; without it, the channel's one corridor outline, or the
mean of all its specimens when it has no outline (a channel with more
than one outline, or outlines and specimens, must name its curve).
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


def _closing_edge(t, v, k):
    """The closing edge at vertex k of the closed outline (t, v): of its two
    adjacent segments (i, i + 1 modulo the length), the index i of the
    steeper one (the larger change of value per time)."""
    n = t.size
    before, after = (k - 1) % n, k

    def steepness(i):
        dv, dt = abs(v[(i + 1) % n] - v[i]), abs(t[(i + 1) % n] - t[i])
        return np.inf if dt == 0.0 and dv > 0.0 else dv / max(dt, 1e-300)
    return before if steepness(before) > steepness(after) else after


def outline_boundaries(t, v):
    """The two boundaries of a closed corridor outline (module docstring):
    [(t, v), (t, v)], each in its digitised order, the closing edges at the
    outline's two ends in time cut out."""
    t, v = np.asarray(t, float), np.asarray(v, float)
    n = t.size
    k = int(np.argmax(t))
    if k == 0 or k == n - 1:
        raise ValueError("not a closed outline: the largest time is at an end of the curve")
    e_end, e_start = _closing_edge(t, v, k), _closing_edge(t, v, int(np.argmin(t)))
    if e_end == e_start:
        raise ValueError("not a closed outline: one segment closes both ends")
    out = []
    for first, last in ((e_start + 1, e_end), (e_end + 1, e_start)):
        idx = np.arange(first, first + (last - first) % n + 1) % n
        if idx.size < 2:
            raise ValueError("not a closed outline: a boundary of one point")
        out.append((t[idx], v[idx]))
    return out


def outline_bounds(t, v, dt=0.1):
    """Lower and upper bounds and midline of a closed corridor outline on a
    grid of step dt [ms] over the times both boundaries cover."""
    (ta, va), (tb, vb) = (_as_function(*b) for b in outline_boundaries(t, v))
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


def reference(path, channel, curve=None, dt=0.1):
    """The reference curve of one channel of an experiment file and its
    bounds, (grid [ms], reference, lower, upper): curve names it, the name
    of a corridor outline (its midline and bounds) or a tuple of specimens
    (their mean, and their lowest and highest value as the bounds); None:
    the channel's one outline, or the mean of all its specimens when it has
    no outline. A name the file does not have, or a channel whose curve is
    not one, is an error naming the curves the file has."""
    by = read_curves(path)[channel]
    outlines = [n for n in by if n.endswith("corridor_outline")]
    if curve is None:
        if len(outlines) > 1 or (outlines and len(by) > len(outlines)):
            raise ValueError("%s: channel %s has the curves %s: name the reference"
                             % (path, channel, ", ".join(sorted(by))))
        curve = outlines[0] if outlines else tuple(by)
    names = (curve,) if isinstance(curve, str) else tuple(curve)
    missing = [n for n in names if n not in by]
    if missing:
        raise ValueError("%s: channel %s has no curve %s (it has %s)"
                         % (path, channel, ", ".join(missing), ", ".join(sorted(by))))
    if isinstance(curve, str) and curve.endswith("corridor_outline"):
        return (lambda g, lo, hi, mid: (g, mid, lo, hi))(*outline_bounds(*by[curve], dt=dt))
    chosen = {n: by[n] for n in names}
    grid, mean = specimen_mean(chosen, dt)
    each = np.array([np.interp(grid, *_as_function(*c)) for c in chosen.values()])
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
