"""Calibration over the specimen cases of the catalogue, and its
leave-one-out test: for each specimen case (Stemper 2004 rear, Kang 2018
front and side; the decks of hhneck.specimens), fit the passive
parameters to the other cases with `hhneck --calibrate` (ISO/TS 18571
objective, RATING F5 ISO18571) and score the case left out with the fitted
values: a prediction, since the case took no part in its fit.

    write_case(case, workdir) -> (deck, reference CSV, RATED card lines)
    calibration_deck(cases, workdir, params, evals, starts, values=None) -> path
    run_calibration(deck, workdir, exe=None) -> dict(values=, objective=, cases=)
    leave_one_out(workdir, cases=CASES, params=PARAMS, evals=..., starts=...) -> rows

Reference CSVs: each case's rated channels, their reference curve (the
corridor's midline or the specimens' mean, hhneck.specimen_data) and
bounds, on the common grid k 0.1 ms (each channel linearly interpolated
from its own 0.1 ms grid onto the grid points its curve covers; Kang: 0 to
1.2 x the time of the reference's largest magnitude, as hhneck.specimens
rates), empty cells elsewhere. The model channel of each column is a
RATED card: the sign changes and "from the start" of hhneck.specimens.
The rated channels and their model channels are those of the catalogue
(hhneck.specimens.CHANNELS), load cells included.

Parameters (PARAMS): scale factors of the passive elements, within bounds
from reference/parameters.md where sourced (VAXIAL: the disc damping range
of Izambert et al. 2003, S13), assumed otherwise (the spans the NBDL
calibration deck uses; the ligaments' stiffness a factor 2 either way).
The shipped model deck is not changed: the fitted values are reported.

Usage: hhneck-calibrate-catalogue WORKDIR [--quick] [--evals N] [--starts N] [--table FILE]
"""
import argparse
import os
import re
import subprocess
import sys

import numpy as np

from . import segments, specimen_data, specimens
from .deck_fields import number_field

GRID = 0.1   # ms: the reference CSVs' time step (the data's and ISO 18571's 10 kHz)

# name, kind, target, item, low, high, spacing, bounds' source
PARAMS = [
    ("AXIAL", "FIELD4", "SCALE", "AXIAL", 0.3, 3.0, "LOG", "assumed"),
    ("SHEAR", "FIELD4", "SCALE", "SHEAR", 0.3, 3.0, "LOG", "assumed"),
    ("VBEND", "FIELD4", "SCALE", "VBEND", 0.5, 100.0, "LOG", "assumed (the NBDL calibration deck's)"),
    ("VAXIAL", "FIELD4", "SCALE", "VAXIAL", 0.0128, 0.8376, "LOG", "S13 (Izambert 2003, 32-2094 N s/m)"),
    ("ROMK", "FIELD4", "SCALE", "ROMK", 0.05, 5.0, "LOG", "assumed"),
    ("LIGK", "FAMILY", "LIGAMENTS", "L1", 0.5, 2.0, "LOG", "assumed"),
]
QUICK_PARAMS = PARAMS[4:5]

# case: (data file stem, Kang window); the rated channels are hhneck.specimens.CHANNELS,
# each a reference column C01, C02, ... of the case's CSV
CASES = {"stemper": ("stemper2004_1p8ms", False), "kang_front": ("kang2018_front", True),
         "kang_side": ("kang2018_side", True)}


def case_channels(case):
    """[(column, data channel, model channel, scale, subtracted, from the start)] of `case`."""
    return [("C%02d" % (k + 1), name, run, scale, "", start)
            for k, (name, run, scale, start) in enumerate(specimens.CHANNELS[case])]


def write_reference(case, path, data_dir=segments.DATA_DIR):
    """The reference CSV of `case` (module docstring); its RATED card lines."""
    stem, kang = CASES[case]
    chans = case_channels(case)
    src = os.path.join(data_dir, stem + "_experiment.csv")
    curves = []
    for col, ch, *_ in chans:
        g, ref, lo, hi = specimen_data.reference(src, ch)
        if kang:
            keep = g >= 0.0
            g, ref, lo, hi = g[keep], ref[keep], lo[keep], hi[keep]
            keep = g <= 1.2 * g[int(np.argmax(np.abs(ref)))]
            g, ref, lo, hi = g[keep], ref[keep], lo[keep], hi[keep]
        curves.append((col, g, ref, lo, hi))
    k0 = int(np.ceil(min(c[1][0] for c in curves) / GRID - 1e-9))
    k1 = int(np.floor(max(c[1][-1] for c in curves) / GRID + 1e-9))
    grid = GRID * np.arange(k0, k1 + 1)
    cols = []
    for col, g, ref, lo, hi in curves:
        inside = (grid >= g[0] - 1e-9) & (grid <= g[-1] + 1e-9)
        cols.append([(col, np.interp(grid, g, ref), inside), (col + "_LOW", np.interp(grid, g, lo), inside),
                     (col + "_HIGH", np.interp(grid, g, hi), inside)])
    cols = [c for trio in cols for c in trio]
    with open(path, "w") as f:
        f.write(",".join(["time_ms"] + [c[0] for c in cols]) + "\n")
        for i, t in enumerate(grid):
            f.write(",".join(["%.4f" % t] + ["%.9g" % c[1][i] if c[2][i] else "" for c in cols]) + "\n")
    rated = []
    for col, _, model, scale, minus, start in chans:
        rated.append(("RATED     %-10s%-10s%s%-10s%s" % (col, model, number_field(scale), minus,
                                                         "START" if start else "")).rstrip())
    return rated


def write_case(case, workdir, data_dir=segments.DATA_DIR):
    """The specimen deck of `case` and its reference CSV in workdir:
    (deck file name, reference file name, RATED card lines)."""
    if case == "stemper":
        deck = specimens.stemper_deck(workdir, data_dir=data_dir)
    else:
        deck = specimens.kang_deck(workdir, case.split("_")[1], data_dir=data_dir)
    ref = case + "_reference.csv"
    rated = write_reference(case, os.path.join(workdir, ref), data_dir)
    return os.path.basename(deck), ref, rated


def calibration_deck(name, cases, workdir, params=PARAMS, evals=40, starts=8, values=None, seed=1,
                     data_dir=segments.DATA_DIR):
    """A calibration deck fitting `params` to `cases` (ISO 18571 objective,
    unit weights); with `values`, the deck scores that point only (FIT
    with 0 evaluations, VALUES cards) and writes its rated curves
    (CURVES). Returns the deck's path."""
    lines = ["TITLE     SPECIMEN CALIBRATION: %s" % " ".join(c.upper() for c in cases)]
    for case in cases:
        deck, ref, rated = write_case(case, workdir, data_dir)
        lines += ["CASE      %s" % deck, "DATA      %s" % ref] + rated
    lines.append("*         window (ms; volunteer cases only) CFC tolerance metric")
    lines.append("RATING    0.0       200.0     60        10.0      ISO18571")
    lines.append("FIT       NELDER    %-10d%-10d%-10d" % (0 if values is not None else evals, starts, seed))
    for p in params:
        lines.append(("PARAM     %-10s%-10s%-10s%-10s%s%s%s" % (p[0], p[1], p[2], p[3], number_field(p[4]),
                                                               number_field(p[5]), p[6])).rstrip())
    if values is not None:
        vals = list(values)
        for k in range(0, len(vals), 7):
            lines.append("VALUES    " + "".join(number_field(v) for v in vals[k:k + 7]))
        lines.append("CURVES    %s_curves.csv" % name)
    path = os.path.join(workdir, name + ".inp")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return path


def parse_listing(text):
    """dict(objective=, values={PARAM: value}, cases={deck: mean rating},
    channels={deck: {channel: ISO overall}}) of a calibration listing."""
    out = dict(objective=None, values={}, cases={}, channels={})
    deck = None
    for line in text.splitlines():
        m = re.match(r"OBJECTIVE J =\s+(\S+)", line)
        if m:
            out["objective"] = float(m.group(1))
        m = re.match(r"PARAM (\S+)\s+= (\S+)", line)
        if m:
            out["values"][m.group(1)] = float(m.group(2))
        m = re.match(r"CASE (\S+)(?: \(WEIGHT\s*\S+\))?: MEAN RATING\s+(\S+)", line)
        if m:
            deck = m.group(1)
            out["cases"][deck] = float(m.group(2))
            out["channels"][deck] = {}
        m = re.match(r"\s+(\S+)\s+ISO 18571\s+(\S+)", line)
        if m and deck:
            out["channels"][deck][m.group(1)] = float(m.group(2))
    return out


def run_calibration(deck, workdir, exe=None):
    """`hhneck --calibrate DECK` in workdir (shipped decks through -I
    ROOT); the listing's numbers (parse_listing) and its text."""
    exe = exe or segments.default_executable()
    r = subprocess.run([exe, "-I", segments.ROOT, "--calibrate", os.path.basename(deck)], cwd=workdir,
                       capture_output=True, text=True)
    with open(deck[:-4] + ".txt", "w") as f:
        f.write(r.stdout)
    if r.returncode != 0:
        raise RuntimeError("%s: hhneck exit %d: %s" % (deck, r.returncode, r.stderr.strip()[-600:]))
    out = parse_listing(r.stdout)
    out["listing"] = r.stdout
    return out


def leave_one_out(workdir, cases=tuple(CASES), params=PARAMS, evals=40, starts=8, exe=None):
    """For each case: the shipped model's score on it, the fit on the
    other cases (its objective, the values), and the fitted values' score
    on the case left out. Rows of dicts."""
    os.makedirs(workdir, exist_ok=True)
    rows = []
    for out in cases:
        rest = [c for c in cases if c != out]
        shipped = run_calibration(calibration_deck("shipped_%s" % out, [out], workdir, params, values=[]), workdir,
                                  exe)
        fit = run_calibration(calibration_deck("fit_without_%s" % out, rest, workdir, params, evals, starts),
                              workdir, exe)
        values = [fit["values"][p[0]] for p in params]
        pred = run_calibration(calibration_deck("predict_%s" % out, [out], workdir, params, values=values),
                               workdir, exe)
        rows.append(dict(case=out, fitted_on=rest, shipped=list(shipped["cases"].values())[0],
                         calibration=1.0 - fit["objective"], calibration_cases=fit["cases"],
                         prediction=list(pred["cases"].values())[0], values=dict(zip([p[0] for p in params], values)),
                         channels=list(pred["channels"].values())[0],
                         shipped_channels=list(shipped["channels"].values())[0]))
    return rows


def table(rows, params):
    """The leave-one-out table as Markdown."""
    lines = ["| left out | fitted on | shipped model (ISO 18571) | calibration (mean over the fitted cases) | "
             "prediction of the left-out case | fitted values |",
             "|---|---|---|---|---|---|"]
    for r in rows:
        lines.append("| %s | %s | %.3f | %.3f | %.3f | %s |" % (
            r["case"], ", ".join(r["fitted_on"]), r["shipped"], r["calibration"], r["prediction"],
            ", ".join("%s %.3g" % (p[0], r["values"][p[0]]) for p in params)))
    return "\n".join(lines) + "\n"


def main(argv=None):
    ap = argparse.ArgumentParser(prog="hhneck-calibrate-catalogue",
                                 description="Leave-one-out calibration of the passive parameters over the "
                                             "specimen cases (ISO/TS 18571).")
    ap.add_argument("workdir", help="folder for the decks, references and listings (created)")
    ap.add_argument("--quick", action="store_true",
                    help="the test form: Stemper and Kang front, one parameter (ROMK), 2 starts, few evaluations")
    ap.add_argument("--evals", type=int, default=40, help="evaluations per fit (default 40)")
    ap.add_argument("--starts", type=int, default=8, help="LHS starting points per fit (default 8)")
    ap.add_argument("--table", help="write the Markdown table to this file too")
    args = ap.parse_args(argv)
    if args.quick:
        cases, params, evals, starts = ("stemper", "kang_front"), QUICK_PARAMS, 2, 2
    else:
        cases, params, evals, starts = tuple(CASES), PARAMS, args.evals, args.starts
    rows = leave_one_out(os.path.abspath(args.workdir), cases, params, evals, starts)
    text = table(rows, params)
    sys.stdout.write(text)
    for p in params:
        sys.stdout.write("bounds of %s: %g to %g (%s)\n" % (p[0], p[4], p[5], p[7]))
    if args.table:
        with open(args.table, "w") as f:
            f.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
