"""Neutral-zone joint springs (NZSPRING cards) fitted to the segment data of
Panjabi et al. 2001 and Nightingale et al. 2007 (hhneck.validation.segments; data in
shared/data/pmhs_neck).

The NZSPRING law (docs/deck-format.md): on the joint rotation coordinate x
of a body relative to its parent, D = x - x_neutral; for D >= 0
Q = -M0+ sinh(D/ths+), for D < 0 Q = +M0- sinh(-D/ths-) (M0 in N m, ths in
deg), continued linearly with its slope beyond |Q| = Mlin (here the data's
largest moment of the case, the mlin column). The "+" side is the
coordinate's positive direction: flexion is +RY of the upper body, left
lateral bending -RX, left axial rotation +RZ (segments.MOTIONS: the data's
positive direction is the coordinate's times MOTIONS[motion][1]).

What is fitted, for every joint (HEAD on C1 = C0-C1, C1 on C2 = C1-C2, C2 on
C3 = C2-C3 ... C6 on C7 = C6-C7; C7 on T1 takes the C6-C7 values, an
ASSUMPTION: no segment test of C7-T1 is in the data) and every rotation
coordinate (RY from flexion_extension, RX from lateral_bending, RZ from
axial_rotation), each side separately:

 a. the data points (M_k, theta_k) of the side: the Panjabi 2001 loading
    points with |M| > 0.1 N m (+-0.33, 0.67, 1.0 N m; segments.data_branches),
    and for C4-C5 and C6-C7 flexion-extension the Nightingale 2007 mean
    points with |M| > 0.1 N m (segments.load_nightingale), converted to the
    coordinate's sign;
 b. the "others": the segment case of that level and motion run with the
    model deck but its NZSPRING cards dropped, to the largest data moment;
    its rotation against the moment on the two loading ramps gives M_o(theta),
    the moment the other elements carry at a rotation (interpolated; beyond
    the run's largest rotation extrapolated linearly from the points of the
    last TAIL of its moment range, and reported);
 c. M_nz,k = M_k - M_o(theta_k); a point with M_nz,k <= DROP_FRACTION |M_k|
    is dropped (the other elements already carry it) and reported;
 d. (M0, ths) of Q = M0 sinh(theta/ths) by least squares in rotation,
    min sum_k (ths asinh(M_nz,k/M0) - theta_k)^2, ths in THS_BOUNDS on a log
    grid refined by golden section, for each ths M0 in M0_BOUNDS by a log
    grid and golden section in log M0 (fit_sinh). Fewer than 2 points, or a
    fit that fails, take a fallback rule (fallback_law): one point (or a
    failed fit): the secant stiffness M_nz/theta through the point of
    largest M_nz as the nearly linear law of the largest ths (30 deg), M0 =
    M_nz/sinh(theta/30 deg); no point: the weakest spring, M0 = 1e-3 N m at
    ths = 30 deg (3.4e-4 N m at 10 deg), the other elements carrying the data.

Output: reference/nz_springs.csv (a comment line naming the command, then
body, coord, m0_plus, ths_plus_deg, m0_minus, ths_minus_deg, n_plus,
rms_plus_deg, sources_plus, n_minus, rms_minus_deg, sources_minus,
method_plus, method_minus, segment, mlin), a table on standard output, and
the dropped and extrapolated points.

The flow is dev/fit_model.sh: hhneck.validation.fit_column calls this fit (statics)
at every candidate of the column's factors (the discs' bending and torsion
fractions, the range-of-motion factors), so that the others are the
candidate's; its best point's springs are written into
reference/model_parameters.csv. Since the others' runs drop the
NZSPRING cards, fitting again on a deck that has them gives the same
constants. --check runs each segment case with the cards and reports the
rotation at each data moment against the data (model/data).

With --upper-cervical the factors of hhneck.validation.upper_cervical (the C2-C1 and
C1-HEAD ligaments, and those discs' flexion bending and torsion) are fitted
first, on the deck without them (refused on one that has them), written to
reference/upper_cervical.csv, and the springs fitted on the deck with them
(an option, not the shipped model's flow: docs/validation.md, "The upper
cervical joints").

Command: python3 -m hhneck.validation.fit_joints [--exe HHNECK] [--model DECK] [--data DIR]
[--csv PATH] [--work DIR] [--jobs N] [--check] [--upper-cervical
[--upper-csv PATH]]
"""
import argparse
import csv
import math
import os
import sys
import tempfile
import time

import numpy as np

from . import segments, upper_cervical
from ..decks import write_deck
from ..paths import project_path, project_root

CSV_PATH = project_path("reference", "nz_springs.csv")
#: (body, segment of the data) per joint; C7 on T1 takes C6-C7 (ASSUMED)
JOINTS = (("HEAD", "C0_C1"), ("C1", "C1_C2"), ("C2", "C2_C3"), ("C3", "C3_C4"), ("C4", "C4_C5"),
          ("C5", "C5_C6"), ("C6", "C6_C7"), ("C7", "C6_C7"))
#: rotation coordinate -> the motion of the data
COORD_MOTION = (("RX", "lateral_bending"), ("RY", "flexion_extension"), ("RZ", "axial_rotation"))
NIGHTINGALE_SEGMENTS = ("C4_C5", "C6_C7")        # flexion-extension only
PANJABI, NIGHTINGALE = "Panjabi 2001", "Nightingale 2007"
MIN_MOMENT = 0.1          # [N m] data points with |M| above it
DROP_FRACTION = 0.02      # a point whose M_nz <= this |M| is dropped
THS_BOUNDS = (0.2, 30.0)  # [deg]
M0_BOUNDS = (1e-3, 10.0)  # [N m]
MLIN = 100.0              # [N m] the law's linear continuation beyond it (the card's default)
TAIL = 0.1                # the last fraction of a run's moment range its extrapolation is fitted to
DROP = ("NZSPRING",)      # the cards the others' runs leave out
GRID = 41                 # points of the log grids of ths and M0
TOL = 1e-12               # golden section: width of the final bracket in log ths and log M0
CSV_COLUMNS = ("body", "coord", "m0_plus", "ths_plus_deg", "m0_minus", "ths_minus_deg",
               "n_plus", "rms_plus_deg", "sources_plus", "n_minus", "rms_minus_deg", "sources_minus",
               "method_plus", "method_minus", "segment", "mlin")
SIDES = ((+1, "plus"), (-1, "minus"))


# ---------------------------------------------------------------- data

def data_points(segment, motion, data_dir=segments.DATA_DIR, panjabi=None, night=None):
    """The data points of a segment and motion with |M| > MIN_MOMENT, in the
    coordinate's sign: a list of (source, moment [N m], rotation [deg]).
    Panjabi: the two loading branches of segments.data_branches; Nightingale
    (C4-C5, C6-C7 flexion-extension): its mean curve. panjabi, night: the
    loaded files (segments.load_panjabi, load_nightingale), read if None."""
    sign = segments.MOTIONS[motion][1]
    panjabi = segments.load_panjabi(data_dir) if panjabi is None else panjabi
    out = []
    (mp, rp), (mn, rn) = segments.data_branches(*panjabi[(segment, motion)])
    for m, r in zip(mp, rp):
        if abs(m) > MIN_MOMENT:
            out.append((PANJABI, sign * float(m), sign * float(r)))
    for m, r in zip(mn, rn):                 # the branch's moments are magnitudes of negative ones
        if abs(m) > MIN_MOMENT:
            out.append((PANJABI, -sign * float(m), sign * float(r)))
    if motion == "flexion_extension" and segment in NIGHTINGALE_SEGMENTS:
        night = segments.load_nightingale(data_dir) if night is None else night
        mm, rm = night[segment]["mean"]
        for m, r in zip(mm, rm):
            if abs(m) > MIN_MOMENT:
                out.append((NIGHTINGALE, sign * float(m), sign * float(r)))
    return out


def side_points(points, side):
    """The points of one side (side +1: positive coordinate moments, -1:
    negative) as magnitudes: (sources list, moment [N m] > 0, rotation
    [deg], in the side's direction)."""
    sel = [p for p in points if p[1] * side > 0]
    return ([p[0] for p in sel], np.array([abs(p[1]) for p in sel]), np.array([side * p[2] for p in sel]))


# ---------------------------------------------------------------- the others

def ramp_curves(t, rot, peak, sign):
    """The two loading ramps of a segment run (segments' protocol) as
    {side: (rotation [deg], moment [N m])}, magnitudes in the side's
    direction, moment ascending: `rot` the run's rotation in the data's
    sign (segments.run_case), `sign` MOTIONS[motion][1]. The data's
    positive ramp (0 .. RAMP) is the coordinate's side `sign`, the negative
    one (T_NEG .. T_NEG + RAMP) the other."""
    t, rot = np.asarray(t, dtype=float), np.asarray(rot, dtype=float)
    out = {}
    for t0, data_sign in ((0.0, +1.0), (segments.T_NEG, -1.0)):
        sel = (t >= t0 - 1e-9) & (t <= t0 + segments.RAMP + 1e-9)
        moment = peak * (t[sel] - t0) / segments.RAMP
        out[int(sign * data_sign)] = (data_sign * rot[sel], moment)
    return out


def others_moment(theta, curve_theta, curve_moment, tail=TAIL):
    """M_o(theta): the moment [N m] the other elements carry at the
    rotations `theta` [deg], from a run's loading ramp (curve_theta,
    curve_moment, moment ascending). The rotation made non-decreasing
    (its running maximum) and interpolated; beyond the run's largest rotation
    extrapolated linearly with the slope fitted (least squares) to the
    points of the last `tail` of the moment range (the secant through the
    origin when that slope is not positive). Returns (M_o, extrapolated
    mask)."""
    theta = np.atleast_1d(np.asarray(theta, dtype=float))
    th = np.maximum.accumulate(np.asarray(curve_theta, dtype=float))
    m = np.asarray(curve_moment, dtype=float)
    keep = np.r_[True, np.diff(th) > 0]
    th, m = th[keep], m[keep]
    out = np.interp(theta, th, m)
    beyond = theta > th[-1]
    if np.any(beyond):
        last = m >= m[-1] - tail * (m[-1] - m[0])
        slope = np.polyfit(th[last], m[last], 1)[0] if np.count_nonzero(last) >= 2 else 0.0
        if not np.isfinite(slope) or slope <= 0.0:
            slope = m[-1] / th[-1] if th[-1] > 0 else 0.0
        out[beyond] = m[-1] + slope * (theta[beyond] - th[-1])
    return out, beyond


def neutral_zone_moments(moment, theta, curve_theta, curve_moment, drop_fraction=DROP_FRACTION):
    """The neutral-zone springs' share of the data moments: M_nz = M - M_o(theta)
    (others_moment). Returns (M_nz, M_o, kept mask: M_nz > drop_fraction M and
    theta > 0, extrapolated mask)."""
    moment, theta = np.asarray(moment, dtype=float), np.asarray(theta, dtype=float)
    m_o, extrapolated = others_moment(theta, curve_theta, curve_moment)
    m_nz = moment - m_o
    kept = (m_nz > drop_fraction * np.abs(moment)) & (theta > 0)
    return m_nz, m_o, kept, extrapolated


# ---------------------------------------------------------------- the law and its fit

def sinh_moment(theta, m0, ths):
    """The NZSPRING law on one side: M0 sinh(theta/ths) [N m], theta and ths in deg."""
    return m0 * np.sinh(np.asarray(theta, dtype=float) / ths)


def golden_section(f, a, b, tol=TOL):
    """The minimiser of f on [a, b] by golden section (f unimodal there),
    to a bracket narrower than tol; returns (x, f(x))."""
    g = (math.sqrt(5.0) - 1.0) / 2.0
    c, d = b - g * (b - a), a + g * (b - a)
    fc, fd = f(c), f(d)
    while b - a > tol:
        if fc <= fd:
            b, d, fd = d, c, fc
            c = b - g * (b - a)
            fc = f(c)
        else:
            a, c, fc = c, d, fd
            d = a + g * (b - a)
            fd = f(d)
    x = 0.5 * (a + b)
    fx = f(x)
    for y, fy in ((c, fc), (d, fd)):
        if fy < fx:
            x, fx = y, fy
    return x, fx


def _grid_then_golden(f, lo, hi, n=GRID):
    """Minimise f(u) on [lo, hi]: the best of n grid points, then golden
    section between its neighbours."""
    grid = np.linspace(lo, hi, n)
    values = [f(u) for u in grid]
    k = int(np.nanargmin(values))
    x, fx = golden_section(f, grid[max(k - 1, 0)], grid[min(k + 1, n - 1)])
    return (x, fx) if fx <= values[k] else (grid[k], values[k])


def rotation_residuals(theta, moment, m0, ths):
    """ths asinh(M/M0) - theta [deg]: the rotation of the law at each moment less the data's."""
    return ths * np.arcsinh(np.asarray(moment, dtype=float) / m0) - np.asarray(theta, dtype=float)


def fit_sinh(theta, moment, ths_bounds=THS_BOUNDS, m0_bounds=M0_BOUNDS):
    """(M0 [N m], ths [deg], rms rotation residual [deg]) of M = M0 sinh(theta/ths)
    through the points (theta [deg] > 0, moment [N m] > 0) by least squares in
    rotation, min sum (ths asinh(M/M0) - theta)^2: for each ths the best M0 by
    a log grid and golden section in log M0, and ths the same way over its
    bounds."""
    theta, moment = np.asarray(theta, dtype=float), np.asarray(moment, dtype=float)
    ulo, uhi = math.log(m0_bounds[0]), math.log(m0_bounds[1])

    def cost(u, ths):
        r = rotation_residuals(theta, moment, math.exp(u), ths)
        return float(np.dot(r, r))

    def best_m0(v):
        ths = math.exp(v)
        return _grid_then_golden(lambda u: cost(u, ths), ulo, uhi)

    v, _ = _grid_then_golden(lambda v: best_m0(v)[1], math.log(ths_bounds[0]), math.log(ths_bounds[1]))
    u, f = best_m0(v)
    return math.exp(u), math.exp(v), math.sqrt(f / theta.size)


def fallback_law(theta, moment, ths_bounds=THS_BOUNDS, m0_bounds=M0_BOUNDS):
    """The rule for a side with fewer than two points (or a failed fit):
    (M0, ths, method). With points: the secant stiffness through the point
    of largest moment as the nearly linear law of the largest ths, M0 =
    M/sinh(theta/ths) (within the M0 bounds), method "secant"; without: the
    weakest spring, the smallest M0 at the largest ths, method "none"."""
    ths = ths_bounds[1]
    if len(moment) == 0:
        return m0_bounds[0], ths, "none"
    k = int(np.argmax(moment))
    m0 = float(moment[k]) / math.sinh(float(theta[k]) / ths)
    return min(max(m0, m0_bounds[0]), m0_bounds[1]), ths, "secant"


def fit_side(theta, m_nz):
    """The law of one side from its kept points: a dict m0, ths, n, rms
    [deg] (None without points), method ("lsq", with " (ths at bound)" or
    " (M0 at bound)" when the fit ends on a bound, "secant" or "none", see
    fallback_law)."""
    theta, m_nz = np.asarray(theta, dtype=float), np.asarray(m_nz, dtype=float)
    n = int(theta.size)
    if n >= 2:
        m0, ths, rms = fit_sinh(theta, m_nz)
        if all(np.isfinite([m0, ths, rms])):
            method = "lsq"
            for name, value, bounds in (("ths", ths, THS_BOUNDS), ("M0", m0, M0_BOUNDS)):
                if min(abs(value / b - 1.0) for b in bounds) < 1e-6:
                    method += " (%s at bound)" % name
            return dict(m0=m0, ths=ths, n=n, rms=rms, method=method)
    m0, ths, method = fallback_law(theta, m_nz)
    if n >= 2:
        method += " (fit failed)"
    rms = None
    if n:
        r = rotation_residuals(theta, m_nz, m0, ths)
        rms = float(np.sqrt(np.mean(r * r)))
    return dict(m0=m0, ths=ths, n=n, rms=rms, method=method)


# ---------------------------------------------------------------- the whole fit

def _cases():
    """The (segment, motion) of every data curve the joints need, once each."""
    return sorted({(seg, motion) for _, seg in JOINTS for _, motion in COORD_MOTION})


def run_others(cases, exe, model, workdir, jobs=None, data_dir=segments.DATA_DIR, drop=DROP, statics=False):
    """Run each (segment, motion) case to its largest data moment with the
    `drop` cards left out (statics: as equilibria, segments.write_deck);
    {case: (points, peak, t, rot, wall [s])}."""
    from concurrent.futures import ThreadPoolExecutor
    panjabi, night = segments.load_panjabi(data_dir), segments.load_nightingale(data_dir)
    points = {c: data_points(c[0], c[1], data_dir, panjabi, night) for c in cases}
    peaks = {c: max(abs(p[1]) for p in points[c]) for c in cases}

    def one(c):
        t0 = time.perf_counter()
        t, rot = segments.run_case(c[0], c[1], peaks[c], workdir, exe, drop=drop, model=model, statics=statics)
        return t, rot, time.perf_counter() - t0

    with ThreadPoolExecutor(max_workers=jobs or os.cpu_count() or 1) as pool:
        runs = list(pool.map(one, cases))
    return {c: (points[c], peaks[c]) + run for c, run in zip(cases, runs)}


def fit_case(points, peak, t, rot, motion):
    """The two sides of one joint coordinate from its data points and its
    others' run: {side: dict of fit_side plus sources (str), and points, a
    list of dicts source, moment, theta, m_o, m_nz, kept, extrapolated
    (magnitudes in the side's direction)}."""
    curves = ramp_curves(t, rot, peak, segments.MOTIONS[motion][1])
    out = {}
    for side, _ in SIDES:
        sources, moment, theta = side_points(points, side)
        m_nz, m_o, kept, extra = neutral_zone_moments(moment, theta, *curves[side])
        res = fit_side(theta[kept], m_nz[kept])
        used = [s for s, k in zip(sources, kept) if k]
        res["sources"] = "; ".join(s for s in (PANJABI, NIGHTINGALE) if s in used)
        res["points"] = [dict(source=s, moment=float(m), theta=float(th), m_o=float(mo), m_nz=float(mn),
                              kept=bool(k), extrapolated=bool(e))
                         for s, m, th, mo, mn, k, e in zip(sources, moment, theta, m_o, m_nz, kept, extra)]
        out[side] = res
    return out


def fit_joints(exe=None, model=segments.MODEL_DECK, data_dir=segments.DATA_DIR, workdir=None, jobs=None,
               statics=False):
    """Fit every joint and coordinate (module docstring; statics: the
    others' runs as equilibria, their zero-rate limit); a list of rows,
    one per (body, coord) in JOINTS x COORD_MOTION order: dicts body, coord,
    segment, motion, plus (side +1 and -1) the fit_case dicts; and the
    others' wall times {case: s}."""
    exe = exe or segments.default_executable()
    work = workdir or tempfile.mkdtemp(prefix="hhneck-fit-joints-")
    os.makedirs(work, exist_ok=True)
    runs = run_others(_cases(), exe, model, work, jobs, data_dir, statics=statics)
    fits = {c: fit_case(pts, peak, t, rot, c[1]) for c, (pts, peak, t, rot, _) in runs.items()}
    peaks = {c: r[1] for c, r in runs.items()}
    rows = []
    for body, seg in JOINTS:
        for coord, motion in COORD_MOTION:
            f = fits[(seg, motion)]
            # Mlin: the largest moment of the data; beyond it the law goes on linearly (no extrapolated sinh)
            rows.append({"body": body, "coord": coord, "segment": seg, "motion": motion, +1: f[+1], -1: f[-1],
                         "mlin": peaks[(seg, motion)]})
    return rows, {c: r[-1] for c, r in runs.items()}


# ---------------------------------------------------------------- files and tables

def _num(v):
    return "" if v is None else "%.6g" % v


def write_csv(path, rows):
    """reference/nz_springs.csv: a comment line naming the command, the
    header CSV_COLUMNS, one row per (body, coord)."""
    with open(path, "w", newline="") as f:
        f.write("# written by python3 -m hhneck.validation.fit_joints (python/hhneck/validation/fit_joints.py): "
                "NZSPRING constants of every "
                "joint coordinate, M0 [N m], ths [deg], per side (plus = the coordinate's positive direction) "
                "the points used, the rms rotation residual [deg], the data sources and the rule; "
                "C7 takes C6-C7 (assumed)\n")
        w = csv.writer(f, lineterminator="\n")
        w.writerow(CSV_COLUMNS)
        for r in rows:
            p, m = r[+1], r[-1]
            w.writerow([r["body"], r["coord"], _num(p["m0"]), _num(p["ths"]), _num(m["m0"]), _num(m["ths"]),
                        p["n"], _num(p["rms"]), p["sources"], m["n"], _num(m["rms"]), m["sources"],
                        p["method"], m["method"], r["segment"], _num(r.get("mlin", MLIN))])


def read_csv(path):
    """The rows of a nz_springs.csv (comment lines skipped) as dicts of strings."""
    with open(path, newline="") as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def table(rows):
    """The fitted constants as text lines: one per joint coordinate and side."""
    lines = ["%-5s %-3s %-5s %-5s %2s %10s %8s %8s  %-28s %s" % (
        "body", "crd", "seg", "side", "n", "M0 [N m]", "ths[deg]", "rms[deg]", "method", "sources")]
    for r in rows:
        for side, name in SIDES:
            s = r[side]
            lines.append("%-5s %-3s %-5s %-5s %2d %10.4g %8.4g %8s  %-28s %s" % (
                r["body"], r["coord"], r["segment"].replace("_", "-"), name, s["n"], s["m0"], s["ths"],
                "-" if s["rms"] is None else "%.3g" % s["rms"], s["method"], s["sources"] or "-"))
    return lines


def point_notes(rows):
    """Text lines naming each dropped data point (and why) and each point
    whose M_o was extrapolated beyond its run, once per segment and motion."""
    lines, seen = [], set()
    for r in rows:
        key = (r["segment"], r["motion"])
        if key in seen:
            continue
        seen.add(key)
        for side, name in SIDES:
            for p in r[side]["points"]:
                why = []
                if not p["kept"]:
                    why.append("dropped: " + ("rotation not in the moment's direction" if p["theta"] <= 0 else
                                              "M_nz %.3g <= %.0f %% of M (the others carry it)"
                                              % (p["m_nz"], 100 * DROP_FRACTION)))
                if p["extrapolated"]:
                    why.append("M_o extrapolated beyond the run's largest rotation")
                if why:
                    lines.append("%-5s %-18s %-5s %-16s M %.3g N m theta %.3g deg M_o %.3g N m: %s" % (
                        r["segment"].replace("_", "-"), r["motion"], name, p["source"], p["moment"], p["theta"],
                        p["m_o"], "; ".join(why)))
    return lines


# ---------------------------------------------------------------- check

def check(exe=None, model=segments.MODEL_DECK, data_dir=segments.DATA_DIR, workdir=None, jobs=None):
    """Run every segment case with the model deck as it is (its NZSPRING
    cards present) and compare the rotation at each data moment with the
    data; a list of dicts segment, motion, source, moment, data, model,
    ratio (data sign, the moment on its loading ramp)."""
    exe = exe or segments.default_executable()
    work = workdir or tempfile.mkdtemp(prefix="hhneck-fit-joints-check-")
    os.makedirs(work, exist_ok=True)
    runs = run_others(_cases(), exe, model, work, jobs, data_dir, drop=())
    out = []
    for (seg, motion), (points, peak, t, rot, _) in sorted(runs.items()):
        sign = segments.MOTIONS[motion][1]
        for src, m, th in points:                  # back to the data's sign for rotations_at
            got = float(segments.rotations_at(t, rot, peak, [sign * m])[0])
            out.append(dict(segment=seg, motion=motion, source=src, moment=sign * m, data=sign * th,
                            model=got, ratio=got / (sign * th) if th else float("nan")))
    return out


def _has_nzspring(model):
    """Whether the deck `model` has an NZSPRING card."""
    return any(segments._fields(b[0])[0] == "NZSPRING" for b in segments.card_blocks(model))


def main(argv=None):
    """python3 -m hhneck.validation.fit_joints: fit the NZSPRING constants and write the CSV (or,
    with --check, compare the model with the NZSPRING cards to the data)."""
    p = argparse.ArgumentParser(prog="python3 -m hhneck.validation.fit_joints", description=__doc__.split("\n\n")[0])
    p.add_argument("--exe", help="the hhneck executable (default $HHNECK, else fpm's release build)")
    p.add_argument("--model", default=segments.MODEL_DECK, help="the model deck (default input/head_neck_54dof.inp)")
    p.add_argument("--data", default=segments.DATA_DIR, help="the pmhs_neck data folder")
    p.add_argument("--csv", default=CSV_PATH, help="the table to write (default reference/nz_springs.csv)")
    p.add_argument("--upper-cervical", action="store_true",
                   help="first fit the upper-cervical factors (hhneck.validation.upper_cervical) on the deck "
                        "without them, "
                        "then the springs on the deck with them")
    p.add_argument("--upper-csv", default=upper_cervical.CSV_PATH,
                   help="where --upper-cervical writes its factors (default reference/upper_cervical.csv)")
    p.add_argument("--work", help="working directory for the decks, listings and result files")
    p.add_argument("--jobs", type=int, help="runs at a time (default: the number of cores)")
    p.add_argument("--check", action="store_true",
                   help="run the segment cases with the model deck's NZSPRING cards and compare with the data")
    a = p.parse_args(argv)
    t0 = time.perf_counter()
    if a.check:
        if not _has_nzspring(a.model):
            print("python3 -m hhneck.validation.fit_joints: %s has no NZSPRING card (write it with "
                  "python3 -m hhneck.validation.model_deck "
                  "--nz-springs %s)" % (a.model, os.path.relpath(a.csv, project_root())), file=sys.stderr)
            return 1
        res = check(a.exe, a.model, a.data, a.work, a.jobs)
        print("%-5s %-18s %-16s %9s %9s %9s %9s" % ("seg", "motion", "source", "M [N m]", "data", "model",
                                                   "model/data"))
        for r in res:
            print("%-5s %-18s %-16s %+9.3g %+9.3g %+9.3g %9.3g" % (
                r["segment"].replace("_", "-"), r["motion"], r["source"], r["moment"], r["data"], r["model"],
                r["ratio"]))
        ratios = np.array([r["ratio"] for r in res if np.isfinite(r["ratio"]) and r["ratio"] > 0])
        print("model/data over %d points: geometric mean %.3g, range %.3g .. %.3g (%.1f s)" % (
            ratios.size, float(np.exp(np.mean(np.log(ratios)))), ratios.min(), ratios.max(),
            time.perf_counter() - t0))
        return 0
    work = a.work or tempfile.mkdtemp(prefix="hhneck-fit-joints-")
    os.makedirs(work, exist_ok=True)
    exe = a.exe or segments.default_executable()
    model = a.model
    if a.upper_cervical:
        try:
            upper = upper_cervical.fit_factors(exe, a.model, a.data, os.path.join(work, "upper_cervical"))
        except ValueError as e:
            print("python3 -m hhneck.validation.fit_joints: %s" % e, file=sys.stderr)
            return 1
        upper_cervical.write_csv(a.upper_csv, upper)
        for name, r in upper.items():
            print("%s = %.3g: %s %s turns %.3g deg at the data's largest moment (wanted %.3g), springs dropped"
                  % (name, r["value"], r["segment"].replace("_", "-"), r["motion"], r["model_deg"],
                     r["target_deg"]))
        with open(a.model) as f:
            lines = upper_cervical.scale_cards(f.read().splitlines(), upper["f_rot"]["value"],
                                               upper["f_lig"]["value"])
        model = os.path.join(work, "model_upper_cervical.inp")
        write_deck(model, lines)
    rows, walls = fit_joints(exe, model, a.data, work, a.jobs)
    write_csv(a.csv, rows)
    print("\n".join(table(rows)))
    notes = point_notes(rows)
    if notes:
        print("\npoints dropped or extrapolated:")
        print("\n".join(notes))
    print("\nwrote %s%s (%d rows); %d runs of the others (NZSPRING dropped), %.1f s in all" % (
        a.upper_csv + " and " if a.upper_cervical else "", a.csv, len(rows), len(walls), time.perf_counter() - t0))
    return 0


if __name__ == "__main__":
    sys.exit(main())
