#!/usr/bin/env python3
"""What moves the late head x-acceleration trough of the NBDL 15 g run?

    python3 studies/probe_x_trough.py [--case 15g|12g]

The model's head x-acceleration has a first trough near 97 ms, where the
volunteers' peak is, and a deeper second one near 110 ms, which makes its
peak 11.8 ms late (docs/validation-history.md, "What limits the fit"). This runs the
case deck with one change at a time to the shipped model deck (copies in a
temporary directory; nothing in input/ is changed) and prints, per change,
the head x-acceleration (CFC 60) at 97 and 109 ms, its peak and the peak's
time less the volunteers' mean time, and the head angular acceleration at
110 ms (the volunteers' mean there: 911 rad/s2 at 15 g). Changes: the
scale factors of the element families (SCALE cards; the discs' damping
also by mode, axial alone and shear-bending-torsion alone), the
range-of-motion stiffness of the upper cervical joints and of T1-C7, the
activation (bracing, reflex, short-range stiffness), the T1 x drive
filtered at a lower class, a per-level range-of-motion split (White and Panjabi's representative
flexion-extension ranges scaled to the C2-T1 total of reference-data.md),
the head's joint point (the mass centre's offset from the occipital
condyles), the point of T1 that follows the measured translation, the
measured T1 rotation scaled, the lowest joints' rotation held or their discs' bending
stiffened, the ligaments' stiffness scaled, every disc's bending stiffness
scaled (a scan over which the peak jumps from the late trough to an early
one) or every joint's rotation held, and extensors the model does not have
(a deep T1-C2 pair, segmental fascicles over two joints).

After the table it prints the T1 and head x-acceleration (CFC 60; the
volunteers' means and the shipped model) at T1's first trough, its rebound
and its second trough (86, 98 and 110 ms at 15 g): which of T1's troughs
the head follows. Then the head's x-velocity relative to T1 (the
integral from 30 ms of head minus T1 x-acceleration, each CFC 60: the
volunteers' means and the shipped model) at a few times, which shows where
the late trough comes from. Last it prints the shipped run's head
x-acceleration peak at points 1 to 4 cm below the mass centre (fixed in the
head), a_P = a + alpha x r + omega x (omega x r) in the sagittal plane,
filtered as the others: the source does not document where its head
accelerations are measured, and the rotation's share of a_P is largest near
97 ms, at the model's angular acceleration peak.
"""
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))
from hhneck.ratings import peak  # noqa: E402
from hhneck.signals import cfc  # noqa: E402
from hhneck.volunteers import runs, stop, volunteer_channels  # noqa: E402
from hhneck.validation import nbdl_tables as make_nbdl_tables  # noqa: E402
from hhneck.decks import CardError, check_cards, field, held, is_card, set_field, write_deck  # noqa: E402

MODEL = "input/head_neck_54dof.inp"
HISTORIES = ("FLEX", "EXT")  # the model deck's ACTIVATE cards


def scale(fam, item, f):
    card = "%-10s%-10s%-10s%-10s%g" % ("SCALE", "PROBE", fam, item, f)
    return lambda s: s.replace("HEADNECK  HEAD      T1", card + "\nHEADNECK  HEAD      T1")


def card_field(card, names, n, new, coord=None, offset=0):
    """Model edit: on every `card` image whose F1 is in `names` (and F2 is
    `coord`, when given), field n of the image `offset` lines below (its
    continuation) becomes new(old field text)."""
    def edit(s):
        out = s.splitlines()
        for i, line in enumerate(out):
            if is_card(line, card) and field(line, 1) in names and coord in (None, field(line, 2)):
                out[i + offset] = set_field(out[i + offset], n, new(field(out[i + offset], n)))
        return "\n".join(out) + "\n"
    return edit


def times(f):
    """new() of card_field: the field's number times f."""
    return lambda old: "%.6g" % (float(old) * f)


def rom_k(bodies, f):
    """ROM cards' stiffness (F5) times f on the RY rows of `bodies`."""
    return card_field("ROM", bodies, 5, times(f), coord="RY")


def activation(n, value):
    """Field F2 (bracing) or F3 (reflex level) of both ACTIVATE cards (FLEX, EXT) set to value."""
    return card_field("ACTIVATE", HISTORIES, n, lambda old: value)


def rom_split(totals):
    """LIMIT and ROM RY ranges centred on each joint's neutral angle with the given totals (deg)."""
    def edit(s):
        neutral = {m.group(1): float(m.group(2)) for m in re.finditer(r"^NEUTRAL\s+(\S+)\s+RY\s+(\S+)", s, re.M)}
        out = []
        for line in s.splitlines():
            body = field(line, 1)
            if field(line, 0) in ("LIMIT", "ROM") and body in totals and field(line, 2) == "RY":
                n, t = neutral.get(body, 0.0), totals[body]
                line = set_field(set_field(line, 3, "%.4f" % (n - t / 2)), 4, "%.4f" % (n + t / 2))
            out.append(line)
        return "\n".join(out) + "\n"
    return edit


def joint_point(body, x, z):
    """A body's joint point in its own frame (JOINT F5, F7) set to (x, 0, z).
    For T1 that is the point whose translation is prescribed: the measured
    T1 motion is applied there instead of at T1's mass centre."""
    at_x = card_field("JOINT", (body,), 5, lambda old: x)
    at_z = card_field("JOINT", (body,), 7, lambda old: z)
    return lambda s: at_z(at_x(s))


def t1_drive(sev, deck, path, lines):
    """The case deck reading its T1 tables from `path`, written with `lines`."""
    write_deck(path, lines)
    return deck.replace("input/nbdl%s_t1.inp" % sev, path)


def t1x_class(cls):
    """Deck edit: the T1 x-acceleration table filtered CFC cls instead of 60."""
    return lambda deck, sev, tmp: t1_drive(sev, deck, os.path.join(tmp, "t1_%d.inp" % cls),
                                           make_nbdl_tables.t1_tables(sev, x_cfc=cls))


def t1_rotation(f):
    """Deck edit: the T1 rotation drive (TABLE T1RY's value scale, F4) times f."""
    def edit(deck, sev, tmp):
        lines = [set_field(l, 4, "%g" % (float(field(l, 4)) * f)) if is_card(l, "TABLE", "T1RY") else l
                 for l in open("input/nbdl%s_t1.inp" % sev).read().splitlines()]
        return t1_drive(sev, deck, os.path.join(tmp, "t1_rot%g.inp" % f), lines)
    return edit


def lock(*pairs):
    """Deck edit: the given (body, coordinate) pairs held at their neutral values."""
    def edit(deck, sev, tmp):
        cards = "".join(held(*p) + "\n" for p in pairs)
        return deck.replace("INCLUDE   input/nbdl%s_t1.inp" % sev, cards + "INCLUDE   input/nbdl%s_t1.inp" % sev)
    return edit


def short_range(q=None, span=None):
    """The ACTIVATE continuation card's short-range stiffness q (F3) or its span (F4)."""
    if q is not None:
        return card_field("ACTIVATE", HISTORIES, 3, lambda old: q, offset=1)
    return card_field("ACTIVATE", HISTORIES, 4, lambda old: span, offset=1)


def disc_bending(discs, f):
    """Flexion-extension bending stiffness (Iy, continuation card F3) of the named discs times f."""
    return card_field("DISC", discs, 3, times(f), offset=2)


def extra_muscles(muscles):
    """Model edit: Hill muscles the model does not have, on the extensors'
    activation history EXT, inserted before the ACTIVATE cards; each muscle
    (name, body a, body b, F0, lopt, point on a, point on b, [(via body,
    point)]), the damping F0/10 s/m as the model deck's."""
    def edit(s):
        cards = []
        for name, ba, bb, f0, lopt, pa, pb, vias in muscles:
            cards.append("%-10s%-10s%-10s%-10s%-10s%-10s%-10s%g" % ("HILL", name, ba, bb, "%g" % f0, lopt, "EXT",
                                                                    f0 / 10))
            cards.append(" " * 10 + "".join("%-10s" % ("%g" % v) for v in pa + pb))
            cards += ["%-10s%-10s%-10s" % ("VIA", name, body) + "".join("%-10s" % ("%g" % v) for v in at)
                      for body, at in vias]
        anchor = "* Activation histories"
        return s.replace(anchor, "\n".join(cards) + "\n" + anchor)
    return edit


def deep_extensor(f0):
    """A pair of Hill muscles T1 -> C2 behind the lower column (a semispinalis
    cervicis, which the model does not have; geometry and F0 assumed), with
    vias on C7 ... C3."""
    return extra_muscles([(name, "T1", "C2", f0, "0.06", (-0.035, 0.02 * side, 0.005), (-0.04, 0.01 * side, 0.0),
                           [(body, (-0.03, 0.018 * side, 0.0)) for body in ("C7", "C6", "C5", "C4", "C3")])
                          for name, side in (("DEXTL", 1), ("DEXTR", -1))])


def segmental_extensors(f0):
    """Pairs of Hill muscles each spanning two joints behind the column
    (multifidus-like fascicles T1 -> C6, C7 -> C5, ..., C4 -> C2, which the
    model does not have; geometry and F0 assumed): from the articular process
    of the lower vertebra to the spinous process of the upper, via the middle
    one."""
    column = ("T1", "C7", "C6", "C5", "C4", "C3", "C2")
    return extra_muscles([("MF%s%s" % (column[k + 2], side), column[k], column[k + 2], f0, "0.03",
                           (-0.02, 0.02 * sgn, 0.0), (-0.04, 0.005 * sgn, 0.0),
                           [(column[k + 1], (-0.03, 0.012 * sgn, 0.0))])
                          for k in range(len(column) - 2) for side, sgn in (("L", 1), ("R", -1))])


JOINTS = ("C7", "C6", "C5", "C4", "C3", "C2", "C1", "HEAD")  # each body's joint with its parent, T1-C7 ... C1-head
DISC_NAMES = ("T1C7", "C7C6", "C6C5", "C5C4", "C4C3", "C3C2", "C2C1", "C1HD")

# White & Panjabi's representative flexion-extension ranges C2-C3 ... C7-T1
# (10, 15, 20, 20, 17, 9 deg) scaled to reference-data.md's C2-T1 total of 82 deg
WP = dict(zip(("C2", "C3", "C4", "C5", "C6", "C7"), (9.0, 13.5, 18.0, 18.0, 15.3, 8.1)))

PROBES = [
    ("shipped", None, None),
    ("disc axial stiffness x2", scale("DISCS", "E", 2.0), None),
    ("disc shear stiffness x2", scale("DISCS", "G", 2.0), None),
    ("disc retardation time x2", scale("DISCS", "VISCOUS", 2.0), None),
    ("disc retardation time x0.5", scale("DISCS", "VISCOUS", 0.5), None),
    ("disc axial damping x0.3", scale("DISCS", "VAXIAL", 0.3), None),
    ("disc axial damping x0.1", scale("DISCS", "VAXIAL", 0.1), None),
    ("disc axial damping x0.05", scale("DISCS", "VAXIAL", 0.05), None),
    ("disc shear, bending and torsion damping x0.1", scale("DISCS", "VBEND", 0.1), None),
    ("muscle strength x2", scale("MUSCLES", "F0", 2.0), None),
    ("muscle strength x0.5", scale("MUSCLES", "F0", 0.5), None),
    ("joint-limit damping x10", scale("LIMITS", "C1", 10.0), None),
    ("range-of-motion stiffness x30, all joints", scale("LIMITS", "ROMK", 30.0), None),
    ("range-of-motion stiffness x10, C1 and head", rom_k(("HEAD", "C1"), 10.0), None),
    ("range-of-motion stiffness x30, T1-C7", rom_k(("C7",), 30.0), None),
    ("no bracing", activation(2, "0.0"), None),
    ("no reflex", activation(3, "0.0"), None),
    ("full reflex", activation(3, "1.0"), None),
    ("per-level ROM split (White & Panjabi)", rom_split(WP), None),
    ("head joint 10 mm lower (z -0.045)", joint_point("HEAD", "-0.02", "-0.045"), None),
    ("head joint 15 mm further back (x -0.035)", joint_point("HEAD", "-0.035", "-0.035"), None),
    ("T1 drive at a point 60 mm behind T1's mass centre", joint_point("T1", "-0.06", "0.0"), None),
    ("T1 drive at a point 30 mm ahead of T1's mass centre", joint_point("T1", "0.03", "0.0"), None),
    ("T1 drive at a point 50 mm below T1's mass centre", joint_point("T1", "0.0", "-0.05"), None),
    ("T1 x drive CFC 20", None, t1x_class(20)),
    ("T1 x drive CFC 10", None, t1x_class(10)),
    ("T1 x drive CFC 5", None, t1x_class(5)),
    ("T1 rotation drive x0.5", None, t1_rotation(0.5)),
    ("T1 rotation drive x1.5", None, t1_rotation(1.5)),
    ("rotation held at C1-head and C1-C2", None, lock(("HEAD", "RY"), ("C1", "RY"))),
    ("rotation held at T1-C7 and C7-C6", None, lock(("C7", "RY"), ("C6", "RY"))),
    ("rotation held at every joint", None, lock(*[(b, "RY") for b in JOINTS])),
    ("disc bending stiffness x10, T1-C7 and C7-C6", disc_bending(("T1C7", "C7C6"), 10.0), None),
    ("disc bending stiffness x100, T1-C7 and C7-C6", disc_bending(("T1C7", "C7C6"), 100.0), None),
    ("disc bending stiffness x30, every disc", disc_bending(DISC_NAMES, 30.0), None),
    ("disc bending stiffness x50, every disc", disc_bending(DISC_NAMES, 50.0), None),
    ("disc bending stiffness x100, every disc", disc_bending(DISC_NAMES, 100.0), None),
    ("ligament stiffness x0.1", scale("LIGAMENTS", "L2", 0.1), None),
    ("ligament stiffness x10", scale("LIGAMENTS", "L2", 10.0), None),
    ("ligament stiffness x100", scale("LIGAMENTS", "L2", 100.0), None),
    ("deep extensor T1-C2, F0 100 N per side", deep_extensor(100.0), None),
    ("deep extensor T1-C2, F0 400 N per side", deep_extensor(400.0), None),
    ("segmental extensors T1-C2 over two joints, F0 40 N per fascicle and side", segmental_extensors(40.0), None),
    ("segmental extensors T1-C2 over two joints, F0 160 N per fascicle and side", segmental_extensors(160.0), None),
    ("short-range stiffness q 5", short_range(q="5.0"), None),
    ("short-range stiffness q 40", short_range(q="40.0"), None),
    ("short-range stiffness over 0.5 % of lopt", short_range(span="0.005"), None),
    ("short-range stiffness over 2 % of lopt", short_range(span="0.02"), None),
]


def probe_deck(k, sev, model, edit_model, edit_deck, tmp):
    """The case deck of probe k (PROBES) for standard input, its model deck
    and any T1 tables written in `tmp` and named on its INCLUDE cards;
    CardError when a card would pass column 80 (an INCLUDE card, with a long
    `tmp` path)."""
    inc = os.path.join(tmp, "model%d.inp" % k)
    write_deck(inc, edit_model(model) if edit_model else model)
    deck = open("input/nbdl%s.inp" % sev).read().replace(MODEL, inc)
    if edit_deck:
        deck = edit_deck(deck, sev, tmp)
    check_cards(deck.splitlines(), "the case deck of probe %d" % k)
    return deck


def x_accelerations(sev, h5):
    """Head and T1 x-acceleration (g, CFC 60) on the volunteers' times:
    (t, volunteers' mean head, their mean T1, model head, model T1)."""
    import h5py
    t, hx, _ = runs("Head_XAccel", sev)
    tx = runs("T1_XAccel", sev)[1]
    dt = (t[1] - t[0]) * 1e-3
    mean = lambda a: np.mean([cfc(r, 60, dt) for r in a], axis=0)
    f = h5py.File(h5, "r")
    tm = f["time"][:] * 1e3
    dtm = (tm[1] - tm[0]) * 1e-3
    model = lambda name: np.interp(t, tm, cfc(f["channels"][name][:], 60, dtm))
    return t, mean(hx), mean(tx), model("HEAD_AX"), model("T1_AX")


def t1_troughs(t, t1):
    """Times of T1's first x-acceleration trough, the rebound after it and its
    second trough (each within 20 ms of the one before)."""
    first = t[np.argmin(np.where(t < 95.0, t1, 0.0))]
    after = (t > first) & (t < first + 20.0)
    rebound = t[after][np.argmax(t1[after])]
    after = (t > rebound) & (t < rebound + 20.0)
    return first, rebound, t[after][np.argmin(t1[after])]


def relative_velocity(t, vh, vt, mh, mt):
    """Head x-velocity relative to T1 (m/s) from 30 ms, from x_accelerations():
    (volunteers' mean, model)."""
    g, dt = 9.80665, (t[1] - t[0]) * 1e-3
    on = t >= 30.0
    return (np.cumsum(np.where(on, (vh - vt) * g, 0.0)) * dt,
            np.cumsum(np.where(on, (mh - mt) * g, 0.0)) * dt)


def measuring_point(h5, rz):
    """Head x-acceleration (g, unfiltered) at the point r = (0, 0, rz) m of the
    head frame: the mass centre's plus alpha x r + omega x (omega x r), sagittal
    motion (rotation HEAD_THETY about y, flexion positive)."""
    import h5py
    ch = h5py.File(h5, "r")["channels"]
    th = np.radians(ch["HEAD_THETY"][:])
    w, al = ch["HEAD_OMEGY"][:], ch["HEAD_ALPHY"][:]
    rx, rzl = rz * np.sin(th), rz * np.cos(th)   # r in R's axes (x, z)
    return ch["HEAD_AX"][:] + (al * rzl - w ** 2 * rx) / 9.80665


def main():
    sev = "15g"
    if sys.argv[1:3] and sys.argv[1] == "--case":
        sev = sys.argv[2]
    exe = subprocess.run(["fpm", "run", "--profile", "release", "--runner", "echo"], capture_output=True,
                         text=True, check=True).stdout.split()[-1]
    vol, _ = volunteer_channels(sev)
    t, data = vol["head x-acceleration (g)"]
    tmean = np.mean([peak(t, r, -1)[1] for r in data])
    model = open(MODEL).read()
    tmp = tempfile.mkdtemp()
    print("| change (%s) | head x-acc. at 97 ms (g) | at 109 ms (g) | peak (g) | peak time − volunteers' (ms) |"
          " head angular acc. at 110 ms (rad/s2) |" % sev.replace("g", " g"))
    print("|---|---|---|---|---|---|")
    for k, (label, edit_model, edit_deck) in enumerate(PROBES):
        try:
            deck = probe_deck(k, sev, model, edit_model, edit_deck, tmp)
        except CardError as e:
            stop("%s (a shorter TMPDIR fits)" % e)
        h5 = os.path.join(tmp, "r%d.h5" % k)
        r = subprocess.run([exe, "-I", os.getcwd(), "--h5", h5], input=deck, capture_output=True, text=True)
        if r.returncode:
            print("| %s | run failed: %s |" % (label, r.stderr.strip().splitlines()[-1]))
            continue
        import h5py
        f = h5py.File(h5, "r")
        tm = f["time"][:] * 1e3
        dt = (tm[1] - tm[0]) * 1e-3
        ax = cfc(f["channels"]["HEAD_AX"][:], 60, dt)
        al = cfc(f["channels"]["HEAD_ALPHY"][:], 60, dt)
        p, pt = peak(tm, ax, -1)
        at = lambda x, ms: x[np.argmin(np.abs(tm - ms))]
        print("| %s | %.1f | %.1f | %.1f | %+.1f | %.0f |" % (label, at(ax, 97), at(ax, 109), p, pt - tmean,
                                                              at(al, 110)))
        if k == 0:
            shipped = h5
    t, vh, vt, mh, mt = x_accelerations(sev, shipped)
    at = lambda x, ms: x[np.argmin(np.abs(t - ms))]
    print("\nT1 and head x-acceleration (g), volunteers' mean / shipped model, at T1's first trough, its rebound"
          " and its second trough: " + "; ".join("%.1f ms T1 %.1f / %.1f, head %.1f / %.1f" % (
              ms, at(vt, ms), at(mt, ms), at(vh, ms), at(mh, ms)) for ms in t1_troughs(t, vt)))
    vol, mod = relative_velocity(t, vh, vt, mh, mt)
    iv, im = np.argmax(vol), np.argmax(mod)
    print("\nHead x-velocity relative to T1 (m/s), volunteers' mean / shipped model: largest %.2f at %.1f ms /"
          " %.2f at %.1f ms; " % (vol[iv], t[iv], mod[im], t[im]) +
          ", ".join("%d ms %.2f / %.2f" % (ms, vol[np.argmin(np.abs(t - ms))], mod[np.argmin(np.abs(t - ms))])
                    for ms in (95, 100, 105, 110, 115, 120, 130)))
    import h5py
    tm = h5py.File(shipped, "r")["time"][:] * 1e3
    dt = (tm[1] - tm[0]) * 1e-3
    points = []
    for rz in (-0.01, -0.02, -0.03, -0.04):
        p, pt = peak(tm, cfc(measuring_point(shipped, rz), 60, dt), -1)
        points.append("%d mm %.1f g, %+.1f ms" % (round(-1e3 * rz), p, pt - tmean))
    print("\nShipped run, head x-acceleration peak at a point below the mass centre (peak time less the"
          " volunteers' mean): " + "; ".join(points))


if __name__ == "__main__":
    main()
