#!/usr/bin/env python3
"""Can the muscles' stretch reflexes (SPINDLE cards) carry the NBDL
volunteers on the softer, segment-matching column that does not stand on
its discs, and what does that column give the catalogue?

    python3 studies/spindle_segmental.py [--fit LABEL=LISTING ...]

The segmental column is docs/validation-history.md's "Segmental muscles" deck at
its starting point: python3 -m hhneck.validation.model_deck --segmental yes --sub-bend
0.2 (a multifidus-like extensor and an intertransversarius per subaxial
level and side, the subaxial discs' bending at 0.2), its neutral-zone
springs refitted by python3 -m hhneck.validation.fit_joints (written into the copy's parameter
table), the shipped calibration's starting point otherwise (the steps 1-2
of `SEGMENTAL=1 dev/fit_model.sh`), built in a scratch copy of the repository (shared/ beside it as a link). On it,
without --fit, two calibrations run side by side (release build):
input/calibrate_nbdl12g_spindle.inp (the fifteen parameters and the loops'
gains and delays, standing judged by the run at rest
input/rest_spindle.inp within 2 deg) and the same with the disc and stop
factors held at the column's (the muscles and the loops alone, so that the
segments keep what the springs' fit gave them). Each set is scored:
- NBDL (studies/feedback_nbdl.py's score: CORA-style and ISO/TS 18571 of
  hhneck-compare-nbdl at 12 g, calibration, and 15 g, prediction; the 8 g
  head peaks in SDs, prediction; the braking arcs; range warnings), its
  values by CHANGE cards on the decks with the SPINDLE cards of
  input/nbdl12g_spindle.inp;
- at rest: a 6 s run of studies/rest_motion.py's deck with the loops, the
  largest joint excursion and the head's rotation;
- the catalogue (hhneck-catalogue in the copy, its model deck regenerated
  with the set's disc and stop factors): every source's mean ISO/TS 18571
  and Nightingale's levels inside +-1 SD.
The column's starting point is scored with the loops off and at the
VALUES point's gains.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path[:0] = [os.path.join(ROOT, "python"), HERE]
from hhneck import run  # noqa: E402
from hhneck.ratings import s3  # noqa: E402
from feedback_nbdl import fit_arguments, reduced_deck, run_calibrations, score  # noqa: E402
from predict_nbdl8g import ROWS, bindings, fitted_values, volunteer_peaks  # noqa: E402
import rest_motion  # noqa: E402

CALIBRATION = "input/calibrate_nbdl12g_spindle.inp"
CASE = "input/nbdl12g_spindle.inp"
PASSIVE = ("VBEND", "VAXIAL", "ETENSION", "SHEAR", "AXIAL", "ROMK", "ROMT0", "LIMC1")
LOOPS = ("KPSE", "KPSF", "TAUSE", "TAUSF")
SEGMENTAL = ["--upper-cervical", "none", "--suboccipital", "no", "--segmental", "yes", "--sub-bend", "0.2"]


def spindle_cards():
    """The SPINDLE cards of the 12 g stretch-loop deck (as rest_motion reads them)."""
    return rest_motion.SPINDLES.splitlines()


def deck_values(path):
    """[(name, value)] of a calibration deck's PARAM cards at its VALUES point."""
    lines = open(path).read().splitlines()
    names = [ln[10:20].strip() for ln in lines if ln.startswith("PARAM")]
    values = [float(v) for ln in lines if ln.startswith("VALUES") for v in ln[10:].split()]
    return list(zip(names, values))


def scratch_copy(tmp):
    """A copy of the repository's tracked files in tmp/p, shared/ linked beside it."""
    copy = os.path.join(tmp, "p")
    files = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True, check=True).stdout.split()
    for f in files:
        os.makedirs(os.path.join(copy, os.path.dirname(f)), exist_ok=True)
        shutil.copy2(os.path.join(ROOT, f), os.path.join(copy, f))
    os.symlink(os.path.join(os.path.dirname(ROOT), "shared"), os.path.join(tmp, "shared"))
    return copy


def generate(copy, env, fit):
    """The copy's model deck from the generator and the copy's parameter table: the segmental column
    at the values of `fit` (a listing)."""
    subprocess.run([sys.executable, "-m", "hhneck.validation.model_deck", "--fit", fit, "--output",
                    "input/head_neck_54dof.inp"] + SEGMENTAL, cwd=copy, env=env, check=True)


def segmental_column(copy, env, tmp):
    """Steps 1-2 of SEGMENTAL=1 dev/fit_model.sh in the copy: the springs fitted on the column at the
    calibration's starting point; returns that point as a listing of PARAM lines."""
    start = os.path.join(tmp, "start.txt")
    values = deck_values(os.path.join(copy, "input/calibrate_nbdl12g.inp"))
    open(start, "w").write("".join("PARAM %s = %.9g\n" % nv for nv in values))
    generate(copy, env, start)
    subprocess.run([sys.executable, "-c", "from hhneck.validation.fit_joints import main; main([])"], cwd=copy, env=env,
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    subprocess.run([sys.executable, "-m", "hhneck.validation.model_deck", "--record", "nz_springs", "reference/nz_springs.csv"],
                   cwd=copy, env=env, check=True, stderr=subprocess.DEVNULL)
    generate(copy, env, start)
    return start


def column_copy(prefix):
    """(tmp, copy, env, start): a scratch folder, the repository's copy in it with the segmental
    column at the calibration's starting point (that point's listing `start`), the environment
    that runs the copy's tools; the working directory the copy's."""
    tmp = tempfile.mkdtemp(prefix=prefix)
    copy = scratch_copy(tmp)
    env = dict(os.environ, PYTHONPATH=os.path.join(copy, "python"), HHNECK=run.find_executable())
    start = segmental_column(copy, env, tmp)
    os.chdir(copy)
    return tmp, copy, env, start


def merged(start, point, tmp):
    """A listing of the starting point's PARAM lines with the (name, value) pairs `point` in their
    place (a fit of some of the parameters keeps the others at the column's)."""
    values = dict(fitted_values(start))
    values.update(point)
    path = os.path.join(tmp, "merged.txt")
    open(path, "w").write("".join("PARAM %s = %.9g\n" % nv for nv in values.items()))
    return path


def rest_row(values, cards, bind, tmp):
    """(largest excursion [rad], where, head rotation [deg]) of 6 s at rest with the loops."""
    changes = [run.change_card("P%d" % k, "FIELD%d" % bind[n][0], bind[n][1], bind[n][2], "SET", "%.6g" % v)
               for k, (n, v) in enumerate(values)]
    deck = rest_motion.REST.format(model="input/head_neck_54dof.inp") + "\n".join(cards) + "\n"
    h5 = os.path.join(tmp, "rest.h5")
    run.run_deck(deck, changes=changes, h5=h5)
    peak, where, _, head = rest_motion.excursion(h5)
    return "%.3g rad (%.3g deg, %s); head %.3g deg" % (peak, peak * 57.29578, where, head)


def catalogue_row(copy, env, listing, tmp, label):
    """The catalogue on the copy's column at the disc and stop factors of `listing`."""
    generate(copy, env, listing)
    report = os.path.join(tmp, "catalogue_%s.md" % re.sub(r"\W", "_", label))
    subprocess.run([sys.executable, "-m", "hhneck.validation.catalogue", "--out", os.path.join(tmp, "cat"), "--report", report],
                   cwd=copy, env=env, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    cells = []
    for line in open(report):
        m = re.match(r"\| ([^|]+) \| (segment|specimen|volunteer)[^|]*\| \d+ \| ([^|]+) \|", line)
        if m and m.group(2) != "volunteer":
            inside = re.search(r"(\d+ of \d+ levels)", line)
            cells.append("%s %s%s" % (m.group(1).strip(), m.group(3).strip(),
                                      " (%s)" % inside.group(1) if inside else ""))
    return "; ".join(cells)


def main():
    fits = fit_arguments(sys.argv[1:], "spindle_segmental.py")
    tmp, copy, env, start = column_copy("spindle-")
    if not fits:
        muscles = reduced_deck(CALIBRATION, PASSIVE,
                               "NBDL CALIBRATION: 12 G, THE MUSCLES AND THEIR STRETCH LOOPS ONLY")
        fits = run_calibrations([("the fifteen and the loops (19 parameters)", open(CALIBRATION).read()),
                                 ("the muscles and the loops (11)", muscles)], tmp)
    start_values = deck_values(CALIBRATION)
    no_loops = [(n, 0.0 if n in ("KPSE", "KPSF") else v) for n, v in start_values]
    rows = [("the column's starting point, loops off", no_loops, start),
            ("the column's starting point, the VALUES loops", start_values, start)]
    rows += [(label, fitted_values(listing), listing) for label, listing in fits]
    report(rows, fits, CALIBRATION, start, copy, env, tmp)


def report(rows, fits, calibration, start, copy, env, tmp):
    """Print the tables of the sets `rows` ((label, values, listing) on the copy's column, `start`
    its starting point; the PARAM cards of `calibration` bind the values): the NBDL scores, then
    6 s at rest and the catalogue, then the values and objectives of the listings `fits`."""
    vol = volunteer_peaks()
    bind = bindings(calibration)
    cards = spindle_cards()
    print("| set | 12 g CORA-style (calibration) | 15 g (prediction) | 8 g head peaks, (model - mean)/SD: "
          + ", ".join(r[0].replace("peak ", "") for r in ROWS[1:]) + " | braking arc 8 / 12 / 15 g (deg) |"
          " range warnings |")
    print("|---|---|---|---|---|---|")
    for label, values, _ in rows:
        print(score(label, values, cards, bind, vol, tmp))
    print("\n| set | 6 s at rest with the loops: largest excursion; head rotation | catalogue (ISO/TS 18571) |")
    print("|---|---|---|")
    done = {}
    for label, values, _ in rows:
        point = merged(start, values, tmp)
        passive = tuple((n, v) for n, v in fitted_values(point) if n in PASSIVE)
        generate(copy, env, point)
        rest = rest_row(values, cards, bind, tmp)
        if passive not in done:
            done[passive] = catalogue_row(copy, env, point, tmp, label)
        print("| %s | %s | %s |" % (label, rest, done[passive]))
    print("\nThe fits' values (PARAM lines of each listing) and objectives:")
    for label, listing in fits:
        best = [ln.strip() for ln in open(listing) if ln.startswith("BEST OBJECTIVE")]
        stand = [ln.strip() for ln in open(listing) if ln.startswith("STANDING CASE")]
        print("%s: %s (%s; %s)" % (label, ", ".join("%s %s" % (n, s3(v)) for n, v in fitted_values(listing)),
                                   best[0] if best else "no objective", "; ".join(stand)))

if __name__ == "__main__":
    main()
