"""The model deck input/head_neck_54dof.inp (the 9-body head/neck model shared
by the case decks), written from its parameter table
reference/model_parameters.csv (reference/parameters.md: one row per value,
with its unit, source tag, status sourced / assumed / fitted and, for a
fitted value, the fit stage that wrote it). The cards' values are the
table's numbers or arithmetic on them (the derived card values of
reference/parameters.md); the structure (bodies, which ligaments and muscles
join which bodies, the card layout) is this module's.

    python3 -m hhneck.validation.model_deck --output input/head_neck_54dof.inp
    python3 -m hhneck.validation.model_deck [options] > DECK

A fit writes its values into the table, never into the deck by hand
(dev/fit_model.sh), then regenerates the deck:

    python3 -m hhneck.validation.model_deck --record segments reference/column_fit.csv
    python3 -m hhneck.validation.model_deck --record nz_springs reference/nz_springs.csv --output input/head_neck_54dof.inp

(stage segments: the CSV hhneck.validation.fit_column writes, the column's factors
fitted to the segment tests; stage nz_springs: the neutral-zone springs of
that fit, reference/nz_springs.csv). The deck is the specimen state: its
52 Hill muscles are passive (their activation histories FLEX and EXT at
zero); the volunteer state adds the controller (input/volunteer_controller.inp,
included after it).

Variants (experiments, not the shipped model; docs/validation-history.md):
--fit LISTING takes the PARAM values of a calibration listing in place of
the table's rows of those names (the table unchanged); --posture straight
a straight column, seated-held the seated angles as an initial deflection
of the straight neutral; --t1-slope and --lordosis (deg) another seated
posture; --nz-springs CSV the neutral-zone springs of that CSV (a file not
written yet: no springs; none: no springs either); --upper-cervical CSV the upper-cervical factors of
hhneck.validation.upper_cervical; --suboccipital yes the four suboccipital muscles per
side; --segmental yes two segmental muscles per subaxial level and side;
--cervical yes the eight cervical muscles of S22 per side (scalenes, levator
scapulae, the cervical splenius, semispinalis, longissimus, iliocostalis:
hhneck.validation.hyoid_muscles); --sub-bend F the subaxial discs' own bending Ix, Iy times F; --sub-flexion F
the flexion-extension bending Iy of the discs C3-C4 ... C7-T1 times F.

Pure arithmetic on the table's numbers: no solver code lives here.

API: read_table, write_table, table_values, deck_lines, record, main."""
import argparse
import csv
import io
import math
import os
import re
import sys

from . import segments, upper_cervical
from ..decks import CardError, card, check_cards, scale_fields
from ..decks import card_number as fmt  # noqa: F401 (the tests' md.fmt)

TABLE = os.path.join(segments.ROOT, "reference", "model_parameters.csv")
COLUMNS = ("name", "value", "unit", "status", "source", "stage", "description")
STATUSES = ("sourced", "assumed", "fitted")
#: the fit stages that write rows: (the source tag of the data they fit, what --record reads)
STAGES = {"nz_springs": ("S21", "the CSV of python3 -m hhneck.validation.fit_joints (reference/nz_springs.csv)"),
          "segments": ("S21", "the CSV of hhneck.validation.fit_column (reference/column_fit.csv)")}
#: the rows of the passive column (discs, ligaments, joint stops, neutral-zone
#: springs) by name prefix or name: constraint 1 (docs/validation.md,
#: "Calibration"), no volunteer fit writes them
PASSIVE_PREFIXES = ("disc.", "lig.", "rom.", "limit.", "nz.")
PASSIVE_SCALES = ("VBEND", "VAXIAL", "ETENSION", "SHEAR", "AXIAL", "ROMK", "ROMT0", "LIMC1")
NZ_COLUMNS = ("m0_plus", "ths_plus_deg", "m0_minus", "ths_minus_deg", "mlin")
NZ_MLIN = 100.0       # N m: the NZSPRING card's default Mlin, for a CSV without the mlin column


class DeckError(ValueError):
    """A table, listing or CSV the generator cannot use (nothing is written)."""


# ---------------------------------------------------------------- the table

def read_table(path=TABLE):
    """The rows of a parameter table (dicts of the COLUMNS' strings), in
    order; DeckError naming the line for a wrong header, a repeated or empty
    name, a value that is not a finite number, an unknown status, or a stage
    missing on a fitted row, unknown, or on a row not fitted."""
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        if tuple(reader.fieldnames or ()) != COLUMNS:
            raise DeckError("%s, line 1: the columns are %s; expected %s"
                            % (path, ",".join(reader.fieldnames or ()), ",".join(COLUMNS)))
        rows, seen = [], set()
        for r in reader:
            where = "%s, line %d" % (path, reader.line_num)
            if None in r or any(r[c] is None for c in COLUMNS):
                raise DeckError("%s: %d columns expected" % (where, len(COLUMNS)))
            if not r["name"] or r["name"] in seen:
                raise DeckError("%s: the name %r is empty or repeated" % (where, r["name"]))
            seen.add(r["name"])
            _number(r["value"], "%s (%s)" % (where, r["name"]))
            if r["status"] not in STATUSES:
                raise DeckError("%s (%s): status %r; expected one of %s"
                                % (where, r["name"], r["status"], ", ".join(STATUSES)))
            if (r["status"] == "fitted") != bool(r["stage"]) or (r["stage"] and r["stage"] not in STAGES):
                raise DeckError("%s (%s): stage %r with status %s; a fitted row names one of %s, "
                                "another none" % (where, r["name"], r["stage"], r["status"], ", ".join(STAGES)))
            rows.append(r)
    return rows


def write_table(path, rows):
    """Write the table `rows` to `path` (replaced at once: a reader never
    sees half a table)."""
    text = io.StringIO()
    w = csv.DictWriter(text, fieldnames=COLUMNS, lineterminator="\n")
    w.writeheader()
    w.writerows(rows)
    _replace(path, text.getvalue())


def _replace(path, text):
    """Write `text` to `path` through a new file renamed over it."""
    new = path + ".new"
    with open(new, "w", newline="") as f:
        f.write(text)
    os.replace(new, path)


def _number(text, where):
    try:
        v = float(text)
    except ValueError:
        v = math.nan
    if not math.isfinite(v):
        raise DeckError("%s: %r is not a finite number" % (where, text))
    return v


class Values(dict):
    """{row name: value} of a table; remembers the names read (`used`)."""

    def __init__(self, *args):
        super().__init__(*args)
        self.used = set()

    def __getitem__(self, name):
        self.used.add(name)
        return super().__getitem__(name)


def table_values(rows):
    """The Values of table `rows` (read_table)."""
    return Values({r["name"]: float(r["value"]) for r in rows})


# ---------------------------------------------------------------- fits

def read_fit(listing):
    """The PARAM lines of a calibration listing: [(name, value text)]."""
    out = []
    with open(listing) as f:
        for line in f:
            m = re.match(r"PARAM (\S+)\s+= (\S+)", line)
            if m:
                out.append((m.group(1), m.group(2)))
    return out


def read_nz_springs(path):
    """The rows of a python3 -m hhneck.validation.fit_joints CSV (comment lines skipped):
    [(body, coord, {column: text} of NZ_COLUMNS)], each M0 and ths > 0 (an
    empty mlin: NZ_MLIN)."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    out = []
    for r in rows:
        vals = {k: r.get(k) or "" for k in NZ_COLUMNS}
        if not vals["mlin"]:
            vals["mlin"] = repr(NZ_MLIN)
        try:
            num = [float(vals[k]) for k in NZ_COLUMNS]
        except ValueError:
            num = [math.nan]
        if r["coord"] not in ("RX", "RY", "RZ") or not all(v > 0 for v in num):
            raise DeckError("%s: a row with coord %r and constants %s"
                            % (path, r["coord"], tuple(vals[k] for k in NZ_COLUMNS[:4])))
        out.append((r["body"], r["coord"], vals))
    return out


def read_column_fit(path):
    """The (name, value text) rows of a hhneck.validation.fit_column CSV (comment lines
    skipped; columns name, value, ...); DeckError for none or a value that
    is not a finite number."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    if not rows or "name" not in rows[0] or "value" not in rows[0]:
        raise DeckError("%s has no row with a name and a value" % path)
    for r in rows:
        _number(r["value"], "%s: %s" % (path, r["name"]))
    return [(r["name"], r["value"]) for r in rows]


def record(rows, stage, path):
    """Write the values a fit stage produced (the file `path`: STAGES) into
    the table `rows` (in place): value, status fitted, the stage and the
    stage's source tag. Stage nz_springs: every nz.BODY.COORD.COLUMN row
    from the CSV's row of BODY, COORD, which must cover the table's springs
    and name no other; stage segments: the rows named by the CSV of
    hhneck.validation.fit_column (read_column_fit), each a row of the table. The
    names written, in order; DeckError (the table untouched) otherwise."""
    if stage not in STAGES:
        raise DeckError("stage %r; expected one of %s" % (stage, ", ".join(STAGES)))
    if stage == "nz_springs":
        values = [("nz.%s.%s.%s" % (b, c, k), v[k]) for b, c, v in read_nz_springs(path) for k in NZ_COLUMNS]
        want = {r["name"] for r in rows if r["name"].startswith("nz.")}
        missing = sorted(want - {n for n, _ in values})
        if missing:
            raise DeckError("%s has no value for %s" % (path, " ".join(missing)))
    else:
        values = read_column_fit(path)
    by_name = {r["name"]: r for r in rows}
    unknown = [n for n, _ in values if n not in by_name]
    if unknown:
        raise DeckError("%s names no row of the table: %s" % (path, " ".join(unknown)))
    for n, v in values:
        by_name[n].update(value=v, status="fitted", stage=stage, source=STAGES[stage][0])
    return [n for n, _ in values]


# ---------------------------------------------------------------- card text

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


def cont(*fields):
    """A continuation card (no name) of `fields` (decks.card)."""
    return card("", *fields)


def _rounded(point):
    return [round(v, 6) for v in point]


# ---------------------------------------------------------------- structure

BODIES = ("T1", "C7", "C6", "C5", "C4", "C3", "C2", "C1", "HEAD")   # T1 the root, each the next's parent
PARENT = {BODIES[i]: BODIES[i - 1] for i in range(1, len(BODIES))}
# the region of S1's rotational stiffness of the joint below each body
REGION = {"C7": "C5-T1", "C6": "C5-T1", "C5": "C5-T1", "C4": "C3-C5", "C3": "C3-C5",
          "C2": "skull-C3", "C1": "skull-C3", "HEAD": "skull-C3"}
LIGAMENTS = ("ALL", "PLL", "LF", "CL", "ISL")      # at every level (A)
# muscle groups per side: name, origin body, insertion body; a point on HEAD is
# given from the occipital condyles (OC), the others from the body's mass centre
MUSCLES = (("SCM", "T1", "HEAD"), ("SPLC", "C7", "HEAD"), ("TRAP", "T1", "HEAD"), ("SSC", "C5", "HEAD"),
           ("LCOL", "T1", "C2"), ("LCAP", "C5", "HEAD"))
# the suboccipital muscles (--suboccipital yes; docs/validation.md "The upper
# cervical joints"): extensors of C0-C2 on EXT, straight
SUBOCCIPITAL_MUSCLES = (("RCPMAJ", "C2", "HEAD"), ("RCPMIN", "C1", "HEAD"), ("OCI", "C2", "C1"),
                        ("OCS", "C1", "HEAD"))
# the segmental muscles (--segmental yes; docs/validation-history.md "Segmental muscles"):
# at every subaxial level per side a multifidus-like extensor MU and an
# intertransversarius IT from the lower vertebra to the upper one, on EXT, straight
SEGMENTAL_LEVELS = (("T1", "C7"), ("C7", "C6"), ("C6", "C5"), ("C5", "C4"), ("C4", "C3"), ("C3", "C2"))
SEGMENTAL_KINDS = ("MU", "IT")
# the cervical muscles of S22 (--cervical yes, shipped; hhneck.validation.hyoid_muscles maps
# their rows from the HYOID model): the scalenes, levator scapulae and the cervical
# parts of splenius, semispinalis, longissimus and iliocostalis, T1 to C2-C5, straight
CERVICAL_MUSCLES = (("SCALA", "T1", "C4"), ("SCALM", "T1", "C3"), ("SCALP", "T1", "C5"), ("LEVS", "T1", "C2"),
                    ("SPLCV", "T1", "C3"), ("SSCV", "T1", "C3"), ("LNGCV", "T1", "C4"), ("ILCV", "T1", "C5"))
# Muscles that run along the vertebral column follow it through a via point on
# every vertebra they pass, where the straight neutral line crosses that
# vertebra's mass-centre height; the superficial SCM and trapezius run straight (A)
VIA_MUSCLES = ("SPLC", "SSC", "LCOL", "LCAP")
FLEXORS = ("SCM", "LCOL", "LCAP", "SCALA", "SCALM", "SCALP")   # on FLEX; the others on EXT
HISTORIES = (("FLEX", "F"), ("EXT", "E"))   # the activation histories, the suffix of their rows
# the fitted SCALE cards: name (the row), family, item
SCALES = (("SIGMA", "MUSCLES", "F0"), ("VBEND", "DISCS", "VBEND"), ("VAXIAL", "DISCS", "VAXIAL"),
          ("ETENSION", "DISCS", "ETENSION"), ("SHEAR", "DISCS", "G"), ("AXIAL", "DISCS", "E"),
          ("ROMK", "LIMITS", "ROMK"), ("ROMT0", "LIMITS", "ROMT0"), ("LIMC1", "LIMITS", "C1"))
POSTURES = ("straight", "seated", "seated-held")
UPPER = ("C1", "HEAD")                       # the joints of skull-C2 (C2-C1, C1-HEAD)
FLEXION_LEVELS = SEGMENTAL_LEVELS[:5]        # --sub-flexion: C3-C4 ... C7-T1


def segment_inertia(p, m, h):
    """Solid elliptic cylinder of mass m, axis z, height h, the semi-axes of p."""
    a, b = p["neck.semi_axis_x"], p["neck.semi_axis_y"]
    return m * (b**2 / 4 + h**2 / 12), m * (a**2 / 4 + h**2 / 12), m * (a**2 + b**2) / 4


def disc_constants(p, lat, flex, axial, h):
    """E, d2, G, Ix, Iy, J of a disc of height h from its rotational stiffness."""
    e = p["disc.k_axial"] * h / p["disc.area"]      # eq 1: k_axial = A d1 / h
    ix = lat * h / e                                 # free-shear bending stiffness E I / h
    iy = flex * h / e
    phi = 12 * e * iy / (h**3 * p["disc.k_shear"]) - 1     # 12 E I / (h^3 (1 + Phi)) = k_shear
    g = 12 * e * iy * p["disc.shear_factor"] / (phi * p["disc.area"] * h**2)
    j = axial * h / g                                # eq 7: G J / h = k_torsion
    return e, p["disc.tau"] * e, g, ix, iy, j


def fit_ligament(k, fp, dp):
    """F = l2 d^n (l1 = 0) through (dp, fp) whose secant stiffness between 20 %
    and 80 % of the peak force is k (S2's definition)."""
    k, dp = k * 1e3, dp * 1e-3              # N/m, m
    target = 0.6 * fp / k                    # d80 - d20
    lo, hi = 1.0, 20.0
    f = lambda n: dp * (0.8 ** (1 / n) - 0.2 ** (1 / n)) - target  # noqa: E731
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if f(lo) * f(mid) <= 0:
            hi = mid
        else:
            lo = mid
    n = 0.5 * (lo + hi)
    return n, fp / dp ** n


class _Geometry:
    """The neutral positions in R (T1 centre at the origin; every body frame
    parallel to R): mass centres and the joint points below each body."""

    def __init__(self, p):
        self.centre, self.joint = {"T1": (0.0, 0.0, 0.0)}, {}
        z, prev_hv = 0.0, p["body.T1.height"]
        for name in BODIES[1:]:
            hd = p["joint.%s.height" % name]
            jz = z + prev_hv / 2 + hd / 2
            self.joint[name] = (0.0, 0.0, jz)
            if name == "HEAD":
                self.centre[name] = (p["head.cg_x"], 0.0, jz + p["head.cg_z"])
            else:
                prev_hv = p["body.%s.height" % name]
                z = jz + hd / 2 + prev_hv / 2
                self.centre[name] = (0.0, 0.0, z)

    def rel(self, point, body):
        c = self.centre[body]
        return tuple(point[i] - c[i] for i in range(3))

    def at(self, body, d, s):
        """The point (body, position in R) offset d = (x, y, z) from the body's
        mass centre (HEAD: from the occipital condyles), y times the side s."""
        base = self.joint["HEAD"] if body == "HEAD" else self.centre[body]
        return body, (base[0] + d[0], base[1] + s * d[1], base[2] + d[2])


def _muscle_rows(p, suboccipital, segmental, cervical=True):
    """[(name, origin body, insertion body, the rows' name)] of the muscles."""
    rows = [(m, a, b, m) for m, a, b in MUSCLES]
    if cervical:
        rows += [(m, a, b, m) for m, a, b in CERVICAL_MUSCLES]
    if suboccipital:
        rows += [(m, a, b, m) for m, a, b in SUBOCCIPITAL_MUSCLES]
    if segmental:
        rows += [(k + up, lo, up, k) for lo, up in SEGMENTAL_LEVELS for k in SEGMENTAL_KINDS]
    return rows


def _point(p, key, end):
    return tuple(p["muscle.%s.%s_%s" % (key, end, a)] for a in "xyz")


def _rom(p, body):
    """The half ranges (deg) of a joint's RX, RY, RZ: S3's regional totals
    split evenly over the region's joints, symmetric about neutral; skull-C2's
    axial rotation rom.c1c2_axial at C2-C1, the rest at C1-HEAD."""
    if body in UPPER:
        fe, lb = p["rom.upper.flexion"] / 2, p["rom.upper.lateral"] / 2
        ax = p["rom.c1c2_axial"] if body == "C1" else p["rom.upper.axial"] - p["rom.c1c2_axial"]
    else:
        n = len(BODIES) - 1 - len(UPPER)
        fe, lb, ax = p["rom.lower.flexion"] / n, p["rom.lower.lateral"] / n, p["rom.lower.axial"] / n
    return {"RX": lb / 2, "RY": fe / 2, "RZ": ax / 2}


def _nz_cards(p, nz_springs):
    """The NZSPRING rows (body, coord, M0+, ths+, M0-, ths-, Mlin): the
    table's springs, none (`nz_springs` "none"), or a CSV's (none while the
    file is not written)."""
    if nz_springs == "none":
        return []
    if nz_springs is None:
        springs = [(b, c) for b in reversed(BODIES[1:]) for c in ("RX", "RY", "RZ")]
        return [(b, c) + tuple(p["nz.%s.%s.%s" % (b, c, k)] for k in NZ_COLUMNS) for b, c in springs]
    if not os.path.exists(nz_springs):
        return []
    rows = read_nz_springs(nz_springs)
    unknown = sorted({r[0] for r in rows} - set(BODIES[1:]))
    if unknown:
        raise DeckError("%s names no joint body: %s" % (nz_springs, " ".join(unknown)))
    return [(b, c) + tuple(float(v[k]) for k in NZ_COLUMNS) for b, c, v in rows]


def _header_and_bodies(w, p, geo):
    """The header comments, the BODY and the JOINT cards."""
    w("* HEAD/NECK MODEL: 9 BODIES (T1, C7 ... C1, HEAD), 6 RELATIVE COORDINATES EACH")
    w("* Shared by the case decks through  INCLUDE   input/head_neck_54dof.inp")
    w("* Generated by dev/make_head_neck_deck.py; edit the script, not this file.")
    w("* Units SI (m, kg, s, N); angles on cards in degrees. Axes: X forward, Y left,")
    w("* Z up; every body frame is parallel to R with every joint coordinate zero")
    w("* (a straight column; the seated neutral posture is on the NEUTRAL cards).")
    w(SOURCES.rstrip())
    w("*")
    w("*         name      parent    mass      Ixx       Iyy       Izz")
    for name in BODIES:
        m = p["body.%s.mass" % name]
        if name in ("T1", "HEAD"):
            ixx, iyy, izz = (p["body.%s.%s" % (name, a)] for a in ("Ixx", "Iyy", "Izz"))
            w("* HEAD: mass and principal inertia S1 (OpenSim axes mapped: x->X, z->Y, y->Z)" if name == "HEAD"
              else "* T1: upper-torso mass and inertia A (used only when T1 is not prescribed)")
        else:
            h = p["body.%s.height" % name] + p["joint.%s.height" % name]
            ixx, iyy, izz = segment_inertia(p, m, h)
            w("* %s: mass S1; inertia A (elliptic cylinder %.3f x %.3f m, height %.4f m)"
              % (name, p["neck.semi_axis_x"], p["neck.semi_axis_y"], h))
        w(card("BODY", name, PARENT.get(name, "R"), m, ixx, iyy, izz))
    w("*")
    w("* Joint points (disc or joint centre) in the parent and own body frames, from")
    w("* each mass centre. Heights A: vertebral bodies 14-20 mm, discs 4.5-5.5 mm,")
    w("* C1-C2, C0-C1 gaps 4 mm; HEAD mass centre %.3f m ahead, %.3f m above OC (A)" %
      (p["head.cg_x"], p["head.cg_z"]))
    w("*         body      in parent: x  y         z         in body: x  y         z")
    w(card("JOINT", "T1", 0.0, 0.0, 0.0, 0.0, 0.0, 0.0))
    for name in BODIES[1:]:
        j = geo.joint[name]
        w(card("JOINT", name, *_rounded(geo.rel(j, PARENT[name])), *_rounded(geo.rel(j, name))))


def _discs(w, p, geo):
    """The DISC cards."""
    w("*")
    w("* DISCS (eqs 1-9): one per joint; C2-C1 and C1-HEAD use the same law for the")
    w("* atlanto-axial and atlanto-occipital joints (A). Constants from the rotational")
    w("* stiffness of S1 and the assumed axial %.0f N/mm and shear %.0f N/mm (A):"
      % (p["disc.k_axial"] / 1e3, p["disc.k_shear"] / 1e3))
    w("*   d1 = k_ax h/A; Ix, Iy = K_bend h/d1; G from 12 d1 Iy/(h^3(1+Phi)) = k_shear;")
    w("*   J = K_axial-rotation h/G;  d2 = %.3f s * d1;  A = %.1e m^2, k = %.1f (A)."
      % (p["disc.tau"], p["disc.area"], p["disc.shear_factor"]))
    w("*         name      lower     upper     A         h         d1        d2")
    w("*         lower plate x y z (m)         upper plate x y z (m)         tilt")
    w("*         G         Ix        Iy        J         k")
    for name in BODIES[1:]:
        par, hd = PARENT[name], p["joint.%s.height" % name]
        lat, flex, ax = (p["disc.%s.%s" % (REGION[name], k)] for k in ("lateral", "flexion", "axial"))
        e, d2, g, ix, iy, j = disc_constants(p, lat, flex, ax, hd)
        dname = par + name if name != "HEAD" else "C1HD"
        w("* %s: %s (S1) lateral %.2f, flexion %.2f, axial %.2f N m/rad; h %.4f m" %
          (dname, REGION[name], lat, flex, ax, hd))
        jp, jc = geo.rel(geo.joint[name], par), geo.rel(geo.joint[name], name)
        lower = (jp[0], jp[1], round(jp[2] - hd / 2, 6))
        upper = (jc[0], jc[1], round(jc[2] + hd / 2, 6))
        w(card("DISC", dname, par, name, p["disc.area"], hd, e, d2))
        w(cont(*lower, *upper, 0.0))
        w(cont(g, ix, iy, j, p["disc.shear_factor"]))


def _ligaments(w, p, geo):
    """The LIGAMENT cards: the five ligaments at every level."""
    w("*")
    w("* LIGAMENTS (eq 10) F = l1 d + l2 d^n, l1 = 0: n and l2 fitted to S2 so that the")
    w("* curve passes through the peak (force, elongation) and has S2's secant")
    w("* stiffness between 20 and 80 % of peak. Same five ligaments at every level (A);")
    w("* attachments and free lengths A; slack at the neutral length.")
    lig = {l: tuple(p["lig.%s.%s" % (l, k)] for k in ("k", "peak_force", "peak_elongation")) for l in LIGAMENTS}
    fits = {l: fit_ligament(*lig[l]) for l in LIGAMENTS}
    for lname in LIGAMENTS:
        w("*   %-4s S2: %5.0f N/mm, %4.0f N at %.1f mm  ->  n = %.4f, l2 = %.5g N/m^n"
          % ((lname,) + lig[lname] + fits[lname]))
    w("*         name      body a    body b    l1        l2        n         slack")
    w("*         point on a x y z (m)          point on b x y z (m)")
    for name in BODIES[1:]:
        par, j = PARENT[name], geo.joint[name]
        lev = (par + name) if name != "HEAD" else "C1HD"
        for lname in LIGAMENTS:
            n, l2 = fits[lname]
            x, y, half = p["lig.%s.x" % lname], p["lig.%s.y" % lname], p["lig.%s.length" % lname] / 2
            for yy in ((y,) if y == 0 else (y, -y)):
                pa = geo.rel((j[0] + x, j[1] + yy, j[2] - half), par)
                pb = geo.rel((j[0] + x, j[1] + yy, j[2] + half), name)
                side = "" if yy == 0 else ("L" if yy > 0 else "R")
                w(card("LIGAMENT", (lname + side + lev)[:10], par, name, 0.0, l2, n))
                w(cont(*_rounded(pa), *_rounded(pb)))


def _muscles(w, p, geo, muscles):
    """The HILL and VIA cards of `muscles` (_muscle_rows) and the ACTIVATE cards."""
    sigma_max, damping = p["muscle.sigma_max"], p["muscle.damping"]
    w("*")
    w("* MUSCLES: Hill-type (contractile element with force-length and force-velocity")
    w("* relations, passive element, damping along the line; docs/deck-format.md),")
    cervical = [m for m, _, _ in CERVICAL_MUSCLES if m in {k for _, _, _, k in muscles}]
    if len(muscles) == len(MUSCLES):
        w("* six groups per side, origins and insertions A (simplified anatomy).")
    else:
        w("* %d groups per side (beyond the first six: segmental MU, IT; suboccipital" % len(muscles))
        w("* S15), origins and insertions A (simplified anatomy).")
    if cervical:
        w("* The cervical muscles %s" % ", ".join(cervical))
        w("* (scalenes, levator scapulae, the cervical splenius, semispinalis,")
        w("* longissimus, iliocostalis) are S22's: origins, insertions, F0, lopt and")
        w("* lf/lopt mapped from the HYOID model by hhneck.validation.hyoid_muscles,")
        w("* straight.")
    w("* F0 = PCSA x sigma_max, sigma_max %.2f MPa (x SIGMA); PCSA A; optimal" % (sigma_max / 1e6))
    w("* fibre length lopt and, on the FIBRE cards, the fibre length over lopt in the")
    w("* neutral posture S22 (the mapping in reference/model_parameters.csv; a muscle")
    w("* without a FIBRE card: lopt A, its fibres at lopt); damping %.2f s/m x F0 (A)." % damping)
    w("* The paper's passive muscle (eq 11) stays available as the MUSCLE card.")
    w("* Muscles along the column (%s)" % ", ".join(VIA_MUSCLES))
    w("* follow it through a via point on each vertebra they pass, on their neutral")
    w("* line (A).")
    w("*         name      body a    body b    F0 (N)    lopt (m)  history   damping")
    w("*         point on a x y z (m)          point on b x y z (m)          rest len")
    w("*         muscle    body      via point x y z (m)")
    for (mname, a, b, key) in muscles:
        f0 = p["muscle.%s.pcsa" % key] * 1e-4 * sigma_max
        lopt = p["muscle.%s.lopt" % key]
        for s, side in ((1, "L"), (-1, "R")):
            ba, pa = geo.at(a, _point(p, key, "origin"), s)
            bb, pb = geo.at(b, _point(p, key, "insertion"), s)
            hist = "FLEX" if mname in FLEXORS else "EXT"
            w(card("HILL", mname + side, ba, bb, round(f0, 2), lopt, hist, round(damping * f0, 3)))
            w(cont(*_rounded(geo.rel(pa, ba)), *_rounded(geo.rel(pb, bb))))
            if mname in VIA_MUSCLES:
                for vb in BODIES[BODIES.index(ba) + 1:BODIES.index(bb)]:
                    f = (geo.centre[vb][2] - pa[2]) / (pb[2] - pa[2])
                    pv = tuple(pa[i] + f * (pb[i] - pa[i]) for i in range(3))
                    w(card("VIA", mname + side, vb, *_rounded(geo.rel(pv, vb))))
    w("*         muscle    lf/lopt in the neutral posture")
    for (mname, a, b, key) in muscles:
        if "muscle.%s.ln" % key in p:
            for side in "LR":
                w(card("FIBRE", mname + side, p["muscle.%s.ln" % key]))
    w("* Activation histories: FLEX of the flexors")
    w("* (%s)," % ", ".join(FLEXORS))
    w("* EXT of the extensors (the others), PASSIVE: no bracing, no reflex (the")
    w("* specimen state;")
    w("* the volunteer state's controller, input/volunteer_controller.inp, drives the")
    w("* muscles). Time constants Thelen 2003; short-range stiffness of the active")
    w("* fibres k = q F / L0, q %.0f (Bergmark 1989, Cholewicki & McGill 1996: 10-40)," % p["act.srs_q"])
    w("* over a stretch of %.0f %% of lopt (A)." % (100 * p["act.srs_range"]))
    w("*         name      u0        u1        onset (s) delay (s) rise (s)")
    w("*         tau act   tau deact q (SRS)   range")
    for hist, _ in HISTORIES:
        w(card("ACTIVATE", hist, 0.0, 0.0, None, 0.0, p["act.rise"]))
        w(cont(p["act.tau_act"], p["act.tau_deact"], p["act.srs_q"], p["act.srs_range"]))


def _limits(w, p, neutral):
    """The LIMIT and ROM cards, the ranges about the joints' `neutral` RY (deg)."""
    c0, c1, rom_k, rom_t0 = p["limit.c0"], p["limit.c1"], p["rom.k"], p["rom.t0"]
    w("*")
    w("* JOINT LIMITS (eqs 12-13): one-way dampers on the three rotations of every")
    w("* joint; ranges S3 split per joint (A); C0 %.2f, C1 %.0f N m s/rad per rad (A)" % (c0, c1))
    w("*         body      coord     min (deg) max (deg) C0        C1")
    rom_cards = []
    for name in BODIES[1:]:
        r = _rom(p, name)
        for c in ("RX", "RY", "RZ"):
            d = neutral.get(name, 0.0) if c == "RY" else 0.0
            w(card("LIMIT", name, c, round(d - r[c], 4), round(d + r[c], 4), c0, c1))
            rom_cards.append(card("ROM", name, c, round(d - r[c], 4), round(d + r[c], 4), rom_k, rom_t0))
    w("*")
    w("* RANGE OF MOTION: resistance beyond the physiological range of each joint")
    w("* rotation (the S3 ranges of the LIMIT cards), Q = -K t0 (exp(e/t0) - 1) for an")
    w("* excess e; K %.0f N m/rad, t0 %.0f deg (A): the ligaments and facets that stop" % (rom_k, rom_t0))
    w("* a real joint. A run warns when a joint goes more than 5 deg past its range.")
    w("*         body      coord     min (deg) max (deg) K         t0 (deg)")
    for c in rom_cards:
        w(c)


def _springs_and_scales(w, p, nz_springs):
    """The NZSPRING cards (_nz_cards) and the SCALE cards."""
    nz = _nz_cards(p, nz_springs)
    bend, torsion = p["disc.bend_fraction"], p["disc.torsion_fraction"]
    if nz:
        w("*")
        w("* NEUTRAL-ZONE SPRINGS on the joint rotations: D = x - x_neutral; for D >= 0")
        w("* Q = -M0+ sinh(D/ths+), for D < 0 Q = +M0- sinh(-D/ths-), continued linearly")
        w("* beyond |Q| = Mlin (the data's largest moment). M0 (N m), ths (deg) fitted by")
        w("* hhneck.validation.fit_joints (reference/nz_springs.csv) to the segment tests")
        w("* of Panjabi et al. 2001 (0.33-1 N m) and Nightingale et al. 2007 (C4-C5, C6-C7")
        w("* flexion-extension, to 3.5 N m), less the moment the other elements carry")
        w("* there (the discs' bending and torsion at the fractions NZBEND and NZTORS")
        w("* below); C7-T1 takes the C6-C7 values (A). + is the coordinate's positive")
        w("* direction.")
        w("*         body      coord     M0+ (N m) ths+(deg) M0- (N m) ths-(deg) Mlin (N m)")
        for row in nz:
            w(card("NZSPRING", *row))
    w("*")
    w("* FACTORS on the values above (reference/parameters.md): the column's, fitted")
    w("* to the segment tests alone (hhneck.validation.fit_column,")
    w("* reference/column_fit.csv) or sourced; SIGMA the muscles' stress, sourced. No")
    w("* volunteer fit moves them.")
    w("* VBEND: S1's time constant 0.1 s over the discs' bending fraction NZBEND, so")
    w("* that the discs carry S1's damping coefficient (10 % of its stiffness per s).")
    w("*         name      family    item      factor")
    for (name, fam, item) in SCALES:
        w(card("SCALE", name, fam, item, scale_factor(p, name)))
    w("* the discs' own linear bending and torsion, fractions of S1's segment stiffness")
    w("* (the neutral-zone springs carry the rest); fitted to the segment tests")
    w(card("SCALE", "NZBEND", "DISCS", "BEND", bend))
    w(card("SCALE", "NZTORS", "DISCS", "TORSION", torsion))


def scale_factor(p, name):
    """The factor of the model deck's SCALE card `name` from the table p: the
    table's value, but for VBEND the discs' retardation time that gives the
    segment S1's damping coefficient: S1 gives a segment's damping as 10 %
    of its whole stiffness per second (time constant 0.1 s, the table's
    VBEND 20 over disc.tau), and the discs, the segment's only damped
    element, keep the fraction disc.bend_fraction of that stiffness, so
    their retardation time is the time constant over that fraction."""
    if name == "VBEND":
        return p["VBEND"] / p["disc.bend_fraction"]
    return p[name]


def table_value(p, name, factor):
    """The table's value of SCALE card `name` whose deck factor is `factor`
    (a calibration listing's PARAM value): the inverse of scale_factor."""
    if name == "VBEND":
        return factor * p["disc.bend_fraction"]
    return factor


def _posture(w, posture, t1_slope, lordosis):
    """The HEADNECK card and the posture's NEUTRAL or INITIAL cards; the
    joints' neutral RY (deg) the ranges of motion are centred on."""
    ry = {"C7": t1_slope}
    ry.update({b: -lordosis / 5 for b in ("C6", "C5", "C4", "C3", "C2")})
    ry.update({"C1": 0.0, "HEAD": -(t1_slope - lordosis)})
    w("*")
    w(card("HEADNECK", "HEAD", "T1"))
    if posture != "straight":
        kind = "NEUTRAL" if posture == "seated" else "INITIAL"
        w("*")
        w("* SEATED POSTURE (%s): T1 slope %.1f deg on C7 RY, C2-C7 lordosis %.1f deg" % (kind, t1_slope, lordosis))
        w("* over C6 ... C2, head level (dev/make_head_neck_deck.py, --posture).")
        for name in BODIES[1:]:
            if posture == "seated":
                w(card("NEUTRAL", name, "RY", round(ry[name], 4)))
            else:
                w(card("INITIAL", name, "RY", round(ry[name], 4), 0.0))
    return ry if posture == "seated" else {}


def _scaled_discs(lines, sub_bend, sub_flexion):
    """--sub-bend and --sub-flexion on the DISC cards of `lines` (in place)."""
    for factor, levels, ks in ((sub_bend, SEGMENTAL_LEVELS, (2, 3)), (sub_flexion, FLEXION_LEVELS, (3,))):
        if factor != 1.0:
            names = [lo + up for lo, up in levels]
            for i, line in enumerate(lines):
                if line.startswith("DISC ") and line[10:20].strip() in names:
                    lines[i + 2] = scale_fields(lines[i + 2], ks, factor)


def deck_lines(p, posture="seated", t1_slope=None, lordosis=None, nz_springs=None, upper_cervical_csv="none",
               suboccipital=False, segmental=True, sub_bend=1.0, sub_flexion=1.0, cervical=True):
    """The model deck's lines from the values `p` (table_values): the shipped
    deck with the defaults; the variants of the module's docstring
    otherwise. DeckError for a CSV it cannot use or a card beyond column 80."""
    geo = _Geometry(p)
    if t1_slope is None:
        stand = p["posture.t1_slope_standing"]
        t1_slope = stand + p["posture.erect_fraction"] * (p["posture.t1_slope_sitting"] - stand)
    lordosis = p["posture.lordosis"] if lordosis is None else lordosis
    body, tail = [], []
    _header_and_bodies(body.append, p, geo)
    _discs(body.append, p, geo)
    _ligaments(body.append, p, geo)
    _muscles(body.append, p, geo, _muscle_rows(p, suboccipital, segmental, cervical))
    neutral = _posture(tail.append, posture, t1_slope, lordosis)
    _limits(body.append, p, neutral)
    _springs_and_scales(body.append, p, nz_springs)
    lines = "\n".join(body + tail).split("\n")
    if upper_cervical_csv != "none":
        try:
            lines = upper_cervical.scale_cards(lines, *upper_cervical.read_csv(upper_cervical_csv))
        except (OSError, ValueError, KeyError) as e:
            raise DeckError(str(e))
    _scaled_discs(lines, sub_bend, sub_flexion)
    try:
        return check_cards(lines, "the model deck")
    except CardError as e:
        raise DeckError(str(e))


# ---------------------------------------------------------------- command

def _parser():
    ap = argparse.ArgumentParser(prog="python3 -m hhneck.validation.model_deck", description=__doc__.split("\n\n")[0])
    ap.add_argument("--table", default=TABLE, help="the parameter table (default reference/model_parameters.csv)")
    ap.add_argument("--record", nargs=2, metavar=("STAGE", "FILE"),
                    help="first write the values of fit stage STAGE (%s) from FILE into the table"
                         % ", ".join(STAGES))
    ap.add_argument("--output", "-o", help="write the deck to this file (default: standard output; "
                                           "with --record, no deck unless given)")
    ap.add_argument("--fit", help="a calibration listing whose PARAM values replace the table's rows of "
                                  "those names (the table unchanged)")
    ap.add_argument("--posture", choices=POSTURES, default="seated")
    ap.add_argument("--t1-slope", type=float, help="T1 slope (deg; default the table's)")
    ap.add_argument("--lordosis", type=float, help="C2-C7 lordosis (deg; default the table's)")
    ap.add_argument("--nz-springs", help="the neutral-zone springs of this CSV, or none (default the table's)")
    ap.add_argument("--upper-cervical", default="none", help="the upper-cervical factors of this CSV, or none")
    ap.add_argument("--suboccipital", choices=("yes", "no"), default="no")
    ap.add_argument("--segmental", choices=("yes", "no"), default="yes")
    ap.add_argument("--cervical", choices=("yes", "no"), default="yes")
    ap.add_argument("--sub-bend", type=float, default=1.0, help="the subaxial discs' Ix, Iy times F")
    ap.add_argument("--sub-flexion", type=float, default=1.0, help="the Iy of the discs C3-C4 ... C7-T1 times F")
    return ap


def main(argv=None):
    """Write the model deck from the table (and first, with --record, a fit
    stage's values into the table); 0, else 1 with the reason on standard
    error and nothing written."""
    a = _parser().parse_args(argv)
    try:
        rows = read_table(a.table)
        if a.record:
            names = record(rows, a.record[0], a.record[1])
            write_table(a.table, rows)
            print("model_deck: %d values of stage %s written to %s" % (len(names), a.record[0], a.table),
                  file=sys.stderr)
            if not a.output:
                return 0
        p = table_values(rows)
        if a.fit:
            fitted = {n: _number(v, "%s: PARAM %s" % (a.fit, n)) for n, v in read_fit(a.fit) if n in p}
            p.update({n: table_value(p, n, v) for n, v in fitted.items()})
        lines = deck_lines(p, a.posture, a.t1_slope, a.lordosis, a.nz_springs, a.upper_cervical,
                           a.suboccipital == "yes", a.segmental == "yes", a.sub_bend, a.sub_flexion,
                           a.cervical == "yes")
    except (OSError, DeckError) as e:
        print("model_deck: %s; not written" % e, file=sys.stderr)
        return 1
    text = "\n".join(lines) + "\n"
    if a.output:
        _replace(a.output, text)
    else:
        sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
