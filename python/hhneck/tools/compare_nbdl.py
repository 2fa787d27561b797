"""Compare the model's NBDL sled runs with the volunteers (15 g and 12 g).

    hhneck-compare-nbdl [--case 15g|12g|both|NAME] [--h5 SEV=RESULT.h5 ...] [--out DIR]
                        [--data NAME=DIR] [--deck NAME=DECK]

Without --h5 it runs input/nbdlSEVg.inp for each case (hhneck.run.run_deck:
$HHNECK, else the project's release build). Volunteer data: reference/nbdl_15g
(runs 1635-1644) and reference/nbdl_12g (runs 1607-1617), raw, every 0.5 ms.
The project's input/, reference/ and docs/ are meant (hhneck.paths), from
any working directory; the computations are hhneck.ratings'. Every volunteer
run and the model are filtered CFC 60 (SAE J211/1, as the library does).

Rated channels (the head's kinematics): x- and z-acceleration, angular
acceleration, angular velocity, rotation; each gets a CORA-style rating
(method in docs/validation.md) and the overall rating of a case is their
mean; each gets its ISO/TS 18571 rating too (hhneck.ratings, reference =
the volunteers' mean, same window), and their mean. The head displacements relative to T1 are reported and rated but not
in the overall rating (their frames and points are not documented).
Peaks: x-acceleration, z-acceleration dip and rebound, angular acceleration,
angular velocity, rotation, each against the mean +- SD of the runs' peaks
(value and time). Writes a table on stdout, DIR/validation_table.md and
DIR/validation_nbdlSEV.png (default DIR: the project's docs/). Every
number has three significant digits.

Other runs of the same kind (a directory with the same CHANNEL.csv files,
columns time_ms,run_...): `--data NAME=DIR --case NAME` compares the deck
input/nbdlNAME.inp (or `--deck NAME=DECK`) with them; python3 -m hhneck.validation.nbdl_tables
--data DIR --name nbdlNAME writes that deck and its T1 tables. A channel
whose file the directory lacks is left out (the overall rating is the mean
over the rated channels present, and the table names the missing ones); a
file that cannot be read as evenly spaced runs stops the tool with its name.
"""
import argparse
import os
import sys
import tempfile

import numpy as np

from .. import run
from ..paths import project_path
from ..ratings import RATED, REPORTED, compare, s3
from ..volunteers import SEVERITIES

def tables(sev, chans, peaks, overall, nrun):
    sevt = sev.replace("g", " g")
    L = ["### NBDL %s (%d volunteer runs)" % (sevt, nrun), "",
         "| channel | corridor C | cross-corr. X | CORA-style | lag (ms) | time inside mean ± 1 SD | ISO/TS 18571 |",
         "|---|---|---|---|---|---|---|"]
    for c in chans:
        L.append("| %s%s | %.3f | %.3f | **%.3f** | %+.1f | %.0f %% | %.3f |" % (
            c["label"], "" if c["rated"] else " (reported)", c["C"], c["X"], c["score"], c["lag"], 100 * c["inside"],
            c["iso"]))
    L += ["", "| head peak | model | at (ms) | volunteers (mean ± SD) | at (ms) | (model − mean)/SD | "
          "within 1 SD | within 10 ms |", "|---|---|---|---|---|---|---|---|"]
    for p in peaks:
        L.append("| %s | %s | %.0f | %s ± %s | %.0f ± %.0f | %+.2f | %s | %s |" % (
            p["label"], s3(p["mp"]), p["mt"], s3(p["pm"]), s3(p["ps"]), p["tmn"], p["tsd"], p["z"],
            "yes" if p["ok_peak"] else "no", "yes" if p["ok_time"] else "no"))
    rep = np.mean([c["score"] for c in chans])
    rated = [c["label"] for c in chans if c["rated"]]
    nrep = len(chans) - len(rated)
    which = "the five rated head channels" if len(rated) == len(RATED) else \
        "the %d rated head channels the runs have; not in them: %s" % (
            len(rated), ", ".join(c for c in RATED if c not in rated))
    with_rep = "; with the two displacement channels: %.3f" % rep if nrep == len(REPORTED) else \
        "; with the displacement channel: %.3f" % rep if nrep else ""
    iso = np.mean([c["iso"] for c in chans if c["rated"]])
    L += ["", "Overall CORA-style rating %s (mean of %s): **%.3f** (target ≥ 0.85: %s)%s. "
          "ISO/TS 18571 (objective-rating-metrics; reference the volunteers' mean, CFC 60, the same window), "
          "mean of the same channels: **%.3f**. "
          "Peaks within 1 SD: %d of %d; peak times within 10 ms: %d of %d."
          % (sevt, which, overall, "met" if overall >= 0.85 else "not met", with_rep, iso,
             sum(p["ok_peak"] for p in peaks), len(peaks), sum(p["ok_time"] for p in peaks), len(peaks)), ""]
    return L


def figure(sev, curves, model_curves, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    tm, model = model_curves
    fig, axes = plt.subplots(2, 4, figsize=(18, 8))
    for ax, (label, (t, data, mean, sd)) in zip(axes.flat, curves.items()):
        for r in data:
            ax.plot(t, r, color="0.6", lw=0.6)
        ax.fill_between(t, mean - sd, mean + sd, color="tab:blue", alpha=0.25, label="volunteer mean ± 1 SD")
        ax.plot(t, mean, color="tab:blue", lw=1.2)
        ax.plot(tm, model[label], color="tab:red", lw=2.2, label="model")
        ax.set_xlim(0, 300)
        ax.set_title(label, fontsize=10)
        ax.set_xlabel("time (ms)")
        ax.grid(alpha=0.3)
    axes.flat[0].legend(fontsize=8)
    for ax in axes.flat[len(curves):]:
        ax.axis("off")                      # the channels the runs do not have, and the caption's place
    axes.flat[-1].text(0.0, 0.5, "NBDL %s frontal sled\nvolunteer runs (thin grey),\nmean ± 1 SD (band),\n"
                       "model (thick red);\nall CFC 60" % sev.replace("g", " g"), fontsize=11, va="center")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def run_deck(sev, tmp, deck=None):
    """Run a case's deck (`deck`, default the project's input/nbdlSEV.inp) to
    TMP/nbdlSEV.h5; the result file's path."""
    deck = deck or project_path("input", "nbdl%s.inp" % sev)
    return run.run_deck(deck, h5=os.path.join(tmp, "nbdl%s.h5" % sev)).h5


def pair(text):
    """NAME=VALUE of an option as (NAME, VALUE)."""
    if "=" not in text:
        raise argparse.ArgumentTypeError("expected NAME=VALUE, got %r" % text)
    return tuple(text.split("=", 1))


def main(argv=None):
    p = argparse.ArgumentParser(prog="hhneck-compare-nbdl", description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--case", default="both", help="15g, 12g, both (default) or the NAME of --data")
    p.add_argument("--h5", action="append", type=pair, default=[], metavar="SEV=RESULT.h5",
                   help="the model's result file of a case (default: run its deck)")
    p.add_argument("--out", metavar="DIR",
                   help="where validation_table.md and the figures go (default: the project's docs/)")
    p.add_argument("--data", action="append", type=pair, default=[], metavar="NAME=DIR",
                   help="runs of another case: a directory of CHANNEL.csv files")
    p.add_argument("--deck", action="append", type=pair, default=[], metavar="NAME=DECK",
                   help="the deck of a case (default input/nbdlNAME.inp)")
    args = p.parse_args(argv)
    outdir, which, given = args.out or project_path("docs"), args.case, dict(args.h5)
    data, decks = dict(args.data), dict(args.deck)
    sevs = SEVERITIES if which == "both" else (which,)
    tmp = tempfile.mkdtemp()
    lines = []
    os.makedirs(outdir, exist_ok=True)
    for sev in sevs:
        h5 = given.get(sev) or run_deck(sev, tmp, decks.get(sev))
        chans, peaks, overall, curves, mc, nrun = compare(sev, h5, data.get(sev))
        lines += tables(sev, chans, peaks, overall, nrun)
        figure(sev, curves, mc, os.path.join(outdir, "validation_nbdl%s.png" % sev))
    text = "\n".join(lines)
    print(text)
    with open(os.path.join(outdir, "validation_table.md"), "w") as out:
        out.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
