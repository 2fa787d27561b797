#!/usr/bin/env python3
"""What does postural feedback of the neck muscles (FEEDBACK cards) bring to
the NBDL volunteers: fitted with the other parameters, does it predict 15 g
and the 8 g peaks better, and does the head brake over the volunteers' arc?

    python3 studies/feedback_nbdl.py [--fit LABEL=LISTING ...]

Without --fit it runs four calibrations itself (release build, two at a
time): input/calibrate_nbdl12g_feedback.inp (the shipped calibration's
fifteen parameters and the two loops' gains and delays, on
input/nbdl12g_feedback.inp); the same with the disc and stop factors held
at their shipped values (the seven muscle parameters and the loops');
input/calibrate_nbdl_feedback.inp (the muscles and the loops fitted to the
12 g runs and to the 8 g volunteers' published peaks,
reference/nbdl_8g_peaks.csv); and that one without the loops (the muscles
alone, the control). Each fit's values are set by CHANGE cards on the
8 g, 12 g and 15 g decks (with the two FEEDBACK cards of
input/nbdl12g_feedback.inp added when the fit has loops) and scored as the
shipped set is: the CORA-style rating and ISO/TS 18571 of
hhneck-compare-nbdl at 12 g (calibration) and 15 g (prediction), the 8 g
head peaks against reference/reference-data.md section 3 (prediction, or
calibration for the fits to them), the braking arc at each severity
(studies/braking_nbdl.py), and the runs' range-of-motion warnings. The
shipped set is the first row.
"""
import os
import re
import subprocess
import sys
import tempfile

sys.path[:0] = [os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"),
                os.path.dirname(os.path.abspath(__file__))]
from hhneck import run  # noqa: E402
from hhneck.ratings import compare, s3  # noqa: E402
from hhneck.decks import field, number_field  # noqa: E402
from braking_nbdl import model_arc  # noqa: E402
from predict_nbdl8g import ROWS, SEVERITIES, bindings, fitted_values, model_peaks, volunteer_peaks  # noqa: E402

CALIBRATION = "input/calibrate_nbdl12g_feedback.inp"
TWO_SEVERITIES = "input/calibrate_nbdl_feedback.inp"
CASE = "input/nbdl12g_feedback.inp"
LOOPS = ("KPE", "KPF", "TAUE", "TAUF")
PASSIVE = ("VBEND", "VAXIAL", "ETENSION", "SHEAR", "AXIAL", "ROMK", "ROMT0", "LIMC1")


def feedback_cards(path=CASE):
    """The FEEDBACK cards of the 12 g feedback deck."""
    return [line.rstrip("\n") for line in open(path) if line.startswith("FEEDBACK")]


def reduced_deck(path, drop, title, plain_cases=False):
    """The calibration deck text of `path` with the PARAM cards named in
    `drop` and their VALUES left out (held at the decks' values), the TITLE
    card's text `title`, and with `plain_cases` the CASE decks without
    their FEEDBACK cards (input/nbdlSEV.inp for input/nbdlSEV_feedback.inp)."""
    lines = open(path).read().splitlines()
    names = [field(ln, 1) for ln in lines if ln.startswith("PARAM")]
    values = [v for ln in lines if ln.startswith("VALUES") for v in ln[10:].split()]
    keep = [(n, v) for n, v in zip(names, values) if n not in drop]
    out = []
    for ln in lines:
        if ln.startswith("PARAM") and field(ln, 1) in drop or ln.startswith("VALUES"):
            continue
        if ln.startswith("TITLE"):
            ln = "TITLE     " + title
        if plain_cases and ln.startswith("CASE"):
            ln = ln.replace("_feedback.inp", ".inp")
        out.append(ln)
        if ln.startswith("PARAM") and field(ln, 1) == keep[-1][0]:
            for k in range(0, len(keep), 7):
                out.append("VALUES    " + "".join("%-10s" % v for _, v in keep[k:k + 7]))
    return "\n".join(out) + "\n"


def muscles_only_deck():
    """The 12 g feedback calibration with the disc and stop factors held at the shipped values."""
    return reduced_deck(CALIBRATION, PASSIVE, "NBDL CALIBRATION: 12 G, THE MUSCLES AND THE FEEDBACK LOOPS ONLY")


def without_loops():
    """The two-severity calibration without the loops (the control: the
    muscles alone fitted to the same two severities, on the case decks
    without FEEDBACK cards)."""
    return reduced_deck(TWO_SEVERITIES, LOOPS, "NBDL CALIBRATION: 12 G AND THE 8 G PEAKS, THE MUSCLES ALONE",
                        plain_cases=True)


def variant(sev, cards):
    """The deck text of severity sev with the FEEDBACK cards added."""
    return "TITLE     NBDL %s WITH POSTURAL FEEDBACK\nINCLUDE   input/nbdl%s.inp\n%s\n" % (
        sev.upper(), sev, "\n".join(cards))


def score(label, values, cards, bind, vol, tmp):
    """One table row: the set's values by CHANGE cards on the three decks."""
    changes = [run.change_card("P%d" % k, "FIELD%d" % bind[n][0], bind[n][1], bind[n][2], "SET", number_field(v))
               for k, (n, v) in enumerate(values)]
    h5, warn = {}, []
    for sev in SEVERITIES:
        r = run.run_deck(variant(sev, cards) if cards else "input/nbdl%s.inp" % sev, changes=changes,
                         h5=os.path.join(tmp, "%s_%s.h5" % (re.sub(r"\W", "_", label), sev)))
        h5[sev] = r.h5
        warn += [ln for ln in (r.listing + r.stderr).splitlines() if "past its physiological range" in ln]
    cells = [label]
    for sev in ("12g", "15g"):
        chans, peaks, overall = compare(sev, h5[sev])[:3]
        iso = sum(c["iso"] for c in chans if c["rated"]) / sum(c["rated"] for c in chans)
        inside = sum(p["ok_peak"] for p in peaks)
        cells.append("%s (ISO %s; %d of %d peaks in 1 SD)" % (s3(overall), s3(iso), inside, len(peaks)))
    pk = model_peaks(h5["8g"])
    zs = [(pk[r[0]][0] - vol[r[0]]["8g"][0]) / vol[r[0]]["8g"][1] for r in ROWS[1:]]
    cells.append(" ".join("%+.2f" % z for z in zs) + " (%d in 1 SD)" % sum(abs(z) <= 1 for z in zs))
    cells.append(" / ".join(s3(model_arc(h5[s])[4]) for s in SEVERITIES))
    cells.append(str(len(warn)))
    return "| " + " | ".join(cells) + " |"


def calibrations():
    """(label, calibration deck text) of the four fits, in table order."""
    return [("the fifteen and the loops (19 parameters), 12 g", open(CALIBRATION).read()),
            ("the muscles and the loops (11), 12 g", muscles_only_deck()),
            ("the muscles and the loops (11), 12 g and the 8 g peaks", open(TWO_SEVERITIES).read()),
            ("the muscles alone (7), 12 g and the 8 g peaks", without_loops())]


def run_calibrations(decks, tmp, jobs=2):
    """[(label, listing)] of the calibration decks run, `jobs` at a time."""
    exe = run.find_executable()
    out = []
    for k in range(0, len(decks), jobs):
        procs = []
        for n, (label, text) in enumerate(decks[k:k + jobs]):
            listing = os.path.join(tmp, "fit%d.txt" % (k + n))
            p = subprocess.Popen([exe, "--calibrate"], stdin=subprocess.PIPE, stdout=open(listing, "w"),
                                 stderr=subprocess.DEVNULL, text=True)
            p.stdin.write(text)
            p.stdin.close()
            procs.append((label, listing, p))
        for label, listing, p in procs:
            if p.wait() != 0:
                sys.exit("the calibration %s failed: %s" % (label, listing))
            out.append((label, listing))
    return out


def fit_arguments(args, study):
    """[(label, listing)] of the --fit LABEL=LISTING options of a study's command line."""
    fits = []
    args = list(args)
    while args:
        a = args.pop(0)
        if a == "--fit" and args and "=" in args[0]:
            fits.append(tuple(args.pop(0).split("=", 1)))
        else:
            sys.exit("usage: %s [--fit LABEL=LISTING ...]" % study)
    return fits


def main():
    fits = fit_arguments(sys.argv[1:], "feedback_nbdl.py")
    tmp = tempfile.mkdtemp(prefix="feedback-")
    if not fits:
        fits = run_calibrations(calibrations(), tmp)
    vol = volunteer_peaks()
    bind = bindings(CALIBRATION)
    print("| set | 12 g CORA-style (calibration) | 15 g (prediction) | 8 g head peaks, (model - mean)/SD: "
          + ", ".join(r[0].replace("peak ", "") for r in ROWS[1:]) + " | braking arc 8 / 12 / 15 g (deg) |"
          " range warnings |")
    print("|---|---|---|---|---|---|")
    print(score("shipped (no feedback)", [], [], bind, vol, tmp))
    for label, listing in fits:
        values = fitted_values(listing)
        named = dict(values)
        loops = ", ".join("%s %s" % (n, s3(named[n])) for n in LOOPS if n in named)
        cards = feedback_cards() if loops else []
        print(score("%s: %s" % (label, loops or "no loops"), values, cards, bind, vol, tmp))
    print("\nThe fits' values (PARAM lines of each listing) and objectives:")
    for label, listing in fits:
        best = [ln.strip() for ln in open(listing) if ln.startswith("BEST OBJECTIVE")]
        print("%s: %s (%s)" % (label, ", ".join("%s %s" % (n, s3(v)) for n, v in fitted_values(listing)),
                               best[0] if best else "no objective"))


if __name__ == "__main__":
    main()
