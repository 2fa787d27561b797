#!/usr/bin/env python3
"""Cross-severity table from the listings of the three calibrations:

    fpm run --profile release -- --calibrate < input/calibrate_nbdl15g.inp > fit15.txt
    fpm run --profile release -- --calibrate < input/calibrate_nbdl12g.inp > fit12.txt
    fpm run --profile release -- --calibrate < input/calibrate_nbdl.inp    > fitboth.txt
    python3 tools/cross_severity.py fit15.txt fit12.txt fitboth.txt

Each fit's parameters are scored on both severities (hhneck --calibrate with
FIT NELDER 0 and VALUES cards); prints a Markdown table: the fitted values,
and the mean CORA-style rating and the number of head peaks within 1 SD at
each severity, marked calibration (in-sample) or prediction.
"""
import os
import re
import subprocess
import sys
import tempfile

FITS = [("15 g alone", "15g"), ("12 g alone", "12g"), ("both", "both")]


def params(listing):
    out = []
    for line in open(listing):
        m = re.match(r"PARAM (\S+)\s+= (\S+)", line)
        if m:
            out.append((m.group(1), m.group(2)))
    return out


def score(sev, values):
    deck = open("input/calibrate_nbdl%s.inp" % sev).read().splitlines()
    deck = [("FIT       NELDER    0         2         1" if l.startswith("FIT") else l) for l in deck]
    for i in range(0, len(values), 7):
        deck.append("VALUES    " + "".join("%-10s" % v for v in values[i:i + 7]))
    path = os.path.join(tempfile.mkdtemp(), "score.inp")
    open(path, "w").write("\n".join(deck) + "\n")
    with open(path) as f:
        out = subprocess.run(["fpm", "run", "--profile", "release", "--", "--calibrate"], stdin=f,
                             capture_output=True, text=True, check=True).stdout
    rating = float(re.search(r"MEAN RATING\s+(\S+)", out).group(1))
    z = [float(x) for x in re.findall(r"; Z\s+(\S+)", out)]
    return rating, sum(abs(v) <= 1.0 for v in z), len(z)


def main():
    fits = {tag: params(path) for (_, tag), path in zip(FITS, sys.argv[1:4])}
    names = [n for n, _ in fits["both"]]
    head = "| fitted on | " + " | ".join(names) + " | 15 g rating | 15 g peaks in 1 SD | 12 g rating | 12 g peaks in 1 SD |"
    rows = [head, "|" + "---|" * (len(names) + 5)]
    for label, tag in FITS:
        vals = [v for _, v in fits[tag]]
        cells = ["%.3g" % float(v) for v in vals]
        for sev in ("15g", "12g"):
            r, k, n = score(sev, vals)
            kind = "calibration" if tag in (sev, "both") else "prediction"
            cells += ["%.3f (%s)" % (r, kind), "%d of %d" % (k, n)]
        rows.append("| %s | %s |" % (label, " | ".join(cells)))
    print("\n".join(rows))


if __name__ == "__main__":
    main()
