#!/usr/bin/env python3
"""Cross-severity table from the listings of the three calibrations:

    fpm run --profile release -- --calibrate < input/calibrate_nbdl15g.inp > fit15.txt
    fpm run --profile release -- --calibrate < input/calibrate_nbdl12g.inp > fit12.txt
    fpm run --profile release -- --calibrate < input/calibrate_nbdl.inp    > fitboth.txt
    python3 studies/cross_severity.py fit15.txt fit12.txt fitboth.txt

Each fit's parameters are scored on both severities (hhneck --calibrate with
FIT NELDER 0 and VALUES cards); prints a Markdown table: the fitted values,
and the mean CORA-style rating and the number of head peaks within 1 SD at
each severity, marked calibration (in-sample) or prediction, the number of
head peak times within 10 ms of the volunteers' mean time, and the largest
real part at rest over the cases scored (1/s). A rating printed with three
digits that would round across the 0.850 target is printed with four.
"""
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))
from hhneck.volunteers import stop  # noqa: E402
from hhneck.decks import CardError, field_text, write_deck  # noqa: E402

FITS = [("15 g alone", "15g"), ("12 g alone", "12g"), ("both", "both")]


def params(listing):
    out = []
    for line in open(listing):
        m = re.match(r"PARAM (\S+)\s+= (\S+)", line)
        if m:
            out.append((m.group(1), m.group(2)))
    return out


def score_deck(sev, values):
    """The calibration deck of `sev` scoring the parameter values (text)
    instead of fitting (FIT NELDER 0, VALUES cards); CardError when a value
    is wider than its field."""
    deck = open("input/calibrate_nbdl%s.inp" % sev).read().splitlines()
    # scored as a run, not fitted: the PASSIVE condition is the fit's, so it is left out
    deck = [("FIT       NELDER    0         2         1" if l.startswith("FIT") else l) for l in deck
            if not l.startswith(("PASSIVE", "VALUES"))]   # the deck's own VALUES are its fit's starting point
    for i in range(0, len(values), 7):
        deck.append("VALUES    " + "".join(field_text(v) for v in values[i:i + 7]))
    return deck


def score(sev, values):
    """The parameter values scored on the calibration of `sev` (score_deck(),
    run from a temporary file): (mean rating, head peaks within 1 SD, head
    peaks, peak times within 10 ms, largest real part at rest)."""
    path = os.path.join(tempfile.mkdtemp(), "score.inp")
    try:
        write_deck(path, score_deck(sev, values))
    except CardError as e:
        stop("the calibration deck of %s: %s" % (sev, e))
    with open(path) as f:
        out = subprocess.run(["fpm", "run", "--profile", "release", "--", "--calibrate"], stdin=f,
                             capture_output=True, text=True, check=True).stdout
    rating = float(re.search(r"MEAN RATING\s+(\S+)", out).group(1))
    z = [float(x) for x in re.findall(r"; Z\s+(\S+)", out)]
    times = re.findall(r"MODEL\s+\S+ AT\s+(\S+) MS; VOLUNTEERS\s+\S+ \+-\s+\S+ AT\s+(\S+) ", out)
    intime = sum(abs(float(a) - float(b)) <= 10.0 for a, b in times)
    lmax = float(re.search(r"LARGEST REAL PART AT REST\s+(\S+)", out).group(1))
    return rating, sum(abs(v) <= 1.0 for v in z), len(z), intime, lmax


def rating_text(r, target=0.85):
    """Three digits, four where three would round across the target."""
    text = "%.3f" % r
    return text if (float(text) >= target) == (r >= target) else "%.4f" % r


def main():
    fits = {tag: params(path) for (_, tag), path in zip(FITS, sys.argv[1:4])}
    names = [n for n, _ in fits["both"]]
    head = ("| fitted on | " + " | ".join(names) + " | 15 g rating | 15 g peaks in 1 SD | 15 g times in 10 ms"
            " | 12 g rating | 12 g peaks in 1 SD | 12 g times in 10 ms | largest real part at rest (1/s) |")
    rows = [head, "|" + "---|" * (len(names) + 8)]
    for label, tag in FITS:
        vals = [v for _, v in fits[tag]]
        cells = ["%#.3g" % float(v) for v in vals]
        lmax = -1.0e30
        for sev in ("15g", "12g"):
            r, k, n, kt, lm = score(sev, vals)
            lmax = max(lmax, lm)
            kind = "calibration" if tag in (sev, "both") else "prediction"
            cells += ["%s (%s)" % (rating_text(r), kind), "%d of %d" % (k, n), "%d of %d" % (kt, n)]
        cells.append("%#.3g" % lmax)
        rows.append("| %s | %s |" % (label, " | ".join(cells)))
    print("\n".join(rows))


if __name__ == "__main__":
    main()
