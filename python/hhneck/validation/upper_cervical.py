"""The upper-cervical joints' passive elements scaled to the segment data
of Panjabi et al. 2001 (hhneck.validation.segments; data in shared/data/pmhs_neck).

The model deck joins C2-C1 (atlanto-axial) and C1-HEAD (atlanto-occipital)
by the paper's disc law with the skull-C3 rotational stiffness of S1 and by
the lower-cervical ligament curves of S2 (reference/parameters.md: an
ASSUMPTION, no disc and no such ligaments exist there). The segment data
show these two joints far more flexible in flexion-extension and axial
rotation than that lumped set: at 1 N m C1-C2 turns 22.1 / -32.7 deg (the
deck's elements, springs dropped: 12.6) and flexes 12.2 / -12.1 deg (3.94
/ -5.81). Stiffness cannot be taken away by the neutral-zone springs
(NZSPRING, in parallel), so two factors of these two joints can be fitted
before the springs (python3 -m hhneck.validation.fit_joints --upper-cervical runs this first,
python3 -m hhneck.validation.fit_column --upper-cervical at every candidate
of the column; not the shipped model's flow, docs/validation.md "The upper
cervical joints" says why):

 f_lig  multiplies l1 and l2 of every LIGAMENT card joining the two bodies
        of either joint;
 f_rot  multiplies the flexion bending (Iy) and the torsion (J) of their
        DISC cards; the lateral bending (Ix) stays as the deck has it:
        Panjabi's lateral bending of these joints is met by the deck as it
        is (3.30 / -3.06 deg at C1-C2 against 3.28 / -3.09), and the model
        does not stand at rest with less (the C1 RX mode,
        docs/validation.md).

Each is the largest value in [F_MIN, 1] (3 significant digits, rounded
down) at which the segment case of its motion, run with the NZSPRING
cards dropped, turns at least as far as the data at the data's largest
moment on the data's stiffer side: f_lig from C1-C2 axial rotation (22.1
deg at 1.04 N m), then, with it, f_rot from C1-C2 flexion-extension (12.1
deg at 1.01 N m, but the joint's range-of-motion stop begins 10 deg from
its neutral: where the stop comes first, the factor is fitted to reach the
stop, range_edge; the stop then stands between the model and the data,
which is reported). C0-C1 takes the same factors (the same law at both
joints, as the deck has it). The springs then add what the data show
beyond these elements. Found by bisection in log f (BISECTIONS steps);
the rotation grows monotonically as a factor falls.

The factors are written to reference/upper_cervical.csv; the deck
generator (python3 -m hhneck.validation.model_deck) writes the model deck's cards
through scale_cards, the same function the fit runs its cases on, and the
deck says so in a comment line (MARKER). A deck that has the line is not
fitted again (its cards would be scaled twice).

API: scale_cards, deck_has_factors, range_edge, largest_factor, fit_factors, write_csv,
read_csv.
"""
import csv
import math
import os
import tempfile

from . import segments
from ..decks import number_text, scale_fields, write_deck
from ..paths import project_path

CSV_PATH = project_path("reference", "upper_cervical.csv")
#: (lower, upper) body pairs of the atlanto-axial and atlanto-occipital joints
JOINT_PAIRS = (("C2", "C1"), ("C1", "HEAD"))
#: factor -> (segment, motion) of the data it is fitted to
TARGETS = (("f_lig", ("C1_C2", "axial_rotation")), ("f_rot", ("C1_C2", "flexion_extension")))
F_MIN = 1e-3
BISECTIONS = 12
MARKER = "* UPPER CERVICAL (hhneck.validation.upper_cervical):"


def _joins(f):
    return (f[2], f[3]) in JOINT_PAIRS


def scale_cards(lines, f_rot, f_lig):
    """The deck lines with the upper-cervical DISC cards' Iy and J times
    f_rot and their LIGAMENT cards' l1 and l2 times f_lig (module
    docstring), and the MARKER comment before the first card changed."""
    out, marked = [], False
    i = 0
    while i < len(lines):
        line = lines[i]
        f = segments._fields(line)
        if line[:1] not in ("*", " ", "") and f[0] in ("DISC", "LIGAMENT") and _joins(f):
            if not marked:
                out.append(MARKER)
                out.append("* discs C2-C1, C1-HEAD: Iy, J x %s; their ligaments: l1, l2 x %s" % (
                    number_text(f_rot), number_text(f_lig)))
                out.append("* (reference/upper_cervical.csv: fitted to Panjabi 2001 by")
                out.append("* hhneck.validation.fit_joints before the neutral-zone springs).")
                marked = True
            if f[0] == "LIGAMENT":
                line = scale_fields(line, (4, 5), f_lig)
                out.append(line)
                i += 1
                continue
            out.append(line)                       # DISC: its second continuation holds G Ix Iy J k
            out.extend(lines[i + 1:i + 2])
            c = lines[i + 2]
            c = scale_fields(c, (3, 4), f_rot)
            out.append(c)
            i += 3
            continue
        out.append(line)
        i += 1
    return out


def deck_has_factors(path):
    """Whether the deck at `path` already carries the factors (MARKER)."""
    with open(path) as f:
        return any(line.startswith(MARKER) for line in f)


def range_edge(lines, body, coord):
    """The smaller distance [deg] from the neutral value of `body`'s joint
    rotation `coord` (its NEUTRAL card, else 0) to an end of its ROM card's
    range (inf without a ROM card)."""
    neutral, ends = 0.0, None
    for line in lines:
        f = segments._fields(line)
        if f[0] == "NEUTRAL" and f[1:3] == [body, coord]:
            neutral = float(f[3])
        elif f[0] == "ROM" and f[1:3] == [body, coord]:
            ends = (float(f[3]), float(f[4]))
    return math.inf if ends is None else min(neutral - ends[0], ends[1] - neutral)


def _rotation_reached(exe, lines, target, workdir, data):
    """(model, wanted) [deg]: the smaller |rotation| over the two sides at
    the data's largest moment of `target` (segment, motion) with the deck
    `lines`, NZSPRING dropped; the data's smaller |rotation| there, or the
    distance from the neutral to the upper body's range edge (range_edge)
    when that is less: the stop, not the factor, limits the joint there."""
    seg, motion = target
    moment, rotation = data[target]
    peak = float(max(abs(moment)))
    model = os.path.join(workdir, "model.inp")
    write_deck(model, lines)
    t, rot = segments.run_case(seg, motion, peak, workdir, exe, drop=("NZSPRING",), model=model)
    ends = segments.rotations_at(t, rot, peak, [peak, -peak])
    sides = [rotation[moment.argmax()], rotation[moment.argmin()]]
    edge = range_edge(lines, segments.SEGMENTS[seg][1][-1], segments.MOTIONS[motion][0])
    return float(min(abs(ends))), float(min(min(abs(s) for s in sides), edge))


def _round_down(v):
    """v to 3 significant digits, rounded down."""
    e = math.floor(math.log10(v)) - 2
    return float("%.3g" % (math.floor(v / 10.0 ** e + 1e-9) * 10.0 ** e))


def largest_factor(rotation, want, f_min=F_MIN, steps=BISECTIONS):
    """The largest factor f in [f_min, 1], to 3 significant digits rounded
    down, with rotation(f) >= want, for a rotation that grows as f falls:
    1 when rotation(1) reaches it, else bisection in log f between f_min
    (which must reach it: ValueError otherwise) and 1."""
    if rotation(1.0) >= want:
        return 1.0
    got = rotation(f_min)
    if got < want:
        raise ValueError("even the factor %g leaves the rotation at %.3g deg, below %.3g" % (f_min, got, want))
    lo, hi = math.log(f_min), 0.0                  # reached at lo, not at hi
    for _ in range(steps):
        mid = 0.5 * (lo + hi)
        if rotation(math.exp(mid)) >= want:
            lo = mid
        else:
            hi = mid
    return max(f_min, _round_down(math.exp(lo)))


def fit_factors(exe, model=segments.MODEL_DECK, data_dir=segments.DATA_DIR, workdir=None, at_bound=False):
    """f_lig, then f_rot (module docstring) for the deck `model`; a dict
    {name: {"value", "segment", "motion", "model_deg", "target_deg"}}: the
    rotation of the segment case at the fitted value and the rotation it
    had to reach (the data's, or the range edge where that is less). Where
    even F_MIN does not reach the target (the joint's other elements hold
    it): ValueError, or with `at_bound` the factor F_MIN (a column fit's
    candidate is then rated with its ligaments at the bound)."""
    if deck_has_factors(model):
        raise ValueError("%s already has the upper-cervical factors; fit them on the deck without them "
                         "(python3 -m hhneck.validation.model_deck --upper-cervical none)" % model)
    work = workdir or tempfile.mkdtemp(prefix="hhneck-upper-cervical-")
    os.makedirs(work, exist_ok=True)
    with open(model) as f:
        base = f.read().splitlines()
    data = segments.load_panjabi(data_dir)
    found = {"f_rot": 1.0, "f_lig": 1.0}
    out = {}
    for name, target in TARGETS:
        runs = {}                                  # factor -> (model, wanted): each case run once

        def reached(v):
            if v not in runs:
                trial = dict(found, **{name: v})
                runs[v] = _rotation_reached(exe, scale_cards(base, trial["f_rot"], trial["f_lig"]), target,
                                            work, data)
            return runs[v]
        want = reached(1.0)[1]
        try:
            value = largest_factor(lambda v: reached(v)[0], want)
        except ValueError as e:
            if not at_bound:
                raise ValueError("%s: %s %s %s" % (model, name, target[0], target[1])) from e
            value = F_MIN
        found[name] = value
        got, want = reached(value)
        out[name] = {"value": value, "segment": target[0], "motion": target[1], "model_deg": got,
                     "target_deg": want}
    return out


def write_csv(path, fit):
    """reference/upper_cervical.csv: a comment line, then factor, value,
    segment, motion, model_deg, target_deg."""
    with open(path, "w", newline="") as f:
        f.write("# written by python3 -m hhneck.validation.fit_joints (python/hhneck/validation/upper_cervical.py): "
                "the C2-C1 and C1-HEAD "
                "ligaments' l1, l2 (f_lig) and discs' Iy, J (f_rot) factors, each the largest at which the "
                "segment case turns as far as the data at its largest moment (springs dropped)\n")
        w = csv.writer(f, lineterminator="\n")
        w.writerow(("factor", "value", "segment", "motion", "model_deg", "target_deg"))
        for name, _ in TARGETS:
            r = fit[name]
            w.writerow((name, "%.6g" % r["value"], r["segment"], r["motion"], "%.4g" % r["model_deg"],
                        "%.4g" % r["target_deg"]))


def read_csv(path):
    """(f_rot, f_lig) from a reference/upper_cervical.csv."""
    with open(path, newline="") as f:
        rows = {r["factor"]: float(r["value"]) for r in csv.DictReader(line for line in f
                                                                       if not line.startswith("#"))}
    for k in ("f_rot", "f_lig"):
        if not (F_MIN <= rows.get(k, -1.0) <= 1.0):
            raise ValueError("%s: factor %s missing or outside [%g, 1]" % (path, k, F_MIN))
    return rows["f_rot"], rows["f_lig"]
