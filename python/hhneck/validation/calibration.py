"""Calibration over the catalogue, and its leave-one-out test: for each
group of cases -- a specimen case (Stemper 2004 rear, Kang 2018 front and
side; the decks of hhneck.validation.specimens) or, with --segments, a segment source
(Panjabi 2001's 21 curves, Nightingale 2007's 3; the decks of
hhneck.validation.segments) -- fit the passive parameters to the other groups with
`hhneck --calibrate` (ISO/TS 18571 objective, RATING F5 ISO18571; each
group weighs 1, its curves equally) and score the group left out with the
fitted values: a prediction, since it took no part in its fit.

    write_case(case, workdir) -> (deck, reference CSV, RATED card lines)
    calibration_deck(name, cases, workdir, params, evals, starts, values=None, weights=None) -> path
    run_calibration(deck, workdir, exe=None) -> dict(values=, objective=, cases=)
    leave_one_out(workdir, groups=None, params=PARAMS, evals=..., starts=..., jobs=1) -> rows
    volunteer_scores(params, values, workdir) -> (NBDL case means, largest real part at rest)

Segment cases (write_segment_case): the segment deck of hhneck.validation.segments
with protocol "sweep" (the whole moment-rotation curve on one rising
moment ramp), its reference the data on the catalogue's 0.01 N m grid,
each row at the time its moment is applied, rated row by row (RATED F6
SAMPLES) as the catalogue rates rotation against moment.

Reference CSVs: each case's rated channels, their reference curve (the
corridor's midline or the specimens' mean, hhneck.validation.specimen_data) and
bounds, on the common grid k 0.1 ms (each channel linearly interpolated
from its own 0.1 ms grid onto the grid points its curve covers, the
window hhneck.validation.specimens.rated_reference rates; Kang: 0 to 1.2 x the time
of the reference's largest magnitude in 0-99.9 ms), empty cells elsewhere. The model channel of each column is a
RATED card: the sign changes, "from the start" and the CFC class of
hhneck.validation.specimens.
The rated channels and their model channels are those of the catalogue
(hhneck.validation.specimens.CHANNELS), load cells included; where the catalogue
rates a head angle the result file has no channel of (hhneck.validation.specimens.
ANGLES: the Kang head rotations, integrals of the angular velocity), the
RATED card rates the file's nearest (its Bryant angle).

Parameters (PARAMS): scale factors of the passive elements, within bounds
from reference/parameters.md where sourced (VAXIAL: the disc damping range
of Izambert et al. 2003, S13), assumed otherwise (the spans the NBDL
calibration deck uses; the ligaments' stiffness a factor 2 either way).
The shipped model deck is not changed: the fitted values are reported.

No fit here moves a passive parameter to the volunteers: the shipped
column is fitted to the segment tests alone (hhneck.validation.fit_column), the
volunteers fit the controller alone (input/calibrate_controller.inp).

Usage: python3 -m hhneck.validation.calibration WORKDIR [--quick] [--segments] [--evals N] [--starts N] [--jobs N]
       [--table FILE]
"""
import argparse
import os
import re
import shutil
import subprocess
import sys

import numpy as np

from . import segments, specimens
from ..decks import card, field, is_card, number_field, set_field, write_deck
from ..paths import project_path, project_root

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

# case: (data file stem, Kang window); the rated channels are hhneck.validation.specimens.CHANNELS,
# each a reference column C01, C02, ... of the case's CSV
CASES = {"stemper": ("stemper2004_1p8ms", False), "kang_front": ("kang2018_front", True),
         "kang_side": ("kang2018_side", True)}
#: the segment sources of the catalogue (hhneck.validation.segments): source -> its peak moment [N m]
SEGMENT_SOURCES = {"panjabi": 1.0, "nightingale": 3.5}


def segment_cases(data_dir=segments.DATA_DIR):
    """{source: [case name, ...]} of the segment tests: one case per curve of
    the catalogue, named source_segment_motion (e.g. panjabi_C4_C5_lateral_bending)."""
    out = {"panjabi": ["panjabi_%s_%s" % k for k in sorted(segments.load_panjabi(data_dir))],
           "nightingale": ["nightingale_%s_flexion_extension" % seg
                           for seg in sorted(segments.load_nightingale(data_dir))]}
    return out


def case_groups(data_dir=segments.DATA_DIR):
    """{group: [case, ...]}: each segment source (its curves) and each specimen case
    alone, the units the leave-one-out leaves out."""
    groups = dict(segment_cases(data_dir))
    groups.update({c: [c] for c in CASES})
    return groups


def _segment_key(case):
    """(source, segment, motion) of a segment case's name."""
    source, rest = case.split("_", 1)
    seg = "_".join(rest.split("_")[:2])
    return source, seg, rest[len(seg) + 1:]


def write_segment_case(case, workdir, data_dir=segments.DATA_DIR, model=segments.MODEL_DECK):
    """The deck of segment case `case` (protocol "sweep" of hhneck.validation.segments)
    and its reference CSV in workdir: (deck, reference, RATED card lines).
    The reference: the data's mean rotation [deg] on the catalogue's 0.01 N m
    grid from -M to +M (Nightingale with its lower and upper bounds), each
    row at the time the sweep applies its moment; the model channel the
    relative rotation of the top body to the fixed one (HT1_RX/RY/RZ: the
    HEADNECK card of the segment deck names them), in the data's sign, less
    its start value, its rows the rating's samples (SAMPLES: rotation as a
    function of moment, as the catalogue rates it). model: the model deck
    the segment's cards are taken from."""
    source, seg, motion = _segment_key(case)
    peak = SEGMENT_SOURCES[source]
    coord, sign, _ = segments.MOTIONS[motion]
    grid = np.round(np.arange(-peak, peak + 1e-9, 0.01), 10)
    cols = []
    if source == "panjabi":
        m, r = segments.load_panjabi(data_dir)[(seg, motion)]
        cols.append(("C01", segments.reference_on(grid, m, r)))
    else:
        stats = segments.load_nightingale(data_dir)[seg]
        lo, hi = (np.interp(grid, *stats[k]) for k in ("lower", "upper"))
        cols += [("C01", np.interp(grid, *stats["mean"])), ("C01_LOW", np.minimum(lo, hi)),
                 ("C01_HIGH", np.maximum(lo, hi))]
    deck = os.path.join(workdir, case + ".inp")
    segments.write_deck(deck, seg, motion, peak, model=model, protocol="sweep",
                        title="CALIBRATION SEGMENT %s %s %s" % (source.upper(), seg, motion.upper()))
    ref = case + "_reference.csv"
    times = 1000.0 * segments.sweep_time(grid, peak)
    with open(os.path.join(workdir, ref), "w") as f:
        f.write(",".join(["time_ms"] + [c[0] for c in cols]) + "\n")
        for i, t in enumerate(times):
            f.write(",".join(["%.6f" % t] + ["%.9g" % c[1][i] for c in cols]) + "\n")
    rated = [card("RATED", "C01", "HT1_" + coord, number_field(sign), "", "START", "SAMPLES")]
    return os.path.basename(deck), ref, rated


def case_channels(case):
    """[(column, data channel, model channel, scale, subtracted, from the start, CFC class)] of `case`."""
    return [("C%02d" % (k + 1), name, run, scale, "", start, cls)
            for k, (name, run, scale, start, cls) in enumerate(specimens.CHANNELS[case])]


def write_reference(case, path, data_dir=segments.DATA_DIR):
    """The reference CSV of `case` (module docstring); its RATED card lines."""
    chans = case_channels(case)
    curves = []
    for col, ch, *_ in chans:
        curves.append((col, *specimens.rated_reference(case, ch, data_dir)))
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
    for col, _, model, scale, minus, start, cls in chans:
        rated.append(card("RATED", col, model, number_field(scale), minus, "START" if start else "", "",
                          "%s" % (cls or "")))
    return rated


def write_case(case, workdir, data_dir=segments.DATA_DIR, model=segments.MODEL_DECK):
    """The deck of `case` (a specimen case, or a segment case of
    segment_cases) and its reference CSV in workdir: (deck file name,
    reference file name, RATED card lines)."""
    if case.split("_", 1)[0] in SEGMENT_SOURCES:
        return write_segment_case(case, workdir, data_dir, model)
    if case == "stemper":
        deck = specimens.stemper_deck(workdir, data_dir=data_dir)
    else:
        deck = specimens.kang_deck(workdir, case.split("_")[1], data_dir=data_dir)
    ref = case + "_reference.csv"
    rated = write_reference(case, os.path.join(workdir, ref), data_dir)
    return os.path.basename(deck), ref, rated


def case_cards(case, workdir, weight=1.0, data_dir=segments.DATA_DIR, model=segments.MODEL_DECK):
    """The CASE (with its weight unless 1), DATA and RATED card images of
    `case`, its deck and reference written to workdir (write_case)."""
    deck, ref, rated = write_case(case, workdir, data_dir, model)
    return [card("CASE", deck, None, None, None, None, None, number_field(weight) if weight != 1.0 else None),
            card("DATA", ref)] + rated


def calibration_deck(name, cases, workdir, params=PARAMS, evals=40, starts=8, values=None, seed=1,
                     data_dir=segments.DATA_DIR, weights=None, model=None):
    """A calibration deck fitting `params` to `cases` (ISO 18571 objective;
    weights: {case: weight}, default 1 each); with `values`, the deck scores that point only (FIT
    with 0 evaluations, VALUES cards) and writes its rated curves
    (CURVES). model: another model deck than the shipped one, copied to
    workdir/input/ (where the specimen decks' INCLUDE finds it first) and
    the segment decks' source. Returns the deck's path."""
    weights = weights or {}
    if model is not None:
        copy = os.path.join(workdir, "input", os.path.basename(segments.MODEL_DECK))
        os.makedirs(os.path.dirname(copy), exist_ok=True)
        if os.path.abspath(model) != os.path.abspath(copy):
            shutil.copyfile(model, copy)
        model = copy
    lines = [card("TITLE", ("CATALOGUE CALIBRATION: %s" % " ".join(c.upper() for c in cases))[:70], strip=False)]
    for case in cases:
        lines += case_cards(case, workdir, weights.get(case, 1.0), data_dir, model or segments.MODEL_DECK)
    lines.append("*         window (ms; volunteer cases only) CFC tolerance metric")
    lines.append("RATING    0.0       200.0     60        10.0      ISO18571")
    lines.append(card("FIT", "NELDER", *["%d" % n for n in (0 if values is not None else evals, starts, seed)],
                      strip=False))
    lines += param_cards(params)
    if values is not None:
        lines += values_cards(values)
        lines.append(card("CURVES", name + "_curves.csv"))
    path = os.path.join(workdir, name + ".inp")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return path


def parse_listing(text):
    """dict(objective=, values={PARAM: value}, cases={deck: mean rating},
    channels={deck: {channel: ISO overall}}, rest=the largest real part at
    rest [1/s] or None) of a calibration listing (a case not rated is absent
    from cases)."""
    out = dict(objective=None, values={}, cases={}, channels={}, rest=None)
    deck = None
    for line in text.splitlines():
        m = re.match(r"OBJECTIVE J =\s+(\S+)", line)
        if m:
            out["objective"] = float(m.group(1))
        m = re.match(r"LARGEST REAL PART AT REST\s+([-+0-9.Ee]+) 1/S", line)
        if m:
            out["rest"] = float(m.group(1))
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
    r = subprocess.run([exe, "-I", project_root(), "--calibrate", os.path.basename(deck)], cwd=workdir,
                       capture_output=True, text=True)
    with open(deck[:-4] + ".txt", "w") as f:
        f.write(r.stdout)
    if r.returncode != 0:
        raise RuntimeError("%s: hhneck exit %d: %s" % (deck, r.returncode, r.stderr.strip()[-600:]))
    out = parse_listing(r.stdout)
    out["listing"] = r.stdout
    return out


def group_weights(groups):
    """{case: weight}: each group (a segment source's curves, a specimen
    case) weighs 1 in the objective, its cases equally."""
    return {c: 1.0 / len(cases) for cases in groups.values() for c in cases}


#: the NBDL calibration deck whose cases the volunteer scores rate (CORA-style, its RATING card)
NBDL_DECK = project_path("input", "calibrate_nbdl.inp")


def param_card(lines, p, model):
    """The index in the model deck's `lines` of the one card a FIELDn
    parameter `p` names (card p[2] with F1 p[3], as a sweep binds it)."""
    hits = [k for k, l in enumerate(lines) if is_card(l, p[2], p[3])]
    if len(hits) != 1:
        raise ValueError("%s: %d %s cards of %s" % (model, len(hits), p[2], p[3]))
    return hits[0]


def param_cards(params):
    """PARAM card images of PARAMS-style tuples."""
    return [card("PARAM", p[0], p[1], p[2], p[3], number_field(p[4]), number_field(p[5]), p[6]) for p in params]


def values_cards(values):
    """VALUES card images of a list of values, seven to a card."""
    vals = list(values)
    return [card("VALUES", *[number_field(v) for v in vals[k:k + 7]], strip=False) for k in range(0, len(vals), 7)]


def model_deck_with(params, values, path, model=segments.MODEL_DECK):
    """Write the model deck with `params` at `values` to `path`: a FIELDn
    parameter (PARAM name, FIELDn, card, F1 item) sets field n of the one
    card of the model deck with that F1 (as a sweep binds it), a FAMILY
    parameter appends a SCALE card of its own (a factor on the family's
    item)."""
    lines = open(model).read().splitlines()
    for p, v in zip(params, values):
        if p[1].startswith("FIELD"):
            k = param_card(lines, p, model)
            lines[k] = set_field(lines[k], int(p[1][5:]), number_field(v).strip())
        else:
            lines.append(card("SCALE", p[0], p[2], p[3], number_field(v)))
    write_deck(path, lines)


def volunteer_scores(params, values, workdir, exe=None, nbdl=NBDL_DECK, model=segments.MODEL_DECK):
    """The NBDL cases of the NBDL calibration deck (CORA-style, its own
    study cards) with the model deck's `params` at `values` and every other
    parameter as shipped: {case deck: mean rating}. The model deck with the
    values goes to workdir/input/ (an INCLUDE is found next to the
    calibration deck first) and the calibration deck, evaluate-only (FIT
    with 0 evaluations, no VALUES: the decks' values), to workdir. Returns
    (cases, rest): no cases when the set does not stand at rest (rest, the
    largest real part at rest [1/s], above the calibration's -1 1/s)."""
    os.makedirs(os.path.join(workdir, "input"), exist_ok=True)
    model_deck_with(params, values, os.path.join(workdir, "input", os.path.basename(segments.MODEL_DECK)), model)
    lines = []
    for l in open(nbdl).read().splitlines():
        if is_card(l, "VALUES") or is_card(l, "CURVES"):
            continue
        lines.append(set_field(l, 2, "0") if is_card(l, "FIT") else l)
    deck = os.path.join(workdir, "nbdl_scores.inp")
    write_deck(deck, lines)
    out = run_calibration(deck, workdir, exe)
    return out["cases"], out["rest"]


def by_case(result, cases):
    """{case: mean rating} of a calibration listing's numbers (parse_listing)
    whose deck holds `cases` in this order (its CASE cards' order)."""
    scores = list(result["cases"].values())
    if len(scores) != len(cases):
        raise RuntimeError("the listing rates %d cases, the deck has %d" % (len(scores), len(cases)))
    return dict(zip(cases, scores))


def _fold(args):
    out, groups, workdir, params, evals, starts, exe = args
    workdir = os.path.join(workdir, out)     # each fold its own folder: folds run at once
    os.makedirs(workdir, exist_ok=True)
    rest = {g: c for g, c in groups.items() if g != out}
    rest_cases = [c for cs in rest.values() for c in cs]
    w = group_weights(rest)
    shipped = run_calibration(calibration_deck("shipped_%s" % out, groups[out], workdir, params, values=[]),
                              workdir, exe)
    fit = run_calibration(calibration_deck("fit_without_%s" % out, rest_cases, workdir, params, evals, starts,
                                           weights=w), workdir, exe)
    values = [fit["values"][p[0]] for p in params]
    pred = run_calibration(calibration_deck("predict_%s" % out, groups[out], workdir, params, values=values),
                           workdir, exe)
    fitted = by_case(fit, rest_cases)
    nbdl, rest_growth = volunteer_scores(params, values, os.path.join(workdir, "volunteers"), exe)
    return dict(case=out, fitted_on=list(rest), shipped=float(np.mean(list(by_case(shipped, groups[out]).values()))),
                calibration=1.0 - fit["objective"],
                calibration_groups={g: float(np.mean([fitted[k] for k in c])) for g, c in rest.items()},
                prediction=float(np.mean(list(by_case(pred, groups[out]).values()))),
                values=dict(zip([p[0] for p in params], values)), volunteers=nbdl, rest=rest_growth,
                channels=pred["channels"], shipped_channels=shipped["channels"])


def leave_one_out(workdir, groups=None, params=PARAMS, evals=40, starts=8, exe=None, jobs=1):
    """For each group of cases (case_groups: a segment source's curves, or
    one specimen case): the shipped model's score on it, the fit of
    `params` on the other groups (each group weighing 1: group_weights),
    its objective and values, and the fitted values' score on the group
    left out (a prediction), and on the NBDL volunteers (volunteer_scores:
    a prediction too, the muscles as shipped). Folds run `jobs` at a time, each in its own
    folder WORKDIR/GROUP. Rows of dicts.
    groups: {group: [case, ...]} (default: every specimen case alone)."""
    from concurrent.futures import ThreadPoolExecutor
    groups = groups or {c: [c] for c in CASES}
    os.makedirs(workdir, exist_ok=True)
    args = [(g, groups, workdir, params, evals, starts, exe) for g in groups]
    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        return list(pool.map(_fold, args))


def table(rows, params):
    """The leave-one-out table as Markdown."""
    lines = ["| left out | fitted on | shipped model (ISO 18571) | calibration (mean over the fitted cases) | "
             "prediction of the left-out case | NBDL 15 g / 12 g at the fitted values (CORA-style) | fitted values |",
             "|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append("| %s | %s | %.3f | %.3f | %.3f | %s | %s |" % (
            r["case"], ", ".join(r["fitted_on"]), r["shipped"], r["calibration"], r["prediction"],
            volunteer_text(r["volunteers"], r["rest"]),
            ", ".join("%s %.3g" % (p[0], r["values"][p[0]]) for p in params)))
    return "\n".join(lines) + "\n"


#: the NBDL 12 g calibration deck (the shipped fit's) and its muscles' parameters
NBDL12_DECK = project_path("input", "calibrate_nbdl12g.inp")


def deck_params(path):
    """The PARAM cards of a calibration deck as PARAMS-style tuples (name,
    kind, target, item, low, high, spacing) and its VALUES in their order."""
    params, values = [], []
    for l in open(path).read().splitlines():
        if is_card(l, "PARAM"):
            params.append((field(l, 1), field(l, 2), field(l, 3), field(l, 4), float(field(l, 5)),
                           float(field(l, 6)), field(l, 7)))
        elif is_card(l, "VALUES"):
            values += [float(field(l, k)) for k in range(1, 8) if field(l, k)]
    return params, values


def values_listing(model=segments.MODEL_DECK, deck=NBDL12_DECK):
    """The model deck's values of a calibration deck's parameters as a
    calibration listing gives them ("PARAM NAME = value" lines, what the
    deck generator's --fit reads): the shipped fit's values by default."""
    lines = open(model).read().splitlines()
    out = []
    for p in deck_params(deck)[0]:
        if not p[1].startswith("FIELD"):
            raise ValueError("%s: parameter %s is not a field of a card" % (deck, p[0]))
        out.append("PARAM %s = %s" % (p[0], field(lines[param_card(lines, p, model)], int(p[1][5:]))))
    return "\n".join(out) + "\n"


def volunteer_text(cases, rest):
    """The NBDL cell of a table: the two case means, or why none."""
    if not cases:
        return "not run: unstable at rest (%+.3g 1/s)" % rest if rest is not None else "not rated"
    return " / ".join("%.3f" % cases[k] for k in sorted(cases, key=lambda d: "15g" not in d))


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python3 -m hhneck.validation.calibration",
                                 description="Leave-one-out calibration of the passive parameters over the "
                                             "specimen cases, and with --segments the segment sources "
                                             "(ISO/TS 18571).")
    ap.add_argument("workdir", help="folder for the decks, references and listings (created)")
    ap.add_argument("--quick", action="store_true",
                    help="the test form: Stemper and Kang front, one parameter (ROMK), 2 starts, few evaluations")
    ap.add_argument("--evals", type=int, default=40, help="evaluations per fit (default 40)")
    ap.add_argument("--starts", type=int, default=8, help="LHS starting points per fit (default 8)")
    ap.add_argument("--table", help="write the Markdown table to this file too")
    ap.add_argument("--segments", action="store_true",
                    help="the whole catalogue: the segment sources (Panjabi, Nightingale) as groups beside the "
                         "specimen cases")
    ap.add_argument("--jobs", type=int, default=1, help="folds run at a time (default 1)")
    args = ap.parse_args(argv)
    if args.quick:
        groups, params, evals, starts = {c: [c] for c in ("stemper", "kang_front")}, QUICK_PARAMS, 2, 2
    elif args.segments:
        groups, params, evals, starts = case_groups(), PARAMS, args.evals, args.starts
    else:
        groups, params, evals, starts = {c: [c] for c in CASES}, PARAMS, args.evals, args.starts
    rows = leave_one_out(os.path.abspath(args.workdir), groups, params, evals, starts, jobs=args.jobs)
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
