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
outline's midline, the outline named (REFERENCE; hhneck.specimen_data),
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

API: CHANNELS (the rated channels: the data's and the run's), ANGLES, REFERENCE;
model_channels, filtered, planar_angle, integrated_rotation;
stemper_deck, run_stemper (-> {channel: (t_ms, model)}), rate_stemper;
kang_deck, run_kang, rate_kang, kang_reference, kang_window; rated_reference, rate_channel.
"""
import os
import tempfile

import numpy as np

from . import iso18571, segments, specimen_data
from .compare_nbdl import cfc

#: every rated channel of each case: (the data's channel, the run's
#: channel, the scale to the data's sign, whether taken from its value at
#: the start, the CFC class [Hz] the model curve is filtered by, 0 none);
#: the module docstring says why each is what it is. The catalogue's runs
#: and the calibration's RATED cards (hhneck.calibration) both read this
#: table.
CHANNELS = {
    "stemper": [("seg_angle_C%d_C%d" % (k, k + 1), "C%d_PY" % k, -1.0, True, 0) for k in range(2, 7)]
    + [("head_T1_angle", "HT1_RY", -1.0, True, 0), ("head_T1_retraction", "HT1_DX", 1.0, False, 0)],
    "kang_front": [("head_acc_x", "HEAD_AXS", 1.0, True, 60), ("head_acc_z", "HEAD_AZS", -1.0, True, 180),
                   ("head_rot_y", "HEADL_RY", -1.0, True, 180), ("loadcell_force_x", "T1CELL_JFX", 1.0, True, 60),
                   ("loadcell_force_z", "T1CELL_JFZ", 1.0, True, 60),
                   ("loadcell_moment_y", "T1CELL_JMY", 1.0, True, 180)],
    "kang_side": [("head_acc_y", "HEAD_AYS", -1.0, True, 180), ("head_acc_z", "HEAD_AZS", -1.0, True, 180),
                  ("head_rot_x", "HEADL_RX", 1.0, True, 180), ("loadcell_moment_x", "T1CELL_JMX", 1.0, True, 180),
                  ("loadcell_force_y", "T1CELL_JFY", 1.0, True, 60), ("loadcell_force_z", "T1CELL_JFZ", 1.0, True, 60)],
}
STEMPER_CHANNELS = [c[0] for c in CHANNELS["stemper"]]


#: the angle each rated rotation is, as its source defined it (module
#: docstring, "Head angles"): (case, data channel) -> ("planar", body,
#: parent, axis): the body's rotation relative to its parent seen in the
#: parent's plane normal to axis (planar_angle, from the result file's
#: rotation matrices); ("integrated", channel): the time integral of an
#: angular velocity channel [rad/s] (integrated_rotation). The channel of
#: CHANNELS beside it is the result file's nearest (what the calibration's
#: RATED cards rate: a Fortran channel): HT1_RY equals the planar angle in
#: a sagittal motion; HEADL_RX and HEADL_RY are Bryant angles.
ANGLES = {("stemper", "head_T1_angle"): ("planar", "HEAD", "T1", "y"),
          ("kang_front", "head_rot_y"): ("integrated", "HEAD_OMEGY"),
          ("kang_side", "head_rot_x"): ("integrated", "HEAD_OMEGX")}


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
    """The rated channels of `case` from its result file:
    {data channel: (t [ms], model value in the data's signs)} (CHANNELS,
    the rotations as ANGLES defines them): scaled, less its start value
    where the table says so, then filtered by its CFC class (the order of
    the calibration's RATED cards)."""
    import h5py
    with h5py.File(h5, "r") as f:
        t = f["time"][:] * 1e3
        out = {}
        for name, run, scale, start, cls in CHANNELS[case]:
            v = angle_channel(f, ANGLES[case, name]) if (case, name) in ANGLES \
                else np.asarray(f["channels"][run][:], dtype=float)
            out[name] = (t, filtered(t, scale * (v - v[0] if start else v), cls))
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
    result file: case stemper, kang_front or kang_side."""
    if case == "stemper":
        return "stemper_%s_%s" % (support.lower(), muscles.lower())
    return "%s_%s" % (case, support.lower())


#: the T1 slope [deg] of each source's potting (module docstring)
T1_SLOPE = {"stemper": 25.0, "kang": 24.0}


def model_t1_slope(model_deck=os.path.join(segments.ROOT, "input", "head_neck_54dof.inp")):
    """The model deck's T1 slope [deg]: its NEUTRAL card of C7 RY."""
    for line in open(model_deck):
        if line.startswith("NEUTRAL") and line[10:20].strip() == "C7" and line[20:30].strip() == "RY":
            return float(line[30:40])
    raise ValueError("%s: no NEUTRAL card of C7 RY (the T1 slope)" % model_deck)


def _held_t1(driven, t1_slope):
    """PRESCRIB CONSTANT cards of the potted T1's coordinates but `driven`:
    its pitch RY the tilt that gives the T1 slope t1_slope [deg]."""
    tilt = t1_slope - model_t1_slope()
    return ["PRESCRIB  T1        %s        CONSTANT  %s" % (c, "%-10.4f" % tilt if c == "RY" else "")
            for c in ("TX", "TY", "TZ", "RX", "RY", "RZ") if c != driven]


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


def stemper_deck(workdir, support="HOLD", muscles="PASSIVE", data_dir=segments.DATA_DIR,
                 t1_slope=T1_SLOPE["stemper"]):
    """Write the Stemper 1.8 m/s deck and its two-column pulse table into
    workdir; returns the deck's path. support: RELEASE, HOLD, PRESTRAIN or NONE
    (_support_cards); muscles:
    PASSIVE (activation zero) or REFLEX (the model deck's volunteer
    activation histories); t1_slope: the potted T1's slope [deg]."""
    t, a = specimen_data.read_pulse(os.path.join(data_dir, "stemper2004_1p8ms_pulse.csv"))
    pulse = os.path.join(workdir, "stemper_pulse.csv")
    with open(pulse, "w") as f:
        f.write("time_s,a_m_s2\n" + "".join("%.9g,%.9g\n" % p for p in zip(t, a)))
    name = run_name("stemper", support, muscles)
    lines = [
        "TITLE     STEMPER 2004 REAR 1.8 M/S, T1 POTTED (%s, MUSCLES %s)" % (support, muscles),
        "*         end (s)   step (s)  print (s) method    rtol      atol",
        "CONTROL   0.13      1.0E-4    0.005     ROS34PW2  1.0E-3    1.0E-5",
        "SOLVER    ABA       STRUCT",
        "OUTPUT    1.0E-4",
        "H5FILE    %s.h5" % name,
    ]
    lines += _support_cards(support)
    lines += ["INCLUDE   input/head_neck_54dof.inp",
              "TABLE     STEMPER   %-10d1.0       1.0       CSV" % len(t),
              "          %s" % os.path.basename(pulse),
              "PRESCRIB  T1        TX        ACCEL     STEMPER   0.0       0.0"]
    lines += [c.rstrip() for c in _held_t1("TX", t1_slope)]
    if muscles == "PASSIVE":
        for act in ("FLEX", "EXT"):
            for k, field in ((2, "U0"), (3, "U1")):
                lines.append("CHANGE    %-10sFIELD%d    ACTIVATE  %-10sSET       0.0" % (act[:4] + field, k, act))
    elif muscles != "REFLEX":
        raise ValueError("muscles: PASSIVE or REFLEX, not %r" % muscles)
    deck = os.path.join(workdir, name + ".inp")
    with open(deck, "w") as f:
        f.write("\n".join(lines) + "\n")
    return deck


def run_stemper(workdir=None, exe=None, support="HOLD", muscles="PASSIVE"):
    """Run the Stemper deck; {channel: (t [ms], model value)} in the data's signs."""
    work = workdir or tempfile.mkdtemp(prefix="hhneck-stemper-")
    os.makedirs(work, exist_ok=True)
    return model_channels("stemper", _run(stemper_deck(work, support, muscles), work, exe))


#: the reference curve of each case's channels (hhneck.specimen_data.reference's
#: curve): the corridor outline named in the data file, or the specimens whose mean is taken
REFERENCE = {"stemper": "stemper2004_corridor_outline", "kang_front": "corridor_outline",
             "kang_side": ("pmhs1", "pmhs2")}
#: each case's experiment file in the data folder
DATA_FILE = {"stemper": "stemper2004_1p8ms_experiment.csv", "kang_front": "kang2018_front_experiment.csv",
             "kang_side": "kang2018_side_experiment.csv"}
#: [ms] the times the Kang rating searches for the reference's largest
#: magnitude (its window ends at 1.2 x that time): the source's, 0-99.9 ms
KANG_PEAK_SEARCH = (0.0, 99.9)


def rated_reference(case, channel, data_dir=segments.DATA_DIR, shift=0.0):
    """(grid [ms], reference, lower, upper) of a channel of `case` on its
    rated window: the named reference (REFERENCE) over the times it covers;
    Kang from 0 to 1.2 x the time of the reference's largest magnitude in
    KANG_PEAK_SEARCH (kang_window), the times moved by shift [ms] first."""
    g, ref, lo, hi = specimen_data.reference(os.path.join(data_dir, DATA_FILE[case]), channel, REFERENCE[case])
    if case.startswith("kang"):
        return kang_window(g + shift, ref, lo, hi)
    return g + shift, ref, lo, hi


def kang_window(g, ref, lo, hi):
    """The Kang rating's window of a reference (grid [ms], reference, lower,
    upper): from 0 to 1.2 x the time of the reference's largest magnitude
    between KANG_PEAK_SEARCH's times."""
    keep = g >= 0.0
    g, ref, lo, hi = g[keep], ref[keep], lo[keep], hi[keep]
    search = np.flatnonzero((g >= KANG_PEAK_SEARCH[0] - 1e-9) & (g <= KANG_PEAK_SEARCH[1] + 1e-9))
    keep = g <= 1.2 * g[search[int(np.argmax(np.abs(ref[search])))]]
    return g[keep], ref[keep], lo[keep], hi[keep]


def rate_stemper(model, data_dir=segments.DATA_DIR):
    """ISO/TS 18571 of every Stemper channel: {channel: dict(scores...,
    grid, reference, lower, upper, model, peak_model, peak_ref)}."""
    return {ch: rate_channel(*rated_reference("stemper", ch, data_dir), *model[ch]) for ch in STEMPER_CHANNELS}


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
    sc = iso18571.rate(g * 1e-3, ref, mi)
    km, kr = int(np.argmax(np.abs(mi))), int(np.argmax(np.abs(ref)))
    sc.update(grid=g, reference=ref, lower=lo, upper=hi, model=mi, peak_model=(mi[km], g[km]),
              peak_ref=(ref[kr], g[kr]), inside=float(np.mean((mi >= lo) & (mi <= hi))),
              window=(g[0], g[-1]), reference_end=end)
    return sc


KANG_CHANNELS = {d: [c[0] for c in CHANNELS["kang_" + d]] for d in ("front", "side")}
#: the Kang load cell's point in T1's axes from T1's mass centre [m]: the
#: potting centre 81 mm behind and 229 mm below the head's mass centre
#: (README "Initial position"), the head's mass centre being 54.0 mm ahead of
#: and 175.3 mm above T1's in the model deck at the start
#: (test_specimens checks it against the run)
KANG_CELL_POINT = (0.054 - 0.081, 0.0, 0.1753 - 0.229)



def kang_deck(workdir, direction, support="HOLD", data_dir=segments.DATA_DIR, t1_slope=T1_SLOPE["kang"],
              model="input/head_neck_54dof.inp"):
    """Write the Kang 2018 deck of `direction` (front or side) and its pulse
    table into workdir; returns the deck's path. t1_slope: the potted T1's
    slope [deg]; model: the model deck it includes (a study's variant in
    workdir; the shipped one by default)."""
    t, a = specimen_data.read_pulse(os.path.join(data_dir, "kang2018_sled_pulse.csv"))
    # a TABLE's times increase strictly: the digitised pulse repeats 2.752 ms
    # (30.65 and 35.27 m/s^2), merged into their mean
    t, a = specimen_data._as_function(t, a)
    sign = -1.0                            # front: rearward (-x); side: toward the model's -y
    with open(os.path.join(workdir, "kang_pulse.csv"), "w") as f:
        f.write("time_s,a_m_s2\n" + "".join("%.9g,%.9g\n" % (tt, sign * aa) for tt, aa in zip(t, a)))
    driven = {"front": "TX", "side": "TY"}[direction]
    name = run_name("kang_" + direction, support)
    lines = ["TITLE     KANG 2018 %s SLED 14 KM/H, T1 POTTED (%s, MUSCLES PASSIVE)" % (
                 direction.upper(), support),
             "CONTROL   0.2       1.0E-4    0.005     ROS34PW2  1.0E-3    1.0E-5",
             "SOLVER    ABA       STRUCT",
             "OUTPUT    1.0E-4",
             "H5FILE    %s.h5" % name]
    lines += _support_cards(support)
    lines += ["INCLUDE   %s" % model,
              "TABLE     KANG      %-10d1.0       1.0       CSV" % len(t),
              "          kang_pulse.csv",
              "PRESCRIB  T1        %s        ACCEL     KANG      0.0       0.0" % driven,
              "LOADCELL  T1CELL    C7        %-10.4f%-10.4f%-10.4fT1" % KANG_CELL_POINT]
    lines += [c.rstrip() for c in _held_t1(driven, t1_slope)]
    for act in ("FLEX", "EXT"):
        for k, field in ((2, "U0"), (3, "U1")):
            lines.append("CHANGE    %-10sFIELD%d    ACTIVATE  %-10sSET       0.0" % (act[:4] + field, k, act))
    deck = os.path.join(workdir, name + ".inp")
    with open(deck, "w") as f:
        f.write("\n".join(lines) + "\n")
    return deck


def run_kang(direction, workdir=None, exe=None, support="HOLD"):
    """Run a Kang deck; {channel: (t [ms], model in SAE J211 axes)}."""
    work = workdir or tempfile.mkdtemp(prefix="hhneck-kang-")
    os.makedirs(work, exist_ok=True)
    return model_channels("kang_" + direction, _run(kang_deck(work, direction, support), work, exe))


def rate_kang(direction, model, data_dir=segments.DATA_DIR, shifts=None):
    """ISO/TS 18571 of the rated Kang channels (window 0 to 1.2 x the time
    of the reference's largest magnitude in KANG_PEAK_SEARCH). shifts: {channel: ms} moves
    those references' times (a study of the source notebook's comparison;
    the catalogue moves none)."""
    return {ch: rate_channel(*kang_reference(direction, ch, data_dir, (shifts or {}).get(ch, 0.0)), *model[ch])
            for ch in KANG_CHANNELS[direction]}


def kang_reference(direction, channel, data_dir=segments.DATA_DIR, shift=0.0):
    """(grid [ms], reference, lower, upper) of a Kang channel on its rated
    window (rated_reference), the times moved by shift [ms] first."""
    return rated_reference("kang_" + direction, channel, data_dir, shift)
