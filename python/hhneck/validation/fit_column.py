"""The passive column fitted to the segment tests alone (Panjabi et al.
2001, Nightingale et al. 2007; shared/data/pmhs_neck): constraint 1 of the
model (docs/validation.md, "Calibration"). No volunteer or specimen-sled
run enters the fit.

What is fitted (PARAMS, each within its bounds; reference/parameters.md
names each bound's source or says it is assumed):
 - disc.bend_fraction, disc.torsion_fraction: the discs' own linear bending
   (Ix, Iy) and torsion (J) as fractions of S1's segment stiffness (the
   HYOID bushings are the whole segment's rotational stiffness, so the
   disc's share lies in 0..1; the bending's lower bound 0.03 keeps every
   disc's bending stiffness within the program's plausibility check, two
   orders of magnitude of 20 N m/rad: 0.03 x 7.8 N m/rad above 0.2);
 - ROMK, ROMT0: the range-of-motion resistance's stiffness and e-fold
   excess (the stops the Nightingale moments reach);
 - the neutral-zone springs (NZSPRING) of every joint, refitted by
   hhneck.validation.fit_joints at every candidate on the deck with the candidate's
   other elements (the springs carry what the data ask beyond them);
 - with --upper-cervical (an experiment, not the shipped flow:
   docs/validation.md, "The upper cervical joints"), the upper-cervical
   factors of hhneck.validation.upper_cervical too, fitted on each
   candidate's deck before its springs (at the bound 0.001 where no factor
   reaches the data), written to --upper.

Not fitted (the table's rows as they are, sourced or assumed): the
ligaments (S2), the discs' axial and shear stiffness (AXIAL, SHEAR) and
their tension ratio (ETENSION), which pure moments do not load; the
damping (VBEND, VAXIAL, LIMC1), which quasi-static tests cannot inform;
SIGMA, a muscle property.

Objective: J = 1 - (R_P + R_N) / 2, R_P and R_N the mean ISO/TS 18571
ratings of the Panjabi (21 curves) and Nightingale (3 curves) segment
cases as the catalogue rates them (hhneck.validation.segments), solved as statics
(the ramps' zero-rate limit) for the springs' fit and the rating alike.
Optimizer: a deterministic coordinate search in the logarithm of each
parameter from START (not the table's values, so that a rerun reproduces
the shipped point): each parameter stepped up and down by
the factor STEP in turn, the best move taken, the factor's root taken when
no move lowers J, until the factor is below STEP_MIN or MAX_EVAL
evaluations. A candidate outside its bounds is clipped to them.

Output: reference/column_fit.csv (name, value, lower, upper, J) and
reference/nz_springs.csv of the best point; dev/fit_model.sh records both
into reference/model_parameters.csv (stages segments and nz_springs) and
writes the model deck from it.

Command: python3 -m hhneck.validation.fit_column [--exe HHNECK] [--work DIR]
[--jobs N] [--max-eval N] [--csv PATH] [--springs PATH] [--evaluate]
[--upper-cervical [--upper PATH]]
(--evaluate: J at the table's values, nothing written).
"""
import argparse
import csv
import math
import os
import sys
import tempfile
import time

import numpy as np

from . import fit_joints, model_deck, segments, upper_cervical
from ..paths import project_path

CSV_PATH = project_path("reference", "column_fit.csv")
#: (row, lower, upper): the fitted rows and their bounds (reference/parameters.md)
PARAMS = (("disc.bend_fraction", 0.03, 1.0), ("disc.torsion_fraction", 0.01, 1.0),
          ("ROMK", 0.05, 50.0), ("ROMT0", 0.25, 2.0))
#: the search's starting point: the discs' bending of the segmental-column
#: experiment (0.2), their torsion as kept before (0.6), the stops as assumed
#: (factor 1)
START = {"disc.bend_fraction": 0.2, "disc.torsion_fraction": 0.6, "ROMK": 1.0, "ROMT0": 1.0}
STEP = 2.0          # the first factor of the coordinate search
STEP_MIN = 1.1      # the search stops when the factor falls below it
MAX_EVAL = 60


def clip(name, value):
    """`value` within the bounds of PARAMS' row `name`."""
    lo, hi = [(lo, hi) for n, lo, hi in PARAMS if n == name][0]
    return min(max(value, lo), hi)


def objective(results):
    """(J, R_P, R_N) of the segment catalogue's `results` (segments.catalogue)."""
    means = [float(np.mean([r["iso"]["overall"] for r in results if r["source"].startswith(src)]))
             for src in ("Panjabi", "Nightingale")]
    return 1.0 - 0.5 * sum(means), means[0], means[1]


def evaluate(x, exe, work, jobs=None, rows=None, upper=False):
    """Rate the column at `x` ({row: value} over the table's rows): the
    deck with x (with `upper`, its upper-cervical factors fitted on it,
    hhneck.validation.upper_cervical), the springs refitted on it
    (hhneck.validation.fit_joints, statics), the segment cases rated with
    them. Returns dict J, panjabi, nightingale, springs and upper (the CSVs
    written in `work`; upper None without `upper`), deck, results."""
    os.makedirs(work, exist_ok=True)
    p = model_deck.table_values(rows or model_deck.read_table())
    p.update(x)
    deck = os.path.join(work, "model.inp")
    kw = {}

    def write(**more):
        with open(deck, "w") as f:
            f.write("\n".join(model_deck.deck_lines(p, **dict(kw, **more))) + "\n")
    write()                  # the springs' runs drop the NZSPRING cards: the table's do not matter
    ucsv = None
    if upper:
        found = upper_cervical.fit_factors(exe, deck, workdir=os.path.join(work, "upper"), at_bound=True)
        ucsv = os.path.join(work, "upper_cervical.csv")
        upper_cervical.write_csv(ucsv, found)
        kw["upper_cervical_csv"] = ucsv
        write()
    nz_rows, _ = fit_joints.fit_joints(exe, deck, workdir=os.path.join(work, "others"), jobs=jobs, statics=True)
    springs = os.path.join(work, "nz_springs.csv")
    fit_joints.write_csv(springs, nz_rows)
    write(nz_springs=springs)
    res = segments.catalogue(exe, workdir=os.path.join(work, "rated"), jobs=jobs, solution="statics", model=deck)
    j, rp, rn = objective(res)
    return dict(J=j, panjabi=rp, nightingale=rn, springs=springs, upper=ucsv, deck=deck, results=res)


def search(start, exe, work, jobs=None, max_eval=MAX_EVAL, log=lambda s: print(s, flush=True), upper=False):
    """The coordinate search of the module docstring from `start` ({row:
    value}); returns (best x, its evaluate dict, number of evaluations)."""
    n = [0]

    def ev(x):
        n[0] += 1
        r = evaluate(x, exe, os.path.join(work, "e%03d" % n[0]), jobs, upper=upper)
        log("eval %3d  J %.5f  (Panjabi %.3f, Nightingale %.3f)  %s" % (
            n[0], r["J"], r["panjabi"], r["nightingale"], "  ".join("%s %.4g" % kv for kv in x.items())))
        return r

    x = {k: clip(k, v) for k, v in start.items()}
    best = ev(x)
    step = STEP
    while step >= STEP_MIN and n[0] < max_eval:
        moved = False
        for name, _, _ in PARAMS:
            for f in (step, 1.0 / step):
                if n[0] >= max_eval:
                    break
                y = dict(x)
                y[name] = clip(name, x[name] * f)
                if y[name] == x[name]:
                    continue
                r = ev(y)
                if r["J"] < best["J"] - 1e-6:
                    x, best, moved = y, r, True
                    break
        if not moved:
            step = math.sqrt(step)
    return x, best, n[0]


def write_csv(path, x, best):
    """reference/column_fit.csv: a comment line, then name, value, lower, upper, J."""
    with open(path, "w", newline="") as f:
        f.write("# written by python3 -m hhneck.validation.fit_column: the passive column's factors fitted to the segment "
                "tests (Panjabi 2001, Nightingale 2007); J = 1 - mean of the two sources' mean ISO/TS 18571 "
                "(Panjabi %.4f, Nightingale %.4f)\n" % (best["panjabi"], best["nightingale"]))
        w = csv.writer(f, lineterminator="\n")
        w.writerow(("name", "value", "lower", "upper", "J"))
        for name, lo, hi in PARAMS:
            w.writerow((name, "%.6g" % x[name], lo, hi, "%.6f" % best["J"]))


def main(argv=None):
    """Fit the column (or, with --evaluate, rate the table's) and write the CSVs."""
    ap = argparse.ArgumentParser(prog="python3 -m hhneck.validation.fit_column", description=__doc__.split("\n\n")[0])
    ap.add_argument("--exe", help="the hhneck executable (default $HHNECK, else fpm's release build)")
    ap.add_argument("--work", help="working directory (default a temporary folder)")
    ap.add_argument("--jobs", type=int, help="runs at a time (default: the cores)")
    ap.add_argument("--max-eval", type=int, default=MAX_EVAL, help="evaluations at most (default %d)" % MAX_EVAL)
    ap.add_argument("--csv", default=CSV_PATH, help="the factors' CSV to write (default reference/column_fit.csv)")
    ap.add_argument("--springs", default=fit_joints.CSV_PATH,
                    help="the springs' CSV to write (default reference/nz_springs.csv)")
    ap.add_argument("--evaluate", action="store_true", help="rate the table's values only; nothing written")
    ap.add_argument("--upper-cervical", action="store_true",
                    help="fit the upper-cervical factors at every candidate too (an experiment)")
    ap.add_argument("--upper", default=upper_cervical.CSV_PATH,
                    help="with --upper-cervical, the factors' CSV to write (default reference/upper_cervical.csv)")
    a = ap.parse_args(argv)
    t0 = time.perf_counter()
    exe = a.exe or segments.default_executable()
    work = a.work or tempfile.mkdtemp(prefix="hhneck-fit-column-")
    if a.evaluate:
        p = model_deck.table_values(model_deck.read_table())
        r = evaluate({name: p[name] for name, _, _ in PARAMS}, exe, work, a.jobs, upper=a.upper_cervical)
        print("J %.5f (Panjabi %.4f, Nightingale %.4f) at the table's values (%.0f s)"
              % (r["J"], r["panjabi"], r["nightingale"], time.perf_counter() - t0))
        return 0
    x, best, n = search(START, exe, work, a.jobs, a.max_eval, upper=a.upper_cervical)
    write_csv(a.csv, x, best)
    for got, path in ((best["springs"], a.springs), (best["upper"], a.upper)):
        if got:
            with open(got) as f, open(path, "w") as g:
                g.write(f.read())
    print("best J %.5f (Panjabi %.4f, Nightingale %.4f) after %d evaluations, %.0f s; wrote %s, %s%s"
          % (best["J"], best["panjabi"], best["nightingale"], n, time.perf_counter() - t0, a.csv, a.springs,
             " and " + a.upper if best["upper"] else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
