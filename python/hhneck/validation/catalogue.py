"""The validation catalogue: runs every case of it, rates each curve by
ISO/TS 18571 (objective-rating-metrics) and writes a report with a table
and a figure per source (docs/catalogue.md when asked for it).

Cases in it now: the quasi-static segment tests of Panjabi et al. 2001 (21
curves) and Nightingale et al. 2007 (3), set up by hhneck.validation.segments; the
specimen sled tests of Stemper 2004 (rear, 7 channels, with three variants
of its set-up) and Kang 2018 (front and side, the head's 3 kinematic channels
and the T1 load cell's 3 each, with the settled start as a variant), set up
by hhneck.validation.specimens from their case files (reference/cases, or the folder
--cases names; docs/case-files.md): every rated case file of the folder is
built, run and rated, so a new direction or severity is a new file. The NBDL volunteer sleds (15 g, 12 g) are run and rated
as hhneck-compare-nbdl rates them (docs/validation.md has their tables).
Under each Kang case, the Newton balance of its head and load cell
(hhneck.validation.newton_balance), the data's and the model's. Under each case or
source that misses its goal, a "What stops it" line names what misses,
from this run's ratings (the mean's shortfall, every channel or curve
below 0.50 with the peaks), and links the sections of docs/validation.md
(STOPS) that give the experiments tried for it. A section lists the
warnings the runs printed on their stderr (joints past their range, the
energy balance).

Command: hhneck-catalogue [--quick] [--exe HHNECK] [--jobs N] [--out DIR]
[--cases DIR] [--report FILE | --update-docs]. The report goes to catalogue/catalogue.md
in the current directory (its figures beside it), to FILE with --report,
and to the project's docs/catalogue.md only with --update-docs (or
--report docs/catalogue.md); the default never writes into the project's
docs. The report's folder (and --out) is created and checked before any
run; a folder that cannot be written stops the command at once (exit 2).
The report is rewritten as each case ends (its figures at the end), so an
interrupted run (Ctrl-C: exit 130) or a failed case (exit 1, the other
cases run on) leaves a report of every case done, with a line saying what
is missing. A progress line per case on stderr. The runs' decks, listings,
stderr (NAME.err) and result files go to --out, or to a temporary folder
removed after a complete run. --quick runs one segment (C4-C5) per source
and motion and no set-up variants: the form the test suite runs.
"""
import argparse
import os
import shutil
import sys
import tempfile
import time

import numpy as np

from .. import ratings, run
from . import newton_balance, segments, specimens
from ..ratings import s3

REPORT = os.path.join(segments.ROOT, "docs", "catalogue.md")
NBDL_GOAL = 0.85        # CORA-style, at both severities (the goal of the catalogue)
NBDL_REQUIRED = 0.80    # CORA-style, at both severities (what the model must reach)
#: the segment sources' required mean ISO/TS 18571: the SAFER HBM v11's on the
#: same rating (the specimen cases' are their case files' `required`)
SEGMENT_REQUIRED = {"Nightingale 2007": 0.586, "Panjabi 2001": 0.389}
GOAL_SEGMENT = "the model's rotation inside the reported range at every level, direction and moment"


def _ratio(model, data):
    return np.where(np.abs(data) > 1e-9, model / np.where(np.abs(data) > 1e-9, data, 1.0), np.nan)


def segment_section(results, figdir, relto):
    """Markdown lines of the segment cases: per source a table (rotation at
    each moment level, data against model, the ISO/TS 18571 scores of the
    moment-rotation curve) and a figure written to figdir."""
    lines = ["## Segment tests (quasi-static pure moments)", "",
             "**Calibration**: the passive column is fitted to these data alone (`python3 -m "
             "hhneck.validation.fit_column`: the discs' bending and torsion fractions and the range-of-motion factors "
             "to the two sources' mean ISO/TS 18571, the tests solved as statics, the neutral-zone springs "
             "refitted by `python3 -m hhneck.validation.fit_joints` at every candidate, the other elements' "
             "moment subtracted); "
             "the springs of OC–C2's joints take Panjabi's C0–C1 and C1–C2. Set-up and signs: "
             "`python/hhneck/validation/segments.py` (its docstring): the lower body fixed, a pure moment ramped on "
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


def _pyplot(figdir):
    """matplotlib.pyplot on the Agg backend; None when figdir is None (no
    figures asked for) or matplotlib is missing."""
    if figdir is None:
        return None
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return None
    return plt


def figure(src, rows, figdir):
    """One figure per source: every moment-rotation curve, model against
    data (None when figdir is None)."""
    plt = _pyplot(figdir)
    if plt is None:
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


#: each specimen case's set-up as the report states it, the SAFER HBM v11's
#: published ISO/TS 18571 on it (mean of its channels) where there is one, and
#: the sections of docs/validation.md that say what stops it and what was tried
#: for it with what each experiment changed (the report links them under each
#: case that misses its goal): from the case files (register_case)
SPECIMEN_NOTES, SAFER, REQUIRED = {}, {}, dict(SEGMENT_REQUIRED)
SUBAXIAL_SECTION = "The subaxial discs' flexion–extension"
SEGMENT_SECTIONS = ("Neutral-zone springs, and which fit predicts better", SUBAXIAL_SECTION,
                    "The upper cervical joints")
STOPS = {"Panjabi 2001": SEGMENT_SECTIONS, "Nightingale 2007": SEGMENT_SECTIONS}


def register_case(case):
    """Take a case file's report texts (its note, SAFER score, required score
    and sections of what stops it; hhneck.validation.specimens.load_case) into
    the report's tables."""
    SPECIMEN_NOTES[case["title"]] = case["note"]
    if case["required"]:
        REQUIRED[case["title"]] = case["required"]
    if case["safer"]:
        SAFER[case["title"]] = case["safer"]
    STOPS[case["title"]] = tuple(case["stops"])


list(map(register_case, specimens.CASES.values()))


CASE_GOAL = 0.75        # the specimen goal: the mean over a case's channels at least this ...
CHANNEL_FLOOR = 0.50    # ... and no channel below it; the curves listed under a source below it
GOAL_SPECIMEN = "≥ %.2f, no channel below %.2f" % (CASE_GOAL, CHANNEL_FLOOR)


def met_cell(score, required):
    """The summary's "met" cell of a score against what is required: yes or
    no, with the margin to three significant digits (a score a rounding
    would put on the target shows on which side it is)."""
    return "%s (%+.3g)" % ("yes" if score >= required else "no", score - required)


def required_cells(title, score):
    """The summary's "required" and "met" cells of a source or case: its
    required score (REQUIRED) and whether `score` reaches it."""
    if title not in REQUIRED:
        return "none given | —"
    return "≥ %.3f (SAFER HBM v11) | %s" % (REQUIRED[title], met_cell(score, REQUIRED[title]))


def segment_goal_cell(inside, levels):
    """The summary's goal cell of a segment source with ranges: yes when the
    model's rotation is inside ±1 SD at every one of its `levels`, else no,
    with how many are."""
    return "%s: %d of %d levels inside ±1 SD" % ("yes" if inside == levels else "no", inside, levels)


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
    tried = STOPS.get(title)
    if not tried:
        return "**What stops it**: %s." % "; ".join(misses)
    return "**What stops it**: %s. What was tried, and what each experiment changed: docs/validation.md, %s." % (
        "; ".join(misses), ", ".join("[\"%s\"](validation.md%s)" % (h, anchor(h)) for h in tried))


def newton_lines(rows):
    """Markdown lines of a Kang case's Newton balance (newton_balance.kang_rows)."""
    lines = ["Newton's law between the head and the load cell (`hhneck.validation.newton_balance`): "
             "F = Mh a_head(t + s) + "
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
             "the case files of `reference/cases` (docs/case-files.md), built by "
             "`python/hhneck/validation/specimens.py` "
             "(its docstring names each decision of the data's README).", ""]
    for title, (rated, not_rated) in cases.items():
        lines += ["### %s" % title, "", SPECIMEN_NOTES.get(title) or "(no set-up note in its case file)", "",
                  "| channel | corridor | phase | magnitude | slope | ISO 18571 | model peak (at ms) | "
                  "reference peak (at ms) | time inside the corridor or specimens |", "|---|---|---|---|---|---|---|---|---|"]
        for ch, sc in rated.items():
            lines.append("| %s | %.3f | %.3f | %.3f | %.3f | **%.3f** | %.3g (%.0f) | %.3g (%.0f) | %.0f %% |" % (
                ch, sc["corridor"], sc["phase"], sc["magnitude"], sc["slope"], sc["overall"], sc["peak_model"][0],
                sc["peak_model"][1], sc["peak_ref"][0], sc["peak_ref"][1], 100 * sc["inside"]))
        mean, low, met = case_summary(rated)
        cut = ["%s to %.1f ms of %.1f" % (ch, sc["window"][1], sc["reference_end"]) for ch, sc in rated.items()
               if sc.get("reference_end", sc["grid"][-1]) > sc["grid"][-1] + 1e-6]
        if cut:
            lines += ["", "Rated to the run's end, where the reference runs past it: %s ms." % ", ".join(cut)]
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
    plt = _pyplot(figdir)
    if plt is None:
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


def nbdl_score(sev, exe=None, workdir=None):
    """One NBDL deck (sev "15g" or "12g") run and rated as
    hhneck-compare-nbdl rates it: dict(cora, iso (the mean ISO/TS 18571 of
    the rated channels), peaks (within 1 SD), npeaks, warnings (its run's,
    its stderr kept in workdir as nbdlSEV.err))."""
    work = workdir or tempfile.mkdtemp(prefix="hhneck-catalogue-nbdl-")
    os.makedirs(work, exist_ok=True)
    r = run.run_deck(os.path.join(segments.ROOT, "input", "nbdl%s.inp" % sev), executable=exe,
                     h5=os.path.join(work, "nbdl%s.h5" % sev), cwd=segments.ROOT)
    with open(os.path.join(work, "nbdl%s.err" % sev), "w") as f:
        f.write(r.stderr)
    chans, peaks, overall = ratings.compare(sev, r.h5)[:3]
    return dict(cora=float(overall), iso=float(np.mean([c["iso"] for c in chans if c["rated"]])),
                peaks=sum(bool(p["ok_peak"]) for p in peaks), npeaks=len(peaks),
                warnings=segments.warning_lines(r.stderr))


def warnings_section(warnings):
    """Markdown lines of the runs' warnings (warnings: [(case, line)], the
    WARNING lines of each run's stderr: joints past their range, the
    energy balance)."""
    lines = ["## Warnings of the runs", ""]
    if not warnings:
        return lines + ["No run printed a warning on its stderr (joints past their range plus margin, the "
                        "energy balance, a long run).", ""]
    lines += ["Each run's stderr is kept beside its listing in the work folder (`--out`, NAME.err); its "
              "warning lines (a run's listing says which joints and when):", "",
              "| case | warning |", "|---|---|"]
    return lines + ["| %s | %s |" % (case, line.replace("|", "/")) for case, line in warnings] + [""]


def write_report(results, path, wall, jobs, specimen_cases=None, variants=None, nbdl=None, newton=None,
                 warnings=None, status=None, figures=True):
    """The catalogue's report at `path` (docs/catalogue.md when asked): the
    cases, their scores against the goals, the figures (beside `path`,
    unless figures is False), the runs' warnings and the wall times; nbdl:
    {sev: nbdl_score()}; newton: {title: newton_balance.kang_rows};
    warnings: [(case, line)]; status: None for a complete run, else the
    line that says what is missing (an interrupted or failed run). Written
    to a temporary file and renamed, so a report is never half written."""
    d = os.path.dirname(os.path.abspath(path))
    figdir = d if figures else None
    seg = [r for r in results if r["source"] in ("Panjabi 2001", "Nightingale 2007")]
    night = [r for r in seg if r["lower"] is not None]
    inside = sum(int(np.sum((r["model"] >= r["lower"]) & (r["model"] <= r["upper"]))) for r in night)
    levels = sum(len(r["levels"]) for r in night)
    lines = ["# Validation catalogue", "",
             "Written by `hhneck-catalogue` (python/hhneck/validation/catalogue.py); do not edit by hand. "
             "Every curve is "
             "rated by ISO/TS 18571 through `objective-rating-metrics` (the implementation the open human-body "
             "model catalogues use). Data: `shared/data/pmhs_neck` (its README: sources, signs, decisions).", ""]
    if status:
        lines += ["**Incomplete**: %s" % status, ""]
    lines += ["| source | kind | curves | mean ISO 18571 | required | met | goal | met |",
              "|---|---|---|---|---|---|---|---|"]
    for src in sorted({r["source"] for r in seg}):
        rows = [r for r in seg if r["source"] == src]
        met = segment_goal_cell(inside, levels) if src.startswith("Nightingale") else \
            "no ranges in the data (mean only); see model/data"
        smean = float(np.mean([r["iso"]["overall"] for r in rows]))
        lines.append("| %s | segment, pure moment | %d | %.3f | %s | %s | %s |" % (
            src, len(rows), smean, required_cells(src, smean), GOAL_SEGMENT, met))
    for title, (rated, _) in (specimen_cases or {}).items():
        smean, slow, met = case_summary(rated)
        lines.append("| %s | specimen sled | %d | %.3f | %s | %s | %s (lowest channel %.3f)%s |"
                     % (title, len(rated), smean, required_cells(title, smean), GOAL_SPECIMEN, "yes" if met else "no",
                        rated[slow]["overall"], "; SAFER HBM %s" % SAFER[title] if title in SAFER else ""))
    if nbdl:
        good = all(v["cora"] >= NBDL_GOAL for v in nbdl.values())
        low = min(v["cora"] for v in nbdl.values())
        lines.append("| NBDL %s | volunteer sled | 5 each | %s | CORA-style ≥ %.2f | %s | CORA-style "
                     "≥ %.2f (and on the runs not in the repository) | %s |" % (
                         ", ".join("%s g (%s)" % (sev[:-1], NBDL_ROLE[sev]) for sev in nbdl),
                         "; ".join("%s %.3f (CORA-style %.3f, %d of %d head peaks within 1 SD)" % (
                             sev.replace("g", " g"), v["iso"], v["cora"], v["peaks"], v["npeaks"])
                                   for sev, v in nbdl.items()),
                         NBDL_REQUIRED, met_cell(low, NBDL_REQUIRED), NBDL_GOAL,
                         "yes on %s; the runs not in the repository are not rated here" % (
                             "these two" if len(nbdl) == 2 else "this one") if good else
                         "no (lowest CORA-style %.3f, %.3g short)" % (low, NBDL_GOAL - low)))
    lines.append("")
    if seg:
        lines += segment_section(seg, figdir, d)
    if specimen_cases:
        lines += specimen_section(specimen_cases, variants or {}, figdir, d, newton)
    lines += warnings_section(warnings or [])
    lines += ["## Wall time", "",
              "%d segment cases and the specimen runs in %.1f s wall time, segment runs %d at a time (the "
              "release build; each segment case's own run below)." % (len(results), wall, jobs), "",
              "| case | wall time [s] |", "|---|---|"]
    lines += ["| %s %s %s | %.2f |" % (r["source"], r["segment"].replace("_", "–"), r["motion"].replace("_", " "),
                                       r["wall"]) for r in results]
    part = path + ".part"
    with open(part, "w") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(part, path)
    return path


#: the role of each NBDL severity in the model's calibration (the catalogue's summary row)
NBDL_ROLE = {"15g": "prediction", "12g": "calibration"}
#: the report written with no option: in the folder the command runs in, never the project's docs
DEFAULT_REPORT = os.path.join("catalogue", "catalogue.md")


def report_path(report=None, update_docs=False, cwd=None):
    """The report's path: --report's, docs/catalogue.md with --update-docs,
    else DEFAULT_REPORT in cwd (the current directory). ValueError when
    both options name different files, or when the default would land in
    the project's docs folder (run it elsewhere, or ask for the docs)."""
    if update_docs:
        if report and os.path.abspath(report) != REPORT:
            raise ValueError("--update-docs writes %s; --report names another file (%s)" % (REPORT, report))
        return REPORT
    if report:
        return os.path.abspath(report)
    path = os.path.abspath(os.path.join(cwd or os.getcwd(), DEFAULT_REPORT))
    docs = os.path.dirname(REPORT)
    if os.path.commonpath([path, docs]) == docs:
        raise ValueError("the default report %s would be inside the project's docs: run from another folder, "
                         "or name the report (--report FILE, --update-docs)" % path)
    return path


def writable_folder(path, what):
    """Create the folder `path` (and its parents) if missing and check that a
    file can be written in it; ValueError naming the folder and why not."""
    try:
        os.makedirs(path, exist_ok=True)
        with tempfile.NamedTemporaryFile(dir=path, prefix=".hhneck-catalogue-"):
            pass
    except OSError as e:
        raise ValueError("cannot write the %s folder %s: %s" % (what, path, e.strerror or e))
    return path


class Progress:
    """A catalogue run's results as they come, its progress lines (stderr)
    and its report rewritten as each case ends (write_report)."""

    def __init__(self, path, jobs, steps, total):
        self.path, self.jobs, self.pending, self.total = path, jobs, list(steps), total
        self.results, self.cases, self.variants, self.newton, self.nbdl = [], {}, {}, {}, {}
        self.warnings, self.failed = [], []
        self.t0 = time.perf_counter()
        self.done = 0

    def line(self, text):
        self.done += 1
        print("hhneck-catalogue: [%d/%d] %s (%.1f s)" % (self.done, self.total, text,
                                                         time.perf_counter() - self.t0), file=sys.stderr, flush=True)

    def warn(self, case, lines):
        self.warnings += [(case, w) for w in lines]

    def status(self, interrupted=None):
        """The report's "Incomplete" line, None when every step ran."""
        parts = []
        if interrupted:
            parts.append("interrupted during %s" % interrupted)
        parts += ["%s failed: %s" % (name, msg) for name, msg in self.failed]
        pending = [name for name in self.pending if name != interrupted]
        if pending:
            parts.append("not run: %s" % ", ".join(pending))
        return "; ".join(parts) + "." if parts else None

    def write(self, figures=False, interrupted=None):
        return write_report(self.results, self.path, time.perf_counter() - self.t0, self.jobs, self.cases,
                            self.variants, self.nbdl, self.newton, self.warnings, self.status(interrupted),
                            figures)


def catalogue_steps(a, work):
    """[(name, function(progress))] of a catalogue run, in order (options a:
    main's)."""
    def segment_cases(pr):
        def one(r):
            pr.results.append(r)
            label = "%s %s %s" % (r["source"], r["segment"].replace("_", "–"), r["motion"].replace("_", " "))
            pr.warn(label, r["warnings"])
            pr.line("%s: ISO 18571 %.3f" % (label, r["iso"]["overall"]))
            pr.write()
        order = segments.catalogue(a.exe, a.quick, a.data, os.path.join(work, "segments"), a.jobs, on_case=one)
        pr.results[:] = order

    def specimen(case, support=None, muscles=None):
        def step(pr):
            support_, muscles_ = support or case["support"], muscles or case["muscles"]
            title = case["title"]
            model = specimens.run_case(case, work, a.exe, support_, muscles_)
            rated = specimens.rate_case(case, model, a.data)
            if support is not None:
                pr.variants.setdefault(title, {})[support_, muscles_] = rated
            else:
                pr.cases[title] = (rated, [])
                if case["newton_balance"]:
                    pr.newton[title] = newton_balance.kang_rows(case["newton_balance"], model, a.data)
            label = title + (" (%s, muscles %s)" % (support_, muscles_) if support is not None else "")
            with open(os.path.join(work, specimens.run_name(case["name"], support_, muscles_) + ".err")) as f:
                pr.warn(label, segments.warning_lines(f.read()))
            pr.line("%s: mean ISO 18571 %.3f over %d channels" % (
                label, np.mean([v["overall"] for v in rated.values()]), len(rated)))
        return step

    def nbdl(sev):
        def step(pr):
            pr.nbdl[sev] = v = nbdl_score(sev, a.exe, os.path.join(work, "nbdl"))
            pr.warn("NBDL %s g" % sev[:-1], v["warnings"])
            pr.line("NBDL %s g: CORA-style %.3f, ISO 18571 %.3f" % (sev[:-1], v["cora"], v["iso"]))
        return step

    cases = [c for c in specimens.load_cases(a.cases) if c["rated"]]
    for c in cases:
        register_case(c)
    steps = [("the segment tests", segment_cases)] + [(c["title"], specimen(c)) for c in cases]
    if not a.quick:
        steps += [("%s, %s %s" % ((c["title"],) + v), specimen(c, *v))
                  for c in cases for v in c["variants"]]
    return steps + [("NBDL %s g" % sev[:-1], nbdl(sev)) for sev in ("15g", "12g")]


def main(argv=None):
    """hhneck-catalogue: run, rate and report every case of the catalogue."""
    p = argparse.ArgumentParser(prog="hhneck-catalogue", description=__doc__.split("\n\n")[0])
    p.add_argument("--quick", action="store_true", help="C4-C5 only for the segment tests, no set-up variants "
                   "(the test suite's form)")
    p.add_argument("--exe", help="the hhneck executable (default $HHNECK, else fpm's release build)")
    p.add_argument("--data", default=segments.DATA_DIR, help="the pmhs_neck data folder")
    p.add_argument("--cases", default=specimens.CASES_DIR, help="the folder of the specimen case files "
                   "(docs/case-files.md; default reference/cases)")
    p.add_argument("--out", help="working directory for the decks, listings, stderr and result files "
                   "(default: a temporary folder, removed after a complete run)")
    p.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="runs at a time (default: the cores)")
    p.add_argument("--report", help="the report to write, its figures beside it (default: %s in the current "
                   "directory)" % DEFAULT_REPORT)
    p.add_argument("--update-docs", action="store_true",
                   help="write the project's committed report, docs/catalogue.md, and its figures")
    a = p.parse_args(argv)
    try:
        path = report_path(a.report, a.update_docs)
        writable_folder(os.path.dirname(path), "report")
        if a.out:
            writable_folder(a.out, "work")
        if not os.path.isdir(a.data):
            raise ValueError("no data folder %s (--data)" % a.data)
        if not os.path.isdir(a.cases):
            raise ValueError("no case folder %s (--cases)" % a.cases)
        specimens.load_cases(a.cases)
        a.exe = a.exe or segments.default_executable()
    except (ValueError, RuntimeError) as e:
        print("hhneck-catalogue: %s" % e, file=sys.stderr)
        return 2
    work = a.out or tempfile.mkdtemp(prefix="hhneck-catalogue-")
    steps = catalogue_steps(a, work)
    total = len(segments.case_list(a.quick, a.data)) + len(steps) - 1
    pr = Progress(path, a.jobs, [name for name, _ in steps], total)
    print("hhneck-catalogue: %d cases; report %s, runs in %s" % (total, path, work), file=sys.stderr)
    for name, step in steps:
        try:
            step(pr)
        except KeyboardInterrupt:
            pr.write(figures=True, interrupted=name)
            print("hhneck-catalogue: interrupted during %s; the report %s keeps the cases done, the runs are "
                  "in %s" % (name, path, work), file=sys.stderr)
            return 130
        except (Exception, SystemExit) as e:
            pr.failed.append((name, " ".join(str(e).split())[:300] or type(e).__name__))
            pr.line("%s FAILED: %s" % (name, pr.failed[-1][1]))
        pr.pending.remove(name)
        pr.write()
    pr.write(figures=True)
    wall = time.perf_counter() - pr.t0
    if pr.failed:
        print("hhneck-catalogue: %d of %d steps failed (%s); report %s, runs kept in %s" % (
            len(pr.failed), len(steps), ", ".join(n for n, _ in pr.failed), path, work), file=sys.stderr)
        return 1
    if not a.out:
        shutil.rmtree(work, ignore_errors=True)
    print("hhneck-catalogue: %d segment cases and %d other steps rated in %.1f s; report %s" % (
        len(pr.results), len(steps) - 1, wall, path), file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
