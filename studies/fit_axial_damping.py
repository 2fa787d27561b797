#!/usr/bin/env python3
"""What the shipped calibration's disc parameters and its PASSIVE condition each bring.

    python3 studies/fit_axial_damping.py

The shipped calibration (input/calibrate_nbdl.inp) fits the discs' axial
damping (SCALE VAXIAL) within the range Izambert et al. (2003) measured on
whole lumbar discs (32-2094 N s/m; S13 of reference/parameters.md), the
damping of shear, bending and torsion apart (SCALE VBEND) and the discs'
axial stiffness in tension as a fraction of that in compression (SCALE
ETENSION, DISC card 3 F7), and it rejects parameter sets whose neck stands
without its muscles (PASSIVE card; S14). This runs `hhneck --calibrate` on
copies of that deck (in a temporary directory; nothing in input/ is
changed), the FIT card as shipped, two at a time:
  - the tension fraction held at 1 (the paper's linear eq 1: PARAM ETENSION
    removed, SCALE ETENSION 1 in the model deck), with and without PASSIVE;
  - the tension fraction fitted, without PASSIVE;
  - the shipped deck itself.
One row per fit: J, the fitted axial damping, the retardation time of the
other modes, the tension fraction, and per severity the rating, the head
peaks within 1 SD and their times within 10 ms (the goal's counts), and
the largest real parts at rest with and without the muscles. Release
build; about 15 minutes on two cores.
"""
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))
from hhneck.volunteers import stop  # noqa: E402
from cross_severity import params, rating_text  # noqa: E402
from hhneck.decks import CardError, field, is_card, set_field, write_decks  # noqa: E402
from hhneck.validation import model_deck  # noqa: E402

MODEL = "input/head_neck_54dof.inp"
CALIBRATION = "input/calibrate_nbdl.inp"
# s: the retardation time SCALE VBEND multiplies (the parameter table's disc.tau)
TAU0 = model_deck.table_values(model_deck.read_table())["disc.tau"]
# (label, tension fraction held at 1, PASSIVE card kept)
FITS = [
    ("tension fraction 1 (linear eq 1), PASSIVE", True, True),
    ("tension fraction 1 (linear eq 1), no PASSIVE", True, False),
    ("tension fraction fitted, no PASSIVE", False, False),
    ("tension fraction fitted, PASSIVE (the shipped deck)", False, True),
]


def axial_damping(model):
    """Every disc's (A/h) d2 (N s/m) from the model deck's DISC cards, before any SCALE."""
    return [float(field(l, 7)) * float(field(l, 4)) / float(field(l, 5))
            for l in model.splitlines() if is_card(l, "DISC")]


def linear_model(model):
    """The model deck with the tension fraction held at 1 (SCALE ETENSION 1)."""
    return "\n".join(set_field(l, 4, "1.0") if is_card(l, "SCALE", "ETENSION") else l
                     for l in model.splitlines()) + "\n"


def variant(deck, cases, hold_tension, passive):
    """The calibration deck on the given case copies, without PARAM ETENSION
    when the tension fraction is held and without the PASSIVE card if asked;
    without the deck's VALUES cards (its own fit's starting point, one value
    per PARAM card of that deck): each variant starts from its LHS points."""
    out = []
    for l in deck.splitlines():
        if is_card(l, "CASE"):
            l = "%-10s%s" % ("CASE", cases[l[10:].strip()])
        elif ((is_card(l, "PARAM", "ETENSION") and hold_tension) or (is_card(l, "PASSIVE") and not passive)
              or is_card(l, "VALUES")):
            continue
        out.append(l)
    return "\n".join(out) + "\n"


def fit_decks(model, tmp):
    """Write the calibration decks of FITS in `tmp` (fitK.inp, with the
    linear model deck and the case decks that include it): [(label, path
    without .inp)]. CardError, and nothing written, when a card would pass
    column 80 (a CASE or INCLUDE card, with a long `tmp` path)."""
    decks = {os.path.join(tmp, "linear.inp"): linear_model(model)}
    linear, shipped = {}, {}
    for sev in ("15g", "12g"):
        case = "input/nbdl%s.inp" % sev
        path = os.path.join(tmp, "nbdl%s.inp" % sev)
        decks[path] = open(case).read().replace(MODEL, os.path.join(tmp, "linear.inp"))
        linear[case], shipped[case] = path, case
    deck = open(CALIBRATION).read()
    runs = []
    for k, (label, hold, passive) in enumerate(FITS):
        path = os.path.join(tmp, "fit%d" % k)
        decks[path + ".inp"] = variant(deck, linear if hold else shipped, hold, passive)
        runs.append((label, path))
    write_decks(decks)
    return runs


def summary(path, c0):
    """One table row's numbers from the calibration listing at `path`; None
    when the search met no parameter set that passes the checks at rest (J = 2 or more)."""
    listing = open(path).read()
    j = float(re.search(r"^OBJECTIVE J =\s+(\S+)", listing, re.M).group(1))
    if j >= 2.0:
        return None
    par = dict(params(path))
    cases = []
    for block in re.split(r"^CASE ", listing.split("BEST OBJECTIVE")[-1], flags=re.M)[1:]:
        rating = float(re.search(r"MEAN RATING\s+(\S+)", block).group(1))
        peaks = re.findall(r"^\s+(\S.*?)\s+MODEL\s+\S+ AT\s+(\S+) MS; VOLUNTEERS\s+\S+ \+-\s+\S+ AT\s+(\S+) "
                           r"\+-\s+\S+; Z\s+(\S+)", block, re.M)
        off = ["%s %+.2f SD" % (name.lower(), float(z)) for name, _, _, z in peaks if abs(float(z)) > 1.0]
        late = ["%s %+.1f ms" % (name.lower(), float(t) - float(tv)) for name, t, tv, _ in peaks
                if abs(float(t) - float(tv)) > 10.0]
        count = lambda miss: "%d of %d%s" % (len(peaks) - len(miss), len(peaks),
                                             " (%s)" % ", ".join(miss) if miss else "")
        cases.append("%s | %s | %s" % (rating_text(rating), count(off), count(late)))
    lmax = float(re.search(r"LARGEST REAL PART AT REST\s+(\S+)", listing).group(1))
    m = re.search(r"LARGEST REAL PART AT REST WITHOUT MUSCLES\s+(\S+)", listing)
    lp = "%.2f" % float(m.group(1)) if m else "not checked"
    vaxial, vbend = float(par["VAXIAL"]), float(par["VBEND"])
    ft = "%.3g" % float(par["ETENSION"]) if "ETENSION" in par else "1 (held)"
    return "%.3f | %s | %.1f | %s | %s | %.2f | %s" % (j, span(vaxial * min(c0), vaxial * max(c0)),
                                                      1e3 * TAU0 * vbend, ft, " | ".join(cases), lmax, lp)


def span(lo, hi):
    """'lo to hi' (N s/m), or the one value when they agree."""
    return "%.0f" % lo if round(lo) == round(hi) else "%.0f to %.0f" % (lo, hi)


def main():
    exe = subprocess.run(["fpm", "run", "--profile", "release", "--runner", "echo"], capture_output=True,
                         text=True, check=True).stdout.split()[-1]
    model = open(MODEL).read()
    c0 = axial_damping(model)
    try:
        runs = fit_decks(model, tempfile.mkdtemp())
    except CardError as e:
        stop("%s (a shorter TMPDIR fits)" % e)
    print("Disc axial damping (A/h) d2 of the model deck before its SCALE cards, every disc: %s N s/m.\n"
          % span(min(c0), max(c0)))
    print("| fit | J | axial damping (N s/m) | retardation time of shear, bending, torsion (ms) |"
          " tension fraction | 15 g rating | 15 g peaks in 1 SD | 15 g times in 10 ms | 12 g rating |"
          " 12 g peaks in 1 SD | 12 g times in 10 ms | largest real part at rest (1/s) |"
          " without muscles (1/s) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for first in range(0, len(runs), 2):       # two at a time: one per core
        procs = [(label, path, subprocess.Popen([exe, "--calibrate"], stdin=open(path + ".inp"),
                                                stdout=open(path + ".out", "w"), stderr=subprocess.DEVNULL))
                 for label, path in runs[first:first + 2]]
        for label, path, p in procs:
            if p.wait():
                print("| %s | the calibration failed (exit %d) |" % (label, p.returncode))
                continue
            row = summary(path + ".out", c0)
            print("| %s | %s |" % (label, row or "every point the search met fails a check at rest (J = 2 or more)"),
                  flush=True)


if __name__ == "__main__":
    main()
