"""Quasi-static segment tests of the catalogue: Panjabi et al. 2001 (single
functional spinal units C0-C1 ... C6-C7, pure moments to 1 N m in
flexion-extension, lateral bending and axial rotation) and Nightingale et
al. 2007 (OC-C2, C4-C5, C6-C7, flexion and extension to 3.5 N m); data in
shared/data/pmhs_neck (its README gives sources, signs and the decisions
taken below).

The set-up, as the labs tested (README "Ambiguities" 9): the lower body of
the segment is fixed (its six coordinates locked, its frame the lab's), the
upper body (for OC-C2: C1 and the head) is free in all six coordinates, a
pure moment about one of the lower body's axes is ramped on the upper body
(COUPLE card, frame R), no gravity, no muscles (the specimens were cleaned
of them), and only the elements joining the specimen's bodies: the discs,
ligaments, joint-limit dampers, range-of-motion resistance and neutral-zone
springs (NZSPRING) of the model deck, with its SCALE factors of those
families. write_deck and run_case can drop given cards (drop=("NZSPRING",):
the other elements alone, as hhneck.validation.fit_joints needs them). The deck is written
from the model deck (input/head_neck_54dof.inp) card for card, nothing
retyped, so a change of the model is a change of every segment test.

Moment protocol (one run per segment and axis): 0 -> +M over 20 s, held
2 s, -> 0 at 42 s, -> -M at 62 s, held to 64 s. The rotation at a moment
level is read on the loading ramps (t = RAMP level/M and T_NEG + RAMP
|level|/M). Quasi-static enough: the discs' viscous terms (retardation
time d2b/d1, which carries S1's damping coefficient on the discs' share of
the stiffness) lag the rotation on the ramps; the statics below are the
ramps' zero-rate limit, on which the column is fitted and the catalogue
rates it.
The calibration's protocol (protocol="sweep", hhneck.validation.calibration): 0 -> -M
over 20 s, held 2 s, -M -> +M over 40 s (t = SWEEP_START .. SWEEP_START +
2 RAMP), held to 64 s: the whole moment-rotation curve on one rising ramp,
rotation as a function of time as the calibration's reference rows need it
(the negative branch read unloading from -M, as a cyclic test passes it; the
catalogue's loading branches differ from it by the viscous lag only).

The catalogue solves each test as statics (SOLUTIONS "statics", the
default: the tests are quasi-static, and the column is fitted on them) or
runs the dynamic ramps above ("ramp", python3 -m hhneck.validation.segments --protocol ramp): the
same deck with a STATICS card, one equilibrium per 0.01 N m of the
moment table (rates zero, so the viscous lag of the ramps is absent: the
rotations are the limit of ever slower ramps), read by the same readers
with the load time as time. The segment decks hold no element with a
history: the discs', ligaments' and neutral-zone springs' rate terms and
the one-way joint-limit dampers vanish at rest.

Signs of the data (README): flexion +, extension -; lateral bending and
axial rotation "(+)L". In the project's axes (x forward, y left, z up) a
flexion is +RY of the upper body, a left lateral bending -RX, a left axial
rotation +RZ; the moment vector of the positive direction is (0, 1, 0),
(-1, 0, 0) and (0, 0, 1). The rotation is the upper body's Bryant angle
relative to the lower one minus its neutral value (for OC-C2 the sum of the
C1 and head angles about the same axis, exact for a planar motion).

API: moment_table, sweep_time, write_deck, case_name, run_case, rotation_curve, rotations_at, data_branches,
rate_curve, catalogue (all cases; hhneck.validation.catalogue writes docs/catalogue.md).
Command: python3 -m hhneck.validation.segments [--quick] [--exe HHNECK] [--out DIR] [--jobs N]
[--protocol statics|ramp]
(hhneck-catalogue writes the report).
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile

import numpy as np

from .. import ratings
from ..decks import card
from ..paths import project_root

ROOT = project_root()
MODEL_DECK = os.path.join(ROOT, "input", "head_neck_54dof.inp")
DATA_DIR = os.path.join(os.path.dirname(ROOT), "shared", "data", "pmhs_neck")

#: the lab's name of a segment -> (lower body, upper bodies)
SEGMENTS = {
    "C0_C1": ("C1", ("HEAD",)),
    "C1_C2": ("C2", ("C1",)),
    "C2_C3": ("C3", ("C2",)),
    "C3_C4": ("C4", ("C3",)),
    "C4_C5": ("C5", ("C4",)),
    "C5_C6": ("C6", ("C5",)),
    "C6_C7": ("C7", ("C6",)),
    "OC_C2": ("C2", ("C1", "HEAD")),
}
#: motion -> (coordinate, sign of the data's positive direction, moment vector)
MOTIONS = {
    "flexion_extension": ("RY", +1.0, (0.0, 1.0, 0.0)),
    "lateral_bending": ("RX", -1.0, (-1.0, 0.0, 0.0)),
    "axial_rotation": ("RZ", +1.0, (0.0, 0.0, 1.0)),
}
RAMP, HOLD = 20.0, 2.0                # [s] the protocol of the module docstring
T_NEG = 2.0 * RAMP + HOLD              # start of the negative loading ramp
T_END = 3.0 * RAMP + 2.0 * HOLD
SWEEP_START = RAMP + HOLD              # start of the rising ramp -M -> +M of protocol "sweep"
PROTOCOLS = ("loading", "sweep")
#: how the catalogue solves a segment test: "statics" (the program's STATICS
#: card: one equilibrium per 0.01 N m of the moment table, rates zero) or
#: "ramp" (the dynamic run of the moment table, the check of the statics)
SOLUTIONS = ("statics", "ramp")
#: [N m] the moment step of the catalogue's curves (its grid) and of the
#: STATICS levels
GRID_STEP = 0.01
#: element and coordinate cards of the model deck a segment deck takes
ELEMENT_CARDS = ("DISC", "LIGAMENT")
UPPER_CARDS = ("JOINT", "BODYPI", "NEUTRAL", "LIMIT", "ROM", "NZSPRING")
SCALED_FAMILIES = ("DISCS", "LIGAMENTS", "LIMITS", "NZSPRINGS")
#: the joint-resistance cards of the upper bodies that disc_only leaves out
JOINT_RESISTANCE_CARDS = ("LIMIT", "ROM", "NZSPRING")
#: card -> the element family whose SCALE cards go with it when write_deck
#: drops the card (a SCALE card of a family without elements, or of one the
#: program does not know yet, would not be the model without those cards)
CARD_FAMILY = {"LIGAMENT": "LIGAMENTS", "NZSPRING": "NZSPRINGS"}


def _fields(line):
    return [line[i:i + 10].strip() for i in range(0, 80, 10)]


def card_blocks(path):
    """The data cards of a deck as blocks: a card and its continuation
    cards (lines starting with a blank), comments and blank lines dropped."""
    blocks = []
    with open(path) as f:
        for line in f.read().splitlines():
            if not line.strip() or line.startswith("*"):
                continue
            if line[0] == " ":
                if not blocks:
                    raise ValueError("%s: a continuation card before any card" % path)
                blocks[-1].append(line)
            else:
                blocks.append([line])
    return blocks


def moment_table(peak, protocol="loading"):
    """[(t [s], moment [N m])] of the moment protocol (module docstring)."""
    if protocol == "loading":
        return [(0.0, 0.0), (RAMP, peak), (RAMP + HOLD, peak), (T_NEG, 0.0), (T_NEG + RAMP, -peak), (T_END, -peak)]
    if protocol == "sweep":
        return [(0.0, 0.0), (RAMP, -peak), (SWEEP_START, -peak), (SWEEP_START + 2.0 * RAMP, peak), (T_END, peak)]
    raise ValueError("protocol: one of %s, not %r" % (", ".join(PROTOCOLS), protocol))


def sweep_time(moment, peak):
    """The time [s] at which protocol "sweep" applies `moment` (array) on
    its rising ramp."""
    return SWEEP_START + (np.asarray(moment, dtype=float) + peak) / peak * RAMP


def write_deck(path, segment, motion, peak, model=MODEL_DECK, disc_only=False, title=None, drop=(),
               protocol="loading", statics=False, elements=ELEMENT_CARDS):
    """Write the deck of one segment test (module docstring) to `path`:
    `segment` a key of SEGMENTS, `motion` of MOTIONS, `peak` the moment [N m].
    disc_only keeps the discs alone (the closed-form check of the tests).
    drop: card names (e.g. ("NZSPRING",)) left out of the model deck's cards
    that the segment would otherwise take, with the SCALE cards of their
    family (CARD_FAMILY: "NZSPRING" drops the NZSPRINGS SCALE cards too).
    protocol: "loading" (the catalogue's) or "sweep" (the calibration's;
    moment_table). statics: a STATICS card solves the deck as equilibria
    at load times 0, dt, ... T_END, dt = RAMP GRID_STEP / peak (every grid
    moment of the loading ramps is a level), instead of the dynamic run.
    elements: the element cards taken when they join two of the segment's
    bodies (default ELEMENT_CARDS; a study adds its own, such as FACET).
    Returns the channel names of the upper bodies' rotation coordinate."""
    lower, uppers = SEGMENTS[segment]
    coord, _, vec = MOTIONS[motion]
    bodies = (lower,) + uppers
    drop = tuple(drop)
    dropped_families = [CARD_FAMILY[d] for d in drop if d in CARD_FAMILY]
    kept = []
    for b in card_blocks(model):
        f = _fields(b[0])
        name = f[0]
        if name in drop or (name == "SCALE" and f[2] in dropped_families):
            continue
        if name == "BODY" and f[1] in bodies:
            line = b[0]
            if f[1] == lower:              # the fixed lower body: the root, its frame the lab's
                line = line[:20] + "R".ljust(10) + line[30:]
            kept.append([line])
        elif name in UPPER_CARDS and f[1] in uppers:
            if disc_only and name in JOINT_RESISTANCE_CARDS:
                continue
            kept.append(b)
        elif name in elements and f[2] in bodies and f[3] in bodies:
            if disc_only and name != "DISC":
                continue
            kept.append(b)
        elif name == "SCALE" and f[2] in SCALED_FAMILIES:
            if disc_only and f[2] != "DISCS":
                continue
            kept.append(b)
    if not any(_fields(b[0])[0] == "DISC" for b in kept):
        raise ValueError("%s: no disc joins %s in %s" % (segment, " ".join(bodies), model))
    table = moment_table(peak, protocol)
    pts = ["%.6g" % x for point in table for x in point]
    head = [
        card("TITLE", (title or "SEGMENT TEST %s %s TO %.3g N M" % (segment, motion.upper(), peak))[:70]),
        "*         end (s)   step (s)  print (s) method    rtol      atol",
        card("CONTROL", "%.6g" % T_END, "1.0E-4", "1.0", "ROS34PW2", "1.0E-5", "1.0E-8"),
        "OUTPUT    1.0E-2",
        card("H5FILE", os.path.splitext(os.path.basename(path))[0] + ".h5"),
        "GRAVITY   0.0       0.0       0.0",
        card("HEADNECK", uppers[-1], lower),
        card("LOCK", lower, "TX", "TY", "TZ", "RX", "RY", "RZ"),
        "*         the pure moment: %s about the lower body's axes" % motion,
        card("TABLE", "MOMENT", "%d" % len(table)),
        card("", *pts[:6]),
        card("", *pts[6:]),
        card("COUPLE", uppers[-1], "R", "MOMENT", *["%.1f" % v for v in vec]),
    ]
    if statics:                            # equilibria at the table's times, one per grid moment
        head.append(card("STATICS", "0.0", "%.6g" % T_END, ("%.8g" % (RAMP * GRID_STEP / peak))[:10]))
    if len(uppers) > 1:                    # the moment acts on the top body; say so
        head.insert(1, "* %s: the moment on %s, %s free between" % (segment, uppers[-1], " ".join(uppers[:-1])))
    lines = [line.rstrip() for line in head + [line for b in kept for line in b]]
    for k, line in enumerate(lines):
        if len(line) > 80:
            raise ValueError("%s: card %d is %d columns long" % (path, k + 1, len(line)))
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return ["%s_%s" % (u, coord) for u in uppers]


def default_executable():
    """$HHNECK, else fpm's release build of the project (built if needed)."""
    exe = os.environ.get("HHNECK")
    if not exe:
        out = subprocess.run(["fpm", "run", "--profile", "release", "--runner", "echo"], cwd=ROOT,
                             capture_output=True, text=True)
        lines = out.stdout.strip().splitlines()
        exe = lines[-1] if out.returncode == 0 and lines else ""
        if exe and not os.path.isabs(exe):
            exe = os.path.join(ROOT, exe)
    if not exe or not os.access(exe, os.X_OK):
        raise RuntimeError("no hhneck executable (set HHNECK or build with fpm): %r" % exe)
    return exe


def case_name(segment, motion, peak, disc_only=False, drop=(), protocol="loading", statics=False):
    """The file stem of a segment test (run_case)."""
    return "%s_%s_%gNm%s%s%s%s" % (segment, motion, peak, "_disc" if disc_only else "",
                                   "".join("_no" + d.lower() for d in drop), "_sweep" if protocol == "sweep" else "",
                                   "_statics" if statics else "")


def run_case(segment, motion, peak, workdir, exe=None, disc_only=False, drop=(), model=MODEL_DECK,
             protocol="loading", statics=False):
    """Write and run one segment test in `workdir`; returns (t [s], rotation
    [deg] of the upper body relative to the lower, in the data's sign).
    drop: card names left out of the deck (write_deck); model: the model
    deck the segment's cards are taken from; protocol, statics: write_deck's
    (statics: the equilibria at the table's times, t their load times). The
    files are named after the case (case_name: segment, motion, peak, and
    _disc or _no<card> for each dropped card, _sweep for protocol "sweep",
    _statics)."""
    name = case_name(segment, motion, peak, disc_only, drop, protocol, statics)
    deck = os.path.join(workdir, name + ".inp")
    channels = write_deck(deck, segment, motion, peak, model=model, disc_only=disc_only, drop=drop,
                          protocol=protocol, statics=statics)
    run_listed(deck, [exe or default_executable()], workdir)
    return rotation_curve(os.path.join(workdir, name + ".h5"), channels, MOTIONS[motion][1])


def run_listed(deck, cmd, workdir):
    """Run hhneck (the command line cmd) on a deck in workdir, its listing
    to the deck's name with .txt and its stderr (warnings included) to .err;
    a failed run raises RuntimeError with the end of its stderr."""
    stem = os.path.splitext(deck)[0]
    with open(deck) as fin, open(stem + ".txt", "w") as fout:
        res = subprocess.run(cmd, stdin=fin, stdout=fout, stderr=subprocess.PIPE, text=True, cwd=workdir)
    with open(stem + ".err", "w") as ferr:
        ferr.write(res.stderr)
    if res.returncode != 0:
        raise RuntimeError("%s: hhneck exit %d: %s" % (deck, res.returncode, res.stderr.strip()[-400:]))
    return res.stderr


def warning_lines(stderr):
    """The warnings of a run's stderr: its lines that say WARNING (joints
    past their range, the energy balance, a long run), stripped."""
    return [line.strip() for line in stderr.splitlines() if "warning" in line.lower()]


def rotation_curve(h5path, channels, sign):
    """Time [s] and the summed rotation channels minus their start values
    [deg], times `sign` (the data's positive direction)."""
    import h5py
    with h5py.File(h5path, "r") as f:
        t = np.asarray(f["time"][:], dtype=float)
        total = np.zeros_like(t)
        for c in channels:
            v = np.asarray(f["channels"][c][:], dtype=float)
            total += v - v[0]
    return t, sign * total


def rotations_at(t, rot, peak, levels):
    """The rotation at each moment level (signed, |level| <= peak) on the
    loading ramp of its sign."""
    out = []
    for m in levels:
        tm = m / peak * RAMP if m >= 0 else T_NEG - m / peak * RAMP
        out.append(float(np.interp(tm, t, rot)))
    return np.array(out)


def load_panjabi(data_dir=DATA_DIR):
    """{(segment, motion): (moment [N m], rotation [deg]) in digitised order}."""
    rows = {}
    with open(os.path.join(data_dir, "panjabi2001_moment_rotation.csv")) as f:
        for r in csv.DictReader(f):
            rows.setdefault((r["segment"], r["motion"]), []).append(
                (int(r["point"]), float(r["moment_Nm"]), float(r["rotation_deg"])))
    return {k: (np.array([p[1] for p in sorted(v)]), np.array([p[2] for p in sorted(v)])) for k, v in rows.items()}


def load_nightingale(data_dir=DATA_DIR):
    """{segment: {stat: (moment, rotation)}}, flexion and extension joined
    into one curve from -3.5 to +3.5 N m (moment ascending)."""
    rows = {}
    with open(os.path.join(data_dir, "nightingale2007_moment_rotation.csv")) as f:
        for r in csv.DictReader(f):
            rows.setdefault((r["segment"], r["stat"]), []).append(
                (float(r["moment_Nm"]), float(r["rotation_deg"])))
    out = {}
    for (seg, stat), pts in rows.items():
        pts = sorted(pts)
        out.setdefault(seg, {})[stat] = (np.array([p[0] for p in pts]), np.array([p[1] for p in pts]))
    return out


def data_branches(moment, rotation, zero=0.05):
    """Split a Panjabi curve (digitised from +M through the neutral zone to
    -M) into its positive and negative loading branches, each with moment
    ascending in magnitude: the points up to the first |M| < zero, and from
    the last |M| < zero on (the ends of the neutral zone, README)."""
    small = np.flatnonzero(np.abs(moment) < zero)
    if small.size == 0:
        raise ValueError("no zero-moment point in the curve")
    pos = slice(0, small[0] + 1)
    neg = slice(small[-1], moment.size)
    mp, rp = moment[pos][::-1], rotation[pos][::-1]
    mn, rn = -moment[neg], rotation[neg]
    return (np.maximum(mp, 0.0), rp), (np.maximum(mn, 0.0), rn)


def reference_on(grid, moment, rotation):
    """A Panjabi curve as a function of the signed moment on `grid`."""
    (mp, rp), (mn, rn) = data_branches(moment, rotation)
    return np.where(grid >= 0, np.interp(grid, mp, rp), np.interp(-grid, mn, rn))


#: [s per N m] the moment as the rating's abscissa: the 0.01 N m grid of the
#: curves becomes the 0.1 ms step the rating samples at, so a curve keeps its
#: 201 (Panjabi) or 701 (Nightingale) samples; the rating's windows are
#: fractions of the curve's length, so the scale changes nothing else
MOMENT_AS_TIME = 0.01


def rate_curve(grid, reference, model):
    """ISO/TS 18571 of a moment-rotation curve: rotation as a function of
    the moment (in place of time, MOMENT_AS_TIME), on the 0.01 N m grid."""
    return ratings.rate(np.asarray(grid) * MOMENT_AS_TIME, reference, model)


def _run_timed(args):
    import time
    seg, motion, peak, work, exe, statics, model = args
    t0 = time.perf_counter()
    t, rot = run_case(seg, motion, peak, work, exe, statics=statics, model=model)
    with open(os.path.join(work, case_name(seg, motion, peak, statics=statics) + ".err")) as f:
        stderr = f.read()
    return t, rot, time.perf_counter() - t0, stderr


def case_list(quick=False, data_dir=DATA_DIR):
    """The segment cases of the catalogue: [(source, segment, motion, peak
    moment [N m])]; quick: C4-C5 only."""
    cases = [("Panjabi 2001", seg, motion, 1.0) for (seg, motion) in sorted(load_panjabi(data_dir))]
    cases += [("Nightingale 2007", seg, "flexion_extension", 3.5) for seg in sorted(load_nightingale(data_dir))]
    return [c for c in cases if c[1] == "C4_C5"] if quick else cases


def catalogue(exe=None, quick=False, data_dir=DATA_DIR, workdir=None, jobs=None, on_case=None, solution="statics",
              model=MODEL_DECK):
    """Run and rate every segment case; returns a list of dicts, one per
    (source, segment, motion), with the case's wall time [s] (its run, in
    `jobs` parallel processes, default the number of cores) and its run's
    warnings (warning_lines of its stderr, kept beside its listing as .err).
    quick: C4-C5 only (one segment per source and motion). on_case(r) is
    called with each case's dict as its run ends (in the calling thread);
    the list is in the cases' order whatever order they end in. solution:
    "statics" (the equilibria of the STATICS card, the default: the tests
    are quasi-static) or "ramp" (the dynamic runs of the moment protocol,
    their check), SOLUTIONS. model: the
    model deck the segments' cards are taken from."""
    if solution not in SOLUTIONS:
        raise ValueError("solution: one of %s, not %r" % (", ".join(SOLUTIONS), solution))
    from concurrent.futures import ThreadPoolExecutor, as_completed
    panjabi, night = load_panjabi(data_dir), load_nightingale(data_dir)
    work = workdir or tempfile.mkdtemp(prefix="hhneck-segments-")
    os.makedirs(work, exist_ok=True)
    exe = exe or default_executable()
    cases = case_list(quick, data_dir)
    results = {}
    with ThreadPoolExecutor(max_workers=jobs or os.cpu_count() or 1) as pool:
        futures = {pool.submit(_run_timed, (seg, motion, peak, work, exe, solution == "statics", model)): k
                   for k, (_, seg, motion, peak) in enumerate(cases)}
        try:
            for fut in as_completed(futures):
                k = futures[fut]
                results[k] = _rated_case(cases[k], *fut.result(), panjabi, night)
                if on_case:
                    on_case(results[k])
        except BaseException:
            for fut in futures:
                fut.cancel()
            raise
    return [results[k] for k in sorted(results)]


def _rated_case(case, t, rot, wall, stderr, panjabi, night):
    """The catalogue's dict of one segment case (catalogue) from its run."""
    src, seg, motion, peak = case
    grid = np.round(np.arange(-peak, peak + 1e-9, 0.01), 10)
    model = rotations_at(t, rot, peak, grid)
    r = dict(source=src, segment=seg, motion=motion, peak=peak, grid=grid, curve=model, t=t, rot=rot,
             wall=wall, lower=None, upper=None, warnings=warning_lines(stderr))
    if src.startswith("Panjabi"):
        m, rr = panjabi[(seg, motion)]
        r["levels"] = np.array([1.0, 0.67, 0.33, -0.33, -0.67, -1.0])
        r["reference"] = reference_on(grid, m, rr)
        r["data"] = reference_on(r["levels"], m, rr)
    else:
        stats = night[seg]
        mm, rm = stats["mean"]
        r["levels"] = np.array([3.5, 2.5, 1.5, 1.0, 0.5, -0.5, -1.0, -1.5, -2.5, -3.5])
        r["reference"] = np.interp(grid, mm, rm)
        r["data"] = np.interp(r["levels"], mm, rm)
        bounds = [np.interp(r["levels"], *stats[s]) for s in ("lower", "upper")]
        r["lower"], r["upper"] = np.minimum(*bounds), np.maximum(*bounds)
    r["model"] = rotations_at(t, rot, peak, r["levels"])
    r["iso"] = rate_curve(grid, r["reference"], model)
    return r


def main(argv=None):
    """python3 -m hhneck.validation.segments: run and rate the segment cases, print one line each
    (the catalogue command, hhneck-catalogue, writes them into
    docs/catalogue.md)."""
    p = argparse.ArgumentParser(prog="python3 -m hhneck.validation.segments", description=__doc__.split("\n\n")[0])
    p.add_argument("--quick", action="store_true", help="C4-C5 only (the test suite's form)")
    p.add_argument("--exe", help="the hhneck executable (default $HHNECK, else fpm's release build)")
    p.add_argument("--data", default=DATA_DIR, help="the pmhs_neck data folder")
    p.add_argument("--out", help="working directory for the decks, listings and result files")
    p.add_argument("--jobs", type=int, help="runs at a time (default: the number of cores)")
    p.add_argument("--protocol", choices=SOLUTIONS, default="statics",
                   help="statics (equilibria at each level: the ramps' zero-rate limit, the default, as the "
                        "column's fit solves them) or ramp (the dynamic moment ramps)")
    a = p.parse_args(argv)
    for r in catalogue(a.exe, a.quick, a.data, a.out, a.jobs, solution=a.protocol):
        print("%-17s %-6s %-18s ISO 18571 %.3f  model/data at +peak %.2f, -peak %.2f  (%.2f s)" % (
            r["source"], r["segment"], r["motion"], r["iso"]["overall"],
            r["model"][0] / r["data"][0], r["model"][-1] / r["data"][-1], r["wall"]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
