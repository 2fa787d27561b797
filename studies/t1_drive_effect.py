#!/usr/bin/env python3
"""The effect of each measured T1 motion on the head: runs the NBDL decks with
T1 driven by x only, x + sagittal rotation, x + z + rotation with the z
acceleration filtered CFC 60 like the others (the drive before the z filter)
and x + z + rotation as shipped (z CFC 20; python3 -m hhneck.validation.nbdl_tables), and
prints a Markdown table of the overall CORA-style rating and the
head peaks (hhneck-compare-nbdl) for both severities.

    python3 studies/t1_drive_effect.py [--z-cfc 30,10,5]     (release build; about 30 s)

--z-cfc adds rows with the z table filtered at those CFC classes (the
sensitivity to the choice of CFC 20). A distance of 1.00 SD after rounding is
printed with three decimals (which side of the 1 SD target it is on).
"""
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))
from hhneck.ratings import compare, s3  # noqa: E402
from hhneck.volunteers import stop  # noqa: E402
from hhneck.validation.nbdl_tables import t1_tables  # noqa: E402
from hhneck.decks import CardError, hold, is_card, write_decks  # noqa: E402

# (label, T1 coordinates held instead of driven, CFC class of the z table or None as shipped)
VARIANTS = [
    ("x only", ("TZ", "RY"), None),
    ("x + rotation", ("TZ",), None),
    ("x + z (CFC 60) + rotation", (), 60),
    ("x + z (CFC 20) + rotation (shipped)", (), None),
]


def deck_variant(sev, held, z_cfc, path):
    """The case deck of `sev` at `path` with T1's `held` coordinates held
    and, when z_cfc is given, its T1 tables (z filtered CFC z_cfc) at
    path + ".t1", named on its INCLUDE card; CardError, and nothing written,
    when a card would pass column 80 (that INCLUDE card, with a long path)."""
    out = open("input/nbdl%s.inp" % sev).read().splitlines()
    decks = {}
    if z_cfc is not None:
        table = path + ".t1"
        decks[table] = t1_tables(sev, z_cfc)
        out = [line.replace("input/nbdl%s_t1.inp" % sev, table) if is_card(line, "INCLUDE") else line
               for line in out]
    decks[path] = hold(out, "T1", held)
    write_decks(decks)


def sd(z):
    return ("%+.3f" if round(abs(z), 2) == 1.0 else "%+.2f") % z


def main():
    variants = list(VARIANTS)
    if sys.argv[1:2] == ["--z-cfc"] and len(sys.argv) == 3:
        variants += [("x + z (CFC %s) + rotation" % c, (), int(c)) for c in sys.argv[2].split(",")]
    elif len(sys.argv) > 1:
        sys.exit("usage: t1_drive_effect.py [--z-cfc CLASS,CLASS,...]")
    tmp = tempfile.mkdtemp()
    rows = ["| severity | T1 driven by | rating | x-acc. (g) | z dip (g) | z rebound (g) | ang. acc. (rad/s²) "
            "| ang. vel. (rad/s) | rotation (deg) |", "|---|---|---|---|---|---|---|---|---|"]
    for sev in ("15g", "12g"):
        for label, held, z_cfc in variants:
            deck = os.path.join(tmp, "d.inp")
            try:
                deck_variant(sev, held, z_cfc, deck)
            except CardError as e:
                stop("%s (a shorter TMPDIR fits)" % e)
            h5 = os.path.join(tmp, "r.h5")
            with open(deck) as f:
                subprocess.run(["fpm", "run", "--profile", "release", "--", "--h5", h5], stdin=f,
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
            chans, peaks, overall, _, _, _ = compare(sev, h5)
            rows.append("| %s | %s | %.3f | %s |" % (sev.replace("g", " g"), label, overall, " | ".join(
                "%s (%s SD)" % (s3(p["mp"]), sd(p["z"])) for p in peaks)))
        rows.append("| %s | volunteers (mean ± SD) | | %s |" % (sev.replace("g", " g"), " | ".join(
            "%s ± %s" % (s3(p["pm"]), s3(p["ps"])) for p in peaks)))
    print("\n".join(rows))


if __name__ == "__main__":
    main()
