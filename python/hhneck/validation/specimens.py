"""The specimen sled cases of the catalogue: Stemper et al. 2004, rear
impact at 1.8 m/s (head-neck specimens potted at T1, README of
shared/data/pmhs_neck, "Case 1"), and Kang et al. 2018, frontal and side
mini-sled at 14 km/h ("Cases 2 and 3"; below the Stemper set-up).

Set-up (decisions of the README's "Ambiguities" named by number):
* the model deck (input/head_neck_54dof.inp) as shipped, T1 the potted
  body: its x-acceleration is the source's pulse (the 1.8 m/s curve, t = 0
  at the pulse start, forward, the corridors' time base), its other five
  coordinates held;
* gravity downward, 9.81 m/s^2 (1: the PMHS were upright in 1 g);
* muscles passive: both activation histories of the model deck set to zero
  (u0 = u1 = 0, by CHANGE cards); the specimens' muscles were left attached
  (README), so their passive Hill-type force-length and damping stay;
* the start posture held (2): HOLD POSTURE's generalized forces through
  the test (SUPPORT = "HOLD", the default). The labs cut their positioning
  cables at the pulse; SUPPORT = "RELEASE" does that (HOLD POSTURE released
  as a step at t = 0), but the model's start posture is its unstressed
  neutral, so at the release no element carries the head's weight and the
  neck starts in free fall (the Kang cell reads 0 N at t = 0, not the
  specimen's weight): the specimens were in equilibrium, preloaded, when
  their cables were cut. HOLD's forces are that preload: they act on the
  relative coordinates of each body to its parent, so each body's six are
  one load pair between the two bodies of its joint (Kane's generalized
  force of a pair acting on both vanishes for every other coordinate), an
  internal pre-stress of the joints and not an external support; the
  column carries the head's weight from the start (the Kang cell reads it
  at t = 0) and nothing outside the specimen holds it up. SUPPORT =
  "PRESTRAIN" (HOLD PRESTRAIN, a settled start) carries the same preload
  in the elements instead: the discs' references and the neutral-zone
  springs' neutrals are displaced until the start posture is in
  equilibrium under gravity (Newton's method, hn_prestrain), so no
  generalized force is added; it equals HOLD at t = 0 and differs as the
  joints turn (a strained spring stiffens along its own law, HOLD's forces
  stay constant). "NONE" writes no card (the same motion as RELEASE);
* the T1 slope as the source potted it (25 deg: "anterior of the T1
  vertebra body oriented 25 degree with respect to the vertical"), a tilt
  of the potted body: T1's pitch held at (slope - the model deck's T1
  slope, its C7 NEUTRAL RY, 23.8 deg) by its PRESCRIB CONSTANT card, so the
  whole column turns with T1 and the neck's own posture (the discs'
  neutral shape) stays the model deck's; t1_slope= sets another.

Channels (docs/output-format.md; their signs as the README derives them):
segment angles C2-C3 ... C6-C7 = -(change of the upper body's planar angle
about y relative to the lower one, its parent: C2_PY for C2-C3 ... C6_PY
for C6-C7; extension positive), head-T1 angle = -(change of the head's
planar angle about y in T1's sagittal plane, from the result file's
rotation matrices: ANGLES), retraction = HT1_DX [mm] (head mass centre
relative to T1 in T1's axes, from the start). Reference: each corridor
outline's midline, the outline named (REFERENCE; hhneck.validation.specimen_data),
rated by ISO/TS 18571 over the times the corridor covers (0.3-126 ms) and
the run covers (to 130 ms), no offsets.

Head angles (ANGLES): each rotation is rated as its source defined it.
Stemper's corridors are angles "in the sagittal plane" (README, Case 1:
the film's angles of one plane; the notebook's model readout, differences
of nodal rotations about the global y axis, is the same angle in a
sagittal motion): the planar angles, for the segments (BODY_PY) and for
the head relative to T1 (planar_angle, the result file has no channel of
it; in the sagittal Stemper run it equals HT1_RY). Kang's head rotations
are compared by the source's notebook with the LS-DYNA nodal rotations of
the head's node (README, "What the notebook computes"), the time
integrals of its angular velocity about the fixed global axes: the
catalogue integrates the head's angular velocity in R (HEAD_OMEGX,
HEAD_OMEGY; integrated_rotation), R being the sled's axes (T1 only
translates). In the side case the head's Bryant x angle (HEADL_RX) peaks
at -63.6 deg, the integrated one at -64.9 and the rotation vector's x
component (HEADL_VX) at -66.2: in 3-D the three differ.

Kang 2018 front and side, the same set-up but for (README "Ambiguities"):
* the potted body is T1 (4: the FE model is potted at T3, the data speak of
  "the loadcell at T1"), driven by the source's pulse (SFO as the file
  has it, 6; its one repeated time, 2.752 ms, merged into the mean of its
  two values), t = 0 at the pulse start = the data's time zero;
* front: T1 accelerated rearward (a_x = -pulse, the source's boundary
  condition); side: toward the specimen's right (J211 +y = the model's -y),
  the direction the data's signs fit (5), so that nothing is mirrored;
* the T1 slope 24 deg (the source's "T1 endplate angle 24 +- 5 deg"), as
  for Stemper a tilt of the potted T1;
* no pretension ring (8); none of the notebook's offsets or time shifts (7);
* the load cell (4, "Initial position"): a LOADCELL card cutting T1 from
  C7 (the subtree of C7: the neck and head, what the potted T1 carries; the
  model's T1 holds 20 kg of the volunteer's torso, which no specimen has),
  in T1's axes (the cell is mounted on the sled), about the potting centre
  as the set-up placed it, 81 mm behind and 229 mm below the head's mass centre at the start
  (KANG_CELL_POINT, in T1's axes from T1's mass centre; the model's head
  sits 54 mm ahead of and 175 mm above T1's mass centre, so the point is
  below and behind T1); read in SAE J211 axes as the load on the part above
  the cell (T1CELL_JFX ... _JMZ), from its value at t = 0: the data start
  at zero (the cells were tared with the specimen in place), the model's
  cell starts at the specimen's weight;
* rated: the head kinematics (front: x- and z-acceleration, rotation about
  y; side: y- and z-acceleration, rotation about x) and the load cell
  (front: Fx, Fz, My; side: Mx, Fy, Fz), all in SAE J211 axes (x forward,
  y right, z down: the model's y and z change sign; the head's rotations
  the integrals of its angular velocity about R's x and -y, "Head
  angles" above);
* the head's accelerations as the specimens' head-mounted accelerometers
  give them: in the head's own axes (SAE J211 records a head's
  acceleration in its anatomical, moving frame; the source's notebook
  compares the SAFER model's head accelerometer), as specific force a - g
  (what an accelerometer senses), from its value at t = 0 (the data start
  at zero: tared upright): HEAD_AXS, HEAD_AYS, HEAD_AZS. The lab-frame
  acceleration HEAD_AX ... peaks 24 ms early in the side case, where the
  head turns 64 deg (studies/kang_head_frame.py rates the three readings).
  Reference: the corridor's midline (front) or the mean of PMHS1 and PMHS2
  (side), named in REFERENCE; window 0 to 1.2 x the time of the
  reference's largest magnitude between 0 and 99.9 ms (KANG_PEAK_SEARCH),
  as the source's notebook rates (searched over the whole reference, the
  front's head rotation and moment, still rising at 99.9 ms, would widen
  their windows to 122 and 126 ms);
* each model channel filtered (after its tare) by the SAE J211 class the
  source's notebook gives the SAFER HBM's channels whose ratings the
  catalogue prints beside ours (README "What the notebook computes"): the
  head's x-acceleration and the cell's forces CFC 60, the head's y- and
  z-accelerations, its rotations and the cell's moments CFC 180. The
  Stemper channels are unfiltered, as its notebook plots them.

Each case is a case file of reference/cases/ (docs/case-files.md): its
pulse and direction, potted body and slope, support, muscles, load cell,
reference, window and rated channels with their definitions and filters.
The text above gives the reasons for the given cases' choices; a new
direction or severity is a new case file, read by load_case and built,
run and rated by case_deck, run_case and rate_case, as the catalogue does
for every file of the folder.

API: CASES_DIR, CASES (the given case files by name), load_case, case_files,
case_deck, run_case, rate_case; CHANNELS (the rated channels: the data's and
the run's, from the case files), ANGLES, REFERENCE, DATA_FILE;
model_channels, filtered, planar_angle, integrated_rotation;
stemper_deck, run_stemper (-> {channel: (t_ms, model)}), rate_stemper;
kang_deck, run_kang, rate_kang, kang_reference, kang_window; rated_reference, rate_channel.
"""
import os
import tempfile
import tomllib

import numpy as np

from .. import ratings
from . import segments, specimen_data
from ..decks import card
from ..signals import cfc

#: the folder of the catalogue's case files
CASES_DIR = os.path.join(segments.ROOT, "reference", "cases")
SUPPORTS = ("HOLD", "RELEASE", "PRESTRAIN", "NONE", "CLAMP")
MUSCLES = ("PASSIVE", "REFLEX")
#: what a rated rotation is, as its source defined it: planar (a body's
#: angle in its parent's plane: from the rotation matrices when the channel
#: names body, parent and axis, else the model channel, a BODY_P* channel),
#: integrated (the time integral of the angular velocity channel `omega`),
#: bryant or rotation_vector (the model channel: HEADL_R* or HEADL_V*)
DEFINITIONS = ("planar", "integrated", "bryant", "rotation_vector")


class CaseError(ValueError):
    """A case file that cannot be read: the message names the file and the key."""


def _need(d, key, kind, where, default=None):
    """d[key] checked to be of type kind (default when absent and not None)."""
    if key not in d:
        if default is not None:
            return default
        raise CaseError("%s: missing key %r" % (where, key))
    v = d[key]
    if kind is float and isinstance(v, int) and not isinstance(v, bool):
        v = float(v)
    if not isinstance(v, kind):
        raise CaseError("%s: key %r is %r; expected %s" % (where, key, v, getattr(kind, "__name__", kind)))
    return v


def _vector(d, key, where, n=3):
    v = _need(d, key, list, where)
    if len(v) != n or not all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in v):
        raise CaseError("%s: key %r is %r; expected %d numbers" % (where, key, v, n))
    return [float(x) for x in v]


def load_case(path):
    """A case file (TOML, docs/case-files.md) as a dict, every key checked
    and the defaults filled; CaseError naming the file and the key."""
    try:
        with open(path, "rb") as f:
            d = tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError) as e:
        raise CaseError("%s: %s" % (path, e))
    w = os.path.basename(path)
    c = {"path": os.path.abspath(path), "name": _need(d, "name", str, w), "title": _need(d, "title", str, w),
         "source": _need(d, "source", str, w), "deck_title": _need(d, "deck_title", str, w),
         "end_time": _need(d, "end_time", float, w), "note": _need(d, "note", str, w, ""),
         "stops": _need(d, "stops", list, w, []), "safer": _need(d, "safer", str, w, ""),
         "required": _need(d, "required", float, w, 0.0),
         "newton_balance": _need(d, "newton_balance", str, w, ""),
         "rated": _need(d, "rated", bool, w, True), "order": _need(d, "order", int, w, 100),
         "rtol": _need(d, "rtol", float, w, 1.0e-3), "atol": _need(d, "atol", float, w, 1.0e-5), "model": _need(d, "model", str, w, "input/head_neck_54dof.inp")}
    c["variants"] = [tuple(v) for v in _need(d, "variants", list, w, [])]
    p = d.get("pulse")
    c["pulse"] = None if p is None else {
        "file": _need(p, "file", str, w + " [pulse]"), "table": _need(p, "table", str, w + " [pulse]", "PULSE").upper(),
        "direction": _vector(p, "direction", w + " [pulse]"), "scale": _need(p, "scale", float, w + " [pulse]", 1.0)}
    if p is not None and not any(c["pulse"]["direction"]):
        raise CaseError("%s [pulse]: direction is the zero vector" % w)
    pot = _need(d, "potting", dict, w)
    c["potting"] = {"body": _need(pot, "body", str, w + " [potting]").upper(),
                    "slope": _need(pot, "slope", float, w + " [potting]")}
    s = _need(d, "support", dict, w)
    c["support"] = _need(s, "kind", str, w + " [support]").upper()
    c["clamp"] = [str(x) for x in _need(s, "cards", list, w + " [support]", [])]
    if c["support"] not in SUPPORTS:
        raise CaseError("%s [support]: kind %r; expected one of %s" % (w, c["support"], ", ".join(SUPPORTS)))
    if c["support"] == "CLAMP" and not c["clamp"]:
        raise CaseError("%s [support]: kind CLAMP needs its deck cards (cards = [...])" % w)
    c["muscles"] = _need(_need(d, "muscles", dict, w), "state", str, w + " [muscles]").upper()
    for sup, mus in [(c["support"], c["muscles"])] + c["variants"]:
        if sup not in SUPPORTS or mus not in MUSCLES:
            raise CaseError("%s: support %r / muscles %r; expected %s / %s" % (
                w, sup, mus, ", ".join(SUPPORTS), ", ".join(MUSCLES)))
    cell = d.get("loadcell")
    c["loadcell"] = None if cell is None else {
        "name": _need(cell, "name", str, w + " [loadcell]"), "body": _need(cell, "body", str, w + " [loadcell]"),
        "point": _vector(cell, "point", w + " [loadcell]"), "axes": _need(cell, "axes", str, w + " [loadcell]")}
    ref = d.get("reference", {})
    c["reference"] = None
    if c["rated"]:
        curve = ref.get("curve")
        if curve is None:
            curve = tuple(_need(ref, "specimens", list, w + " [reference]"))
        c["reference"] = {"file": _need(ref, "file", str, w + " [reference]"), "curve": curve}
    win = d.get("window", {"kind": "reference"})
    c["window"] = {"kind": _need(win, "kind", str, w + " [window]")}
    if c["window"]["kind"] == "peak":
        c["window"]["search"] = tuple(_vector(win, "search", w + " [window]", 2))
        c["window"]["factor"] = _need(win, "factor", float, w + " [window]")
    elif c["window"]["kind"] != "reference":
        raise CaseError("%s [window]: kind %r; expected reference or peak" % (w, c["window"]["kind"]))
    c["channels"] = []
    for k, ch in enumerate(_need(d, "channel", list, w, [])):
        where = "%s [[channel]] %d" % (w, k + 1)
        e = {"name": _need(ch, "name", str, where), "model": _need(ch, "model", str, where),
             "scale": _need(ch, "scale", float, where, 1.0), "tare": _need(ch, "tare", bool, where, False),
             "cfc": _need(ch, "cfc", int, where, 0), "definition": _need(ch, "definition", str, where, "")}
        if e["definition"] and e["definition"] not in DEFINITIONS:
            raise CaseError("%s: definition %r; expected one of %s" % (where, e["definition"], ", ".join(DEFINITIONS)))
        if e["cfc"] not in (0, 60, 180, 600, 1000):
            raise CaseError("%s: cfc %r; expected 0 (none), 60, 180, 600 or 1000" % (where, e["cfc"]))
        e["angle"] = None
        if e["definition"] == "integrated":
            e["angle"] = ("integrated", _need(ch, "omega", str, where))
        elif e["definition"] == "planar" and "body" in ch:
            e["angle"] = ("planar", _need(ch, "body", str, where), _need(ch, "parent", str, where),
                          _need(ch, "axis", str, where))
        c["channels"].append(e)
    if c["rated"] and not c["channels"]:
        raise CaseError("%s: a rated case needs at least one [[channel]]" % w)
    return c


def case_files(folder=CASES_DIR):
    """The case files (*.toml) of a folder, sorted by name."""
    return sorted(os.path.join(folder, n) for n in os.listdir(folder) if n.endswith(".toml"))


def load_cases(folder=CASES_DIR):
    """The cases of every case file of a folder, in their order (the key
    order, then the file name); CaseError on a file that cannot be read or
    two files of one name or title."""
    cases = sorted(map(load_case, case_files(folder)), key=lambda c: c["order"])
    for key in ("name", "title"):
        seen = {}
        for c in cases:
            if c[key] in seen:
                raise CaseError("%s and %s: both have the %s %r" % (seen[c[key]], c["path"], key, c[key]))
            seen[c[key]] = c["path"]
    return cases


#: the given cases (the case files of reference/cases) by name
CASES = {c["name"]: c for c in load_cases()}


def _case(case):
    """A case dict from a case dict or the name of a given case."""
    return CASES[case] if isinstance(case, str) else case


#: every rated channel of each case: (the data's channel, the run's
#: channel, the scale to the data's sign, whether taken from its value at
#: the start, the CFC class [Hz] the model curve is filtered by, 0 none),
#: from the case files; the module docstring says why each is what it is.
#: The catalogue's runs and the calibration's RATED cards (hhneck.validation.calibration)
#: both read this table.
CHANNELS = {n: [(e["name"], e["model"], e["scale"], e["tare"], e["cfc"]) for e in c["channels"]]
            for n, c in CASES.items()}
STEMPER_CHANNELS = [c[0] for c in CHANNELS["stemper"]]
#: the angle each rated rotation is, as its source defined it (module
#: docstring, "Head angles"; a case file's definition): (case, data channel)
#: -> ("planar", body, parent, axis): the body's rotation relative to its
#: parent seen in the parent's plane normal to axis (planar_angle, from the
#: result file's rotation matrices); ("integrated", channel): the time
#: integral of an angular velocity channel [rad/s] (integrated_rotation).
#: The channel of CHANNELS beside it is the result file's nearest (what the
#: calibration's RATED cards rate: a Fortran channel): HT1_RY equals the
#: planar angle in a sagittal motion; HEADL_RX and HEADL_RY are Bryant angles.
ANGLES = {(n, e["name"]): e["angle"] for n, c in CASES.items() for e in c["channels"] if e["angle"]}
#: the reference curve of each case's channels (hhneck.validation.specimen_data.reference's
#: curve): the corridor outline named in the data file, or the specimens whose mean is taken
REFERENCE = {n: c["reference"]["curve"] for n, c in CASES.items() if c["reference"]}
#: each case's experiment file in the data folder
DATA_FILE = {n: c["reference"]["file"] for n, c in CASES.items() if c["reference"]}
#: the T1 slope [deg] of each source's potting (the case files)
T1_SLOPE = {"stemper": CASES["stemper"]["potting"]["slope"], "kang": CASES["kang_front"]["potting"]["slope"]}
#: [ms] the times the Kang rating searches for the reference's largest
#: magnitude (its window ends at 1.2 x that time): the source's, 0-99.9 ms
KANG_PEAK_SEARCH = CASES["kang_front"]["window"]["search"]
KANG_CHANNELS = {d: [c[0] for c in CHANNELS["kang_" + d]] for d in ("front", "side")}
#: the Kang load cell's point in T1's axes from T1's mass centre [m]: the
#: potting centre 81 mm behind and 229 mm below the head's mass centre
#: (README "Initial position"), the head's mass centre being 54.0 mm ahead of
#: and 175.3 mm above T1's in the model deck at the start (the case files;
#: test_specimens checks it against the run)
KANG_CELL_POINT = tuple(CASES["kang_front"]["loadcell"]["point"])


def planar_angle(s_parent, s_body, axis):
    """[deg] The rotation of a body relative to its parent seen in the
    parent's plane normal to `axis` (x, y or z) at every sample: with R =
    S_parent^T S_body (S the body-to-R matrices, shape (nt, 3, 3)), about
    y atan2(R13, R33), about x atan2(-R23, R33), about z atan2(R21, R11)
    (a film of that anatomical plane; the result file's BODY_PX/PY/PZ for
    a joint), continued from sample to sample."""
    r = np.einsum("tji,tjk->tik", np.asarray(s_parent, float), np.asarray(s_body, float))
    num, den = {"x": (-r[:, 1, 2], r[:, 2, 2]), "y": (r[:, 0, 2], r[:, 2, 2]), "z": (r[:, 1, 0], r[:, 0, 0])}[axis]
    return np.degrees(np.unwrap(np.arctan2(num, den)))


def integrated_rotation(t, omega):
    """[deg] The time integral of an angular velocity omega [rad/s] at the
    times t [s] from the first (trapezoidal): the rotation an angular-rate
    sensor, or a finite-element code's nodal rotation about a fixed axis,
    reports."""
    t, w = np.asarray(t, float), np.asarray(omega, float)
    return np.degrees(np.concatenate([[0.0], np.cumsum(0.5 * (w[1:] + w[:-1]) * np.diff(t))]))


def body_rotations(f, name):
    """The body-to-R matrices S (nt, 3, 3), S[t, i, j] = S_ij, of the body
    `name` of an open result file."""
    names = [n.decode() if isinstance(n, bytes) else str(n) for n in f["model"].attrs["bodies"]]
    return np.swapaxes(f["bodies/rotation"][:, names.index(name)], 1, 2)


def angle_channel(f, definition):
    """The values [deg] of an ANGLES definition from an open result file."""
    if definition[0] == "planar":
        _, body, parent, axis = definition
        return planar_angle(body_rotations(f, parent), body_rotations(f, body), axis)
    return integrated_rotation(f["time"][:], f["channels"][definition[1]][:])


def model_channels(case, h5):
    """The rated channels of `case` (a case dict or a given case's name)
    from its result file: {data channel: (t [ms], model value in the data's
    signs)} (its channels, the rotations as their definitions say): scaled,
    less its start value where the case says so, then filtered by its CFC
    class (the order of the calibration's RATED cards)."""
    import h5py
    with h5py.File(h5, "r") as f:
        t = f["time"][:] * 1e3
        out = {}
        for e in _case(case)["channels"]:
            v = angle_channel(f, e["angle"]) if e["angle"] else np.asarray(f["channels"][e["model"]][:], dtype=float)
            out[e["name"]] = (t, filtered(t, e["scale"] * (v - v[0] if e["tare"] else v), e["cfc"]))
    return out


def filtered(t, v, cls):
    """The curve v at the even times t [ms] filtered by SAE J211 class cls
    [Hz] (CHANNELS' fifth field); v itself for class 0."""
    return cfc(v, cls, (t[1] - t[0]) * 1e-3) if cls else v


def _run(deck, workdir, exe):
    """Run a deck in workdir (shipped decks found through -I ROOT), its
    listing (.txt) and stderr (.err) beside it; its result file."""
    segments.run_listed(deck, [exe or segments.default_executable(), "-I", segments.ROOT], workdir)
    return deck[:-4] + ".h5"


def run_name(case, support="HOLD", muscles="PASSIVE"):
    """The file name (no extension) of a case's deck, listing, stderr and
    result file: the case's name, support and muscles state."""
    return "%s_%s_%s" % (case if isinstance(case, str) else case["name"], support.lower(), muscles.lower())


def model_t1_slope(model_deck=os.path.join(segments.ROOT, "input", "head_neck_54dof.inp")):
    """The model deck's T1 slope [deg]: its NEUTRAL card of C7 RY."""
    for line in open(model_deck):
        if line.startswith("NEUTRAL") and line[10:20].strip() == "C7" and line[20:30].strip() == "RY":
            return float(line[30:40])
    raise ValueError("%s: no NEUTRAL card of C7 RY (the T1 slope)" % model_deck)


def _held_t1(driven, t1_slope, body="T1"):
    """PRESCRIB CONSTANT cards of the potted body's coordinates but those
    `driven`: its pitch RY the tilt that gives the T1 slope t1_slope [deg]."""
    tilt = t1_slope - model_t1_slope()
    return [card("PRESCRIB", body, c, "CONSTANT", "%.4f" % tilt if c == "RY" else None)
            for c in ("TX", "TY", "TZ", "RX", "RY", "RZ") if c not in driven]


def _support_cards(support):
    """The cards of the start posture's support: RELEASE, held at rest until
    the pulse (t = 0) and free from it, as the labs' positioning support
    was cut at the pulse (HOLD POSTURE released at 0 as a step); HOLD, held
    through the test (HOLD POSTURE's constant forces); PRESTRAIN, settled
    (HOLD PRESTRAIN: the joints' discs and neutral-zone springs pre-strained
    to carry the posture); NONE, no support (free from rest at t = 0: the
    same motion as RELEASE, without the statement)."""
    cards = {"RELEASE": ["HOLD      POSTURE   0.0"], "HOLD": ["HOLD      POSTURE"],
             "PRESTRAIN": ["HOLD      PRESTRAIN"], "NONE": []}
    if support not in cards:
        raise ValueError("support: RELEASE, HOLD, PRESTRAIN or NONE, not %r" % support)
    return cards[support]


def _pulse_tables(c, workdir, data_dir):
    """Write the pulse's component tables along the case's direction into
    workdir: [(coordinate, table name, file name, points)]. One table named
    as the case's pulse table per nonzero component (a suffix X, Y, Z when
    more than one), the pulse times made a function (its repeated times
    merged into their mean value). None without a pulse (the potted body held)."""
    if c["pulse"] is None:
        return []
    t, a = specimen_data.read_pulse(os.path.join(data_dir, c["pulse"]["file"]))
    t, a = specimen_data._as_function(t, a)
    comps = [(k, d) for k, d in enumerate(c["pulse"]["direction"]) if d != 0.0]
    out = []
    for k, d in comps:
        suffix = "XYZ"[k] if len(comps) > 1 else ""
        name = c["pulse"]["table"][:8 - len(suffix)] + suffix
        fname = "%s_pulse%s.csv" % (c["name"], suffix.lower() and "_" + suffix.lower())
        with open(os.path.join(workdir, fname), "w") as f:
            f.write("time_s,a_m_s2\n" + "".join("%.9g,%.9g\n" % (tt, d * c["pulse"]["scale"] * aa)
                                                for tt, aa in zip(t, a)))
        out.append(("T" + "XYZ"[k], name, fname, len(t)))
    return out


def _e(v):
    """A tolerance as a CONTROL card's field: 1.0E-3."""
    m, e = ("%.1e" % v).split("e")
    return "%sE%d" % (m, int(e))


def case_deck(case, workdir, support=None, muscles=None, data_dir=segments.DATA_DIR, t1_slope=None, model=None):
    """Write a case's deck and its pulse tables into workdir; returns the
    deck's path. case: a case dict (load_case) or a given case's name;
    support, muscles: a variant's (default the case's); t1_slope: the potted
    body's slope [deg] (default the case's); model: the model deck it
    includes (default the case's, the shipped one)."""
    c = _case(case)
    support, muscles = (support or c["support"]).upper(), (muscles or c["muscles"]).upper()
    if muscles not in MUSCLES:
        raise ValueError("muscles: PASSIVE or REFLEX, not %r" % muscles)
    body = c["potting"]["body"]
    name = run_name(c["name"], support, muscles)
    lines = [card("TITLE", "%s (%s, MUSCLES %s)" % (c["deck_title"], support, muscles)),
             "*         end (s)   step (s)  print (s) method    rtol      atol",
             card("CONTROL", "%g" % c["end_time"], "1.0E-4", "0.005", "ROS34PW2", _e(c["rtol"]), _e(c["atol"])),
             "SOLVER    ABA       STRUCT",
             "OUTPUT    1.0E-4",
             card("H5FILE", name + ".h5")]
    lines += [] if support == "CLAMP" else _support_cards(support)
    lines += [card("INCLUDE", model or c["model"])] + (c["clamp"] if support == "CLAMP" else [])
    tables = _pulse_tables(c, workdir, data_dir)
    for _, table, fname, n in tables:
        lines += [card("TABLE", table, "%d" % n, "1.0", "1.0", "CSV"), card("", fname)]
    lines += [card("PRESCRIB", body, q, "ACCEL", table, "0.0", "0.0") for q, table, _, _ in tables]
    if c["loadcell"]:
        lc = c["loadcell"]
        lines.append(card("LOADCELL", lc["name"], lc["body"], *["%.4f" % v for v in lc["point"]], lc["axes"]))
    lines += _held_t1([q for q, _, _, _ in tables], c["potting"]["slope"] if t1_slope is None else t1_slope, body)
    if muscles == "PASSIVE":
        for act in ("FLEX", "EXT"):
            for k, field in ((2, "U0"), (3, "U1")):
                lines.append(card("CHANGE", act[:4] + field, "FIELD%d" % k, "ACTIVATE", act, "SET", "0.0"))
    deck = os.path.join(workdir, name + ".inp")
    with open(deck, "w") as f:
        f.write("\n".join(lines) + "\n")
    return deck


def run_case(case, workdir=None, exe=None, support=None, muscles=None):
    """Run a case's deck (a variant's with support, muscles); {channel: (t
    [ms], model value in the data's signs)}."""
    work = workdir or tempfile.mkdtemp(prefix="hhneck-case-")
    os.makedirs(work, exist_ok=True)
    return model_channels(case, _run(case_deck(case, work, support, muscles), work, exe))


def rated_reference(case, channel, data_dir=segments.DATA_DIR, shift=0.0):
    """(grid [ms], reference, lower, upper) of a channel of `case` on its
    rated window: the case's named reference over the times it covers; a
    peak window from 0 to factor x the time of the reference's largest
    magnitude in the case's search times (peak_window), the times moved by
    shift [ms] first."""
    c = _case(case)
    g, ref, lo, hi = specimen_data.reference(os.path.join(data_dir, c["reference"]["file"]), channel,
                                             c["reference"]["curve"])
    if c["window"]["kind"] == "peak":
        return peak_window(g + shift, ref, lo, hi, c["window"]["search"], c["window"]["factor"])
    return g + shift, ref, lo, hi


def peak_window(g, ref, lo, hi, search=KANG_PEAK_SEARCH, factor=1.2):
    """A peak window of a reference (grid [ms], reference, lower, upper):
    from 0 to factor x the time of the reference's largest magnitude
    between the search times."""
    keep = g >= 0.0
    g, ref, lo, hi = g[keep], ref[keep], lo[keep], hi[keep]
    found = np.flatnonzero((g >= search[0] - 1e-9) & (g <= search[1] + 1e-9))
    keep = g <= factor * g[found[int(np.argmax(np.abs(ref[found])))]]
    return g[keep], ref[keep], lo[keep], hi[keep]


def kang_window(g, ref, lo, hi):
    """The Kang rating's window of a reference (grid [ms], reference, lower,
    upper): from 0 to 1.2 x the time of the reference's largest magnitude
    between KANG_PEAK_SEARCH's times."""
    return peak_window(g, ref, lo, hi)


def rate_case(case, model, data_dir=segments.DATA_DIR, shifts=None):
    """ISO/TS 18571 of every rated channel of a case on its window:
    {channel: dict(scores..., grid, reference, lower, upper, model,
    peak_model, peak_ref)}. shifts: {channel: ms} moves those references'
    times (a study of a source's comparison; the catalogue moves none)."""
    return {e["name"]: rate_channel(*rated_reference(case, e["name"], data_dir, (shifts or {}).get(e["name"], 0.0)),
                                    *model[e["name"]]) for e in _case(case)["channels"]}


def stemper_deck(workdir, support="HOLD", muscles="PASSIVE", data_dir=segments.DATA_DIR,
                 t1_slope=T1_SLOPE["stemper"]):
    """Write the Stemper 1.8 m/s deck (its case file) and its pulse table
    into workdir; returns the deck's path. support: RELEASE, HOLD,
    PRESTRAIN or NONE (_support_cards); muscles: PASSIVE (activation zero)
    or REFLEX (the model deck's volunteer activation histories); t1_slope:
    the potted T1's slope [deg]."""
    return case_deck("stemper", workdir, support, muscles, data_dir, t1_slope)


def run_stemper(workdir=None, exe=None, support="HOLD", muscles="PASSIVE"):
    """Run the Stemper deck; {channel: (t [ms], model value)} in the data's signs."""
    return run_case("stemper", workdir, exe, support, muscles)


def rate_stemper(model, data_dir=segments.DATA_DIR):
    """ISO/TS 18571 of every Stemper channel: {channel: dict(scores...,
    grid, reference, lower, upper, model, peak_model, peak_ref)}."""
    return rate_case("stemper", model, data_dir)


def rate_channel(g, ref, lo, hi, t, m):
    """ISO/TS 18571 of the model curve (t [ms], m) against the reference on
    the grid g [ms], with its bounds, over the times both cover (a reference
    that runs past the model's run is rated to the run's end, never against
    a held last value): the scores, the curves on that grid, both peaks
    (value, time), the share of the grid inside the bounds, the rated
    window (first, last time) and the reference's own last time."""
    g, ref, lo, hi = (np.asarray(x, float) for x in (g, ref, lo, hi))
    t, m = np.asarray(t, float), np.asarray(m, float)
    common = (g >= t[0] - 1e-9) & (g <= t[-1] + 1e-9)
    if np.count_nonzero(common) < 2:
        raise ValueError("the model's run (%.4g to %.4g ms) does not cover the reference (%.4g to %.4g ms)"
                         % (t[0], t[-1], g[0], g[-1]))
    end = g[-1]
    g, ref, lo, hi = g[common], ref[common], lo[common], hi[common]
    mi = np.interp(g, t, m)
    sc = ratings.rate(g * 1e-3, ref, mi)
    km, kr = int(np.argmax(np.abs(mi))), int(np.argmax(np.abs(ref)))
    sc.update(grid=g, reference=ref, lower=lo, upper=hi, model=mi, peak_model=(mi[km], g[km]),
              peak_ref=(ref[kr], g[kr]), inside=float(np.mean((mi >= lo) & (mi <= hi))),
              window=(g[0], g[-1]), reference_end=end)
    return sc


def kang_deck(workdir, direction, support="HOLD", data_dir=segments.DATA_DIR, t1_slope=T1_SLOPE["kang"],
              model="input/head_neck_54dof.inp"):
    """Write the Kang 2018 deck of `direction` (front or side, its case
    file) and its pulse table into workdir; returns the deck's path.
    t1_slope: the potted T1's slope [deg]; model: the model deck it
    includes (a study's variant in workdir; the shipped one by default)."""
    return case_deck("kang_" + direction, workdir, support, "PASSIVE", data_dir, t1_slope, model)


def run_kang(direction, workdir=None, exe=None, support="HOLD"):
    """Run a Kang deck; {channel: (t [ms], model in SAE J211 axes)}."""
    return run_case("kang_" + direction, workdir, exe, support)


def rate_kang(direction, model, data_dir=segments.DATA_DIR, shifts=None):
    """ISO/TS 18571 of the rated Kang channels (window 0 to 1.2 x the time
    of the reference's largest magnitude in KANG_PEAK_SEARCH). shifts:
    {channel: ms} moves those references' times (a study of the source
    notebook's comparison; the catalogue moves none)."""
    return rate_case("kang_" + direction, model, data_dir, shifts)


def kang_reference(direction, channel, data_dir=segments.DATA_DIR, shift=0.0):
    """(grid [ms], reference, lower, upper) of a Kang channel on its rated
    window (rated_reference), the times moved by shift [ms] first."""
    return rated_reference("kang_" + direction, channel, data_dir, shift)
