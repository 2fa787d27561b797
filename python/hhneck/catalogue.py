"""The validation catalogue: runs every case of it, rates each curve by
ISO/TS 18571 (objective-rating-metrics) and writes docs/catalogue.md with a
table and a figure per source.

Cases in it now: the quasi-static segment tests of Panjabi et al. 2001 (21
curves) and Nightingale et al. 2007 (3), set up by hhneck.segments; the
specimen sled tests of Stemper 2004 (rear, 7 channels, with three variants
of its set-up) and Kang 2018 (front and side, the head's 3 kinematic channels
and the T1 load cell's 3 each, with the settled start as a variant), set up
by hhneck.specimens. The NBDL volunteer sleds (15 g, 12 g) are run and rated
as hhneck-compare-nbdl rates them (docs/validation.md has their tables).
Under each Kang case, the Newton balance of its head and load cell
(hhneck.newton_balance), the data's and the model's. Under each case or
source that misses its goal, a "What stops it" line names what misses,
from this run's ratings (the mean's shortfall, every channel or curve
below 0.50 with the peaks), and links the sections of docs/validation.md
(STOPS) that give the experiments tried for it.

Command: hhneck-catalogue [--quick] [--exe HHNECK] [--jobs N] [--out DIR]
[--report docs/catalogue.md]. --quick runs one segment (C4-C5) per source
and motion: the form the test suite runs.
"""
import argparse
import os
import sys
import tempfile
import time

import numpy as np

from . import compare_nbdl, newton_balance, run, segments, specimens
from .compare_nbdl import s3

REPORT = os.path.join(segments.ROOT, "docs", "catalogue.md")
NBDL_GOAL = 0.85        # CORA-style, at both severities (the goal of the catalogue)
GOAL_SEGMENT = "the model's rotation inside the reported range at every level, direction and moment"


def _ratio(model, data):
    return np.where(np.abs(data) > 1e-9, model / np.where(np.abs(data) > 1e-9, data, 1.0), np.nan)


def segment_section(results, figdir, relto):
    """Markdown lines of the segment cases: per source a table (rotation at
    each moment level, data against model, the ISO/TS 18571 scores of the
    moment-rotation curve) and a figure written to figdir."""
    lines = ["## Segment tests (quasi-static pure moments)", "",
             "**Calibration**: the model deck's neutral-zone springs (NZSPRING cards) are fitted to these "
             "data by `hhneck-fit-joints` (the other elements' moment subtracted, at the calibration's "
             "starting point; the NBDL calibration then moves the discs' and stops' factors, so the springs "
             "do not meet the data exactly); OC–C2 of Nightingale is not fitted (its joints take Panjabi's "
             "C0–C1 and C1–C2). Set-up and signs: "
             "`python/hhneck/segments.py` (its docstring): the lower body fixed, a pure moment ramped on "
             "the upper one (for OC–C2 on the head, C1 free), no gravity, no muscles, the discs, ligaments, "
             "joint-limit dampers, range-of-motion elements and neutral-zone springs of the model deck "
             "joining the segment's bodies. Rotation of the upper body relative to the lower at each moment level on the loading "
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
        low = sorted((r for r in rows if r["iso"]["overall"] < CHANNEL_FLOOR), key=lambda r: r["iso"]["overall"])
        if low:
            lines += [stops_line(src, ["%d of the %d curves below %.2f: %s" % (
                len(low), len(rows), CHANNEL_FLOOR, ", ".join("%s %s %.3f" % (
                    r["segment"].replace("_", "–"), r["motion"].replace("_", " "), r["iso"]["overall"])
                    for r in low))]), ""]
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


SPECIMEN_NOTES = {
    "Stemper 2004 rear 1.8 m/s": "the source's T1 pulse, gravity down, muscles passive (activation zero), T1 tilted to the source's "
    "25 deg slope, the start posture held by HOLD POSTURE through the test: generalized forces on each joint's relative "
    "coordinates, a pre-stress of the joints (a load pair between its two bodies, no external support), the preload "
    "the specimens stood in when the labs cut their positioning cables (released at the pulse instead, the model's "
    "unstressed neutral starts in free fall: a variant below). "
    "Reference: the corridor "
    "outline's midline; ISO/TS 18571 over the 0.3–126 ms the corridors cover.",
    "Kang 2018 front 14 km/h": "T1 potted and driven rearward by the source's pulse, muscles passive, posture "
    "held as for Stemper, T1 tilted to 24 deg, SAE J211 axes; the head's accelerations as its accelerometer reads them "
    "(the specific force a - g in the head's axes, from its value at t = 0: HEAD_AXS ...; in the lab's axes they score "
    "lower, studies/kang_head_frame.py); the load cell a LOADCELL card cutting the potted T1 from C7 (the load on "
    "the neck and head, in T1's axes) about the potting centre as the set-up placed it (81 mm behind, 229 mm below "
    "the head's mass centre), from its value at t = 0 (the data are tared); every model channel then filtered by the "
    "class the source's notebook gives the SAFER HBM's (head x-acceleration and cell forces CFC 60, the rest CFC 180), "
    "as its rating beside ours was made. Reference: the corridor's midline; window 0 to 1.2 × the time of its "
    "largest magnitude (the source notebook's).",
    "Kang 2018 side 14 km/h": "T1 driven toward the specimen's right (the direction the data's signs fit), "
    "otherwise (load cell included) as the front case. Reference: the mean of PMHS1 and PMHS2; window as the front case.",
}
#: the SAFER HBM v11's published ISO/TS 18571 on a case (mean of its channels), where there is one
SAFER = {"Kang 2018 side 14 km/h": "0.684 (6 channels: kinematics 0.75, loads 0.62)"}
#: the sections of docs/validation.md that say, per case or source, what stops it and what was tried
#: for it with what each experiment changed (the report links them under each case that misses its goal)
KANG_SECTION = "The Kang cases: the head's accelerometer, and the neck's own inertia in the load cell"
SUBAXIAL_SECTION = "The subaxial discs' flexion–extension"
SEGMENT_SECTIONS = ("Neutral-zone springs, and which fit predicts better", SUBAXIAL_SECTION,
                    "The upper cervical joints")
STOPS = {"Stemper 2004 rear 1.8 m/s": ("What is not validated, and what limits the fit", SUBAXIAL_SECTION),
         "Kang 2018 front 14 km/h": (KANG_SECTION,), "Kang 2018 side 14 km/h": (KANG_SECTION,),
         "Panjabi 2001": SEGMENT_SECTIONS, "Nightingale 2007": SEGMENT_SECTIONS}
CASE_GOAL = 0.75        # the specimen goal: the mean over a case's channels at least this ...
CHANNEL_FLOOR = 0.50    # ... and no channel below it; the curves listed under a source below it
GOAL_SPECIMEN = "≥ %.2f, no channel below %.2f" % (CASE_GOAL, CHANNEL_FLOOR)


def case_summary(rated):
    """(mean, lowest channel, whether the specimen goal is met) of a case's
    ratings ({channel: ISO/TS 18571 scores})."""
    mean = float(np.mean([v["overall"] for v in rated.values()]))
    low = min(rated, key=lambda c: rated[c]["overall"])
    return mean, low, mean >= CASE_GOAL and rated[low]["overall"] >= CHANNEL_FLOOR


def anchor(heading):
    """The link fragment a Markdown renderer (GitHub's) gives a heading."""
    out = "".join(c for c in heading.lower() if c.isalnum() or c in " -_")
    return "#" + out.replace(" ", "-")


def stops_line(title, misses):
    """The report's line under a case that misses its goal: what misses
    (computed from this run's ratings) and the link to what was tried."""
    return "**What stops it**: %s. What was tried, and what each experiment changed: docs/validation.md, %s." % (
        "; ".join(misses), ", ".join("[\"%s\"](validation.md%s)" % (h, anchor(h)) for h in STOPS[title]))


def newton_lines(rows):
    """Markdown lines of a Kang case's Newton balance (newton_balance.kang_rows)."""
    lines = ["Newton's law between the head and the load cell (`hhneck.newton_balance`): F = Mh a_head(t + s) + "
             "Mn a_T1(t) fitted by least squares along each axis, the lag s on a 0.5 ms grid; channels on one time "
             "base fit near s = 0 with Mh near a head's mass, and the model's rows, which obey the law by "
             "construction, check the method (docs/validation.md, \"Do the specimens' head and load cell obey "
             "Newton's law together?\"):", "",
             "| axis | curves | window (ms) | lag s (ms) | Mh (kg) | Mn (kg) | R² | at s = 0: Mh, Mn (kg), R² |",
             "|---|---|---|---|---|---|---|---|"]
    for k in range(len(rows["model"])):
        for label in ("model", "specimens"):
            r = rows[label][k]
            (r2, lag, mh, mn), (r20, _, mh0, mn0) = r["best"], r["at_zero"]
            lines.append("| %s | %s | 0–%.0f | %+.1f | %s | %s | %.3f | %s, %s, %.3f |" % (
                r["axis"], label, r["window"][1], lag, s3(mh), s3(mn), r2, s3(mh0), s3(mn0), r20))
    return lines + [""]


def specimen_section(cases, variants, figdir, relto, newton=None):
    """Markdown lines of the specimen cases: per case the ISO/TS 18571 scores
    and peaks of every rated channel, the channels not rated, a figure, the
    Newton balance of its head and load cell where given (newton: {title:
    newton_balance.kang_rows}); its set-up variants' means (variants:
    {title: {(support, muscles): rated}})."""
    lines = ["## Specimen sled tests", "",
             "**Prediction**: nothing of the model was fitted to these data; set-ups in "
             "`python/hhneck/specimens.py` (its docstring names each decision of the data's README).", ""]
    for title, (rated, not_rated) in cases.items():
        lines += ["### %s" % title, "", SPECIMEN_NOTES[title], "",
                  "| channel | corridor | phase | magnitude | slope | ISO 18571 | model peak (at ms) | "
                  "reference peak (at ms) | time inside the corridor or specimens |", "|---|---|---|---|---|---|---|---|---|"]
        for ch, sc in rated.items():
            lines.append("| %s | %.3f | %.3f | %.3f | %.3f | **%.3f** | %.3g (%.0f) | %.3g (%.0f) | %.0f %% |" % (
                ch, sc["corridor"], sc["phase"], sc["magnitude"], sc["slope"], sc["overall"], sc["peak_model"][0],
                sc["peak_model"][1], sc["peak_ref"][0], sc["peak_ref"][1], 100 * sc["inside"]))
        mean, low, met = case_summary(rated)
        lines += ["", "Mean over the %d rated channels: **%.3f** (goal %s: %s; the "
                  "lowest, %s, %.3f).%s%s" % (
                      len(rated), mean, GOAL_SPECIMEN.replace(", ", " with "), "met" if met else "not met", low,
                      rated[low]["overall"],
                      " Not rated: %s." % ", ".join(not_rated)
                      if not_rated else "",
                      " The SAFER HBM's published score: %s." % SAFER[title] if title in SAFER else ""), ""]
        if not met:
            misses = ["the mean %.3f, %.3f below %.2f" % (mean, CASE_GOAL - mean, CASE_GOAL)] \
                if mean < CASE_GOAL else []
            misses += ["%s %.3f (the model's peak %.3g at %.0f ms, the reference's %.3g at %.0f ms)" % (
                ch, sc["overall"], sc["peak_model"][0], sc["peak_model"][1], sc["peak_ref"][0], sc["peak_ref"][1])
                for ch, sc in sorted(rated.items(), key=lambda kv: kv[1]["overall"]) if sc["overall"] < CHANNEL_FLOOR]
            lines += [stops_line(title, misses), ""]
        fig = _case_figure(title, rated, figdir)
        if fig:
            lines += ["![%s: model (red) against the data](%s)" % (title, os.path.relpath(fig, relto)), ""]
        if newton and title in newton:
            lines += newton_lines(newton[title])
        if variants.get(title):
            lines += ["Variants of the set-up (the same channels; experiments, not the shipped set-up; "
                      "specimens.py's SUPPORT):", "",
                      "| support | muscles | mean ISO 18571 | lowest channel |", "|---|---|---|---|"]
            for (sup, mus), r in variants[title].items():
                lowv = min(r, key=lambda c: r[c]["overall"])
                lines.append("| %s | %s | %.3f | %s %.3f |" % (
                    sup, mus, np.mean([v["overall"] for v in r.values()]), lowv, r[lowv]["overall"]))
            lines.append("")
    return lines


def _case_figure(title, rated, figdir):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return None
    n = len(rated)
    fig, axes = plt.subplots(1, n, figsize=(2.45 * n, 2.6), squeeze=False)
    for ax, (ch, sc) in zip(axes.flat, rated.items()):
        ax.fill_between(sc["grid"], sc["lower"], sc["upper"], color="0.85", label="corridor or specimens")
        ax.plot(sc["grid"], sc["reference"], "k-", lw=1.0, label="reference")
        ax.plot(sc["grid"], sc["model"], "r-", lw=1.0, label="model")
        ax.set_title("%s (%.2f)" % (ch.replace("seg_angle_", "").replace("head_T1_", "head-T1 "), sc["overall"]),
                     fontsize=8)
        ax.tick_params(labelsize=6)
    axes.flat[0].legend(fontsize=6)
    fig.supxlabel("time [ms]", fontsize=8)
    fig.tight_layout()
    out = os.path.join(figdir, "catalogue_%s.png" % "_".join(title.lower().split()[:3:2]))
    fig.savefig(out, dpi=100)
    plt.close(fig)
    return out


def nbdl_scores(exe=None, workdir=None):
    """The NBDL 15 g and 12 g decks run and rated as hhneck-compare-nbdl
    rates them: {"15g", "12g": dict(cora, iso (the mean ISO/TS 18571 of the
    rated channels), peaks (within 1 SD), npeaks)}."""
    work = workdir or tempfile.mkdtemp(prefix="hhneck-catalogue-nbdl-")
    os.makedirs(work, exist_ok=True)
    out = {}
    for sev in ("15g", "12g"):
        h5 = run.run_deck(os.path.join(segments.ROOT, "input", "nbdl%s.inp" % sev), executable=exe,
                          h5=os.path.join(work, "nbdl%s.h5" % sev), cwd=segments.ROOT).h5
        chans, peaks, overall = compare_nbdl.compare(sev, h5)[:3]
        out[sev] = dict(cora=float(overall), iso=float(np.mean([c["iso"] for c in chans if c["rated"]])),
                        peaks=sum(bool(p["ok_peak"]) for p in peaks), npeaks=len(peaks))
    return out


def write_report(results, path, wall, jobs, specimen_cases=None, variants=None, nbdl=None, newton=None):
    """docs/catalogue.md: the cases, their scores against the goals, the
    figures (beside `path`) and the wall times; nbdl: nbdl_scores();
    newton: {title: newton_balance.kang_rows}."""
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
    for title, (rated, _) in (specimen_cases or {}).items():
        smean, slow, met = case_summary(rated)
        lines.append("| %s | specimen sled | %d | %.3f | %s | %s (lowest channel %.3f)%s |"
                     % (title, len(rated), smean, GOAL_SPECIMEN, "yes" if met else "no", rated[slow]["overall"],
                        "; SAFER HBM %s" % SAFER[title] if title in SAFER else ""))
    if nbdl:
        good = all(v["cora"] >= NBDL_GOAL for v in nbdl.values())
        lines.append("| NBDL 15 g (prediction), 12 g (calibration) | volunteer sled | 5 each | %s | CORA-style "
                     "≥ 0.85 (and on the runs not in the repository) | %s |" % (
                         "; ".join("%s %.3f (CORA-style %.3f, %d of %d head peaks within 1 SD)" % (
                             sev.replace("g", " g"), v["iso"], v["cora"], v["peaks"], v["npeaks"])
                                   for sev, v in nbdl.items()),
                         "yes on these two; the runs not in the repository are not rated here" if good else "no"))
    lines.append("")
    lines += segment_section(seg, d, d)
    if specimen_cases:
        lines += specimen_section(specimen_cases, variants or {}, d, d, newton)
    lines += ["## Wall time", "",
              "%d segment cases and the specimen runs in %.1f s wall time, segment runs %d at a time (the "
              "release build; each segment case's own run below)." % (len(results), wall, jobs), "",
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
    work = a.out or None
    cases = {"Stemper 2004 rear 1.8 m/s": (specimens.rate_stemper(specimens.run_stemper(work, a.exe), a.data), [])}
    newton = {}
    for d in ("front", "side"):
        title = "Kang 2018 %s 14 km/h" % d
        model = specimens.run_kang(d, work, a.exe)
        cases[title] = (specimens.rate_kang(d, model, a.data), [])
        newton[title] = newton_balance.kang_rows(d, model, a.data)
    variants = {}
    if not a.quick:
        stemper = "Stemper 2004 rear 1.8 m/s"
        variants[stemper] = {(sup, mus): specimens.rate_stemper(specimens.run_stemper(work, a.exe, sup, mus), a.data)
                             for sup, mus in (("RELEASE", "PASSIVE"), ("HOLD", "REFLEX"), ("PRESTRAIN", "PASSIVE"))}
        for d in ("front", "side"):
            variants["Kang 2018 %s 14 km/h" % d] = {("PRESTRAIN", "PASSIVE"): specimens.rate_kang(
                d, specimens.run_kang(d, work, a.exe, "PRESTRAIN"), a.data)}
    nbdl = nbdl_scores(a.exe, os.path.join(work, "nbdl") if work else None)
    wall = time.perf_counter() - t0
    write_report(results, a.report, wall, a.jobs, cases, variants, nbdl, newton)
    print("hhneck-catalogue: %d cases rated in %.1f s; report %s" % (len(results), wall, a.report),
          file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
