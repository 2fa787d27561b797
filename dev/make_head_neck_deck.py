#!/usr/bin/env python3
"""Writes input/head_neck_54dof.inp, the 9-body head/neck model shared by the
case decks, from the parameter choices below. Every number carries its source
(S1..S6, listed in reference/parameters.md) or is marked ASSUMED.

    python3 dev/make_head_neck_deck.py > input/head_neck_54dof.inp
    python3 dev/make_head_neck_deck.py --fit FIT.txt > input/head_neck_54dof.inp

    python3 dev/make_head_neck_deck.py --posture straight [--fit FIT.txt] > DECK

The shipped column takes the sourced seated sagittal posture (T1 slope, C2-C7
lordosis, head level; "posture" below) as its neutral; --t1-slope and
--lordosis (deg) vary it, --posture straight gives the straight column of the
earlier model and --posture seated-held the seated angles as an initial
deflection of the straight neutral.
With --fit, the FITTED values (SCALE cards, ACTIVATE FLEX and EXT levels and delays)
are read from the listing of the calibration (the PARAM lines of
hhneck --calibrate < input/calibrate_nbdl.inp > FIT.txt); without it, the
copy of that output below is used.

Neutral-zone springs (the shipped deck has them): when reference/nz_springs.csv
exists (or the file of --nz-springs CSV; --nz-springs none: the discs alone),
the discs' own bending and torsion are scaled to DISC_ROT_FRACTION by two
SCALE cards (NZBEND, NZTORS) beside the fitted ones and, once the CSV
exists, one NZSPRING card per row of it follows the ROM cards. The constants
come from hhneck-fit-joints (python/hhneck/fit_joints.py), whose runs of the
segment tests drop the NZSPRING cards and must see the discs so scaled; the
whole flow, from the segment data to the muscles' fit, is dev/fit_model.sh.

--suboccipital yes adds the four suboccipital muscles per side (SUBOCCIPITAL_MUSCLES),
--segmental yes two segmental muscles per subaxial level and side (segmental_muscles),
--sub-bend F scales the subaxial discs' own bending Ix, Iy (SUB_BEND): experiments, not
the shipped model (docs/validation.md "Segmental muscles").
--sub-flexion F scales the flexion-extension bending Iy of the discs C3-C4 ... C7-T1
alone (SUB_FLEXION; docs/validation.md "The subaxial discs' flexion-extension").

Upper-cervical factors (an experiment, not the shipped model: docs/validation.md
"The upper cervical joints"): with --upper-cervical CSV (the file
hhneck-fit-joints --upper-cervical writes, reference/upper_cervical.csv) the
C2-C1 and C1-HEAD discs' flexion bending and torsion and their ligaments are
scaled by its factors through hhneck.upper_cervical.scale_cards, the function
the fit runs its cases with; without it (or with none), the cards as sourced.

Pure arithmetic on the published numbers: no solver code lives here.
"""
import math
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))
from hhneck.deck_fields import CardError, check_cards, scale_fields  # noqa: E402
from hhneck import upper_cervical  # noqa: E402

# ---------------------------------------------------------------- sources
SOURCES = """\
* SOURCES (full references in reference/parameters.md)
*  S1  Mortensen et al. 2018, PLOS ONE (HYOID OpenSim neck model): head and
*      vertebral masses, head principal inertia, intervertebral rotational
*      stiffness (bushings) of C5-T1, C3-C5, skull-C3.
*  S2  Mattucci & Cronin 2015, J Mech Behav Biomed Mater 41:251-260: cervical
*      ligament secant stiffness and peak force / elongation (mean values).
*  S3  Vasavada, Li & Delp 1998: ranges of motion skull-C2 and C2-T1.
*  S4  Huston, Huston & Harlow 1978: element laws eqs 1-13 (no parameter table).
*  A   ASSUMED: typical adult cervical geometry and tissue values chosen for
*      this model, listed with reasons in reference/parameters.md.
"""

def fmt(v):
    """A number in at most 9 columns (fields are 10 wide: one blank between)."""
    if isinstance(v, str):
        return v
    if v == 0:
        return "0.0"
    for p in range(6, 0, -1):
        s = "%.*g" % (p, v)
        if "e" in s:
            m, e = s.split("e")
            s = m + "E" + str(int(e))
        elif "." not in s:
            s = s + ".0"
        if len(s) <= 9:
            return s
    raise ValueError(v)

def card(key, *fields):
    s = "%-8s  " % key
    for f in fields:
        s += "%-10s" % ("" if f is None else fmt(f))
    return s.rstrip()        # within 80 columns: checked with the whole deck (check_cards)

def cont(*fields):
    return card("", *fields)

# ---------------------------------------------------------------- bodies
# name, mass (kg), Ixx, Iyy, Izz (kg m^2), vertebral body height hv (m),
# joint/disc height hd below the body (m)
G_STD = 9.80665
bodies = [
    # T1 is the root; it is prescribed in every case deck (mass used only if free)
    ("T1",   20.0,  0.30,    0.25,    0.20,    0.0160, None),
    ("C7",   0.523, None, None, None,          0.0145, 0.0050),
    ("C6",   0.454, None, None, None,          0.0140, 0.0050),
    ("C5",   0.384, None, None, None,          0.0140, 0.0055),
    ("C4",   0.379, None, None, None,          0.0140, 0.0055),
    ("C3",   0.376, None, None, None,          0.0140, 0.0050),
    ("C2",   0.526, None, None, None,          0.0200, 0.0045),
    ("C1",   0.418, None, None, None,          0.0100, 0.0040),
    ("HEAD", 3.847, 0.01662, 0.01813, 0.01203, None,   0.0040),
]
HEAD_CG_FROM_OC = (0.020, 0.0, 0.035)         # A: head mass centre ahead of and above OC
NECK_A, NECK_B = 0.055, 0.055                 # A: elliptic neck section semi-axes (AP, lateral)

def segment_inertia(m, h):
    """Solid elliptic cylinder, axis z, semi-axes NECK_A (x), NECK_B (y), height h."""
    ixx = m * (NECK_B**2 / 4 + h**2 / 12)
    iyy = m * (NECK_A**2 / 4 + h**2 / 12)
    izz = m * (NECK_A**2 + NECK_B**2) / 4
    return ixx, iyy, izz

# neutral positions (R; T1 centre at the origin; every body frame parallel to R)
centre = {}
joint = {}          # joint point below body (between parent and body)
z = 0.0
centre["T1"] = (0.0, 0.0, 0.0)
prev_hv = bodies[0][5]
for (name, m, ixx, iyy, izz, hv, hd) in bodies[1:]:
    jz = z + prev_hv / 2 + hd / 2
    joint[name] = (0.0, 0.0, jz)
    if name == "HEAD":
        centre[name] = (HEAD_CG_FROM_OC[0], 0.0, jz + HEAD_CG_FROM_OC[2])
    else:
        z = jz + hd / 2 + hv / 2
        centre[name] = (0.0, 0.0, z)
        prev_hv = hv
names = [b[0] for b in bodies]
parent = {names[i]: names[i - 1] for i in range(1, len(names))}

def rel(point, body):
    c = centre[body]
    return tuple(point[i] - c[i] for i in range(3))

# ---------------------------------------------------------------- discs
# rotational stiffness (N m/rad) lateral bending (about X), flexion (about Y),
# axial rotation (about Z), by region, from S1 (OpenSim x fwd, y up, z lateral:
# bushing x = lateral bending, y = axial rotation, z = flexion-extension)
ROT = {"C5-T1": (27.5, 27.5, 13.75), "C3-C5": (23.2, 23.2, 11.6), "skull-C3": (7.8, 7.8, 3.9)}
region = {"C7": "C5-T1", "C6": "C5-T1", "C5": "C5-T1", "C4": "C3-C5", "C3": "C3-C5",
          "C2": "skull-C3", "C1": "skull-C3", "HEAD": "skull-C3"}
K_AXIAL = 5.0e5       # A: axial stiffness of a motion segment, N/m (500 N/mm)
K_SHEAR = 3.0e5       # A, tuned: shear stiffness with end rotations held, N/m (300 N/mm)
AREA = 3.0e-4         # A: disc cross-section, m^2
TAU = 0.005           # A, tuned: retardation time d2/d1 of the two-parameter disc law, s
KSHEAR = 1.2          # A: shear shape factor

def disc_constants(lat, flex, axial, h):
    e = K_AXIAL * h / AREA                 # eq 1: k_axial = A d1 / h
    ix = lat * h / e                       # free-shear bending stiffness E I / h
    iy = flex * h / e
    phi = 12 * e * iy / (h**3 * K_SHEAR) - 1     # 12 E I / (h^3 (1 + Phi)) = k_shear
    g = 12 * e * iy * KSHEAR / (phi * AREA * h**2)
    j = axial * h / g                      # eq 7: G J / h = k_torsion
    return e, TAU * e, g, ix, iy, j

# ---------------------------------------------------------------- ligaments
# Mattucci & Cronin 2015 (S2): secant stiffness N/mm, peak force N, elongation at peak mm
LIG = {"ALL": (125.0, 342.0, 3.9), "PLL": (192.0, 341.0, 2.7), "LF": (95.0, 243.0, 5.6),
       "CL": (70.0, 194.0, 4.3), "ISL": (14.0, 55.0, 6.6)}
# A: attachment x, y (m) relative to the disc centre, and free length (m)
LIG_GEOM = {"ALL": [(0.009, 0.0)], "PLL": [(-0.008, 0.0)], "LF": [(-0.022, 0.0)],
            "CL": [(-0.015, 0.022), (-0.015, -0.022)], "ISL": [(-0.040, 0.0)]}
LIG_LEN = {"ALL": 0.010, "PLL": 0.010, "LF": 0.012, "CL": 0.006, "ISL": 0.012}

def fit_ligament(k, fp, dp):
    """F = l2 d^n (l1 = 0) through (dp, fp) whose secant stiffness between 20 %
    and 80 % of the peak force is k (S2's definition)."""
    k, dp = k * 1e3, dp * 1e-3              # N/m, m
    target = 0.6 * fp / k                    # d80 - d20
    lo, hi = 1.0, 20.0
    f = lambda n: dp * (0.8 ** (1 / n) - 0.2 ** (1 / n)) - target
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if f(lo) * f(mid) <= 0:
            hi = mid
        else:
            lo = mid
    n = 0.5 * (lo + hi)
    return n, fp / dp ** n

# ---------------------------------------------------------------- muscles
# A: simplified muscle groups (per side), neutral points in R: (body, point)
OC = joint["HEAD"]
def at(body, dx, dy, dz, ref=None):
    base = centre[body] if ref is None else ref
    return (body, (base[0] + dx, base[1] + dy, base[2] + dz))
MUSCLES = [
    # name, origin, insertion, PCSA per side (cm^2, A), optimal fibre length (m, A)
    ("SCM", lambda s: at("T1", 0.060, s * 0.025, -0.040), lambda s: at("HEAD", -0.005, s * 0.050, 0.015, OC), 4.9, 0.12),
    ("SPLC", lambda s: at("C7", -0.045, s * 0.008, 0.0), lambda s: at("HEAD", -0.040, s * 0.045, 0.020, OC), 3.3, 0.09),
    ("TRAP", lambda s: at("T1", -0.050, s * 0.080, -0.010), lambda s: at("HEAD", -0.060, s * 0.020, 0.025, OC), 4.5, 0.10),
    ("SSC", lambda s: at("C5", -0.025, s * 0.020, 0.0), lambda s: at("HEAD", -0.055, s * 0.015, 0.020, OC), 4.6, 0.08),
    ("LCOL", lambda s: at("T1", 0.012, s * 0.008, 0.0), lambda s: at("C2", 0.010, s * 0.006, 0.0), 1.1, 0.05),
    ("LCAP", lambda s: at("C5", 0.012, s * 0.012, 0.0), lambda s: at("HEAD", 0.015, s * 0.010, 0.005, OC), 1.0, 0.05),
]
# The suboccipital muscles (an experiment, --suboccipital yes; not in the shipped model:
# docs/validation.md "The upper cervical joints"): extensors of C0-C2 on EXT, straight.
# Sectional areas of rectus capitis posterior major and obliquus capitis inferior from
# MRI of 109 adults (Xu et al., Int J Morphol, 30-degree oblique sagittal section, men:
# 1.83 and 2.55 cm^2; S15), minor and superior oblique 0.8 cm^2 (A); attachments and
# optimal lengths A.
SUBOCCIPITAL_MUSCLES = [
    ("RCPMAJ", lambda s: at("C2", -0.040, s * 0.005, 0.005), lambda s: at("HEAD", -0.040, s * 0.025, 0.010, OC),
     1.8, 0.04),
    ("RCPMIN", lambda s: at("C1", -0.040, s * 0.004, 0.0), lambda s: at("HEAD", -0.035, s * 0.010, 0.010, OC),
     0.8, 0.02),
    ("OCI", lambda s: at("C2", -0.040, s * 0.006, 0.0), lambda s: at("C1", -0.005, s * 0.040, 0.0), 2.5, 0.045),
    ("OCS", lambda s: at("C1", -0.005, s * 0.040, 0.0), lambda s: at("HEAD", -0.035, s * 0.040, 0.015, OC),
     0.8, 0.03),
]
# Segmental muscles (--segmental yes; docs/validation.md "Segmental muscles"): at every
# subaxial level (T1-C7 ... C3-C2) per side a multifidus-like extensor from the lower
# vertebra's lamina to the upper one's spinous process (MU, 1.0 cm^2, lopt 0.02 m) and an
# intertransversarius between the transverse processes (IT, 0.4 cm^2, lopt 0.015 m), on
# EXT, straight; PCSA, attachments and lengths A. Active, their short-range stiffness
# stabilises each level the way the long muscles cannot (they span many levels).
SEGMENTAL_LEVELS = (("T1", "C7"), ("C7", "C6"), ("C6", "C5"), ("C5", "C4"), ("C4", "C3"), ("C3", "C2"))


def segmental_muscles():
    """The MU and IT muscles of every subaxial level, as MUSCLES rows."""
    rows = []
    for lo, up in SEGMENTAL_LEVELS:
        rows.append(("MU" + up, (lambda b: lambda s: at(b, -0.020, s * 0.020, 0.0))(lo),
                     (lambda b: lambda s: at(b, -0.040, s * 0.004, 0.0))(up), 1.0, 0.02))
        rows.append(("IT" + up, (lambda b: lambda s: at(b, 0.0, s * 0.030, 0.0))(lo),
                     (lambda b: lambda s: at(b, 0.0, s * 0.030, 0.0))(up), 0.4, 0.015))
    return rows


# Muscles that run along the vertebral column (deep and intermediate posterior
# layers, prevertebral muscles) follow it through a via point on every vertebra
# they pass, where the straight neutral line crosses that vertebra's mass-centre
# height (so the path is straight in the neutral posture); the superficial SCM
# and trapezius, slung from the shoulder girdle, run straight (A; docs/deck-format.md VIA).
VIA_MUSCLES = ("SPLC", "SSC", "LCOL", "LCAP")
SIGMA_MAX = 0.5e6     # maximum isometric stress, Pa (FITTED scale: FAMILY MUSCLES F0; reference/parameters.md)
MUSCLE_DAMPING = 0.1  # damping along the line per newton of F0, s/m (A)
# two activation histories (reference/parameters.md): FLEX for the flexors in front of the
# column, EXT for the extensors behind it; each its own bracing level, reflex level and
# delay, FITTED; onset blank = the sled pulse onset found from the prescribed T1 motion;
# rise time A; time constants Thelen 2003 (OpenSim Thelen2003Muscle defaults)
FLEXORS = ("SCM", "LCOL", "LCAP")
ACT = {"FLEX": dict(u0=0.190079, u1=0.889411, delay=0.0894719),
       "EXT": dict(u0=0.282193, u1=0.760404, delay=0.0996544)}
ACT_RISE, ACT_TAU, DEACT_TAU = 0.020, 0.015, 0.050
# short-range stiffness of the active fibres, k = q F / L0 (Bergmark 1989; Cholewicki &
# McGill 1996: q 10-40; q = 20, the geometric middle), over a stretch of 1 % of lopt (A)
SRS_Q, SRS_RANGE = 20.0, 0.01
# FITTED scale factors (SCALE cards) on the values of this script; the output of
# hhneck --calibrate < input/calibrate_nbdl12g.inp (docs/validation.md), copied here
FITTED_SCALES = [
    ("SIGMA", "MUSCLES", "F0", 0.927739),      # sigma_max / 0.5 MPa
    ("VBEND", "DISCS", "VBEND", 38.664),     # disc retardation time of shear, bending, torsion / 5 ms
    ("VAXIAL", "DISCS", "VAXIAL", 0.529204),  # disc axial damping / 2500 N s/m (bounded by Izambert 2003)
    ("ETENSION", "DISCS", "ETENSION", 0.105985),  # disc axial stiffness in tension / in compression
    ("SHEAR", "DISCS", "G", 0.300001),         # disc shear stiffness / 300 N/mm
    ("AXIAL", "DISCS", "E", 1.85107),         # disc axial stiffness / 500 N/mm
    ("ROMK", "LIMITS", "ROMK", 2.08958),    # range-of-motion stiffness / 50 N m/rad
    ("ROMT0", "LIMITS", "ROMT0", 0.359309),       # range-of-motion stiffening excess / 3 deg
    ("LIMC1", "LIMITS", "C1", 6.74126),          # joint-limit dampers' ramp beyond a limit / 100 N m s/rad per rad
]
# the calibration's PARAM names of the ACTIVATE FLEX and EXT fields
FITTED_ACT = {"BRACEF": ("FLEX", "u0"), "REFLEXF": ("FLEX", "u1"), "DELAYF": ("FLEX", "delay"),
              "BRACEE": ("EXT", "u0"), "REFLEXE": ("EXT", "u1"), "DELAYE": ("EXT", "delay")}


def read_fit(listing):
    """The PARAM lines of a calibration listing: {name: value} (a FITTED
    value the listing has no PARAM line for keeps its value here)."""
    fit = {}
    for line in open(listing):
        m = re.match(r"PARAM (\S+)\s+= (\S+)", line)
        if m:
            fit[m.group(1)] = float(m.group(2))
    return fit


# ---------------------------------------------------------------- posture
# The shipped model (--posture seated, the default) has the sagittal posture of
# a seated adult as the joints' NEUTRAL values
# (the unloaded shape: discs unstressed, ligaments and muscles at their rest
# lengths, ranges of motion about it), --posture seated-held as INITIAL values
# on the straight neutral (a deflection that HOLD POSTURE must hold), and
# --posture straight a straight column (every RY zero). Values:
#   T1 slope (superior endplate of T1 against the horizontal): 17.4 deg standing,
#     30.2 deg natural sitting (Hey et al. 2017, Spine 42:1614-1621, 26 subjects);
#     erect sitting, as the NBDL volunteers sat, taken midway, 23.8 deg (A).
#     Put on the T1-C7 joint (C7 RY), which tilts the column as T1's plate does.
#   C2-C7 Cobb lordosis 16.2 deg (Nojiri et al. 2003, J Neurosurg Spine 99:80-83,
#     155 asymptomatic men, neutral lateral radiographs, SD 12.9 deg; meta-analysis
#     12.7 deg, Guo et al. 2018, J Orthop Surg Res 13:147), split evenly over the
#     five joints C7-C6 ... C3-C2 (A).
#   Head level (the volunteers faced forward; the head rotation channel starts
#     at zero): Oc-C2 extension = T1 slope - lordosis = 7.6 deg (Nojiri et al.
#     2003: 14.5 +- 8 deg in men), all on C1-HEAD (Oc-C1, A): C1 stays aligned
#     with C2 in the neutral posture, as a MERGE of C1 into C2 needs.
POSTURES = ("straight", "seated", "seated-held")
POSTURE, T1_SLOPE, LORDOSIS = "seated", 23.8, 16.2

# ---------------------------------------------------------------- neutral zone
# The neutral-zone model (the shipped one: reference/nz_springs.csv exists, or
# --nz-springs CSV; --nz-springs none: the discs alone): the discs' own linear
# bending (Ix, Iy) and torsion (J) are kept at DISC_ROT_FRACTION and the
# neutral-zone springs (NZSPRING cards, fitted by hhneck-fit-joints to the
# segment tests less the other elements) carry the rest of each segment's
# moment-rotation curve. The fraction is the smallest tried at which the
# model stands at rest with its muscles, as the calibration demands
# (largest real part at rest of the 12 g case at the previous fit's
# muscles, docs/validation.md): 0.02 +44.7 1/s, 0.35 +6.88, 0.45 +1.12,
# 0.6 -2.26 (the calibration asks below -1); below it the head's weight and
# the muscles' compression buckle the lightly sprung vertebrae sideways
# (C1-C3 RX modes). Written as SCALE cards NZBEND and NZTORS beside the
# fitted ones; chosen, not a calibration result, so not in FITTED_SCALES.
DISC_ROT_FRACTION = 0.6
NZ_SPRINGS = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "reference",
                          "nz_springs.csv")
NZ_MLIN = 100.0       # N m: the law continues linearly beyond it (the card's default)


def read_nz_springs(path):
    """The rows of reference/nz_springs.csv (hhneck-fit-joints; comment lines
    skipped): [(body, coord, M0+, ths+, M0-, ths-, Mlin)], M0 and Mlin in N m,
    ths in deg (Mlin NZ_MLIN where the file has no mlin column)."""
    import csv
    with open(path, newline="") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    out = []
    for r in rows:
        vals = tuple(float(r[k]) for k in ("m0_plus", "ths_plus_deg", "m0_minus", "ths_minus_deg"))
        if r["coord"] not in ("RX", "RY", "RZ") or not all(v > 0 for v in vals):
            raise ValueError("%s: a row with coord %r and constants %s" % (path, r["coord"], vals))
        out.append((r["body"], r["coord"]) + vals + (float(r.get("mlin") or NZ_MLIN),))
    return out


NZ_EXPLICIT = False
UPPER_CERVICAL = "none"
# the subaxial discs' (T1-C7 ... C3-C2) own bending Ix, Iy as a fraction of DISC_ROT_FRACTION's
# (--sub-bend F; 1 = as the other discs)
SUB_BEND = 1.0
# the flexion-extension bending Iy of the discs C3-C4 ... C7-T1 (C2-C3 excepted: Panjabi's
# C2-C3 flexion-extension is met at DISC_ROT_FRACTION) as a fraction of DISC_ROT_FRACTION's
# (--sub-flexion F)
SUB_FLEXION = 1.0
FLEXION_LEVELS = SEGMENTAL_LEVELS[:5]
USAGE = ("usage: make_head_neck_deck.py [--fit CALIBRATION_LISTING] [--posture straight|seated|seated-held]\n"
         "                              [--t1-slope DEG] [--lordosis DEG] [--nz-springs CSV|none]\n"
         "                              [--upper-cervical CSV|none] [--suboccipital yes|no]\n"
         "                              [--segmental yes|no] [--sub-bend F] [--sub-flexion F]")
args = sys.argv[1:]
while args:
    a = args.pop(0)
    if not args:
        sys.exit(USAGE)
    if a == "--fit":
        FIT = read_fit(args.pop(0))
        FITTED_SCALES = [(n, fam, item, FIT.get(n, v)) for (n, fam, item, v) in FITTED_SCALES]
        for n, (hist, key) in FITTED_ACT.items():
            ACT[hist][key] = FIT.get(n, ACT[hist][key])
    elif a == "--posture" and args[0] in POSTURES:
        POSTURE = args.pop(0)
    elif a == "--t1-slope":
        T1_SLOPE = float(args.pop(0))
    elif a == "--lordosis":
        LORDOSIS = float(args.pop(0))
    elif a == "--nz-springs":
        # a file not written yet: the discs at DISC_ROT_FRACTION, no springs (hhneck-fit-joints' first pass)
        NZ_SPRINGS = args.pop(0)
        NZ_EXPLICIT = True
    elif a == "--upper-cervical":
        UPPER_CERVICAL = args.pop(0)
    elif a == "--segmental" and args[0] in ("yes", "no"):
        if args.pop(0) == "yes":
            MUSCLES = MUSCLES + segmental_muscles()
    elif a == "--sub-bend":
        SUB_BEND = float(args.pop(0))
    elif a == "--sub-flexion":
        SUB_FLEXION = float(args.pop(0))
    elif a == "--suboccipital" and args[0] in ("yes", "no"):
        if args.pop(0) == "yes":
            MUSCLES = MUSCLES + SUBOCCIPITAL_MUSCLES
    else:
        sys.exit(USAGE)
POSTURE_RY = {"C7": T1_SLOPE}
POSTURE_RY.update({b: -LORDOSIS / 5 for b in ("C6", "C5", "C4", "C3", "C2")})
POSTURE_RY.update({"C1": 0.0, "HEAD": -(T1_SLOPE - LORDOSIS)})

# ---------------------------------------------------------------- limits
# S3: total range of motion (deg) skull-C2 / C2-T1: flexion-extension 40/82,
# lateral bending 13/67, axial rotation 77/55; split evenly over the joints of
# each region and symmetrically about neutral (A), except axial rotation of
# skull-C2, put mostly at C1-C2 (A: 70 of the 77 deg).
UPPER = ("C1", "HEAD")           # joints of skull-C2: C2-C1 (body C1) and C1-HEAD (body HEAD)
LOWER = ("C7", "C6", "C5", "C4", "C3", "C2")
def rom(body):
    if body in UPPER:
        fe, lb = 40.0 / 2, 13.0 / 2
        ax = 70.0 if body == "C1" else 7.0
    else:
        fe, lb, ax = 82.0 / 6, 67.0 / 6, 55.0 / 6
    return {"RX": lb / 2, "RY": fe / 2, "RZ": ax / 2}
LIMIT_C0 = 0.05      # A: N m s/rad inside the range
LIMIT_C1 = 100.0     # A: N m s/rad per rad beyond a limit
ROM_K = 50.0         # A: resistance beyond the range, N m/rad at its edge
ROM_T0 = 3.0         # A: excess (deg) over which that resistance grows e-fold

# ---------------------------------------------------------------- write
out = []
w = out.append
w("* HEAD/NECK MODEL: 9 BODIES (T1, C7 ... C1, HEAD), 6 RELATIVE COORDINATES EACH")
w("* Shared by the case decks through  INCLUDE   input/head_neck_54dof.inp")
w("* Generated by dev/make_head_neck_deck.py; edit the script, not this file.")
w("* Units SI (m, kg, s, N); angles on cards in degrees. Axes: X forward, Y left,")
w("* Z up; every body frame is parallel to R with every joint coordinate zero")
w("* (a straight column; the seated neutral posture is on the NEUTRAL cards).")
w(SOURCES.rstrip())
w("*")
w("*         name      parent    mass      Ixx       Iyy       Izz")
for (name, m, ixx, iyy, izz, hv, hd) in bodies:
    p = parent.get(name, "R")
    if ixx is None:
        h = hv + hd
        ixx, iyy, izz = segment_inertia(m, h)
        w("* %s: mass S1; inertia A (elliptic cylinder %.3f x %.3f m, height %.4f m)" % (name, NECK_A, NECK_B, h))
    elif name == "HEAD":
        w("* HEAD: mass and principal inertia S1 (OpenSim axes mapped: x->X, z->Y, y->Z)")
    else:
        w("* T1: upper-torso mass and inertia A (used only when T1 is not prescribed)")
    w(card("BODY", name, p, m, ixx, iyy, izz))
w("*")
w("* Joint points (disc or joint centre) in the parent and own body frames, from")
w("* each mass centre. Heights A: vertebral bodies 14-20 mm, discs 4.5-5.5 mm,")
w("* C1-C2, C0-C1 gaps 4 mm; HEAD mass centre %.3f m ahead, %.3f m above OC (A)" %
  (HEAD_CG_FROM_OC[0], HEAD_CG_FROM_OC[2]))
w("*         body      in parent: x  y         z         in body: x  y         z")
w(card("JOINT", "T1", 0.0, 0.0, 0.0, 0.0, 0.0, 0.0))
for name in names[1:]:
    jp = rel(joint[name], parent[name])
    jc = rel(joint[name], name)
    w(card("JOINT", name, *[round(v, 6) for v in jp], *[round(v, 6) for v in jc]))
w("*")
w("* DISCS (eqs 1-9): one per joint; C2-C1 and C1-HEAD use the same law for the")
w("* atlanto-axial and atlanto-occipital joints (A). Constants from the rotational")
w("* stiffness of S1 and the assumed axial %.0f N/mm and shear %.0f N/mm (A):" % (K_AXIAL / 1e3, K_SHEAR / 1e3))
w("*   d1 = k_ax h/A; Ix, Iy = K_bend h/d1; G from 12 d1 Iy/(h^3(1+Phi)) = k_shear;")
w("*   J = K_axial-rotation h/G;  d2 = %.3f s * d1;  A = %.1e m^2, k = %.1f (A)." % (TAU, AREA, KSHEAR))
w("*         name      lower     upper     A         h         d1        d2")
w("*         lower plate x y z (m)         upper plate x y z (m)         tilt")
w("*         G         Ix        Iy        J         k")
for name in names[1:]:
    p = parent[name]
    hd = [b for b in bodies if b[0] == name][0][6]
    lat, flex, ax = ROT[region[name]]
    e, d2, g, ix, iy, j = disc_constants(lat, flex, ax, hd)
    dname = p + name if name != "HEAD" else "C1HD"
    w("* %s: %s (S1) lateral %.2f, flexion %.2f, axial %.2f N m/rad; h %.4f m" %
      (dname, region[name], lat, flex, ax, hd))
    jp = rel(joint[name], p)
    jc = rel(joint[name], name)
    lower = (jp[0], jp[1], round(jp[2] - hd / 2, 6))
    upper = (jc[0], jc[1], round(jc[2] + hd / 2, 6))
    w(card("DISC", dname, p, name, AREA, hd, e, d2))
    w(cont(*lower, *upper, 0.0))
    w(cont(g, ix, iy, j, KSHEAR))
w("*")
w("* LIGAMENTS (eq 10) F = l1 d + l2 d^n, l1 = 0: n and l2 fitted to S2 so that the")
w("* curve passes through the peak (force, elongation) and has S2's secant")
w("* stiffness between 20 and 80 % of peak. Same five ligaments at every level (A);")
w("* attachments and free lengths A; slack at the neutral length.")
for lname, (k, fp, dp) in LIG.items():
    n, l2 = fit_ligament(k, fp, dp)
    w("*   %-4s S2: %5.0f N/mm, %4.0f N at %.1f mm  ->  n = %.4f, l2 = %.5g N/m^n" % (lname, k, fp, dp, n, l2))
w("*         name      body a    body b    l1        l2        n         slack")
w("*         point on a x y z (m)          point on b x y z (m)")
fits = {l: fit_ligament(*LIG[l]) for l in LIG}
for name in names[1:]:
    p = parent[name]
    lev = (p + name) if name != "HEAD" else "C1HD"
    for lname, pts in LIG_GEOM.items():
        n, l2 = fits[lname]
        for (x, y) in pts:
            j = joint[name]
            half = LIG_LEN[lname] / 2
            pa = rel((j[0] + x, j[1] + y, j[2] - half), p)
            pb = rel((j[0] + x, j[1] + y, j[2] + half), name)
            side = "" if y == 0 else ("L" if y > 0 else "R")
            nm = (lname + side + lev)[:10]
            w(card("LIGAMENT", nm, p, name, 0.0, l2, n))
            w(cont(*[round(v, 6) for v in pa], *[round(v, 6) for v in pb]))
w("*")
w("* MUSCLES: Hill-type (contractile element with force-length and force-velocity")
w("* relations, passive element, damping along the line; docs/deck-format.md),")
if len(MUSCLES) == 6:
    w("* six groups per side, origins and insertions A (simplified anatomy).")
else:
    w("* %d groups per side (beyond the first six: segmental MU, IT; suboccipital" % len(MUSCLES))
    w("* S15), origins and insertions A (simplified anatomy).")
w("* F0 = PCSA x sigma_max, sigma_max %.2f MPa (FITTED scale); PCSA, optimal fibre" % (SIGMA_MAX / 1e6))
w("* length A; damping %.2f s/m x F0 (A). The paper's passive muscle (eq 11) stays" % MUSCLE_DAMPING)
w("* available as the MUSCLE card. Muscles along the column (%s)" % ", ".join(VIA_MUSCLES))
w("* follow it through a via point on each vertebra they pass, on their neutral")
w("* line (A).")
w("*         name      body a    body b    F0 (N)    lopt (m)  history   damping")
w("*         point on a x y z (m)          point on b x y z (m)          rest len")
w("*         muscle    body      via point x y z (m)")
for (mname, org, ins, pcsa, lopt) in MUSCLES:
    f0 = pcsa * 1e-4 * SIGMA_MAX
    for s, side in ((1, "L"), (-1, "R")):
        ba, pa = org(s)
        bb, pb = ins(s)
        hist = "FLEX" if mname in FLEXORS else "EXT"
        w(card("HILL", mname + side, ba, bb, round(f0, 2), lopt, hist, round(MUSCLE_DAMPING * f0, 3)))
        w(cont(*[round(v, 6) for v in rel(pa, ba)], *[round(v, 6) for v in rel(pb, bb)]))
        if mname in VIA_MUSCLES:
            for vb in names[names.index(ba) + 1:names.index(bb)]:
                f = (centre[vb][2] - pa[2]) / (pb[2] - pa[2])
                pv = tuple(pa[i] + f * (pb[i] - pa[i]) for i in range(3))
                w(card("VIA", mname + side, vb, *[round(v, 6) for v in rel(pv, vb)]))
w("* Activation histories: FLEX of the flexors (%s), EXT of the" % ", ".join(FLEXORS))
w("* extensors (the others); each its bracing level u0, reflex level u1 and delay")
w("* FITTED; onset blank = sled pulse onset (prescribed T1 acceleration first")
w("* above 1 g), rise time A; time constants Thelen 2003; short-range stiffness")
w("* of the active fibres k = q F / L0, q %.0f (Bergmark 1989, Cholewicki & McGill" % SRS_Q)
w("* 1996: 10-40), over a stretch of %.0f %% of lopt (A)." % (100 * SRS_RANGE))
w("*         name      u0        u1        onset (s) delay (s) rise (s)")
w("*         tau act   tau deact q (SRS)   range")
for hist, act in ACT.items():
    w(card("ACTIVATE", hist, act["u0"], act["u1"], None, act["delay"], ACT_RISE))
    w(cont(ACT_TAU, DEACT_TAU, SRS_Q, SRS_RANGE))
w("*")
w("* JOINT LIMITS (eqs 12-13): one-way dampers on the three rotations of every")
w("* joint; ranges S3 split per joint (A); C0 %.2f, C1 %.0f N m s/rad per rad (A)" % (LIMIT_C0, LIMIT_C1))
w("*         body      coord     min (deg) max (deg) C0        C1")
rom_cards = []
for name in names[1:]:
    r = rom(name)
    for c in ("RX", "RY", "RZ"):
        d = POSTURE_RY[name] if (POSTURE == "seated" and c == "RY") else 0.0   # ranges about neutral
        w(card("LIMIT", name, c, round(d - r[c], 4), round(d + r[c], 4), LIMIT_C0, LIMIT_C1))
        rom_cards.append(card("ROM", name, c, round(d - r[c], 4), round(d + r[c], 4), ROM_K, ROM_T0))
w("*")
w("* RANGE OF MOTION: resistance beyond the physiological range of each joint")
w("* rotation (the S3 ranges of the LIMIT cards), Q = -K t0 (exp(e/t0) - 1) for an")
w("* excess e; K %.0f N m/rad, t0 %.0f deg (A): the ligaments and facets that stop" % (ROM_K, ROM_T0))
w("* a real joint. A run warns when a joint goes more than 5 deg past its range.")
w("*         body      coord     min (deg) max (deg) K         t0 (deg)")
for c in rom_cards:
    w(c)
NZ_MODEL = NZ_SPRINGS != "none" and (NZ_EXPLICIT or os.path.exists(NZ_SPRINGS))
if NZ_MODEL and os.path.exists(NZ_SPRINGS):
    try:
        nz = read_nz_springs(NZ_SPRINGS)
    except (KeyError, ValueError) as e:
        sys.exit("make_head_neck_deck.py: %s" % e)
    unknown = sorted({r[0] for r in nz} - set(names[1:]))
    if unknown:
        sys.exit("make_head_neck_deck.py: %s names no joint body: %s" % (NZ_SPRINGS, " ".join(unknown)))
    w("*")
    w("* NEUTRAL-ZONE SPRINGS on the joint rotations: D = x - x_neutral; for D >= 0")
    w("* Q = -M0+ sinh(D/ths+), for D < 0 Q = +M0- sinh(-D/ths-), continued linearly")
    w("* beyond |Q| = Mlin (the data's largest moment). M0 (N m), ths (deg) fitted by")
    w("* hhneck-fit-joints (reference/nz_springs.csv) to the segment tests of Panjabi")
    w("* et al. 2001 (0.33-1 N m) and Nightingale et al. 2007 (C4-C5, C6-C7 flexion-")
    w("* extension, to 3.5 N m), less the moment the other elements carry there (the")
    w("* discs' bending and torsion at %.0f %%, NZBEND and NZTORS below); C7-T1 takes" % (100 * DISC_ROT_FRACTION))
    w("* the C6-C7 values (A). + is the coordinate's positive direction.")
    w("*         body      coord     M0+ (N m) ths+(deg) M0- (N m) ths-(deg) Mlin (N m)")
    for (body, coord, m0p, thp, m0m, thm, mlin) in nz:
        w(card("NZSPRING", body, coord, m0p, thp, m0m, thm, mlin))
w("*")
w("* FITTED FACTORS: scale factors on the values above, fitted by the calibration")
w("* (hhneck --calibrate < input/calibrate_nbdl12g.inp; reference/parameters.md).")
w("*         name      family    item      factor")
for (name, fam, item, value) in FITTED_SCALES:
    w(card("SCALE", name, fam, item, value))
if NZ_MODEL:
    w("* NOT FITTED: the discs' own linear bending and torsion kept at %.0f %% (A; the" % (100 * DISC_ROT_FRACTION))
    w("* neutral-zone springs carry the rest of the segments' rotational stiffness)")
    w(card("SCALE", "NZBEND", "DISCS", "BEND", DISC_ROT_FRACTION))
    w(card("SCALE", "NZTORS", "DISCS", "TORSION", DISC_ROT_FRACTION))
w("*")
w(card("HEADNECK", "HEAD", "T1"))
if POSTURE != "straight":
    kind = "NEUTRAL" if POSTURE == "seated" else "INITIAL"
    w("*")
    w("* SEATED POSTURE (%s): T1 slope %.1f deg on C7 RY, C2-C7 lordosis %.1f deg" % (kind, T1_SLOPE, LORDOSIS))
    w("* over C6 ... C2, head level (dev/make_head_neck_deck.py, --posture).")
    for name in names[1:]:
        if POSTURE == "seated":
            w(card("NEUTRAL", name, "RY", round(POSTURE_RY[name], 4)))
        else:
            w(card("INITIAL", name, "RY", round(POSTURE_RY[name], 4), 0.0))
lines = "\n".join(out).split("\n")
if UPPER_CERVICAL != "none":
    try:
        lines = upper_cervical.scale_cards(lines, *upper_cervical.read_csv(UPPER_CERVICAL))
    except (OSError, ValueError, KeyError) as e:
        sys.exit("make_head_neck_deck.py: %s; not written" % e)
if SUB_BEND != 1.0:
    subaxial = [lo + up for lo, up in SEGMENTAL_LEVELS]
    for i, line in enumerate(lines):
        if line.startswith("DISC ") and line[10:20].strip() in subaxial:
            lines[i + 2] = scale_fields(lines[i + 2], (2, 3), SUB_BEND)
if SUB_FLEXION != 1.0:
    levels = [lo + up for lo, up in FLEXION_LEVELS]
    for i, line in enumerate(lines):
        if line.startswith("DISC ") and line[10:20].strip() in levels:
            lines[i + 2] = scale_fields(lines[i + 2], (3,), SUB_FLEXION)
try:
    lines = check_cards(lines, "the model deck")
except CardError as e:
    sys.exit("make_head_neck_deck.py: %s; not written" % e)
print("\n".join(lines))
