"""The validation catalogue: runs every case of it, rates each curve by
ISO/TS 18571 (objective-rating-metrics) and writes docs/catalogue.md with a
table and a figure per source.

Cases in it now: the quasi-static segment tests of Panjabi et al. 2001 (21
curves) and Nightingale et al. 2007 (3), set up by hhneck.segments. Not yet
in it: the specimen sled tests (Stemper 2004, Kang 2018 front and side) and
the NBDL volunteer sleds (rated by hhneck-compare-nbdl, docs/validation.md).

Command: hhneck-catalogue [--quick] [--exe HHNECK] [--jobs N] [--out DIR]
[--report docs/catalogue.md]. --quick runs one segment (C4-C5) per source
and motion: the form the test suite runs.
"""
import argparse
import os
import sys
import time

import numpy as np

from . import segments

REPORT = os.path.join(segments.ROOT, "docs", "catalogue.md")
GOAL_SEGMENT = "the model's rotation inside the reported range at every level, direction and moment"


def _ratio(model, data):
    return np.where(np.abs(data) > 1e-9, model / np.where(np.abs(data) > 1e-9, data, 1.0), np.nan)


def segment_section(results, figdir, relto):
    """Markdown lines of the segment cases: per source a table (rotation at
    each moment level, data against model, the ISO/TS 18571 scores of the
    moment-rotation curve) and a figure written to figdir."""
    lines = ["## Segment tests (quasi-static pure moments)", "",
             "**Prediction**: nothing of the model was fitted to these data. Set-up and signs: "
             "`python/hhneck/segments.py` (its docstring): the lower body fixed, a pure moment ramped on "
             "the upper one (for OC–C2 on the head, C1 free), no gravity, no muscles, the discs, ligaments, "
             "joint-limit dampers and range-of-motion elements of the model deck joining the segment's "
             "bodies. Rotation of the upper body relative to the lower at each moment level on the loading "
             "ramp, against the data's mean (Nightingale: and its ±1 SD bounds). ISO/TS 18571 of the whole "
             "moment–rotation curve (rotation as a function of moment, −peak to +peak, the data's two "
             "loading branches joined at the neutral zone) by `objective-rating-metrics`.", ""]
    for src in sorted({r["source"] for r in results}):
        rows = [r for r in results if r["source"] == src]
        lines += ["### %s" % src, "",
                  "| segment | motion | moment levels [N m] | data [deg] | model [deg] | model/data | in ±1 SD | "
                  "corridor | phase | magnitude | slope | ISO 18571 |",
                  "|---|---|---|---|---|---|---|---|---|---|---|---|"]
        for r in rows:
            inside = "–"
            if r["lower"] is not None:
                k = int(np.sum((r["model"] >= r["lower"]) & (r["model"] <= r["upper"])))
                inside = "%d of %d" % (k, len(r["levels"]))
            s = r["iso"]
            lines.append("| %s | %s | %s | %s | %s | %s | %s | %.3f | %.3f | %.3f | %.3f | **%.3f** |" % (
                r["segment"].replace("_", "–"), r["motion"].replace("_", " "),
                " ".join("%+.2f" % v for v in r["levels"]), " ".join("%.3g" % v for v in r["data"]),
                " ".join("%.3g" % v for v in r["model"]),
                " ".join("%.2f" % v for v in _ratio(r["model"], r["data"])), inside,
                s["corridor"], s["phase"], s["magnitude"], s["slope"], s["overall"]))
        lines += ["", "Mean ISO/TS 18571 over the %d curves: **%.3f** (lowest %.3f, highest %.3f)." % (
            len(rows), np.mean([r["iso"]["overall"] for r in rows]), min(r["iso"]["overall"] for r in rows),
            max(r["iso"]["overall"] for r in rows)), ""]
        fig = figure(src, rows, figdir)
        if fig:
            lines += ["![%s: model (red) against the data (black)](%s)" % (src, os.path.relpath(fig, relto)), ""]
    return lines


def figure(src, rows, figdir):
    """One figure per source: every moment-rotation curve, model against data."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return None
    n = len(rows)
    cols = min(n, 7)
    nr = (n + cols - 1) // cols
    fig, axes = plt.subplots(nr, cols, figsize=(2.4 * cols, 2.2 * nr), squeeze=False)
    for ax, r in zip(axes.flat, rows):
        if r["lower"] is not None:
            ax.fill_between(r["levels"], r["lower"], r["upper"], color="0.85", label="±1 SD")
        ax.plot(r["grid"], r["reference"], "k-", lw=1.2, label="data")
        ax.plot(r["grid"], r["curve"], "r-", lw=1.0, label="model")
        ax.set_title("%s %s (%.2f)" % (r["segment"].replace("_", "-"), r["motion"].split("_")[0],
                                       r["iso"]["overall"]), fontsize=8)
        ax.tick_params(labelsize=6)
    for ax in list(axes.flat)[n:]:
        ax.axis("off")
    axes.flat[0].legend(fontsize=6)
    fig.supxlabel("moment [N m]", fontsize=8)
    fig.supylabel("rotation [deg]", fontsize=8)
    fig.tight_layout()
    out = os.path.join(figdir, "catalogue_%s.png" % src.split()[0].lower())
    fig.savefig(out, dpi=100)
    plt.close(fig)
    return out


def write_report(results, path, wall, jobs):
    """docs/catalogue.md: the cases, their scores against the goals, the
    figures (beside `path`) and the wall times."""
    d = os.path.dirname(os.path.abspath(path))
    seg = [r for r in results if r["source"] in ("Panjabi 2001", "Nightingale 2007")]
    night = [r for r in seg if r["lower"] is not None]
    inside = sum(int(np.sum((r["model"] >= r["lower"]) & (r["model"] <= r["upper"]))) for r in night)
    levels = sum(len(r["levels"]) for r in night)
    lines = ["# Validation catalogue", "",
             "Written by `hhneck-catalogue` (python/hhneck/catalogue.py); do not edit by hand. Every curve is "
             "rated by ISO/TS 18571 through `objective-rating-metrics` (the implementation the open human-body "
             "model catalogues use). Data: `shared/data/pmhs_neck` (its README: sources, signs, decisions).", "",
             "| source | kind | curves | mean ISO 18571 | goal | met |", "|---|---|---|---|---|---|"]
    for src in sorted({r["source"] for r in seg}):
        rows = [r for r in seg if r["source"] == src]
        met = "no: %d of %d levels inside ±1 SD" % (inside, levels) if src.startswith("Nightingale") else \
            "no ranges in the data (mean only); see model/data"
        lines.append("| %s | segment, pure moment | %d | %.3f | %s | %s |" % (
            src, len(rows), np.mean([r["iso"]["overall"] for r in rows]), GOAL_SEGMENT, met))
    lines += ["| Stemper 2004, Kang 2018 front and side | specimen sled | – | not yet in the catalogue | ≥ 0.75 "
              "each, no channel below 0.50 | not built: the potted-specimen decks and the T1 load-cell, "
              "segment-angle and 3-D head-angle channels are still to come |",
              "| NBDL 15 g, 12 g (and runs not in the repository) | volunteer sled (calibration) | 5 each | "
              "in docs/validation.md (`hhneck-compare-nbdl`: CORA-style 0.888 and 0.891, ISO/TS 18571 0.854 and "
              "0.845 when this was written) | ≥ 0.85 | CORA-style yes; ISO/TS 18571 at 15 g only |", ""]
    lines += segment_section(seg, d, d)
    lines += ["## Wall time", "",
              "%d cases in %.1f s wall time, %d runs at a time (the release build; each case's own run below)." % (
                  len(results), wall, jobs), "",
              "| case | wall time [s] |", "|---|---|"]
    lines += ["| %s %s %s | %.2f |" % (r["source"], r["segment"].replace("_", "–"), r["motion"].replace("_", " "),
                                       r["wall"]) for r in results]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return path


def main(argv=None):
    """hhneck-catalogue: run, rate and report every case of the catalogue."""
    p = argparse.ArgumentParser(prog="hhneck-catalogue", description=__doc__.split("\n\n")[0])
    p.add_argument("--quick", action="store_true", help="C4-C5 only for the segment tests (the test suite's form)")
    p.add_argument("--exe", help="the hhneck executable (default $HHNECK, else fpm's release build)")
    p.add_argument("--data", default=segments.DATA_DIR, help="the pmhs_neck data folder")
    p.add_argument("--out", help="working directory for the decks, listings and result files")
    p.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="runs at a time (default: the cores)")
    p.add_argument("--report", default=REPORT, help="the report to write (default docs/catalogue.md)")
    a = p.parse_args(argv)
    t0 = time.perf_counter()
    results = segments.catalogue(a.exe, a.quick, a.data, a.out, a.jobs)
    wall = time.perf_counter() - t0
    write_report(results, a.report, wall, a.jobs)
    print("hhneck-catalogue: %d cases rated in %.1f s; report %s" % (len(results), wall, a.report),
          file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
